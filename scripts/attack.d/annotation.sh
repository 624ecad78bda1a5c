# Annotations (docs/annotation.md): written in each controller's comment syntax, never inside a
# call, an expression or a string; within what the controller or its sender takes on a line; and
# an annotation copied from another file is the user's text, kept byte for byte. Sourced by
# scripts/attack.sh: uses case_, check_, $N, $M, $P and $root, runs in its folder, adds to $failures.

# same_canon DIALECT A B: A and B run the same canonical commands in DIALECT.
same_canon() {
  "$N" canon --dialect "$1" -- "$2" > canon_a.txt 2> /dev/null &&
    "$N" canon --dialect "$1" -- "$3" > canon_b.txt 2> /dev/null && cmp -s canon_a.txt canon_b.txt &&
    [ -s canon_a.txt ]
}
# strips_back ANNOTATED ORIGINAL: strip gives ORIGINAL back, byte for byte.
strips_back() { "$N" strip -- "$1" 2> /dev/null | cmp -s - "$2"; }
# longest FILE: the length of its longest line, without the line ending.
longest() { awk '{ sub(/\r$/, ""); if (length($0) > m) m = length($0) } END { print m + 0 }' "$1"; }

# Sinumerik: a call, an expression and a string with ';' and parentheses in it. The annotation is
# a ';' comment after them, never "CYCLE81 (NCJ ..)(10,0,2,-5)"; the header comes after the
# %_N_ and ;$PATH lines and the title comment.
printf '%%_N_PART_MPF\n;$PATH=/_N_WKS_DIR/_N_PART_WPD\n;PART TITLE\nG0 X0 Y0 Z5\n%s\n%s\n%s\nG1 X5 ;note\nM30\n' \
  'CYCLE81(10,0,2,-5)' 'G1 X10 Y=COS (0) F100' 'G0 X1 MSG("a;b(c)")' > sinumerik.mpf
case_ "annotate: Sinumerik calls, strings" 0 "" -- \
  "$N" annotate sinumerik.mpf -m "$M" --no-removal --dialect siemens -o sinumerik_annotated.mpf
check_ "annotate: ... canon unchanged" same_canon siemens sinumerik.mpf sinumerik_annotated.mpf
check_ "annotate: ... no ( ) comment added" bash -c '! grep -q "(NCJ" sinumerik_annotated.mpf'
check_ "annotate: ... after the call" grep -qF 'CYCLE81(10,0,2,-5) ;NCJ T=' sinumerik_annotated.mpf
check_ "annotate: ... after the expression" grep -qF 'G1 X10 Y=COS (0) F100 ;NCJ T=' sinumerik_annotated.mpf
check_ "annotate: ... after the string" grep -qF 'G0 X1 MSG("a;b(c)") ;NCJ T=' sinumerik_annotated.mpf
check_ "annotate: ... header after ;\$PATH, title" \
  bash -c 'sed -n 3p sinumerik_annotated.mpf | grep -qx ";PART TITLE" && sed -n 4p sinumerik_annotated.mpf | grep -q "^;NCJ SEAL "'
check_ "annotate: ... strip gives it back" strips_back sinumerik_annotated.mpf sinumerik.mpf

# An annotation copied from another annotated file, after a block and as a header line: the
# user's note there. annotate and strip keep it byte for byte, and a comment that only looks like
# one ("(NCJ T=1s CK=ABCDEF)") too.
printf 'G21 G90\nG0 X0 Y0 Z5\nG1 X40 F500\nM2\n' > pasted_from.ngc
"$N" annotate pasted_from.ngc -m "$M" --no-removal -o pasted_from_annotated.ngc 2> /dev/null
note=$(grep -o ' (NCJ T=[^)]*)' pasted_from_annotated.ngc | head -1)
total=$(grep -m1 '^(NCJ TOTAL ' pasted_from_annotated.ngc)
printf 'G21 G90\n%s\nG0 X10 Y10 Z5\nG1 X40 F500%s\nG1 X80 (NCJ T=1s CK=ABCDEF)\nM2\n' "$total" "$note" > pasted.ngc
case_ "annotate: a pasted annotation" 0 "" -- "$N" annotate pasted.ngc -m "$M" --no-removal -o pasted_annotated.ngc
check_ "annotate: ... it was one" test -n "$note" -a -n "$total"
check_ "annotate: ... kept through annotate+strip" strips_back pasted_annotated.ngc pasted.ngc
check_ "annotate: ... and strip alone" strips_back pasted.ngc pasted.ngc

# grbl: senders stream a line only when it fits the 128-byte receive buffer with the lines in
# flight: no annotated line over 125 bytes; a block without room gets its comment on the line
# before it, which strip takes out with its line ending.
printf 'G21 G90\nG0 X0 Y0 Z5\nG1 X10 Y20 F300 (%s)\nG1 X20.123456 Y30.123456 Z-1.123456 F300 (%s)\nM2\n' \
  "$(printf 'a%.0s' $(seq 95))" "$(printf 'b%.0s' $(seq 40))" > grbl_long.nc
case_ "annotate: grbl line limit" 0 "" -- \
  "$N" annotate grbl_long.nc -m "$M" --no-removal --dialect grbl -o grbl_annotated.nc
check_ "annotate: ... no line over 125 bytes" test "$(longest grbl_annotated.nc)" -le 125
check_ "annotate: ... own line before the block" \
  bash -c 'grep -B1 "^G1 X10 Y20 F300 (a" grbl_annotated.nc | head -1 | grep -q "^(NCJ T="'
check_ "annotate: ... strip gives it back" strips_back grbl_annotated.nc grbl_long.nc
check_ "annotate: ... canon unchanged" same_canon grbl grbl_long.nc grbl_annotated.nc

# Marlin: ';' comments ("( )" would be parameters to it, E= an extrusion), lines within its
# 96-byte command buffer.
printf 'G21\nG90\nG0 X0 Y0 Z5\nG1 X20 F600 ; perimeter\nM84\n' > marlin.gcode
case_ "annotate: Marlin ';' comments" 0 "" -- \
  "$N" annotate marlin.gcode -m "$M" --no-removal --dialect reprap -o marlin_annotated.gcode
check_ "annotate: ... no ( ) comment added" bash -c '! grep -q "(" marlin_annotated.gcode'
check_ "annotate: ... no line over 95 bytes" test "$(longest marlin_annotated.gcode)" -le 95
check_ "annotate: ... strip gives it back" strips_back marlin_annotated.gcode marlin.gcode
