#!/usr/bin/env bash
# Tests the Windows build (dist/ncjoule-VERSION-win64.zip, from scripts/build-windows.sh) under
# Debian's Wine, headless: the zip is unpacked into a folder with a blank and a non-ASCII letter
# in its name, as a user would install it, and
#  - the CLI tests of tests/cli that do not need LinuxCNC's rs274 run against ncjoule.exe;
#  - tests/windows/windows_paths_test.py: Windows paths (Z:\..., backslashes, blanks, non-ASCII
#    names), CR LF programs, atomic replace, a file still being written, %APPDATA%, profiles;
#  - tests/windows/same_as_linux_test.py: every program in samples/ (and in CORPUS_DIR) gives
#    the Linux build's JSON to 1e-9 relative and its annotated bytes;
#  - the Windows hooks: ncjoule-hook.cmd under Wine's cmd, the Fusion 360 hook with Windows paths.
# The Linux build compared against is build/plugin/ncjoule when it exists (used read-only), else
# one built into build-linux-cmp/ as scripts/build.sh builds.
# Usage: scripts/test-windows.sh [CORPUS_DIR]     (as root, or with sudo available)
# Environment: NCJOULE_WIN_DIR (default build-win).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
. scripts/lib.sh # (the folder is the repository's root here)
out=$(windows_build_dir)
corpus=${1:+$(cd "$1" && pwd)}

results=()
print_summary() {
  print_stage_times test-windows.sh
  if [ "${#results[@]}" -gt 0 ]; then
    echo "test-windows.sh results:" >&2
    printf '  %s\n' "${results[@]}" >&2
  fi
  if [ -n "${WINEPREFIX:-}" ] && [ -d "$WINEPREFIX" ]; then wineserver -k 2>/dev/null || true; fi
}
trap print_summary EXIT

stage "Debian packages"
packages=(wine wine64 python3 nodejs unzip bc cmake ninja-build)
install_packages "${packages[@]}"

stage "Linux build to compare with"
if [ -x build/plugin/ncjoule ]; then
  linux=$root/build/plugin/ncjoule
else
  cmake -S . -B build-linux-cmp -G Ninja -DCMAKE_BUILD_TYPE=Release -U NCJOULE_STAGES \
    -U NCJOULE_COMMANDS >/dev/null
  cmake --build build-linux-cmp --parallel "$(nproc)" --target ncjoule
  linux=$root/build-linux-cmp/plugin/ncjoule
fi
echo "Linux build: $linux" >&2

stage "unpack the zip"
version=$(sed -n 's/^project(ncjoule VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
zip=$root/dist/ncjoule-$version-win64.zip
[ -f "$zip" ] || { echo "no $zip: run scripts/build-windows.sh first" >&2; exit 1; }
test_dir=$out/wine-test
rm -rf "$test_dir"
install_dir="$test_dir/Program Files é/ncjoule"
mkdir -p "$install_dir" "$test_dir/work"
unzip -q "$zip" -d "$test_dir/unzipped"
mv "$test_dir/unzipped/ncjoule-$version-win64/"* "$install_dir/"
exe="$install_dir/bin/ncjoule.exe"

stage "Wine prefix (headless)"
export WINEPREFIX=$test_dir/prefix WINEDEBUG=-all WINEDLLOVERRIDES="mscoree,mshtml="
unset DISPLAY WAYLAND_DISPLAY
mkdir -p "$WINEPREFIX"
wineserver -p # started first and kept up between the tests' many short runs
wineboot -i >/dev/null 2>&1
cat >"$test_dir/ncjoule" <<EOF
#!/bin/sh
exec wine "$exe" "\$@"
EOF
chmod +x "$test_dir/ncjoule"
export NCJOULE=$test_dir/ncjoule NCJOULE_EXE=$exe NCJOULE_LINUX=$linux NCJOULE_SOURCE_DIR=$root \
  NCJOULE_WIN_WORK=$test_dir/work
"$NCJOULE" --version

failed=0
run_test() { # name command...
  local name=$1 start rc=0 note=""
  shift
  start=$(date +%s.%N)
  "$@" >"$test_dir/$name.log" 2>&1 || rc=$?
  if [ "$rc" -ne 0 ] && [ "$rc" -ne 77 ]; then
    # Wine now and then fails to start a process: no output at all and exit 1, once in a few
    # hundred runs (a `compare --help`, or an estimate that passes on every other run). A test
    # that fails runs once more; a failure of ncjoule's fails again. The first log is kept.
    mv "$test_dir/$name.log" "$test_dir/$name.first.log"
    rc=0
    "$@" >"$test_dir/$name.log" 2>&1 || rc=$?
    note="  (passed on its second run; the first: $test_dir/$name.first.log)"
    grep -m3 '^FAIL' "$test_dir/$name.first.log" >&2 || true
  fi
  local seconds
  seconds=$(echo "$(date +%s.%N) - $start" | bc)
  if [ "$rc" -eq 0 ]; then
    results+=("$(printf 'pass  %-32s %6.1f s%s' "$name" "$seconds" "$note")")
  elif [ "$rc" -eq 77 ]; then # the test says why it cannot run here
    results+=("$(printf 'skip  %-32s %6.1f s  (%s)' "$name" "$seconds" "$(grep -m1 '^SKIP' "$test_dir/$name.log")")")
  else
    results+=("$(printf 'FAIL  %-32s %6.1f s  (exit %d; %s)' "$name" "$seconds" "$rc" "$test_dir/$name.log")")
    failed=1
    tail -n 30 "$test_dir/$name.log" >&2
  fi
}

stage "CLI tests (tests/cli) under Wine"
# The tests of tests/cli that need neither rs274 nor POSIX-only behaviour (file modes and
# owners, /proc, /dev/full, ulimit, signals, symbolic links) run as they are, against the wrapper;
# the Windows counterparts of the others are in tests/windows.
run_test cli_estimate python3 tests/cli/estimate_cli_test.py
run_test cli_compare python3 tests/cli/compare_cli_test.py
run_test cli_calibrate python3 tests/cli/calibrate_cli_test.py
run_test cli_measure python3 tests/cli/measure_cli_test.py
run_test cli_removal python3 tests/cli/removal_cli_test.py
run_test samples_summary_programs python3 tests/cli/samples_summary_test.py programs
run_test samples_summary_freecad python3 tests/cli/samples_summary_test.py freecad

stage "Windows paths, CR LF, replace, locks, %APPDATA%"
run_test windows_paths python3 tests/windows/windows_paths_test.py

stage "same results as the Linux build"
run_test same_as_linux python3 tests/windows/same_as_linux_test.py ${corpus:+"$corpus"}

stage "hooks: ncjoule-hook.cmd under Wine's cmd"
run_test cmd_hook python3 tests/windows/cmd_hook_test.py

stage "hooks: Fusion 360 with Windows paths"
run_test fusion_hook_windows node tests/windows/fusion_hook_windows_test.js

exit "$failed"
