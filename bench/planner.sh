#!/usr/bin/env bash
# Planner throughput on the 1,000,000-block synthetic program, next to the interpreter's.
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
interp = re.search(r"interpret: (\d+) blocks, (\d+) commands in ([\d.]+) s", text)
plan = re.search(r"plan: (\d+) commands in ([\d.]+) s", text)
if not (interp and plan):
    sys.exit("planner.sh: no stage times in the log:\n" + text)
blocks, commands, t_interp = int(interp[1]), int(interp[2]), float(interp[3])
t_plan = float(plan[2])
print(f"{sys.argv[2]}: {blocks} blocks, {commands} commands")
print(f"  interpreter {t_interp:7.3f} s  {blocks / t_interp:12,.0f} blocks/s")
print(f"  planner     {t_plan:7.3f} s  {blocks / t_plan:12,.0f} blocks/s")
PY
done
