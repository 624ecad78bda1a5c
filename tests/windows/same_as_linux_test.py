#!/usr/bin/env python3
"""The Windows build (under Wine) gives the Linux build's results, program by program.

For every program in samples/ (on the machine it is meant for, with the stock file next to it)
and every program of the corpus folders given as arguments (on the generic profile):
- `estimate --json`: the same exit status, the same document, every number (time and energy
  among them) equal to 1e-9 relative;
- `annotate` to standard output: the same bytes (standard output in binary mode on Windows, so
  LF stays LF and CR LF stays CR LF);
- `strip` of that annotated program gives the same bytes as on Linux.
Both run from the repository with the same relative paths, so the programs' own texts are all
that differ between the two runs: nothing.
Usage: same_as_linux_test.py [CORPUS_DIR...]   (environment: wine_common.py)
"""
import os
import sys
import tempfile

from wine_common import (ROOT, WORK, check, compare_numbers, finish, parse_json, run_linux,
                         run_windows)

PROGRAM_EXTENSIONS = (".ngc", ".nc", ".tap", ".gcode", ".cnc", ".txt", ".mpf", ".min", ".eia",
                      ".ptp", ".h", ".iso", ".nci")


def machine_for(name):
    # As tests/cli/samples_summary_test.py: the machine of the paper each sample comes from.
    if name.startswith("anziani-") or name == "bracket-linuxcnc":
        return "zhou2017-anziani2025.toml"
    if name.startswith("pavanaskar-"):
        return "haas-vf0-pavanaskar2014.toml"
    return "generic-3axis.toml"


def programs_in(folder):
    for base, _, names in os.walk(folder):
        for name in sorted(names):
            if name.lower().endswith(PROGRAM_EXTENSIONS):
                yield os.path.join(base, name)


compared = {"programs": 0, "numbers": 0, "time_energy": 0, "annotated_bytes": 0}


def compare(program, machine, cwd):
    rel = os.path.relpath(program, cwd)
    what = rel
    args = ["estimate", rel, "--machine", machine, "--json"]
    lin, windows = run_linux(*args, cwd=cwd), run_windows(*args, cwd=cwd)
    if not check(lin.returncode == windows.returncode,
                 "%s: estimate exits %d on Linux, %d on Windows: %s" %
                 (what, lin.returncode, windows.returncode, windows.stderr.decode(errors="replace")[-400:])):
        return
    if lin.stdout.strip():
        a, b = parse_json(lin.stdout, what + " (Linux)"), parse_json(windows.stdout, what + " (Windows)")
        if a is None or b is None:
            return
        differences, numbers, time_energy = compare_numbers(a, b, what)
        check(not differences, "%s: the JSON differs: %s" % (what, "; ".join(differences[:5])))
        check(time_energy > 0 or lin.returncode != 0, "%s: no time or energy compared" % what)
        compared["numbers"] += numbers
        compared["time_energy"] += time_energy
    compared["programs"] += 1
    args = ["annotate", rel, "--machine", machine]
    lin, windows = run_linux(*args, cwd=cwd), run_windows(*args, cwd=cwd)
    check(lin.returncode == windows.returncode,
          "%s: annotate exits %d on Linux, %d on Windows" % (what, lin.returncode, windows.returncode))
    if check(lin.stdout == windows.stdout,
             "%s: the annotated bytes differ (Linux %d bytes, Windows %d)" %
             (what, len(lin.stdout), len(windows.stdout))):
        compared["annotated_bytes"] += len(lin.stdout)
    if lin.stdout:
        with tempfile.NamedTemporaryFile(dir=WORK, suffix=".ngc", delete=False) as f:
            f.write(lin.stdout)
        try:
            sl, sw = run_linux("strip", f.name), run_windows("strip", f.name)
            check(sl.stdout == sw.stdout and sl.returncode == sw.returncode,
                  "%s: strip differs between Linux and Windows" % what)
        finally:
            os.unlink(f.name)


for program in programs_in(os.path.join(ROOT, "samples")):
    name = os.path.splitext(os.path.basename(program))[0]
    compare(program, os.path.join("samples", "machines", machine_for(name)), ROOT)
for corpus in sys.argv[1:]:
    folder = os.path.abspath(corpus)
    for program in programs_in(folder):
        compare(program, os.path.join(ROOT, "samples", "machines", "generic-3axis.toml"), folder)

print("compared %(programs)d programs: %(numbers)d JSON numbers (%(time_energy)d of time and "
      "energy) within 1e-9 relative, %(annotated_bytes)d annotated bytes identical" % compared)
check(compared["programs"] >= 30, "fewer than 30 programs compared: %d" % compared["programs"])
finish("same_as_linux")
