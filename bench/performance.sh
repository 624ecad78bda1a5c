#!/usr/bin/env bash
# Every row of ncjoule's speed and memory goals in one run, as ratios to LinuxCNC's rs274 measured
# side by side (docs/performance.md shows its output and says how to read it).
#
#   bench/performance.sh [CORPUS_DIR] [BLOCKS] [RUNS]
#       CORPUS_DIR  the real-post corpus (tests/corpus/fetch.sh); without it the corpus rows are
#                   skipped
#       BLOCKS      size of the scale program (bench/make_scale_program.py), default 1000000
#       RUNS        runs of each command, default 3; the best time of each counts
#   CAMSIM=PATH and CAMOTICS_REPO=DIR (a clone of CAMotics) add the row against camsim
#   (bench/camsim.py); camsim is found on PATH too.
#
# Each run times rs274 -g and every ncjoule command on the same program one after the other, so
# that a machine busy with other work slows them alike; a ratio is of the best wall-clock times,
# and the CPU column the same for user + system time (more steady on a busy machine; above the
# wall ratio where ncjoule works on several cores). Builds ncjoule if needed ($BUILD_DIR or
# build/). Needs GNU time and rs274 (Debian packages time and linuxcnc-uspace).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
corpus="${1:-}"
blocks="${2:-1000000}"
runs="${3:-3}"
build="${BUILD_DIR:-$root/build}"
source "$root/bench/measure.sh"
command -v rs274 > /dev/null || { echo "rs274 not found (Debian package linuxcnc-uspace)" >&2; exit 1; }
if [ ! -f "$build/build.ninja" ] && [ ! -f "$build/Makefile" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
fi
cmake --build "$build" --target ncjoule > /dev/null
ncjoule="$build/plugin/ncjoule"
machine="$root/samples/machines/generic-3axis.toml"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export HOME="$work" # rs274 writes ~/.tool.mmap; no user config of ncjoule applies
tools="$work/tools.tbl"
echo "T1 P1 Z0 D6 ;6 mm flat end mill" > "$tools"
program="$work/scale.ngc"
python3 "$root/bench/make_scale_program.py" "$blocks" > "$program"
stock="box:0,0,-10,100,100,0"
scale=(--machine "$machine" --stock "$stock")

# --- the scale program: rs274 and each command, best of `runs` ------------------------------
names=(rs274 canon annotate json compact)
declare -A wall cpu peak
for n in "${names[@]}"; do wall[$n]=nan cpu[$n]=nan peak[$n]=nan; done
for _ in $(seq "$runs"); do
  for n in "${names[@]}"; do
    case $n in
    rs274) cmd=(rs274 -t "$tools" -g "$program") ;;
    canon) cmd=("$ncjoule" canon -t "$tools" "$program") ;;
    annotate) cmd=("$ncjoule" annotate "$program" "${scale[@]}" -o "$work/annotated.ngc") ;;
    json) cmd=("$ncjoule" estimate --json "$program" "${scale[@]}") ;;
    compact) cmd=("$ncjoule" estimate --json-compact "$program" "${scale[@]}") ;;
    esac
    read -r w c m < <(measure "${cmd[@]}")
    wall[$n]=$(smaller "${wall[$n]}" "$w")
    cpu[$n]=$(smaller "${cpu[$n]}" "$c")
    peak[$n]=$(larger "${peak[$n]}" "$m")
  done
done

lines=$(wc -l < "$program")
echo "scale program: $lines lines ($(du -h "$program" | cut -f1)), best of $runs runs, $(nproc) cores"
echo
row() { printf "%-46s %-22s %9s %9s %9s\n" "$@"; }
row measure goal "wall" "CPU" "peak MiB"
row "rs274 -g, the reference (its seconds)" "-" "${wall[rs274]}" "${cpu[rs274]}" "${peak[rs274]}"
row "canon vs rs274 -g (x faster)" ">= 5x" "$(ratio "${wall[rs274]}" "${wall[canon]}")x" \
  "$(ratio "${cpu[rs274]}" "${cpu[canon]}")x" "${peak[canon]}"
row "annotate, with removal (x rs274's time)" "<= 1x" "$(ratio "${wall[annotate]}" "${wall[rs274]}")x" \
  "$(ratio "${cpu[annotate]}" "${cpu[rs274]}")x" "${peak[annotate]}"
row "estimate --json (x rs274's time)" "<= 0.5x, < 256 MiB" \
  "$(ratio "${wall[json]}" "${wall[rs274]}")x" "$(ratio "${cpu[json]}" "${cpu[rs274]}")x" \
  "${peak[json]}"
row "estimate --json-compact (x rs274's time)" "-" "$(ratio "${wall[compact]}" "${wall[rs274]}")x" \
  "$(ratio "${cpu[compact]}" "${cpu[rs274]}")x" "${peak[compact]}"

# --- removal against CAMotics' camsim -------------------------------------------------------
camsim="${CAMSIM:-$(command -v camsim || true)}"
if [ -n "$camsim" ] && [ -n "${CAMOTICS_REPO:-}" ]; then
  python3 "$root/bench/camsim.py" "$ncjoule" "$CAMOTICS_REPO" --camsim "$camsim" --runs "$runs" \
    2> /dev/null |
    tail -1
elif [ -n "$camsim" ]; then
  echo "removal vs camsim (>= 10x at camsim's grid): not measured, give CAMOTICS_REPO (a clone" \
    "of CauldronDevelopmentLLC/CAMotics, for its example projects)"
else
  echo "removal vs camsim (>= 10x at camsim's grid): not measured, camsim is not installed" \
    "(Debian has no camotics package; CAMSIM=PATH names a build of it)"
fi

[ -n "$corpus" ] || { echo "corpus rows: not measured (give the corpus folder)"; exit 0; }

# --- every corpus program with default settings: bench/corpus_budget.py, the removal grid's bench
# (it chooses the grid; this row only reports its summary line) ------------------------------------
if [ -f "$root/bench/corpus_budget.py" ]; then
  echo "corpus, default settings (<= 2 s and <= 256 MiB each): $(python3 "$root/bench/corpus_budget.py" \
    "$ncjoule" "$corpus" --no-fine | tail -1)"
else
  echo "corpus, default settings (<= 2 s and <= 256 MiB each): not measured here," \
    "bench/corpus_budget.py (the removal grid's bench) is not in this tree"
fi

# --- a client reading the JSON of the corpus's longest program ----------------------------------
longest=$(wc -l "$corpus"/* 2> /dev/null | grep -v ' total$' | sort -n | tail -1 | awk '{print $2}')
"$ncjoule" estimate --json "$longest" --machine "$machine" > "$work/full.json" 2> /dev/null || true
"$ncjoule" estimate --json-compact "$longest" --machine "$machine" > "$work/compact.json" \
  2> /dev/null || true
parse_s() { # best of `runs` times Python's json module takes to read the file
  python3 - "$1" "$runs" << 'EOF'
import json, sys, time
best = float("inf")
for _ in range(int(sys.argv[2])):
    with open(sys.argv[1], "rb") as f:
        text = f.read()
    start = time.perf_counter()
    json.loads(text)
    best = min(best, time.perf_counter() - start)
print(f"{best:.3f}")
EOF
}
full_s=$(parse_s "$work/full.json")
compact_s=$(parse_s "$work/compact.json")
full_mb=$(awk -v b="$(wc -c < "$work/full.json")" 'BEGIN { printf "%.1f", b / 1048576 }')
compact_mb=$(awk -v b="$(wc -c < "$work/compact.json")" 'BEGIN { printf "%.1f", b / 1048576 }')
echo "client reading the JSON of $(basename "$longest") ($(wc -l < "$longest") lines), Python's" \
  "json: --json $full_mb MiB, --json-compact $compact_mb MiB ($(ratio "$compact_mb" "$full_mb")x)," \
  "read in $(ratio "$compact_s" "$full_s")x the time"
