#!/usr/bin/env bash
# Times the G-code interpreter against LinuxCNC's rs274 on one synthetic program.
#
#   bench/interpreter.sh [BLOCKS] [RUNS]      defaults: 1000000 blocks, best of 3 runs
#
# Builds `ncjoule` if needed (build directory: $BUILD_DIR or build/), writes the program once
# into a temporary directory, then times, on that same file:
#   ncjoule canon FILE > /dev/null        interpret and print every canonical command
#   ncjoule canon --parse-only FILE       interpret only
#   rs274 -t TOOLS -g FILE > /dev/null            LinuxCNC's interpreter printing the same stream
# and prints blocks per second for each and how many times faster ncjoule is than rs274.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
blocks="${1:-1000000}"
runs="${2:-3}"
build="${BUILD_DIR:-$root/build}"

if [ ! -f "$build/build.ninja" ] && [ ! -f "$build/Makefile" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DNCJOULE_STAGES=gcode \
    -DNCJOULE_COMMANDS=canon > /dev/null
fi
if ! build_log=$(cmake --build "$build" --target ncjoule --parallel 2 2>&1); then
  echo "$build_log" | tail -20 >&2
  echo "building ncjoule failed" >&2
  exit 1
fi
ncjoule="$build/plugin/ncjoule"
command -v rs274 > /dev/null || { echo "rs274 not found (Debian package linuxcnc-uspace)" >&2; exit 1; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
program="$work/synthetic.ngc"
python3 "$root/bench/make_synthetic.py" "$blocks" > "$program"
# rs274's built-in tool table has tools 1-3 only; the program changes to tool 4.
tools="$work/tools.tbl"
for t in 1 2 3 4 5 6 7 8; do echo "T$t P$t Z0 D6 ;end mill $t"; done > "$tools"
lines=$(wc -l < "$program")
echo "program: $lines lines ($(du -h "$program" | cut -f1)), best of $runs runs"

# Best wall-clock time of `runs` runs of a command, in seconds.
best_time() {
  local best="" t
  for _ in $(seq "$runs"); do
    local start end
    start=$(date +%s.%N)
    "$@" > /dev/null 2>&1 || true
    end=$(date +%s.%N)
    t=$(echo "$end - $start" | bc -l)
    if [ -z "$best" ] || [ "$(echo "$t < $best" | bc -l)" = 1 ]; then best=$t; fi
  done
  echo "$best"
}

t_canon=$(best_time "$ncjoule" canon -t "$tools" "$program")
t_parse=$(best_time "$ncjoule" canon --parse-only -t "$tools" "$program")
t_rs274=$(best_time rs274 -t "$tools" -g "$program")

report() { printf '%-34s %8.3f s %14.0f blocks/s\n' "$1" "$2" "$(echo "$lines / $2" | bc -l)"; }
report "ncjoule canon" "$t_canon"
report "ncjoule canon --parse-only" "$t_parse"
report "rs274 -g" "$t_rs274"
printf 'rs274 / ncjoule canon:               %6.1fx\n' "$(echo "$t_rs274 / $t_canon" | bc -l)"
printf 'rs274 / ncjoule canon --parse-only:  %6.1fx\n' "$(echo "$t_rs274 / $t_parse" | bc -l)"
