#!/usr/bin/env bash
# Fuzzes the G-code lexer and interpreter with libFuzzer (clang, ASan, UBSan).
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]     default: 60 s for each of interpreter and lexer
#
# Builds in fuzz-build/ with clang++ directly (the library has no dependencies of its own, so
# the normal CMake build and its packages are not needed), seeds each target's corpus from
# LinuxCNC's bundled nc_files and samples/programs, and runs each target for SECONDS. Crashes,
# hangs and sanitizer reports land in fuzz-build/artifacts/ and make the script fail.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(interpreter lexer)
out="$root/fuzz-build"
ncfiles="${LINUXCNC_NCFILES:-/usr/share/linuxcnc/ncfiles}"
cxx="${CXX_FUZZ:-clang++}"
mkdir -p "$out/obj" "$out/artifacts"

# Library objects are instrumented for coverage but not linked with libFuzzer's main.
flags=(-std=c++20 -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined
       -fno-sanitize-recover=undefined -I"$root/core/include" -I"$root/core/gcode")
objects=()
for src in "$root"/core/gcode/*.cpp; do
  obj="$out/obj/$(basename "${src%.cpp}").o"
  if [ ! -f "$obj" ] || [ "$src" -nt "$obj" ] || \
     [ -n "$(find "$root/core/gcode" "$root/core/include/ncjoule/gcode.hpp" -newer "$obj" \
              -name '*.hpp' 2>/dev/null)" ]; then
    "$cxx" "${flags[@]}" -fsanitize=fuzzer-no-link -c "$src" -o "$obj" &
    # Two compilers at a time at most.
    [ "$(jobs -r | wc -l)" -lt 2 ] || wait -n
  fi
  objects+=("$obj")
done
wait

for target in "${targets[@]}"; do
  binary="$out/fuzz_$target"
  "$cxx" "${flags[@]}" -fsanitize=fuzzer "$root/tests/fuzz/fuzz_$target.cpp" "${objects[@]}" \
    -o "$binary"
  corpus="$out/corpus-$target"
  seeds="$out/seeds"
  mkdir -p "$corpus" "$seeds"
  # Seeds: real programs, small enough to mutate quickly.
  if [ -d "$ncfiles" ]; then
    find "$ncfiles" -maxdepth 1 -type f \( -name '*.ngc' -o -name '*.nc' \) -size -64k \
      -exec cp -f {} "$seeds/" \;
  fi
  find "$root/samples/programs" -type f -size -64k -exec cp -f {} "$seeds/" \; 2>/dev/null || true
  echo "== fuzz_$target for ${seconds}s (corpus: $corpus)"
  "$binary" "$corpus" "$seeds" -max_total_time="$seconds" -max_len=16384 -timeout=10 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$out/artifacts/$target-" \
    2>&1 | tee "$out/fuzz_$target.log" | grep -E '^(#[0-9]+ +(DONE|INITED)|==|SUMMARY|stat::|artifact)' || true
  if grep -qE 'ERROR: (libFuzzer|AddressSanitizer|UndefinedBehaviorSanitizer)|runtime error|Test unit written' \
       "$out/fuzz_$target.log"; then
    echo "fuzz_$target found a problem: see $out/fuzz_$target.log and $out/artifacts/" >&2
    exit 1
  fi
done
