#!/usr/bin/env python3
"""Fails when a doctest case name holds ';' or starts or ends with a blank.

ctest's doctest discovery splits the list of names it reads at ';', so such a case becomes two
names that match nothing and never runs under ctest, while the run still reports all passed.
"""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent)
# A name may be several adjacent string literals, over several lines.
literal = r'"(?:[^"\\]|\\.)*"'
name = re.compile(r'\b(?:TEST_CASE|SUBCASE|SCENARIO)\(\s*((?:' + literal + r'\s*)+)')
bad = []
for path in sorted(root.rglob("*.cpp")):
    source = path.read_text(encoding="utf-8")
    for match in name.finditer(source):
        text = "".join(part[1:-1] for part in re.findall(literal, match.group(1)))
        if ";" in text or text != text.strip():
            number = source.count("\n", 0, match.start()) + 1
            bad.append(f"{path}:{number}: test case name {text!r}")
for line in bad:
    print(line)
if bad:
    print(f"{len(bad)} test case name(s) ctest cannot run: drop ';' and outer blanks")
sys.exit(1 if bad else 0)
