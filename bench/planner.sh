#!/usr/bin/env bash
# Planner throughput on the 1,000,000-block synthetic program, next to the interpreter's, then
# on 10,000 and 100,000 zero-length moves in an o-word loop (five lines): the two rates must be
# about the same (the planner is linear in the moves; they once made it quadratic).
#
#   bench/planner.sh [BUILD_DIR] [BLOCKS]
#
# Runs `ncjoule -v estimate` (interpret + plan, end points only) and reads the stage times it
# logs. BUILD_DIR defaults to build; the ncjoule target must be built there.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
build="${1:-$root/build}"
blocks="${2:-1000000}"
ncjoule="$build/plugin/ncjoule"
[ -x "$ncjoule" ] || { echo "planner.sh: $ncjoule not built" >&2; exit 1; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
program="$work/synthetic.ngc"
python3 "$here/make_synthetic.py" "$blocks" > "$program"

for machine in generic-3axis haas-vf0-pavanaskar2014; do
  log="$work/$machine.log"
  # Stage times are log lines; read them from both streams, wherever the logger writes.
  "$ncjoule" -v estimate "$program" --no-removal --machine "$root/samples/machines/$machine.toml" \
    > "$log" 2>&1
  python3 - "$log" "$machine" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
# The estimate interprets the program twice: alone (scan), then streamed into the planner
# (stream); the planner's time is the difference.
interp = re.search(r"scan: (\d+) blocks, (\d+) commands in ([\d.]+) s", text)
stream = re.search(r"stream: (\d+) commands in ([\d.]+) s", text)
if not (interp and stream):
    sys.exit("planner.sh: no stage times in the log:\n" + text)
blocks, commands, t_interp = int(interp[1]), int(interp[2]), float(interp[3])
t_plan = max(float(stream[2]) - t_interp, 1e-6)
print(f"{sys.argv[2]}: {blocks} blocks, {commands} commands")
print(f"  interpreter {t_interp:7.3f} s  {blocks / t_interp:12,.0f} blocks/s")
print(f"  planner     {t_plan:7.3f} s  {blocks / t_plan:12,.0f} blocks/s")
PY
done

# Zero-length moves: "G1 X5" at X5 in an o-word loop, behind a move that waits for the next one.
for count in 10000 100000; do
  program="$work/zero_length_$count.ngc"
  printf 'G1 X5 F100\no100 repeat [%d]\nG1 X5\no100 endrepeat\nM2\n' "$count" > "$program"
  log="$work/zero_length_$count.log"
  "$ncjoule" -v estimate "$program" --no-removal \
    --machine "$root/samples/machines/generic-3axis.toml" > "$log" 2>&1
  python3 - "$log" "$count" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
interp = re.search(r"scan: (\d+) blocks, (\d+) commands in ([\d.]+) s", text)
stream = re.search(r"stream: (\d+) commands in ([\d.]+) s", text)
if not (interp and stream):
    sys.exit("planner.sh: no stage times in the log:\n" + text)
commands, t_interp = int(stream[1]), float(interp[3])
t_plan = max(float(stream[2]) - t_interp, 1e-6)
print(f"zero-length moves, loop of {int(sys.argv[2]):,}: {commands} commands")
print(f"  interpreter {t_interp:7.3f} s  {commands / max(t_interp, 1e-6):12,.0f} commands/s")
print(f"  planner     {t_plan:7.3f} s  {commands / t_plan:12,.0f} commands/s")
PY
done
