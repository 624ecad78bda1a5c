# Files: what is read (size, encoding, not G-code, STL stocks) and what --in-place replaces
# (posts still writing, symbolic links). Sourced by scripts/attack.sh.

good='G21 G90\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X20 Y10\nG0 Z5\nM2\n'

# A post still writing: it holds the file open for writing while ncjoule runs.
printf "$good" > held.ngc
cp held.ngc held.before
exec 7>>held.ngc
case_ "in-place, a post still writing" 3 "still being written" -- \
  "$N" annotate held.ngc -m "$M" --no-removal --in-place
exec 7>&-
cmp -s held.ngc held.before || { echo "FAIL in-place on a held file changed it"; failures=$((failures + 1)); }

# A post that keeps appending between looks (open, write, close), to a program with no end yet.
printf 'G21 G90\nG0 X0 Y0 Z5\n' > growing.ngc
( for k in $(seq 40); do printf 'G1 X%s F100\n' "$k" >> growing.ngc; sleep 0.1; done ) &
writer=$!
case_ "in-place, a file still growing" 3 "changed while" -- \
  "$N" annotate growing.ngc -m "$M" --no-removal --in-place
wait "$writer"
[ "$(grep -c '^G1 X' growing.ngc)" = 40 ] && ! grep -q NCJ growing.ngc ||
  { echo "FAIL a growing file lost lines or was annotated"; failures=$((failures + 1)); }

# A symbolic link to a file outside the folder: --in-place does not follow it.
printf 'root:x:0:0:root:/root:/bin/bash\n' > passwd.like
cp passwd.like passwd.before
ln -sf "$work/passwd.like" link.ngc
case_ "in-place on a symbolic link" 3 "symbolic link" -- \
  "$N" annotate link.ngc -m "$M" --no-removal --in-place
case_ "followed link to a non-program" 2 "no G-code" -- \
  "$N" annotate link.ngc -m "$M" --no-removal --in-place --follow-symlinks
cmp -s passwd.like passwd.before || { echo "FAIL a linked file was rewritten"; failures=$((failures + 1)); }

# Inputs that are not G-code programs: refused, never annotated.
printf "$good" | iconv -t UTF-16 > utf16.ngc
cp utf16.ngc utf16.before
case_ "UTF-16 program in place" 2 "UTF-16"      -- "$N" annotate utf16.ngc -m "$M" --in-place
cmp -s utf16.ngc utf16.before || { echo "FAIL a UTF-16 file was rewritten"; failures=$((failures + 1)); }
printf "$good" | iconv -t UTF-32BE > utf32.ngc
case_ "UTF-32 program"            2 "UTF-32"      -- "$N" estimate utf32.ngc -m "$M"
case_ "passwd-like text"          2 "no G-code"   -- "$N" annotate passwd.like -m "$M" -o out.ngc
[ -e out.ngc ] && { echo "FAIL a non-program was annotated"; failures=$((failures + 1)); }
case_ "/dev/urandom"              2 ""            -- "$N" estimate /dev/urandom -m "$M" --input-limit 4
case_ "/dev/zero"                 2 "larger than" -- "$N" estimate /dev/zero -m "$M" --input-limit 64
case_ "/dev/zero on stdin"        2 "larger than" -- sh -c "'$N' estimate - -m '$M' --input-limit 8 < /dev/zero"
case_ "config at /dev/zero"       2 "larger than" -- env NCJOULE_CONFIG=/dev/zero "$N" estimate "$P" -m "$M"
case_ "profile at /dev/zero"      2 "larger than" -- "$N" estimate "$P" -m /dev/zero
if [ "$quick" = 0 ]; then
  head -c 50000000 /dev/zero | tr '\0' '\n' > newlines.ngc
  case_ "50 MB of newlines"       2 "memory budget" -- "$N" annotate newlines.ngc -m "$M" -o out.ngc
fi

# An STL of forty stacked triangles: 4 KB that would fill gigabytes at the finest grid.
{
  echo "solid stacked"
  for k in $(seq 0 39); do
    printf 'facet normal 0 0 1\nouter loop\nvertex -10 -10 -%s\nvertex 120 -10 -%s\nvertex 50 120 -%s\nendloop\nendfacet\n' "$k" "$k" "$k"
  done
  echo "endsolid stacked"
} > stacked.stl
case_ "stacked STL, a given grid"  2 "memory budget" -- "$N" estimate "$P" -m "$M" --stock stacked.stl --grid 0.01 --memory-limit 200
case_ "stacked STL within 200 MiB" 0 "coarsened"     -- "$N" estimate "$P" -m "$M" --stock stacked.stl --memory-limit 200
printf 'solid far\nfacet normal 0 0 1\nouter loop\nvertex -1e308 -1e308 0\nvertex 1e308 -1e308 -10\nvertex 0 1e308 0\nendloop\nendfacet\nendsolid far\n' > far.stl
case_ "STL at 1e308"               2 "units"         -- "$N" estimate "$P" -m "$M" --stock far.stl

# Output and messages.
case_ "--help to a full disk"      3 "standard output" -- sh -c "'$N' --help > /dev/full"
printf "G21\nG1 X1 F100 %s\nM2\n" "$(head -c 2000000 /dev/zero | tr '\0' 'Q')" > long_word.ngc
case_ "a 2 MB word in a message"   0 "more bytes"    -- "$N" estimate long_word.ngc -m "$M" --no-removal
[ "$(wc -c < err.txt)" -lt 20000 ] || { echo "FAIL a long word printed whole"; failures=$((failures + 1)); }
printf 'G21\nG1 X1 F100\n\342\200\256FOO \302\233 BAR\nM2\n' > bidi.ngc
case_ "bidi override and C1 CSI"   0 'u{202e'      -- "$N" estimate bidi.ngc -m "$M" --no-removal
LC_ALL=C grep -qaP '\xe2\x80\xae|\xc2\x9b' err.txt && { echo "FAIL bidi or C1 printed raw"; failures=$((failures + 1)); }
