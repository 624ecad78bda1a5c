#!/usr/bin/env bash
# ncjoule's block times next to LinuxCNC 2.9's real trajectory planner.
#
#   bench/linuxcnc_time.sh [--build DIR] [--jobs N] [--markdown] [--lines PROGRAM] [PROGRAM[@LINES]...]
#
# Prints, per program: its lines, LinuxCNC's run time, ncjoule's, the error of the total, and the
# 95th percentile of the per-line error over lines longer than 0.1 s in LinuxCNC. Programs default
# to bench/linuxcnc_programs.txt; PROGRAM@LINES times the first LINES lines with M2 appended.
# 'ncfiles/NAME' is a program of LinuxCNC's nc_files, 'corpus/NAME' one in $NCJOULE_CORPUS.
#
# LinuxCNC runs headless through the lcnc-time tool (set LCNC_TIME to its path, or put it on PATH;
# it needs root and Debian's linuxcnc-uspace) in real time, two programs side by side by default;
# its results are cached in BUILD/linuxcnc-time, so a second run takes seconds. Run it on an idle
# machine: LinuxCNC skips blends when its task falls behind the motion. ncjoule runs on
# bench/machines/linuxcnc-sim.toml, the same machine: trivkins XYZ, 1000 mm/s^2, 100 mm/s per axis.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
exec python3 "$here/linuxcnc_time.py" "$@"
