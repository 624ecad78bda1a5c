#!/usr/bin/env python3
"""Runs `rs274 -g` (LinuxCNC's own interpreter) and `ncjoule canon` on every milling program in
LinuxCNC's bundled nc_files, and compares the canonical moves: kind, end points, arc centres,
turns and the feed rate in effect, to 1e-4 in the program's units (both print 4 decimals).

Files listed in SUPPORTED must agree on >= 99.9% of rs274's moves; every other file must not
crash ncjoule and must give a diagnostic where it is not followed. The programs of rs274_comp/
(cutter radius compensation: entry and exit moves, convex and concave corners between lines and
arcs, G41.1 D diameters, G10 L1 R radii, the XZ plane) must agree on every move. Prints one line
per file, and the largest difference of a position between agreeing moves.
Environment: NCJOULE (path of the ncjoule program), NCFILES (default: LinuxCNC's install).
"""
import atexit
import os
import re
import shutil
import subprocess
import sys
import tempfile

# rs274 keeps its tool table in a file under $HOME (~/.tool.mmap) that every run truncates: runs
# in parallel (ctest -j) with other tool tables would read each other's. Each test gets its own.
RS274_HOME = tempfile.mkdtemp(prefix="rs274-home-")
atexit.register(shutil.rmtree, RS274_HOME, ignore_errors=True)
RS274_ENV = dict(os.environ, HOME=RS274_HOME)

NCFILES = os.environ.get("NCFILES", "/usr/share/linuxcnc/ncfiles")
NCJOULE = os.environ.get("NCJOULE", "ncjoule")
TOLERANCE = 1.5e-4  # both sides round to 4 decimals
REQUIRED_AGREEMENT = 0.999

# Milling programs whose every construct ncjoule follows. Keep in step with the README.
SUPPORTED = {
    "3D_Chips.ngc", "3dtest.ngc", "arcspiral.ngc", "b-index.ngc", "cds.ngc", "daisy.ngc",
    "flowsnake.ngc", "hole-circle.ngc", "plasmatest.ngc", "polar.ngc", "skeleton.ngc",
    "spiral.ngc", "tort.ngc", "threading.ngc",
    "gridprobe.ngc", "toplevel.ngc", "nestedcall.ngc", "cone.ngc",
    "comp.ngc", "comp-g1.ngc", "comp311.ngc", "comp311_2.ngc",
}
# Files whose differences are known and not an error of ncjoule's: the moves that differ, and why.
KNOWN_DIFFERENCES = {
    # After "T3 M6 G43" rs274 moves the program's Z by the new tool length offset before any Z
    # word, so that its first "G0 X50 Y50" goes to Z -offset; ncjoule keeps Z where the program
    # put it until the program's next Z word.
    "gmoccapy_2_tools_with_cutter_radius_compensation.ngc": 2,
}
# This project's own cutter compensation programs: all of them, every move.
COMP_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "rs274_comp")
COMP_PREFIX = "rs274_comp/"
# Not milling programs (lathe cycles, plasma THC macros, GUI macros): run for robustness only.
NOT_MILLING = re.compile(r"lathe|plasmac/|macros/|g7x|g76")

MOVE = re.compile(r"^\s*\d+\s+N\S*\s+(STRAIGHT_TRAVERSE|STRAIGHT_FEED|ARC_FEED|STRAIGHT_PROBE)"
                  r"\(([^)]*)\)")
FEED = re.compile(r"^\s*\d+\s+N\S*\s+SET_FEED_RATE\(([^)]*)\)")


def moves(text):
    """[(kind, numbers, feed)] from a canon listing. Moves of zero length are dropped: they take
    no time, and rs274 makes some from rounding (a rise to an R plane it is already at)."""
    out, feed, last = [], 0.0, None
    for line in text.splitlines():
        m = FEED.match(line)
        if m:
            feed = float(m.group(1))
            continue
        m = MOVE.match(line)
        if m:
            numbers = [float(x) for x in m.group(2).split(",")]
            kind = m.group(1)
            if kind != "ARC_FEED" and last is not None and all(
                    abs(a - b) <= TOLERANCE for a, b in zip(numbers, last)):
                continue
            last = numbers if kind != "ARC_FEED" else None
            out.append((kind, numbers, feed if kind != "STRAIGHT_TRAVERSE" else 0.0))
    return out


def same(a, b):
    if a[0] != b[0] or len(a[1]) != len(b[1]):
        return False
    if any(abs(x - y) > TOLERANCE for x, y in zip(a[1], b[1])):
        return False
    return abs(a[2] - b[2]) <= TOLERANCE


def main():
    files = []
    for root, _, names in os.walk(NCFILES):
        for n in names:
            if n.endswith(".ngc"):
                files.append(os.path.relpath(os.path.join(root, n), NCFILES))
    files.sort()
    if not files:
        print(f"no .ngc files under {NCFILES}: is linuxcnc-uspace installed?")
        return 1
    # rs274's machine units are inches: one tool table, in inches, for both interpreters.
    tool_table = os.path.join(tempfile.mkdtemp(), "tools.tbl")
    with open(tool_table, "w") as f:
        for t in range(1, 100):
            f.write(f"T{t} P{t} Z{0.1 + 0.01 * t:.4f} D0.2500 ;tool {t}\n")
    own = sorted(COMP_PREFIX + n for n in os.listdir(COMP_DIR) if n.endswith(".ngc"))
    failures, total_moves, total_agree, largest = [], 0, 0, 0.0
    for rel in files + own:
        mine = rel.startswith(COMP_PREFIX)
        path = (os.path.join(COMP_DIR, rel[len(COMP_PREFIX):]) if mine
                else os.path.join(NCFILES, rel))
        ref = subprocess.run(["rs274", "-g", "-t", tool_table, path], capture_output=True, text=True,
                             stdin=subprocess.DEVNULL, timeout=120, cwd=os.path.dirname(path),
                             env=RS274_ENV)
        ours = subprocess.run([NCJOULE, "canon", "--tool-table", tool_table, "--tool-units", "inch",
                               path], capture_output=True, text=True,
                              stdin=subprocess.DEVNULL, timeout=120)
        if ours.returncode < 0 or ours.returncode >= 4:
            failures.append(rel)
            print(f"CRASH  {rel}: ncjoule exit {ours.returncode}: {ours.stderr.strip()[:200]}")
            continue
        ref_moves, our_moves = moves(ref.stdout), moves(ours.stdout)
        agree = sum(1 for a, b in zip(ref_moves, our_moves) if same(a, b))
        for a, b in zip(ref_moves, our_moves):
            if same(a, b):
                largest = max([largest] + [abs(x - y) for x, y in zip(a[1], b[1])])
        first_bad = next((i for i, (a, b) in enumerate(zip(ref_moves, our_moves))
                          if not same(a, b)), None)
        n = len(ref_moves)
        ratio = agree / n if n else 1.0
        milling = not NOT_MILLING.search(rel)
        status = "ok"
        if rel in SUPPORTED or mine:
            total_moves += n
            total_agree += agree
            required = 1.0 if mine else REQUIRED_AGREEMENT
            if ratio < required or (n == 0 and our_moves) or (mine and len(our_moves) != n):
                status = "FAIL"
                failures.append(rel)
        else:
            status = "unsupported" if milling else "not-milling"
            if rel in KNOWN_DIFFERENCES and n - agree <= KNOWN_DIFFERENCES[rel]:
                status = "known"
            elif ratio < 1.0 and not ours.stderr.strip():
                status = "FAIL (no diagnostic)"
                failures.append(rel)
        detail = ""
        if first_bad is not None:
            detail = (f"  first difference at move {first_bad + 1}: "
                      f"rs274 {ref_moves[first_bad]} / ncjoule {our_moves[first_bad]}")
        elif len(our_moves) < n:
            detail = f"  ncjoule stopped after {len(our_moves)} moves"
        print(f"{status:12s} {rel}: {agree}/{n} moves agree ({100 * ratio:.2f}%), "
              f"ncjoule made {len(our_moves)}{detail}")
    pct = 100 * total_agree / total_moves if total_moves else 100
    print(f"supported files: {total_agree}/{total_moves} moves agree ({pct:.3f}%), largest "
          f"difference of agreeing positions {largest:.2g}")
    print(f"{len(files) + len(own) - len(failures)} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
