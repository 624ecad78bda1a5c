#!/usr/bin/env bash
# Runs ncjoule over a local copy of the real-post corpus (tests/corpus/manifest.tsv; the programs
# themselves are not in the repository, see fetch.sh) and prints one row per program: whether
# LinuxCNC's rs274 reads it, ncjoule estimate's exit status and time with default settings (the
# generic profile), whether annotate wrote a file, whether strip gives the original back byte
# for byte, and the first warning or error. A summary row follows.
#
#   tests/corpus/run.sh DIR [path/to/ncjoule]
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
dir="${1:?usage: run.sh DIR [ncjoule]}"
N="${2:-$root/build/plugin/ncjoule}"
M="$root/samples/machines/generic-3axis.toml"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export HOME="$work" # rs274 writes ~/.tool.mmap

printf "%-44s %-34s %6s %5s %4s %4s %5s %7s %4s  %s\n" id cam lines rs274 exit ann strip seconds warn "first message"
total=0 ok=0 annotated=0 identical=0 rs_ok=0
times=()
while IFS=$'\t' read -r id repo path commit sha cam dialect units features lines notes; do
  [ "$id" = id ] && continue
  f="$dir/$id"
  [ -f "$f" ] || { printf "%-44s missing\n" "$id"; continue; }
  total=$((total + 1))
  rs=no
  if timeout 120 rs274 -g "$f" > "$work/rs.txt" 2>&1 && ! grep -qiE "^(error|.*: error)" "$work/rs.txt"; then
    rs=yes; rs_ok=$((rs_ok + 1))
  fi
  start=$(date +%s.%N)
  timeout 300 "$N" estimate "$f" -m "$M" > "$work/est.txt" 2> "$work/err.txt"
  code=$?
  end=$(date +%s.%N)
  secs=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }')
  times+=("$secs")
  [ "$code" = 0 ] && ok=$((ok + 1))
  ann=no strip=-
  rm -f "$work/out.nc"
  timeout 300 "$N" annotate "$f" -m "$M" -o "$work/out.nc" > /dev/null 2>&1
  if [ -s "$work/out.nc" ]; then
    ann=yes; annotated=$((annotated + 1))
    if "$N" strip "$work/out.nc" > "$work/back.nc" 2> /dev/null && cmp -s "$work/back.nc" "$f"; then
      strip=same; identical=$((identical + 1))
    else
      strip=DIFF
    fi
  fi
  warns=$(grep -cE ": (warning|error): " "$work/err.txt")
  first=$(grep -m1 -E ": (warning|error): " "$work/err.txt" | sed 's/^[^:]*:[0-9:]*: //' | cut -c1-70)
  printf "%-44s %-34s %6s %5s %4s %4s %5s %7s %4s  %s\n" "${id:0:44}" "${cam:0:34}" "$lines" "$rs" \
    "$code" "$ann" "$strip" "$secs" "$warns" "$first"
done < "$here/manifest.tsv"
median=$(printf "%s\n" "${times[@]}" | sort -n | awk '{ a[NR] = $1 } END { if (NR) print a[int((NR + 1) / 2)]; else print 0 }')
max=$(printf "%s\n" "${times[@]}" | sort -n | tail -1)
echo
echo "programs $total; rs274 reads $rs_ok; estimate exit 0: $ok; annotated: $annotated; strip identical: $identical; seconds median $median, max $max"
