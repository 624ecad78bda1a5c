#!/usr/bin/env bash
# Time and peak memory of ncjoule against program size, each as a ratio to LinuxCNC's rs274 on
# the same file: estimate with and without removal, estimate --json and --json-compact, annotate.
#
#   bench/scale.sh [BLOCKS...]        default: 10000 100000 1000000 4000000
#
# The programs come from bench/make_scale_program.py (short random moves over 80 x 80 mm, an arc
# every 50 blocks, one 6 mm tool; stock 100 x 100 x 10 mm). Builds ncjoule if needed ($BUILD_DIR
# or build/). Needs GNU time (/usr/bin/time) for peak memory.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(10000 100000 1000000 4000000)
source "$root/bench/measure.sh"
command -v rs274 > /dev/null || { echo "rs274 not found (Debian package linuxcnc-uspace)" >&2; exit 1; }
if [ ! -f "$build/build.ninja" ] && [ ! -f "$build/Makefile" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
fi
cmake --build "$build" --target ncjoule --parallel 2 > /dev/null
ncjoule="$build/plugin/ncjoule"
machine="$root/samples/machines/generic-3axis.toml"
stock="box:0,0,-10,100,100,0"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export HOME="$work" # rs274 writes ~/.tool.mmap
tools="$work/tools.tbl"
echo "T1 P1 Z0 D6 ;6 mm flat end mill" > "$tools"

printf "%-9s %-30s %9s %9s %9s %9s\n" blocks run seconds "x rs274" MiB "x rs274"
for n in "${sizes[@]}"; do
  program="$work/scale-$n.ngc"
  python3 "$root/bench/make_scale_program.py" "$n" > "$program"
  read -r rs_s _ rs_mb < <(measure rs274 -t "$tools" -g "$program")
  printf "%-9s %-30s %9s %9s %9s %9s\n" "$n" "rs274 -g" "$rs_s" 1.00 "$rs_mb" 1.00
  while IFS='|' read -r label args; do
    # shellcheck disable=SC2086
    read -r s _ mb < <(measure "$ncjoule" $args "$program" --machine "$machine" --stock "$stock")
    printf "%-9s %-30s %9s %9s %9s %9s\n" "$n" "$label" "$s" "$(ratio "$s" "$rs_s")" "$mb" \
      "$(ratio "$mb" "$rs_mb")"
  done <<RUNS
estimate --no-removal|estimate --no-removal
estimate --no-removal --json|estimate --no-removal --json
estimate --json|estimate --json
estimate --json-compact|estimate --json-compact
annotate|annotate -o $work/out.ngc
RUNS
  rm -f "$program" "$work/out.ngc"
done
