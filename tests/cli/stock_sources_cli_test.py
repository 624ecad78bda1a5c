#!/usr/bin/env python3
"""Where the stock comes from, end to end (docs/stock.md): --stock (and a hook's, named by
--stock-from), the job file, PROGRAM.stock, a CAMotics project beside the program, the user
config, in that order; each named in the JSON (stock_from, stock_origin) and the annotated
header (FROM=); a damaged project beside the program is a warning and the next source is used."""
import json
import os
import shutil
import subprocess
import sys
import tempfile

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
GENERIC = os.path.join(ROOT, "samples/machines/generic-3axis.toml")
failures = []

# Two passes of a tool nothing in the program describes: the project's tools must describe it.
PROGRAM = """G21 G90 G17
T1 M6
S3000 M3
G0 X-10 Y10 Z5
G1 Z-2 F300
G1 X110
G1 Z-4
G1 X-10
G0 Z5
M30
"""
PROJECT = {"units": "imperial",
           "tools": {"1": {"units": "metric", "shape": "cylindrical", "length": 30,
                           "diameter": 12}},
           "workpiece": {"automatic": False, "margin": 0,
                         "bounds": {"min": [-20, 0, -6], "max": [120, 20, 0]}},
           "files": ["part.ngc"]}


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def write(path, text):
    with open(path, "w") as f:
        f.write(text)
    return path


def run(*args, config=None):
    env = dict(os.environ, NCJOULE_CONFIG=config or os.path.join(work, "no-config.toml"))
    return subprocess.run([NCJOULE, *args], capture_output=True, text=True, env=env)


def estimate(*args, config=None):
    r = run("estimate", "--json", "--machine", GENERIC, *args, config=config)
    try:
        return r, json.loads(r.stdout)
    except ValueError:
        return r, {}


def stock_of(doc):
    setup = (doc.get("setups") or [{}])[0]
    return doc.get("stock_from"), setup.get("stock_origin", ""), setup.get("stock_box_mm")


work = tempfile.mkdtemp(prefix="ncjoule-stock-sources-")
try:
    part = write(os.path.join(work, "part.ngc"), PROGRAM)
    write(os.path.join(work, "part.camotics"), json.dumps(PROJECT))
    config = write(os.path.join(work, "config.toml"), 'stock = "box:0,0,-9,100,20,0"\n')

    # The project beside the program: its workpiece (mm, though the project shows inches) and
    # its tool, over the user config's stock.
    r, doc = estimate(part, config=config)
    kind, origin, box = stock_of(doc)
    check(r.returncode == 0 and kind == "camotics" and origin == "CAMotics project part.camotics"
          and box == [-20, 0, -6, 120, 20, 0], f"the CAMotics project's stock ({kind}, {origin}, {box})")
    check(doc.get("unsimulated_tools") == [] and doc.get("removed_mm3", 0) > 0,
          f"the project's tool cuts ({doc.get('unsimulated_tools')}, {doc.get('removed_mm3')})")
    # Two 2 mm passes of the 12 mm cutter from X-10 to X110, inside the project's stock: a
    # 120 x 12 mm strip and the cutter's round ends, 4 mm deep.
    expected = (120 * 12 + 3.14159265 * 36) * 4
    check(abs(doc.get("removed_mm3", 0) - expected) < 0.01 * expected,
          f"the removed volume is the two passes' ({doc.get('removed_mm3')} mm^3, {expected:.0f})")
    r = run("estimate", "--machine", GENERIC, part, config=config)
    check("from camotics (CAMotics project part.camotics)" in r.stdout,
          f"the summary names the source ({r.stdout[-600:]!r})")

    # Each source before the project wins over it, named.
    r, doc = estimate(part, "--stock", "box:0,0,-8,100,20,0", config=config)
    check(stock_of(doc)[0] == "option", f"--stock: option ({stock_of(doc)})")
    r, doc = estimate(part, "--stock", "box:0,0,-8,100,20,0", "--stock-from", "fusion360")
    kind, origin, _ = stock_of(doc)
    check(kind == "hook-fusion360" and "fusion360 hook" in origin,
          f"--stock-from names the hook ({kind}, {origin})")
    write(os.path.join(work, "part.stock"), "box:0,0,-3,100,20,0\n")
    r, doc = estimate(part, config=config)
    check(stock_of(doc)[0] == "stock-file", f"PROGRAM.stock before the project ({stock_of(doc)})")
    write(os.path.join(work, "part.ncjoule.toml"), 'stock = "box:0,0,-5,100,20,0"\n')
    r, doc = estimate(part, config=config)
    check(stock_of(doc)[0] == "job-file", f"the job file before PROGRAM.stock ({stock_of(doc)})")
    os.remove(os.path.join(work, "part.ncjoule.toml"))
    os.remove(os.path.join(work, "part.stock"))

    # The annotated header says where its stock came from.
    r = run("annotate", "--machine", GENERIC, part, config=config)
    stock_line = next((l for l in r.stdout.splitlines() if "NCJ STOCK" in l), "")
    check("FROM=camotics" in stock_line and "BOX_MM=-20,0,-6,120,20,0" in stock_line,
          f"the header's stock line ({stock_line!r})")

    # A damaged project beside the program: a warning at its line and column, then the next
    # source (the user config's stock); the program is still estimated.
    write(os.path.join(work, "part.camotics"), '{"files": ["part.ngc"],\n "workpiece": {\n')
    r, doc = estimate(part, config=config)
    check(r.returncode == 0 and stock_of(doc)[0] == "user-config",
          f"a damaged project: the next source ({r.returncode}, {stock_of(doc)})")
    check("part.camotics:3:1: warning: CAMotics project not read: it is not JSON" in r.stderr,
          f"the damaged project is named at its line and column ({r.stderr[-300:]!r})")
    # A project whose workpiece is CAMotics' own guess: not taken, said in a note.
    project = dict(PROJECT, workpiece=dict(PROJECT["workpiece"], automatic=True))
    write(os.path.join(work, "part.camotics"), json.dumps(project))
    r, doc = estimate(part)
    check(stock_of(doc)[0] == "guess" and "automatic" in r.stderr,
          f"an automatic workpiece is not taken ({stock_of(doc)}, {r.stderr[-300:]!r})")

    # --stock-from: a name, and only with --stock.
    r = run("estimate", part, "--stock-from", "fusion360")
    check(r.returncode == 1 and "give --stock too" in r.stderr,
          f"--stock-from without --stock ({r.returncode}, {r.stderr[-200:]!r})")
    r = run("estimate", part, "--stock", "box:0,0,-8,100,20,0", "--stock-from", "Fusion 360")
    check(r.returncode == 1 and "lowercase letters" in r.stderr,
          f"--stock-from takes a name ({r.returncode}, {r.stderr[-200:]!r})")
finally:
    shutil.rmtree(work, ignore_errors=True)

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("all checks passed")
