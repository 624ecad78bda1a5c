#!/usr/bin/env python3
"""Removal against CAMotics' own simulator, camsim, on CAMotics' example projects at camsim's
grid (issue 43's row: ncjoule >= 10x faster on every one).

    bench/camsim.py NCJOULE CAMOTICS_REPO [--camsim PATH] [--runs N]

CAMOTICS_REPO: a clone of CauldronDevelopmentLLC/CAMotics (a bare one too). camsim is taken from
--camsim, else from PATH. For every example project whose workpiece its author set by hand, both
tools run on the same program, stock and tools at the resolution the project gives camsim (its
"resolution", else CAMotics' rule for its resolution mode: the cube root of the workpiece's volume
over 250,000 for medium, 5,000,000 for high): camsim writes the cut workpiece's surface (an STL),
ncjoule's `estimate --json --grid R` reads, plans, removes and prices the program. Both are timed
from start to end (wall clock, the best of N runs), on every core each uses. The volume camsim
leaves (its STL's enclosed volume) is printed beside ncjoule's stock less what it removed: at
the same grid the two should agree to a few percent (camsim's surface is a contour of a sampled
field, ncjoule's columns are exact in Z).

Projects whose workpiece is automatic are listed and skipped: camsim sizes their stock from the
tool path with a margin of its own, so the two would not cut the same stock.
"""
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "corpus"))
sys.path.insert(0, HERE)
import camotics_layout  # noqa: E402
from camotics_projects import stock_option, tool_options  # noqa: E402

DIVISORS = {"low": 100000, "medium": 250000, "high": 5000000, "very_high": 10000000,
            "very-high": 10000000}


def resolution_of(project):
    """The grid camsim uses for a project (mm), as CAMotics' Project::getResolution: the
    project's "resolution" in manual mode, else from its mode and the workpiece's volume."""
    mode = project.get("resolution-mode", "medium")
    if mode == "manual":
        return float(project.get("resolution", 1))
    b = project["workpiece"]["bounds"]
    volume = math.prod(hi - lo for lo, hi in zip(b["min"], b["max"]))
    return (volume / DIVISORS.get(mode, DIVISORS["medium"])) ** (1.0 / 3.0)


def stl_volume(path):
    """Enclosed volume of an STL (binary or ASCII), by the divergence theorem (mm^3)."""
    with open(path, "rb") as f:
        data = f.read()
    triangles = []
    if len(data) >= 84 and 84 + 50 * struct.unpack_from("<I", data, 80)[0] == len(data):
        count = struct.unpack_from("<I", data, 80)[0]
        for i in range(count):
            v = struct.unpack_from("<9f", data, 84 + 50 * i + 12)
            triangles.append((v[0:3], v[3:6], v[6:9]))
    else:
        points = [tuple(map(float, line.split()[1:4])) for line in data.decode().splitlines()
                  if line.strip().startswith("vertex")]
        triangles = [tuple(points[i:i + 3]) for i in range(0, len(points) - 2, 3)]
    total = 0.0
    for a, b, c in triangles:
        total += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                  a[2] * (b[0] * c[1] - b[1] * c[0]))
    return abs(total) / 6.0


def best_time(command, runs, env=None):
    """(best wall seconds, last CompletedProcess) of `runs` runs."""
    best, last = float("inf"), None
    for _ in range(runs):
        start = time.perf_counter()
        last = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
        best = min(best, time.perf_counter() - start)
    return best, last


def main():
    args = sys.argv[1:]
    camsim = shutil.which("camsim")
    runs = 3
    if "--camsim" in args:
        i = args.index("--camsim")
        camsim = args[i + 1]
        del args[i:i + 2]
    if "--runs" in args:
        i = args.index("--runs")
        runs = int(args[i + 1])
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    if not camsim:
        sys.exit("camsim not found: give --camsim PATH (CAMotics is not packaged in Debian)")
    ncjoule, repo = args
    env = dict(os.environ, NCJOULE_CONFIG=os.devnull + ".toml")
    machine = os.path.join(HERE, "..", "samples", "machines", "generic-3axis.toml")
    worst = float("inf")
    compared = 0
    with tempfile.TemporaryDirectory(prefix="ncjoule-camsim-") as out:
        laid = camotics_layout.lay_out(repo, out)
        print("| project | lines | grid mm | camsim s | ncjoule s | x faster | camsim left mm^3 "
              "| ncjoule left mm^3 | left diff |")
        print("|---|---|---|---|---|---|---|---|---|")
        automatic = []
        for folder, project_path, is_automatic, programs in laid:
            name = os.path.splitext(os.path.basename(project_path))[0]
            if is_automatic:
                automatic.append(name)
                continue
            project = json.load(open(project_path))
            grid = resolution_of(project)
            stl = os.path.join(out, name + ".stl")
            camsim_s, c = best_time([camsim, "--resolution", "%.9g" % grid, project_path, stl],
                                    runs)
            if c.returncode != 0 or not os.path.exists(stl):
                print("| %s | | %.4f | failed: %s | | | | | |" % (
                    name, grid, c.stderr.decode(errors="replace").strip().splitlines()[-1:]))
                continue
            camsim_left = stl_volume(stl)
            ncjoule_s, left, lines = 0.0, float("nan"), 0
            failed = None
            for program in programs:
                lines += sum(1 for _ in open(program, "rb"))
                s, r = best_time([ncjoule, "estimate", "--json", program, "--machine", machine,
                                  "--stock", stock_option(project), "--grid", "%.9g" % grid] +
                                 tool_options(project), runs, env)
                if r.returncode != 0 or not r.stdout:
                    failed = r.stderr.decode(errors="replace").strip().splitlines()[-1:]
                    break
                doc = json.loads(r.stdout)
                ncjoule_s += s
                left = doc["removal"]["stock_volume_mm3"] - doc["removed_mm3"]
            if failed:
                print("| %s | %d | %.4f | %.2f | failed: %s | | | | |" % (name, lines, grid,
                                                                          camsim_s, failed))
                continue
            compared += 1
            faster = camsim_s / ncjoule_s
            worst = min(worst, faster)
            # Several programs cut one stock in camsim, each its own in ncjoule (one estimate a
            # program): their volumes are not compared.
            volumes = ("%.0f | %.0f | %+.2f%%" % (
                camsim_left, left, (left / camsim_left - 1) * 100 if camsim_left > 0 else
                float("nan")) if len(programs) == 1 else
                "%.0f | - | - (%d programs)" % (camsim_left, len(programs)))
            print("| %s | %d | %.4f | %.2f | %.2f | %.1fx | %s |" % (
                name, lines, grid, camsim_s, ncjoule_s, faster, volumes))
        print()
        print("automatic workpiece (not compared): " + (", ".join(automatic) or "none"))
        print("removal vs camsim at camsim's grid: %d projects, worst %.1fx faster (>= 10x: %s)" %
              (compared, worst, "yes" if compared and worst >= 10 else "no"))


if __name__ == "__main__":
    main()
