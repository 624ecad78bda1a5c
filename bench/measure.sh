# shellcheck shell=bash
# Shared by the bench scripts (sourced, not run): time and peak memory of a command, and ratios.
# Needs GNU time (/usr/bin/time, Debian package time).

[ -x /usr/bin/time ] || { echo "GNU time (/usr/bin/time, Debian package time) is needed" >&2; exit 1; }

# Runs a command under GNU time, its output to /dev/null; prints "wall_s cpu_s peak_MiB" (cpu:
# user + system), or "nan nan nan" when it fails. Needs $work (a scratch folder).
# shellcheck disable=SC2154 # $work is the sourcing script's
measure() {
  /usr/bin/time -f "%e %U %S %M" -o "$work/time.txt" "$@" > /dev/null 2> "$work/stderr.txt" || {
    echo "failed: $*" >&2
    tail -3 "$work/stderr.txt" >&2
    echo "nan nan nan"
    return
  }
  awk '{printf "%.3f %.3f %.0f\n", $1, $2 + $3, $4 / 1024}' "$work/time.txt"
}

# a / b to two decimals, "-" when either is not a number.
ratio() {
  awk -v a="$1" -v b="$2" 'BEGIN { if (a != "nan" && b != "nan" && b > 0) printf "%.2f", a / b; else print "-" }'
}

# The smaller of two numbers ("nan" loses).
smaller() { awk -v a="$1" -v b="$2" 'BEGIN { if (a == "nan") print b; else if (b == "nan" || a + 0 <= b + 0) print a; else print b }'; }
# The larger.
larger() { awk -v a="$1" -v b="$2" 'BEGIN { if (a == "nan") print b; else if (b == "nan" || a + 0 >= b + 0) print a; else print b }'; }
