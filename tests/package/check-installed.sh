#!/bin/sh
# Checks an installed ncjoule package: run inside a fresh Debian root where the package was
# installed (PREFIX empty: /usr), or against a folder it was unpacked into (PREFIX=/that/folder,
# with LD_LIBRARY_PATH pointing at its library folder). scripts/test-package.sh runs it.
# Usage: check-installed.sh WORKDIR    (WORKDIR: a writable folder holding the files of tests/package)
set -eu
work=$1
usr=${PREFIX:-}/usr
ncjoule=$usr/bin/ncjoule
failures=0
check() { # check WHAT COMMAND...: runs COMMAND, says ok or FAIL
  what=$1
  shift
  if "$@" >"$work/out.txt" 2>&1; then
    echo "ok    $what"
  else
    echo "FAIL  $what"
    sed 's/^/      /' "$work/out.txt" | tail -n 30
    failures=$((failures + 1))
  fi
}
expect() { # expect WHAT PATTERN: the output of the last check holds PATTERN
  if grep -q -- "$2" "$work/out.txt"; then
    echo "ok    $1"
  else
    echo "FAIL  $1 (no '$2' in its output)"
    failures=$((failures + 1))
  fi
}

cd "$work"
export HOME="$work/home"
mkdir -p "$HOME"
unset NCJOULE_CONFIG NCJOULE_DATA_DIR XDG_CONFIG_HOME

check "ncjoule is on the PATH" sh -c "command -v ncjoule || test -x '$ncjoule'"
check "ncjoule --version" "$ncjoule" --version
expect "  it says the version" '^ncjoule [0-9]'

check "ncjoule doctor passes" "$ncjoule" doctor
sed 's/^/      /' "$work/out.txt"
expect "  it found the installed profiles" "machine profile folder $usr/share/ncjoule/machines: [1-9]"
expect "  it found the installed hooks" "post-processor hooks in $usr/share/ncjoule/hooks"
expect "  it found libncjoule" "C library (libncjoule) .* at .*libncjoule.so"

check "ncjoule profiles lists the installed profiles" "$ncjoule" profiles
expect "  generic-3axis among them" '^generic-3axis '
expect "  haas-vf2 among them" '^haas-vf2 '

check "ncjoule estimate -m haas-vf2 on a bundled sample" \
  "$ncjoule" estimate sample.ngc -m haas-vf2 --stock "$(cat sample.stock)"
expect "  it was estimated on the Haas profile" "on Haas VF-2"
expect "  it gives the time" "^  time  "
check "ncjoule estimate --json -m router-2.2kw-vfd" "$ncjoule" estimate sample.ngc -m router-2.2kw-vfd --json
check "ncjoule annotate -o" "$ncjoule" annotate sample.ngc -m generic-3axis -o annotated.ngc
check "ncjoule strip gives the original back" sh -c "'$ncjoule' strip annotated.ngc -o stripped.ngc && cmp sample.ngc stripped.ngc"

check "man page ncjoule(1)" sh -c "gzip -dc '$usr/share/man/man1/ncjoule.1.gz' | grep -q '^\.TH NCJOULE'"
check "man page ncjoule-estimate(1)" sh -c "gzip -dc '$usr/share/man/man1/ncjoule-estimate.1.gz' | grep -q 'machine TEXT'"
if command -v man >/dev/null && [ -z "${PREFIX:-}" ]; then check "man -w ncjoule" man -w ncjoule; fi
check "header /usr/include/ncjoule.h" test -f "$usr/include/ncjoule.h"
check "libncjoule.so for -lncjoule" sh -c "ls $usr/lib/*/libncjoule.so"
check "documentation" test -f "$usr/share/doc/ncjoule/README.md"
check "copyright file" test -f "$usr/share/doc/ncjoule/copyright"

# A C program against the header and the library, when there is a compiler.
if command -v cc >/dev/null; then
  lib=$(dirname "$(ls $usr/lib/*/libncjoule.so)")
  check "a C program compiles and links with -lncjoule" \
    cc -Wall -Werror -o capi_smoke capi_smoke.c -I"$usr/include" -L"$lib" -lncjoule
  check "  and estimates a program through the C API" ./capi_smoke "$usr/share/ncjoule/machines/generic-3axis.toml" sample.ngc
  cat out.txt | sed 's/^/      /'
else
  echo "note  no C compiler here: the C API was checked by its files only"
fi

if [ "$failures" -ne 0 ]; then
  echo "check-installed: $failures check(s) failed"
  exit 1
fi
echo "check-installed: every check passed"
