#!/usr/bin/env python3
"""Every program FreeCAD's posts wrote (samples/freecad, made by scripts/make_freecad_samples.py)
estimates end to end: `ncjoule estimate --json` exits 0, every block that has code has a finite
time >= 0, unknown codes show up only as warnings, and removal runs where the post kept the tool
changes. Also a small 4th-axis program: its rotary moves are timed, not refused."""
import glob
import json
import math
import os
import subprocess
import sys
import tempfile

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
MACHINE = os.path.join(ROOT, "samples/machines/generic-3axis.toml")
# The controller family of each post, as `--dialect` (the sample machine profile says linuxcnc).
# Philips controls are ISO controls of the Fanuc family: their "%PM" program start is a line
# LinuxCNC refuses ("Bad character '%' used").
DIALECT = {"fanuc": "fanuc", "grbl": "grbl", "jtech": "grbl", "marlin": "reprap",
           "rrf": "reprap", "smoothie": "reprap", "mach3_mach4": "mach3", "uccnc": "mach3",
           "philips": "fanuc"}
# Posts whose output does not say which tool cuts, so removal cannot run:
NO_REMOVAL = {
    "grbl": "grbl has no tool changer: the post comments M6 out",
    "jtech": "a laser post: no tool change at all",
    "marlin": "the post comments M6 out",
    "rrf": "the post writes T1 without M6",
    "fablin": "the post drops the tool controller labels and tool changes",
    "nccad": "the post writes the tool change as text (M01 Insert tool 1)",
    "philips": "the post writes M66 for the tool change",
    "centroid": "the tool controller label is a ';' comment, which tool comments do not read",
    "comparams": "the post writes 'M6T2' glued, which tool comments do not read",
}
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def estimate(path, *extra):
    r = subprocess.run([NCJOULE, "estimate", path, "--machine", MACHINE, "--json", *extra],
                       capture_output=True, text=True)
    doc = json.loads(r.stdout) if r.returncode == 0 and r.stdout else None
    return r, doc


def line_count(path):
    with open(path, errors="replace") as f:
        return sum(1 for _ in f)


samples = sorted(glob.glob(os.path.join(ROOT, "samples/freecad/*.nc")))
check(len(samples) >= 16, f"{len(samples)} FreeCAD samples")
for path in samples:
    post = os.path.basename(path)[:-3]
    args = ["--dialect", DIALECT.get(post, "linuxcnc")]
    with open(path[:-3] + ".stock") as f:
        args += ["--stock", f.read().strip()]
    if post in NO_REMOVAL:
        args.append("--no-removal")
    r, doc = estimate(path, *args)
    check(r.returncode == 0 and doc is not None,
          f"{post}: estimate exits 0 (got {r.returncode}: {r.stderr.strip()[:200]!r})")
    if doc is None:
        continue
    blocks = doc["blocks"]
    check(all(math.isfinite(b["time_s"]) and b["time_s"] >= 0 for b in blocks),
          f"{post}: every block's time is finite and >= 0")
    timed = {b["line"] for b in blocks}
    moves = [b for b in blocks if b["kind"] in ("rapid", "feed", "arc")]
    check(len(moves) > 50, f"{post}: {len(moves)} motion blocks")
    check(all(1 <= n <= line_count(path) for n in timed), f"{post}: blocks name lines of the file")
    check(doc["time_s"] > 30, f"{post}: program time {doc['time_s']:.1f} s")
    check(all(w.get("severity", "warning") != "error" for w in doc["warnings"]),
          f"{post}: only warnings, no errors")
    if post not in NO_REMOVAL:
        # Facing 0.5 mm over 60 x 40, the pocket and the profile groove all remove material.
        check(doc["removed_mm3"] > 1200, f"{post}: removes {doc['removed_mm3']:.0f} mm^3")

# A 4th-axis program: A moves are timed.
with tempfile.TemporaryDirectory() as tmp:
    four = os.path.join(tmp, "rotary.ngc")
    with open(four, "w") as f:
        f.write("(TC: 6mm Endmill)\nG21 G90\nM6 T1\nM3 S6000\nG0 X0 Y0 Z5 A0\nG1 Z-1 F300\n"
                "G1 X20 A90 F300\nG0 A360\nM30\n")
    r, doc = estimate(four, "--no-removal")
    check(r.returncode == 0 and doc is not None, f"4th axis: estimate exits 0 ({r.stderr[:200]!r})")
    if doc:
        by_line = {b["line"]: b for b in doc["blocks"]}
        check(7 in by_line and by_line[7]["time_s"] > 0, "4th axis: the X+A feed is timed")
        check(8 in by_line and by_line[8]["time_s"] > 0, "4th axis: the A-only rapid is timed")

print(f"{len(failures)} failed")
sys.exit(1 if failures else 0)
