#!/usr/bin/env python3
"""Every corpus program with default settings: wall time, peak memory, the removal grid, and the
removed volume against a run on a grid three times finer (issue 43's targets: within 256 MiB and
2 s each, volume within 0.5% of the fine grid).

Usage: bench/corpus_budget.py NCJOULE CORPUS_DIR [--no-fine] [--markdown] [FILES...]

Times are wall-clock on this machine as it is: run it on an idle machine. Peak memory is the
process's maximum resident set (GNU time's %M).
"""
import json
import os
import subprocess
import sys
import tempfile

MIB = 1 << 20


def run(ncjoule, program, extra, env):
    with tempfile.NamedTemporaryFile() as t:
        p = subprocess.run(["/usr/bin/time", "-f", "%e %M", "-o", t.name, ncjoule, "estimate",
                            program, "--json"] + extra, capture_output=True, text=True, env=env)
        seconds, kib = open(t.name).read().split("\n")[-2].split()
    try:
        doc = json.loads(p.stdout)
    except json.JSONDecodeError:
        doc = None
    return doc, float(seconds), int(kib) * 1024


def main():
    args = sys.argv[1:]
    fine = "--no-fine" not in args
    markdown = "--markdown" in args
    args = [a for a in args if a not in ("--no-fine", "--markdown")]
    if len(args) < 2:
        sys.exit(__doc__)
    ncjoule, corpus, files = args[0], args[1], args[2:]
    if not files:
        files = sorted(os.path.join(corpus, f) for f in os.listdir(corpus)
                       if not f.startswith("."))
    env = dict(os.environ, XDG_CONFIG_HOME=tempfile.mkdtemp(), NCJOULE_CONFIG="")
    head = ("program", "s", "MiB", "grid mm", "columns", "removed mm3", "fine grid mm3", "vol.")
    if markdown:
        print("| " + " | ".join(head) + " |\n|" + "---|" * len(head))
    else:
        print("%-46s %6s %6s %8s %9s %12s %14s %7s" % head)
    over, worst, count = [], 0.0, 0
    for program in files:
        doc, seconds, peak = run(ncjoule, program, [], env)
        name = os.path.basename(program)[:46]
        if doc is None:
            print("%-46s %6.2f %6.0f  (no estimate)" % (name, seconds, peak / MIB))
            continue
        count += 1
        removal = doc.get("removal") or {}
        grid = removal.get("grid_mm", 0)
        cells = [name, "%.2f" % seconds, "%.0f" % (peak / MIB), "%.4f" % grid,
                 str(removal.get("columns", 0)), "%.0f" % doc["removed_mm3"], "-", "-"]
        if fine and grid > 0 and doc["removed_mm3"] > 0:
            f, _, _ = run(ncjoule, program, ["--grid", "%.6f" % (grid / 3), "--memory-limit",
                                             "16000"], env)
            if f and f["removed_mm3"] > 0:
                diff = (doc["removed_mm3"] / f["removed_mm3"] - 1) * 100
                worst = max(worst, abs(diff))
                cells[6] = "%.0f" % f["removed_mm3"]
                cells[7] = "%+.2f%%" % diff
        if seconds > 2 or peak > 256 * MIB:
            over.append(name)
        if markdown:
            print("| " + " | ".join(cells) + " |")
        else:
            print("%-46s %6s %6s %8s %9s %12s %14s %7s" % tuple(cells))
    print("%d programs; %d over 2 s or 256 MiB%s%s" % (count, len(over),
                                                        (": " + ", ".join(over)) if over else "",
                                                        ("; worst volume difference to the fine "
                                                         "grid %.2f%%" % worst) if fine else ""))


if __name__ == "__main__":
    main()
