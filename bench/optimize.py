#!/usr/bin/env python3
"""ncjoule optimize on real posts whose stock is known: the programs of bench/known_stock.tsv
(with their stock and tools) and the corpus programs whose CAM writes the stock in their header
(stock comments, a Sinumerik WORKPIECE, a Vectric Material Size block). Prints, per program, the
time, energy and cost of the original and the optimized program, the air-cut time of each, the
changed blocks (air feeds / rapids) and restore blocks, the removed volume's difference and the
collisions before and after, and how long optimize took. A program optimize refuses or cannot
improve says so. With `-- --load-feeds`, the air/rapid column leaves out the load-scaled blocks,
and a column gives those lowered and raised, and the finishing passes left as they were.

Usage: bench/optimize.py NCJOULE CORPUS_DIR [--markdown] [-- extra ncjoule arguments]

The machine is the generic 3-axis profile unless the extra arguments name another (-m NAME).
The checks of issue 44: volume within 0.5%, no new collision, the time not larger.
"""
import json
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
GENERIC = os.path.join(ROOT, "samples/machines/generic-3axis.toml")
# What the stock readers take from a header (docs/stock.md), searched in the first 1000 lines.
CAM_STOCK = re.compile(r"stockMin|WORKPIECE\(|STOCK/BLOCK|Material Size|\(\s*STOCK(\s+SIZE)?:?\s*[\d.]",
                       re.I)


def known_rows(corpus):
    rows = []
    with open(os.path.join(HERE, "known_stock.tsv")) as f:
        for line in f:
            if line.startswith("#") or line.startswith("id\t") or not line.strip():
                continue
            name, _set, stock, tools, _source = line.rstrip("\n").split("\t")
            path = os.path.join(ROOT, name) if "/" in name else os.path.join(corpus, name)
            args = ["--stock", stock]
            for t in tools.split():
                args += ["--tool", t]
            rows.append((name, path, args, "known_stock.tsv"))
    listed = {os.path.basename(r[1]) for r in rows}
    for name in sorted(os.listdir(corpus)):
        if name in listed:
            continue
        path = os.path.join(corpus, name)
        with open(path, errors="replace") as f:
            head = "".join(line for _, line in zip(range(1000), f))
        if CAM_STOCK.search(head):
            rows.append((name, path, [], "CAM header"))
    return rows


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
    if not any(a in ("-m", "--machine") for a in extra):
        extra = ["--machine", GENERIC] + extra
    env = dict(os.environ, XDG_CONFIG_HOME=tempfile.mkdtemp(), NCJOULE_CONFIG="",
               NCJOULE_PROGRESS="0")
    out_dir = tempfile.mkdtemp(prefix="ncjoule-optimize-bench-")
    head = ("program", "time s", "opt. s", "time", "air s", "opt. air s", "energy kJ", "opt. kJ",
            "cost", "opt. cost", "changed (air/rapid)", "restores", "volume", "collisions",
            "run s")
    load_feeds = "--load-feeds" in extra
    if load_feeds:
        head = head[:-1] + ("load lowered/raised/finishing", "run s")
    fmt = "%-40s %9s %9s %7s %8s %10s %9s %9s %8s %9s %19s %8s %8s %10s" + (
        " %29s" if load_feeds else "") + " %6s"
    if markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
    else:
        print(fmt % head)
    failed = 0
    for name, path, args, source in known_rows(corpus):
        out = os.path.join(out_dir, os.path.basename(path) + ".opt")
        start = time.time()
        p = subprocess.run([ncjoule, "optimize", path, "-o", out, "--json"] + args + extra,
                           capture_output=True, text=True, env=env)
        seconds = time.time() - start
        label = os.path.basename(name)
        if p.returncode != 0 or not p.stdout.strip():
            why = (p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1]
            failed += p.returncode == 3
            print(("| %s | %s |" if markdown else "%-40s %s") % (label, why[:150]))
            continue
        try:
            r = json.loads(p.stdout)
        except ValueError:
            print(("| %s | unreadable output |" if markdown else "%-40s unreadable output")
                  % label)
            continue
        if not r["changed_blocks"]:
            why = "no block to change (%d feed moves, %d clear)" % (r["feed_moves"],
                                                                    r["clear_moves"])
            print(("| %s | %s |" if markdown else "%-40s %s") % (label, why))
            continue
        progs = {os.path.basename(x["file"]): x for x in r["comparison"]["programs"]}
        a, b = progs[os.path.basename(path)], progs[os.path.basename(out)]
        v0, v1 = r["removed_mm3"]
        dv = (v1 / v0 - 1) * 100 if v0 else 0.0
        cells = (label, "%.1f" % a["time_s"], "%.1f" % b["time_s"],
                 "%+.1f%%" % ((b["time_s"] / a["time_s"] - 1) * 100), "%.1f" % a["air_cut_s"],
                 "%.1f" % b["air_cut_s"], "%.2f" % (a["energy_j"] / 1000),
                 "%.2f" % (b["energy_j"] / 1000), "%.4f" % a["cost"], "%.4f" % b["cost"],
                 "%d (%d/%d)" % (r["changed_blocks"] - r.get("load_feeds", {}).get("lowered", 0)
                                 - r.get("load_feeds", {}).get("raised", 0), r["air_feeds"],
                                 r["rapids"]),
                 "%d" % r["restore_blocks"], "%+.3f%%" % dv,
                 "%d -> %d" % tuple(r["collisions"]))
        if load_feeds:
            load = r.get("load_feeds", {})
            cells += ("%d/%d/%d" % (load.get("lowered", 0), load.get("raised", 0),
                                    load.get("finishing_passes", 0)),)
        cells += ("%.1f" % seconds,)
        print(("| " + " | ".join(cells) + " |") if markdown else fmt % cells)
    print("%d program(s) failed the checks" % failed)


if __name__ == "__main__":
    main()
