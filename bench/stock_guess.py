#!/usr/bin/env python3
"""The guessed stock against the known one: real programs whose stock is known (bench/known_stock.tsv),
each run with its tools and its stock, then with its tools alone (the stock guessed), with default
settings. Prints, per program, the removed volume, the energy and the peak power of both runs and
the differences, and how long the guessed run took.

Usage: bench/stock_guess.py NCJOULE CORPUS_DIR [--markdown] [-- extra ncjoule arguments]

CORPUS_DIR holds the corpus programs (tests/corpus/fetch.sh); programs named by a path are the
repository's own samples. The targets (issue 39): volume within 10%, energy within 3%, peak no
higher than with the real stock (+5%).
"""
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def run(ncjoule, args, env):
    start = time.time()
    p = subprocess.run([ncjoule, "estimate", "--json"] + args, capture_output=True, text=True,
                       env=env)
    seconds = time.time() - start
    try:
        return json.loads(p.stdout), seconds
    except json.JSONDecodeError:
        return None, seconds


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    markdown = "--markdown" in argv
    argv = [a for a in argv if a != "--markdown"]
    if len(argv) != 2:
        sys.exit(__doc__)
    ncjoule, corpus = argv
    # No user config: default settings.
    env = dict(os.environ, XDG_CONFIG_HOME=tempfile.mkdtemp(), NCJOULE_CONFIG="")
    rows = []
    with open(os.path.join(HERE, "known_stock.tsv")) as f:
        for line in f:
            if line.startswith("#") or line.startswith("id\t") or not line.strip():
                continue
            rows.append(line.rstrip("\n").split("\t"))
    head = ("program", "set", "vol. known mm3", "vol. guessed mm3", "vol.", "energy", "peak",
            "peak known W", "peak guessed W", "guessed run s")
    if markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
    else:
        print("%-44s %-4s %14s %16s %7s %7s %7s %12s %14s %13s" % head)
    misses = 0
    for name, subset, stock, tools, _source in rows:
        program = os.path.join(ROOT, name) if "/" in name else os.path.join(corpus, name)
        tool_args = []
        for t in tools.split():
            tool_args += ["--tool", t]
        known, _ = run(ncjoule, [program, "--stock", stock] + tool_args + extra, env)
        guessed, seconds = run(ncjoule, [program] + tool_args + extra, env)
        if not known or not guessed:
            print("%-44s failed" % name)
            misses += 1
            continue
        def change(a, b):
            return (b / a - 1) * 100 if a else float("nan")
        dv = change(known["removed_mm3"], guessed["removed_mm3"])
        de = change(known["energy_j"], guessed["energy_j"])
        dp = change(known["peak_power_w"], guessed["peak_power_w"])
        ok = abs(dv) <= 10 and abs(de) <= 3 and dp <= 5
        misses += not ok
        cells = (os.path.basename(name), subset, "%.0f" % known["removed_mm3"],
                 "%.0f" % guessed["removed_mm3"], "%+.1f%%" % dv, "%+.2f%%" % de, "%+.1f%%" % dp,
                 "%.0f" % known["peak_power_w"], "%.0f" % guessed["peak_power_w"],
                 "%.2f" % seconds)
        if markdown:
            print("| " + " | ".join(cells) + (" |" if ok else " (miss) |"))
        else:
            print("%-44s %-4s %14s %16s %7s %7s %7s %12s %14s %13s" % cells + ("" if ok else "  miss"))
    print("%d of %d within the targets (volume 10%%, energy 3%%, peak +5%%)" %
          (len(rows) - misses, len(rows)))


if __name__ == "__main__":
    main()
