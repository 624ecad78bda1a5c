# Issue 40 (round three): output paths that replaced what they should append to, dialects
# guessed from a customer's name, edited annotations strip missed, files with nothing to run,
# absurd numbers in profiles, job files, tool tables, power logs and calibration tables, L2.5,
# G16, and the LinuxCNC filter's promise never to change the file. Sourced by scripts/attack.sh:
# uses case_, check_, $N, $M, $P, $root and $quick, runs in its folder, adds to $failures.

# -o /dev/stdout >> log: appended, never replaced (the log lost its first line).
echo "earlier line" > r3_log.txt
case_ "r3: -o /dev/stdout >> log"         0 "" -- sh -c "'$N' annotate '$P' -m '$M' --no-removal -o /dev/stdout >> r3_log.txt"
check_ "r3: ... the log keeps its line"   grep -qx "earlier line" r3_log.txt
check_ "r3: ... and gets the program"     grep -q "NCJ" r3_log.txt

# A part's name in a comment names no dialect: G4 P5 stays 5 s under LinuxCNC (Haas: 5 ms).
printf 'G21 G90\n(OP 7: HOLES FOR THE HAAS TRUNNION ADAPTER)\n(CUSTOMER: SIEMENS AG - BRACKET)\nG0 X0 Y0 Z5\nG4 P5\nM2\n' > r3_haas_word.ngc
case_ "r3: HAAS in a comment"              0 "" -- "$N" estimate r3_haas_word.ngc -m "$M" --no-removal --json
check_ "r3: ... is still linuxcnc"         grep -q '"dialect": *"linuxcnc"' out.txt

# strip after the header was deleted and blanks removed (a DNC sender): no NCJ left.
"$N" annotate "$P" -m "$M" --no-removal -o r3_annotated.ngc 2>/dev/null
grep -v '^(NCJ' r3_annotated.ngc | sed 's/ (NCJ/(NCJ/' > r3_edited.ngc
case_ "r3: strip, header deleted"          0 "" -- "$N" strip r3_edited.ngc -o r3_stripped.ngc
check_ "r3: ... no annotation left"        sh -c "! grep -q 'NCJ' r3_stripped.ngc"

# Nothing to run: a setup sheet saved as .ngc, a '%'-only file.
printf '(SETUP SHEET)\n(T1 6 MM FLAT)\n' > r3_comments.ngc
printf '%%\n%%\n' > r3_percent.ngc
case_ "r3: comment-only file"              2 "" -- "$N" annotate r3_comments.ngc -m "$M" -o r3_out.ngc
case_ "r3: %-only file"                    2 "" -- "$N" annotate r3_percent.ngc -m "$M" -o r3_out.ngc

# Profiles, job files, tool tables: absurd numbers refused at their line.
sed 's/^\(move_ka_w\) *=.*/\1 = -1e6/' "$M" > r3_negative_move.toml
grep -q '^move_ka_w = -1e6' r3_negative_move.toml || printf '\n[power.pavanaskar]\nmove_ka_w = -1e6\n' >> r3_negative_move.toml
case_ "r3: move_ka_w = -1e6"               2 "" -- "$N" estimate "$P" -m r3_negative_move.toml --no-removal
printf '[[tool]]\nnumber = 4294967297\ntype = "flat"\ndiameter_mm = 50\n' > r3_job.toml
case_ "r3: job tool number 2^32+1"         2 "1000000" -- "$N" estimate "$P" -m "$M" --job r3_job.toml
printf 'T4294967297 P1 D50\n' > r3_tools.tbl
case_ "r3: tool table T2^32+1"             2 "1000000" -- "$N" estimate "$P" -m "$M" --tool-table r3_tools.tbl --no-removal

# Power logs and calibration tables.
printf 'time_s,power_w\n0,100\n1,1e308\n2,100\n' > r3_huge_log.csv
case_ "r3: measure 1e308 W"                2 "beyond" -- "$N" measure r3_huge_log.csv
check_ "r3: ... prints no inf"             sh -c "! grep -qi 'inf' out.txt"
printf 'time_s,power_w\n0,100\n1,-50\n2,100\n' > r3_negative_log.csv
case_ "r3: measure -50 W"                  2 "negative" -- "$N" measure r3_negative_log.csv
printf 'rpm,power_w\n3000,1e308\n4000,1e308\n5000,1e308\n' > r3_huge_table.csv
case_ "r3: calibrate 1e308 W"              2 "beyond" -- "$N" calibrate --spindle r3_huge_table.csv -o r3_fit.toml
printf 'rpm,power_w\n3000,1100\n' > r3_one_row.csv
case_ "r3: calibrate one row"              2 "1 usable row" -- "$N" calibrate --spindle r3_one_row.csv -o r3_fit.toml
check_ "r3: ... writes no profile"         test ! -e r3_fit.toml

# L2.5 is refused as rs274 refuses it; G16 where the dialect has none is a warning.
printf 'G21 G90\nG0 X0 Y0 Z5\nG91 G81 X10 Y0 Z-6 R-4 F100 L2.5\nG80\nG90\nM2\n' > r3_l25.ngc
case_ "r3: G81 L2.5"                       2 "whole number" -- "$N" estimate r3_l25.ngc -m "$M" --no-removal
printf 'G21 G90\nG0 X0 Y0 Z5\nG16\nG0 X50 Y90\nG15\nM2\n' > r3_g16.ngc
case_ "r3: G16 under linuxcnc"             0 "polar" -- "$N" estimate r3_g16.ngc -m "$M" --no-removal

# The LinuxCNC filter: --in-place in its ARGS is refused, the file on disk never changes.
cp "$P" r3_filter.ngc
case_ "r3: filter ARGS --in-place"         0 "write a file" -- env NCJOULE_ARGS=--in-place "$root/postprocessor-templates/linuxcnc/ncjoule-filter" --ncjoule "$N" --machine "$M" r3_filter.ngc
check_ "r3: ... the file is unchanged"     cmp -s "$P" r3_filter.ngc

# A comment that retitles the terminal (ESC ] 0; ... BEL) or colours it: escaped on stdout too
# (the text summary, the CSV), not only on stderr.
printf 'G21 G90\n(OP \033]0;title\007 \033[31mRED)\nT1 M6\nG0 X0 Y0 Z5\nG1 X10 F100\nM2\n' > r3_title.ngc
case_ "r3: ESC ] title, summary"           0 "" -- "$N" estimate r3_title.ngc -m "$M" --no-removal
check_ "r3: ... escaped on stdout"         sh -c "! LC_ALL=C grep -qaP '[\x07\x1b]' out.txt"
case_ "r3: ESC ] title, CSV"               0 "" -- "$N" estimate r3_title.ngc -m "$M" --no-removal --csv
check_ "r3: ... escaped in the CSV"        sh -c "! LC_ALL=C grep -qaP '[\x07\x1b]' out.txt"

# Work budgets: programs a control would run for days stop within seconds, exit 5 (not 2: the
# program is not refused), saying which budget, where and how to raise it; nothing is written.
# The defaults are what these use: each must end within 20 s of one core (the 60 s limit is of
# the wall clock, which a busy machine stretches).
printf 'G21 G90 G17\nT1 M6\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F500\no100 repeat [1000000]\nG5 X10 Y0 I5000 J5000 P5000 Q-5000\nG5 X0 Y0 I-5000 J5000 P-5000 Q-5000\no100 endrepeat\nM2\n' > r3_spline_loop.ngc
printf 'G21 G90\nT1 M6\nS1000 M3\nG0 X0 Y0 Z5\no100 repeat [1000000]\nG91 G81 X1 Y0 Z-1 R1 F100 L100000\nG80 G90\no100 endrepeat\nM2\n' > r3_cycle_loop.ngc
# 9 lines, 19.6 km of cutting: a helix of 62,400 turns of 100 mm across, at a fine grid (the
# automatic grid, coarsened for its length, times it in about 30 s of one core).
printf 'G21 G90 G17\nT1 M6\nS10000 M3\nG0 X-50 Y0 Z5\nG1 Z-1 F5000\nG2 X-50 Y0 I50 J0 Z-2 P62400\nG0 Z5\nM5\nM2\n' > r3_helix.ngc
children_cpu_() { # the processor seconds of this shell's finished children so far
  times > r3_times.txt # here, not in a pipeline's subshell (which has no children yet)
  awk 'NR == 2 { n = split($0, t, /[ms ]+/); s = 0
    for (i = 1; i + 1 <= n; i += 2) s += 60 * t[i] + t[i + 1]; printf "%.0f", s }' r3_times.txt
}
budget_case_() { # NAME WORD -- command...: case_ with exit 5, and the processor time it took
  local name="$1" word="$2" before
  shift 3
  children_cpu_ > r3_cpu.txt # called here: $(...) would run it in a subshell
  before=$(< r3_cpu.txt)
  case_ "$name" 5 "$word" -- "$@"
  children_cpu_ > r3_cpu.txt
  local cpu=$(($(< r3_cpu.txt) - before))
  check_ "r3: ... within 20 s of one core ($cpu s)" test "$cpu" -le 20
}
# With the default budgets these take seconds each: left out of --quick (the test suite's run;
# tests/cli/work_budgets_cli_test.py checks the same with small budgets).
if [ "$quick" = 0 ]; then
budget_case_ "r3: G5 spline in repeat [1e6]"    "max-moves" -- "$N" annotate r3_spline_loop.ngc -m "$M" -o r3_budget.ngc
check_ "r3: ... writes nothing"            test ! -e r3_budget.ngc
check_ "r3: ... says where"                grep -q "r3_spline_loop.ngc:7:" err.txt
budget_case_ "r3: G81 L100000 in repeat [1e6]"  "max-moves" -- "$N" estimate r3_cycle_loop.ngc -m "$M" --no-removal
budget_case_ "r3: 19.6 km at a 0.05 mm grid" "max-removal-work" -- "$N" annotate r3_helix.ngc -m "$M" --stock box:-60,-60,-5,60,60,0 --tool 1:flat:6 --grid 0.05 -o r3_budget.ngc
check_ "r3: ... writes nothing"            test ! -e r3_budget.ngc
cp r3_helix.ngc r3_helix_in_place.ngc
case_ "r3: budget, --in-place"             5 "max_removal_work" -- "$N" annotate r3_helix_in_place.ngc -m "$M" --stock box:-60,-60,-5,60,60,0 --tool 1:flat:6 --grid 0.05 --in-place
check_ "r3: ... the file is unchanged"     cmp -s r3_helix.ngc r3_helix_in_place.ngc
fi

# Control bytes in the names other printers show: calibrate's report, check-log's tables, doctor.
esc_name="$(printf 'r3_\033]0;title\007\033[31m')"
printf 'rpm,power_w\n1000,560\n2000,770\n3000,980\n4000,1195\n' > "${esc_name}.csv"
case_ "r3: ESC in a table's name"          0 "" -- "$N" calibrate -m "$M" --spindle "${esc_name}.csv" -o r3_fit_esc.toml
check_ "r3: ... escaped on stdout"         sh -c "! LC_ALL=C grep -qaP '[\x07\x1b]' out.txt"
case_ "r3: ESC in the config's name"       0 "" -- env NCJOULE_CONFIG="$PWD/${esc_name}.toml" "$N" doctor
check_ "r3: ... doctor escapes it"         sh -c "! LC_ALL=C grep -qaP '[\x07\x1b]' out.txt"
