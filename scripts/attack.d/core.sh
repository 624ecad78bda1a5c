# The interpreter and the planner (core/gcode, core/kinematics): programs of a few bytes that
# once took minutes (zero-length moves in a loop, a label searched from the top at every branch,
# a line of unclosed brackets), nesting that overflowed the stack, and values no control takes
# (infinite, 1e300) that were timed or dropped. Sourced by scripts/attack.sh: uses case_, check_, $N, $M,
# runs in its folder, adds to $failures.

# no_inf_nan FILE: no 'inf' or 'nan' in FILE; no_odd_numbers FILE: nor a number with an exponent
# (JSON may have those: its numbers are for programs to read).
no_inf_nan() { ! grep -qaiE '(^|[^a-z])(inf|nan|infinity)([^a-z]|$)' "$1"; }
no_odd_numbers() { no_inf_nan "$1" && ! grep -qaE '[0-9]e[-+]?[0-9]' "$1"; }

# 75 bytes: 100,000 zero-length moves (G1 to where the tool is) in a loop. Each one rescanned
# the queue behind the move waiting for the next: 33 s, now well under a second.
printf 'G1 X5 F100\n#1=0\no101 while [#1 lt 100000]\nG1 X5\n#1=[#1+1]\no101 endwhile\nM2\n' \
  > zero_length.ngc
case_ "zero-length G1 x100k in a while"  0 "" -- timeout 10 "$N" estimate zero_length.ngc -m "$M" --no-removal
printf 'G64 P0.01\nG0 X5\no100 repeat [100000]\nG0 X5\no100 endrepeat\nM2\n' > zero_length_g0.ngc
case_ "zero-length G0 x100k, G64 P"      0 "" -- timeout 10 "$N" estimate zero_length_g0.ngc -m "$M" --no-removal
# 50,000 'o100 if [0]' blocks: each branch searched the label's lines from the top (6.7 s).
python3 -c "print('G21\n' + 'o100 if [0]\nG1 X1 F100\no100 endif\n' * 50000 + 'M2')" > many_ifs.ngc
case_ "50,000 ifs of one label"          0 "" -- timeout 10 "$N" estimate many_ifs.ngc -m "$M" --no-removal
# A line of 100,000 unclosed brackets: each word scanned to the end of the line for its ']'.
python3 -c "print('G1 ' + 'x[' * 100000 + '\nM2')" > unclosed.ngc
case_ "100,000 unclosed brackets"        0 "no number" -- timeout 10 "$N" estimate unclosed.ngc -m "$M" --no-removal

# Nesting: 26,600 brackets crashed the CLI (stack overflow); 200,000 signs and '#' are a loop.
python3 -c "print('G21\nG0 X' + '[' * 26600 + '1' + ']' * 26600 + '\nM2')" > brackets.ngc
case_ "26,600 nested brackets"           2 "nested more than 128" -- "$N" estimate brackets.ngc -m "$M" --no-removal
python3 -c "print('G21\nG0 X' + '- ' * 200000 + '1\nM2')" > signs.ngc
case_ "200,000 unary minus"              0 "" -- "$N" estimate signs.ngc -m "$M" --no-removal
python3 -c "print('G21\n#1=1\nG0 X' + '#' * 200000 + '1\nM2')" > hashes.ngc
case_ "200,000 parameter references"     0 "" -- "$N" estimate hashes.ngc -m "$M" --no-removal

# Values no control takes: errors with file:line:column, not an infinite dwell dropped, an arc
# of no time or a dwell printed with hundreds of digits.
printf 'G21\nG4 P[10**308*10]\nM2\n' > infinite_dwell.ngc
case_ "infinite dwell"                   2 "infinite_dwell.ngc:2:4: error" -- "$N" estimate infinite_dwell.ngc -m "$M" --no-removal
printf 'G21 G90\nG0 X0 Y0 Z0\nG2 X1 Y0 R1%s F100\nM2\n' "$(printf '0%.0s' $(seq 300))" > radius_1e300.ngc
case_ "arc of radius 1e300"              2 "out of range" -- "$N" estimate radius_1e300.ngc -m "$M" --no-removal
printf 'G21\nG4 P1%s\nM2\n' "$(printf '0%.0s' $(seq 300))" > dwell_1e300.ngc
case_ "dwell of 1e300 s"                 2 "out of range" -- "$N" estimate dwell_1e300.ngc -m "$M" --no-removal

# The most a program can still ask: 100,000 dwells of 99,999.999 s (3e6 hours) and the longest
# move at the slowest feed. Every number written is finite, without an exponent.
printf 'G21\no1 repeat [100000]\nG4 P99999.999\no1 endrepeat\nG1 X99999.999 F0.0001\nM2\n' > longest.ngc
case_ "longest program, annotated"       0 "" -- "$N" annotate longest.ngc -m "$M" --no-removal
check_ "... no inf, nan or exponent" no_odd_numbers out.txt
case_ "longest program, JSON"            0 "" -- "$N" estimate longest.ngc -m "$M" --no-removal --json
check_ "... no inf or nan" no_inf_nan out.txt
case_ "longest program, CSV"             0 "" -- "$N" estimate longest.ngc -m "$M" --no-removal --csv
check_ "... no inf or nan" no_inf_nan out.txt
case_ "longest program, text"            0 "" -- "$N" estimate longest.ngc -m "$M" --no-removal
check_ "... no inf, nan or exponent" no_odd_numbers out.txt
