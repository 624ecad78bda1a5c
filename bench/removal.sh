#!/usr/bin/env bash
# Builds and runs the removal benchmark (dexel vs voxel on the same program and grid).
# Usage: bench/removal.sh [grid_mm=0.25] [stock_height_mm=20]   (build directory: $BUILD_DIR or
# build-bench). Prints steps/s and columns/s for both engines and the dexel / voxel ratio.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build-bench}"
if ! grep -q 'add_subdirectory(bench)' "$root/CMakeLists.txt"; then
  echo "bench/ is not part of the build: add add_subdirectory(bench) to CMakeLists.txt" >&2
  exit 1
fi
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$build" --target bench_removal
"$build/bench/bench_removal" "$@"
