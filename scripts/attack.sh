#!/usr/bin/env bash
# Replays hostile inputs and faults against a build of ncjoule, under a memory cap, and prints
# what happened next to what must happen: a clear refusal (its exit status and a word of its
# message) or a labelled success, never a crash, a hang, a raw control byte or a damaged file.
#
#   scripts/attack.sh [--quick] [path/to/ncjoule]
#
# --quick leaves out the slow cases (the test suite runs it so). Exit status: the number of cases
# that did not behave as they must (0: all held).
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
quick=0
if [ "${1:-}" = "--quick" ]; then quick=1; shift; fi
N="${1:-$root/build/plugin/ncjoule}"
# Absolute: the cases run in a folder of their own.
N="$(cd "$(dirname "$N")" && pwd)/$(basename "$N")"
M="$root/samples/machines/generic-3axis.toml"
P="$root/samples/programs/bracket-linuxcnc.ngc"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
limit_kib=$((2 * 1024 * 1024)) # 2 GiB of address space for each run
failures=0

# case NAME EXPECTED_EXIT WORD -- command...: runs it with a 60 s limit and the memory cap.
case_() {
  local name="$1" expect="$2" word="$3"
  shift 4
  ( ulimit -v "$limit_kib"; timeout 60 "$@" > out.txt 2> err.txt )
  local got=$?
  local verdict=ok
  [ "$got" = "$expect" ] || verdict=FAIL
  if [ -n "$word" ] && ! grep -qa -- "$word" err.txt; then verdict=FAIL; fi
  # No raw control bytes (other than newline and tab) in what is printed to the terminal.
  if LC_ALL=C grep -qaP '[\x00-\x08\x0b-\x1f\x7f]' err.txt; then verdict=FAIL; fi
  [ "$verdict" = ok ] || failures=$((failures + 1))
  printf "%-4s %-34s exit %-3s (want %-3s) %s\n" "$verdict" "$name" "$got" "$expect" \
    "$(head -c 90 err.txt | tr '\n\t' '  ')"
}

# check_ NAME COMMAND...: one more case, held when the command succeeds (a file's content, a
# file left alone, ...: what an exit code alone does not tell).
# shellcheck disable=SC2317 # called from the sourced scripts/attack.d parts
check_() {
  local name="$1"
  shift
  if "$@"; then
    printf "ok   %-34s\n" "$name"
  else
    printf "FAIL %-34s\n" "$name"
    failures=$((failures + 1))
  fi
}

printf 'G21 G90\nT1 M6\nS1000 M3\nG0 X0 Y0 Z5\nG81 X1 Y1 Z-1 R1 F100 L10000000\nM2\n' > cycle.ngc
printf 'G21 G90\nG0 X0 Y0 Z0\nG1 X1e3 F100\nM2\n' > exponent.ngc
printf 'G21 G90\nG0 X0 Y0 Z0\nG2 X1 Y0 R10000000000000 F100\nM2\n' > huge_radius.ngc
printf 'G21 G90\nG0 X0 \x1b[31m Y0 \x00 Z0\nM2\n' > escapes.ngc
printf 'G21 G90\nG0 X0 Y0 Z0\nG1 X100000000000000000000000000000 F0.001\nM2\n' > far.ngc
# Found by fuzzing: a move to X6.7e101 then a peck cycle; each long move was sampled for removal
# at the grid step (6.5 GB, 21 s).
printf 'G21 G90\nT1 M6\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X%s\nG0 Z5\nG0 X15 Y15\nG83 X15 Y15 Z-15 R2 Q4 F90\nG80\nM2\n' \
  "$(printf '6%.0s' $(seq 100))" > far_then_drill.ngc
# Found by fuzzing (UBSan): an arc ending at Y4e24 turned a column index into an int overflow.
printf 'G21 G90\nT1 M6\nS5500 M3\nG0 X50 Y40 Z5\nG1 Z-3 F200\nG3 X42 Y4033333333333333333333333 I-7 J0 F800\nG0 Z15\nM30\n' > far_arc.ngc
# Found by fuzzing: a peck cycle at R1e117 whose Q is no step there pecked forever.
printf 'G21 G90\nG0 X0 Y0 Z5\nG83 X15 Y15 Z-15 R%s. Q4 F90\nG80\nM2\n' "$(printf '1%.0s' $(seq 118))" > endless_peck.ngc
sed 's/^tool_change_s.*/tool_change_s = 1e308/' "$M" > huge_tool_change.toml
mkdir profile_dir

case_ "grid nan"                 1 "--grid"      -- "$N" estimate "$P" -m "$M" --grid nan
case_ "grid 1e300"               1 "--grid"      -- "$N" estimate "$P" -m "$M" --grid 1e300
case_ "grid 1e-6"                 1 "--grid"      -- "$N" estimate "$P" -m "$M" --grid 1e-6
case_ "grid 0.001 over budget"   2 "--memory-limit" -- "$N" estimate "$P" -m "$M" --grid 0.001 --memory-limit 4000
case_ "tool 1e-300 mm"           1 "diameter"    -- "$N" estimate "$P" -m "$M" --tool 1:flat:1e-300
case_ "canned cycle L10000000"   2 "refused"     -- "$N" estimate cycle.ngc -m "$M" --no-removal
case_ "exponent under LinuxCNC"  2 "no exponent" -- "$N" estimate exponent.ngc -m "$M" --dialect linuxcnc
case_ "exponent under Fanuc"     0 "no exponent" -- "$N" estimate exponent.ngc -m "$M" --dialect fanuc
case_ "arc of radius 1e13"       2 "out of range" -- "$N" estimate huge_radius.ngc -m "$M" --no-removal
case_ "control bytes"            0 '\x1b'        -- "$N" estimate escapes.ngc -m "$M" --no-removal
case_ "6e33 s move annotated"    2 "out of range" -- "$N" annotate far.ngc -m "$M" --no-removal
case_ "peck Q4 at R1e117"          2 "out of range" -- "$N" estimate endless_peck.ngc -m "$M" --no-removal --dialect fanuc
case_ "arc to Y4e24 with removal"  2 "out of range" -- "$N" estimate far_arc.ngc -m "$M" --stock box:0,0,-5,100,80,0 --tool 1:flat:10
case_ "X6e99 move, then removal" 2 "out of range" -- "$N" estimate far_then_drill.ngc -m "$M" --stock box:0,0,-5,20,20,0 --grid 0.5 --tool 1:flat:6
case_ "tool_change_s = 1e308"    2 "plausible"   -- "$N" estimate "$P" -m huge_tool_change.toml
case_ "directory as profile"     2 "directory"   -- "$N" estimate "$P" -m profile_dir
case_ "stock 1e300 wide"         2 "stock"       -- "$N" estimate "$P" -m "$M" --stock box:-1e300,-1e300,-1e300,1e300,1e300,1e300
case_ "json to /dev/full"        3 "standard output" -- sh -c "'$N' estimate '$P' -m '$M' --json > /dev/full"
case_ "report to a device"       0 ""            -- "$N" report "$P" -m "$M" --no-removal -o /dev/null
case_ "program named -h"         0 ""            -- sh -c "cp '$P' ./-h && '$N' estimate -m '$M' -- -h"
if [ "$quick" = 0 ]; then
  python3 -c "print('G21\n' + 'G1 X1 Q5 ' * 3000000 + '\nM2')" > long_line.ngc
  case_ "50 MB line of words"    2 "too many"    -- "$N" estimate long_line.ngc -m "$M" --no-removal
  lines=$(wc -l < err.txt)
  [ "$lines" -le 1100 ] || { echo "FAIL 50 MB line: $lines lines of diagnostics"; failures=$((failures + 1)); }
fi
# Cases by area, one file each (scripts/attack.d/*.sh): they use case_, $N, $M, $P and $quick,
# run in $work, and add to $failures.
for part in "$root"/scripts/attack.d/*.sh; do
  [ -f "$part" ] || continue
  # shellcheck source=/dev/null
  . "$part"
done
[ -c /dev/null ] || { echo "FAIL /dev/null is no longer a device"; failures=$((failures + 1)); }
echo "$failures case(s) did not hold"
exit "$failures"
