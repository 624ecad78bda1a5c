#!/usr/bin/env bash
# Removed volume against closed-form volumes at grid spacings from a 120th to a tenth of the tool
# diameter: the table behind docs/removal.md. Runs the removal tests' "volume error against the
# grid spacing" case and prints its measurements.
#
#   bench/grid_accuracy.sh
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"
if [ ! -f "$build/build.ninja" ] && [ ! -f "$build/Makefile" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
fi
cmake --build "$build" --target test_removal --parallel 2 > /dev/null
printf "%-34s %-6s %9s %12s\n" case grid mm "volume error"
NCJOULE_TEST_VERBOSE=1 "$build/tests/removal/test_removal" \
  -tc="volume error against the grid spacing*" 2>&1 |
  awk -F' [|] |: ' '/^grid accuracy/ { printf "%-34s %-6s %9.3f %11.3f%%\n", $2, $3, $4, 100 * $5 }'
