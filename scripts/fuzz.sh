#!/usr/bin/env bash
# Fuzzes ncjoule with libFuzzer (clang, ASan, UBSan): the G-code lexer, the interpreter, the whole
# pipeline (estimate with removal, annotate, strip), machine profiles (TOML), the annotator in
# every dialect (annotation: strip gives the program back, the annotated program runs block for
# block as the original, no line outgrows the dialect's limit), and the readers of what users
# measure and write besides programs: power logs (power_log), calibration tables fitted with
# Ceres (calibration_tables), job files (job_file) and MTConnect controller logs
# (controller_log).
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]     default: 60 s for each of lexer, interpreter,
#                                             pipeline, profile, annotation, power_log,
#                                             calibration_tables, job_file, controller_log
#   RUNS=1000000 scripts/fuzz.sh 0 pipeline   a number of executions instead of a time
#
# Builds in fuzz-build/ (or $FUZZ_BUILD_DIR; CMake, NCJOULE_FUZZ=ON, clang), seeds each target's
# corpus from LinuxCNC's bundled nc_files and samples/ (programs, or profiles for the profile
# target; the readers' targets from their committed seeds, tests/fuzz/seeds/TARGET, which the
# test suite replays through each target built without libFuzzer), and runs it. Crashes, hangs and sanitizer reports land in fuzz-build/artifacts/ and
# make the script fail; the last lines of each run (executions, speed) are printed.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] ||
  targets=(lexer interpreter pipeline profile annotation power_log calibration_tables job_file
           controller_log)
out="${FUZZ_BUILD_DIR:-$root/fuzz-build}" # FUZZ_BUILD_DIR: a build folder of one's own
ncfiles="${LINUXCNC_NCFILES:-/usr/share/linuxcnc/ncfiles}"
mkdir -p "$out/artifacts"

cmake -S "$root" -B "$out" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER="${CC_FUZZ:-clang}" -DCMAKE_CXX_COMPILER="${CXX_FUZZ:-clang++}" \
  -DNCJOULE_FUZZ=ON -DNCJOULE_BUILD_TESTS=OFF > "$out/configure.log"
build=("${targets[@]/#/fuzz_}")
# The pipeline's and the annotator's seeds include annotated programs (strip's matching, from real
# markers): the CLI writes them.
[[ " ${targets[*]} " == *" pipeline "* || " ${targets[*]} " == *" annotation "* ]] && build+=(ncjoule)
cmake --build "$out" --parallel "$(nproc)" --target "${build[@]}"

for target in "${targets[@]}"; do
  corpus="$out/corpus-$target"
  seeds="$out/seeds-$target"
  mkdir -p "$corpus" "$seeds"
  if [ -d "$root/tests/fuzz/seeds/$target" ]; then
    cp -f "$root/tests/fuzz/seeds/$target"/* "$seeds/"
  elif [ "$target" = profile ]; then
    cp -f "$root"/samples/machines/*.toml "$seeds/"
  else
    # Real programs, small enough to mutate quickly.
    if [ -d "$ncfiles" ]; then
      find "$ncfiles" -maxdepth 1 -type f \( -name '*.ngc' -o -name '*.nc' \) -size -16k \
        -exec cp -f {} "$seeds/" \;
    fi
    find "$root/samples" -type f \( -name '*.ngc' -o -name '*.nc' \) -size -16k \
      -exec cp -f {} "$seeds/" \; 2>/dev/null || true
  fi
  if [ "$target" = annotation ]; then
    # What each dialect's syntax makes tricky: Sinumerik calls, expressions and strings, ';' and
    # '*' block ends, lines at grbl's and Marlin's limits; and annotated programs, with a header
    # (sealed with the file's key) and without (sealed with their lines).
    printf '%%_N_PART_MPF\n;$PATH=/_N_WKS_DIR/_N_PART_WPD\n;PART\nG0 X0 Y0 Z5\nCYCLE81(10,0,2,-5)\nG1 X1 Y=COS (0) F100\nG0 X1 MSG("a;b(c)")\nG1 X5 ;n\nM30\n' \
      > "$seeds/sinumerik.mpf"
    printf '%%PART G71 *\nN10 G00 X+0 Y+0 Z+5 *\nN20 G01 X+10 F100 * ;c\nN30 %%PART G71 *\n' > "$seeds/tnc.h"
    printf '%%\nO1234\n(TITLE)\nG21 G90\nG00 X1. ;EOB\nG01 X2. F100. (C)\nM30\n%%\n' > "$seeds/fanuc.nc"
    printf 'G21\nG0 X0 Y0 Z1 ; m\nG1 X%s F600\nG4 P5\n' "$(printf '1%.0s' $(seq 80))" > "$seeds/marlin.gcode"
    printf 'G21\nG0 X0 Y0 Z1\nG1 X1 F100 (%s)\nG1 X2\n' "$(printf 'c%.0s' $(seq 104))" > "$seeds/grbl-long.nc"
    tiny="$seeds/tiny.ngc"
    printf 'G21 G90\nG0 X0 Y0 Z1\nG1 Z-1 F100\nG1 X5\nM2\n' > "$tiny"
    cli=("$out/plugin/ncjoule" annotate --no-removal -m "$root/samples/machines/generic-3axis.toml")
    "${cli[@]}" --fields T -o "$seeds/annotated-header.ngc" -- "$tiny" 2>/dev/null
    "${cli[@]}" --no-header --fields T -o "$seeds/annotated-inline.ngc" -- "$tiny" 2>/dev/null
    "${cli[@]}" --no-header --fields T --dialect siemens -o "$seeds/annotated-siemens.mpf" \
      -- "$seeds/sinumerik.mpf" 2>/dev/null
  fi
  if [ "$target" = pipeline ]; then
    # Annotated programs, short enough that their markers fit the target's input length: inline
    # comments only, a summary header first, and the ';' comments of a Heidenhain program.
    tiny="$seeds/tiny.ngc"
    printf 'G21 G90\nG0 X0 Y0 Z1\nG1 Z-1 F100\nG1 X5\nM2\n' > "$tiny"
    cli=("$out/plugin/ncjoule" annotate --no-removal -m "$root/samples/machines/generic-3axis.toml")
    "${cli[@]}" --no-header --fields T -o "$seeds/annotated-inline.ngc" -- "$tiny" 2>/dev/null
    "${cli[@]}" --fields T -o "$seeds/annotated-header.ngc" -- "$tiny" 2>/dev/null
    "${cli[@]}" --no-header --fields T,E --dialect heidenhain -o "$seeds/annotated-semicolon.h" \
      -- "$tiny" 2>/dev/null
  fi
  # Short inputs keep the targets fast: the pipeline interprets twice, plans, removes,
  # integrates power, annotates and strips every input, so it reads the shortest (128 bytes: a
  # dozen blocks, and loops make long programs of them). It gets a longer timeout: a short loop
  # can be a legitimately long program. Its runs touch thousands of counters, and the entropic
  # scheduler's bookkeeping per counter was a quarter of each run (perf): the plain scheduler
  # runs it a quarter faster. On one core (the other busy), inputs a second over 1M runs:
  # lexer 1,190, interpreter 1,550, profiles 27,800, pipeline 1,450 (1M runs in 12 minutes).
  # annotation annotates and runs every input in each of the 8 dialects: 85 a second (300 s,
  # 25,663 runs, both cores shared).
  timeout=10
  extra=()
  case "$target" in
    lexer) max_len=4096 ;;
    profile | job_file) max_len=2048 ;;
    power_log | calibration_tables) max_len=1024 ;;
    controller_log) max_len=4096 ;;
    interpreter) max_len=1024 ;;
    # Every input annotated in each of the 8 dialects: long enough for lines past grbl's 125 bytes
    # and the default 250.
    annotation) max_len=512 timeout=60 extra=(-entropic=0) ;;
    *) max_len=128 timeout=60 extra=(-entropic=0) ;;
  esac
  limit=(-max_total_time="$seconds")
  [ -n "${RUNS:-}" ] && limit=(-runs="$RUNS")
  if [ -n "${RUNS:-}" ]; then what="$RUNS runs"; else what="${seconds} s"; fi
  echo "== fuzz_$target ($what; corpus: $corpus)"
  status=0
  stamp="$out/.fuzz_$target.start"
  touch "$stamp"
  # Without the stack of every allocation (ASan records one per malloc, a tenth of the pipeline's
  # time): a finding is replayed below with them, for the report of where the memory came from.
  ASAN_OPTIONS="${ASAN_OPTIONS:-malloc_context_size=0}" \
    "$out/fuzz_$target" "$corpus" "$seeds" "${limit[@]}" "${extra[@]}" -max_len="$max_len" \
    -timeout="$timeout" -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$out/artifacts/$target-" > "$out/fuzz_$target.log" 2>&1 || status=$?
  grep -E '^(#[0-9]+[[:space:]]+(DONE|INITED)|SUMMARY|stat::number_of_executed_units|stat::average_exec_per_sec|stat::peak_rss_mb|artifact)' \
    "$out/fuzz_$target.log" || true
  if [ "$status" -ne 0 ] || grep -qE 'ERROR: (libFuzzer|AddressSanitizer|UndefinedBehaviorSanitizer)|runtime error|Test unit written' \
       "$out/fuzz_$target.log"; then
    find "$out/artifacts" -maxdepth 1 -type f -name "$target-*" ! -name "*.replay.log" -newer "$stamp" -print0 |
      while IFS= read -r -d '' artifact; do
        "$out/fuzz_$target" -timeout="$timeout" "$artifact" > "$artifact.replay.log" 2>&1 || true
        echo "replayed with full stacks: $artifact.replay.log" >&2
      done
    echo "fuzz_$target found a problem: see $out/fuzz_$target.log and $out/artifacts/" >&2
    exit 1
  fi
done
