#!/usr/bin/env bash
# Cross-builds ncjoule for Windows x64 on Debian 12 with MinGW-w64 (g++-mingw-w64-x86-64-posix)
# and writes dist/ncjoule-VERSION-win64.zip: ncjoule.exe, ncjoule.dll (the C API) and the runtime
# DLLs they load, the C header, the machine profiles, the hooks for Windows CAM systems and a
# README for Windows users.
#
# Every feature is in: removal runs on TBB, calibrate on Ceres, the controller logs (check-log,
# calibrate --timing) read XML with pugixml. Debian ships those three only as Linux binaries, so
# they are built for Windows from Debian's own source packages (apt-get source, with a deb-src
# entry this script adds); the header-only libraries (Eigen, CLI11, toml++,
# nlohmann-json, spdlog and fmt in their header-only modes) are taken from Debian's -dev packages.
# Nothing is downloaded from anywhere but Debian's archive.
#
# The third-party builds are kept in build-win/deps (outside the tracked tree), so a second run
# only rebuilds ncjoule. Usage: scripts/build-windows.sh   (as root, or with sudo available)
# Environment: NCJOULE_WIN_DIR (default build-win), JOBS (default: the number of cores).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
. scripts/lib.sh # (the folder is the repository's root here)
out=$(windows_build_dir)
deps=$out/deps
prefix=$deps/prefix # the Windows builds of the libraries, installed
jobs=${JOBS:-$(nproc)}

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

# Each stage is timed; the times are printed at the end (and when a stage fails).
trap 'print_stage_times build-windows.sh' EXIT

stage "Debian packages"
# The cross compiler, the tools apt-get source needs, zip; the header-only libraries come from
# the -dev packages scripts/setup.sh installs (listed again here so this script stands alone).
packages=(
  g++-mingw-w64-x86-64-posix binutils-mingw-w64-x86-64 # the Windows x64 cross compiler (posix threads)
  dpkg-dev                                             # apt-get source unpacks with dpkg-source
  cmake ninja-build zip bc
  libz-mingw-w64-dev                                   # zlib for Windows: FreeCAD documents are zips
  libeigen3-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libspdlog-dev libfmt-dev
)
install_packages "${packages[@]}"
cc=x86_64-w64-mingw32-gcc-posix
cxx=x86_64-w64-mingw32-g++-posix

stage "Debian source packages (onetbb, ceres-solver, pugixml)"
mkdir -p "$deps/src"
need_source=()
for src in onetbb ceres-solver pugixml; do
  [ -f "$deps/src/$src.unpacked" ] || need_source+=("$src")
done
if [ "${#need_source[@]}" -gt 0 ]; then
  # The source index of bookworm, from Debian's archive like the binary packages.
  if ! apt-cache showsrc onetbb 2>/dev/null | grep -q '^Package: onetbb'; then
    "${sudo_cmd[@]}" tee /etc/apt/sources.list.d/ncjoule-deb-src.sources >/dev/null <<'EOF'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
    "${sudo_cmd[@]}" apt-get update
  fi
  for src in "${need_source[@]}"; do
    rm -rf "$deps/src/$src"
    mkdir -p "$deps/src/$src"
    # Downloaded as this user into the cache (apt's sandbox user may not write there).
    (cd "$deps/src/$src" && apt-get source -q -o APT::Sandbox::User=root "$src" >/dev/null)
    touch "$deps/src/$src.unpacked"
  done
fi
tbb_src=$(find "$deps/src/onetbb" -mindepth 1 -maxdepth 1 -type d | head -n1)
ceres_src=$(find "$deps/src/ceres-solver" -mindepth 1 -maxdepth 1 -type d | head -n1)
pugixml_src=$(find "$deps/src/pugixml" -mindepth 1 -maxdepth 1 -type d | head -n1)

# The toolchain: Windows x64 with MinGW-w64's posix-thread compilers; libraries and packages are
# looked for only in the MinGW sysroot and the prefix built here, never in Linux's /usr.
mkdir -p "$prefix"
cat >"$deps/toolchain.cmake" <<EOF
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(CMAKE_C_COMPILER $cc)
set(CMAKE_CXX_COMPILER $cxx)
set(CMAKE_RC_COMPILER x86_64-w64-mingw32-windres)
set(CMAKE_FIND_ROOT_PATH /usr/x86_64-w64-mingw32 "$prefix")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
EOF
# A library's build and install, its compiler's chatter in a log shown only when it fails.
build_logged() {
  if ! cmake --build "$1" --parallel "$jobs" >"$1.log" 2>&1; then
    tail -n 60 "$1.log" >&2
    echo "the build in $1 failed; its log: $1.log" >&2
    exit 1
  fi
  cmake --install "$1" >/dev/null
}
cross=(-G Ninja -DCMAKE_TOOLCHAIN_FILE="$deps/toolchain.cmake" -DCMAKE_BUILD_TYPE=Release
       -DCMAKE_INSTALL_PREFIX="$prefix" -DCMAKE_PREFIX_PATH="$prefix")

stage "header-only libraries (Debian's -dev packages)"
# Their headers are copied into the prefix (so that no -I/usr/include reaches the cross
# compiler), each with a small CMake package file that gives the target ncjoule links.
if [ ! -f "$prefix/header-only.done" ]; then
  mkdir -p "$prefix/include" "$prefix/share"
  cp -r /usr/include/eigen3 "$prefix/include/"
  mkdir -p "$prefix/share/eigen3"
  cp -r /usr/share/eigen3/cmake "$prefix/share/eigen3/" # finds include/eigen3 relative to itself
  for h in CLI toml++ nlohmann spdlog fmt; do cp -r "/usr/include/$h" "$prefix/include/"; done
  # Debian's spdlog is configured for its shared fmt library: here fmt is header-only too.
  sed -i 's|^#define SPDLOG_FMT_EXTERNAL 1|#define SPDLOG_FMT_EXTERNAL 1\n#define FMT_HEADER_ONLY 1|' \
    "$prefix/include/spdlog/tweakme.h"
  shim() { # package target version definitions
    local dir="$prefix/lib/cmake/$1"
    mkdir -p "$dir"
    cat >"$dir/$1Config.cmake" <<EOF
# Header-only use of Debian's $1 headers (written by scripts/build-windows.sh).
if(NOT TARGET $2)
  add_library($2 INTERFACE IMPORTED)
  set_target_properties($2 PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "\${CMAKE_CURRENT_LIST_DIR}/../../../include"
    INTERFACE_COMPILE_DEFINITIONS "$4")
endif()
set($1_FOUND TRUE)
EOF
    cat >"$dir/$1ConfigVersion.cmake" <<EOF
set(PACKAGE_VERSION "$3")
if(PACKAGE_FIND_VERSION VERSION_GREATER PACKAGE_VERSION)
  set(PACKAGE_VERSION_COMPATIBLE FALSE)
else()
  set(PACKAGE_VERSION_COMPATIBLE TRUE)
  if(PACKAGE_FIND_VERSION STREQUAL PACKAGE_VERSION)
    set(PACKAGE_VERSION_EXACT TRUE)
  endif()
endif()
EOF
  }
  version_of() { dpkg-query -W -f='${Version}' "$1" | sed 's/^[0-9]*://; s/[-+~].*//'; }
  shim CLI11 CLI11::CLI11 "$(version_of libcli11-dev)" ""
  shim tomlplusplus tomlplusplus::tomlplusplus "$(version_of libtomlplusplus-dev)" "TOML_HEADER_ONLY=1"
  shim nlohmann_json nlohmann_json::nlohmann_json "$(version_of nlohmann-json3-dev)" ""
  shim spdlog spdlog::spdlog "$(version_of libspdlog-dev)" "SPDLOG_FMT_EXTERNAL;FMT_HEADER_ONLY"
  touch "$prefix/header-only.done"
fi

stage "oneTBB for Windows (Debian source)"
if [ ! -f "$prefix/tbb.done" ]; then
  rm -rf "$deps/tbb-build"
  cmake -S "$tbb_src" -B "$deps/tbb-build" "${cross[@]}" -DBUILD_SHARED_LIBS=ON \
    -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF -DTBB_STRICT=OFF -DTBBMALLOC_BUILD=OFF \
    -DTBB_ENABLE_IPO=OFF >"$deps/tbb-configure.log"
  build_logged "$deps/tbb-build"
  touch "$prefix/tbb.done"
fi

stage "Ceres for Windows (Debian source, minimal)"
if [ ! -f "$prefix/ceres.done" ]; then
  rm -rf "$deps/ceres-build"
  # Only what calibrate uses: dense solvers on Eigen, no SuiteSparse/LAPACK, glog replaced by
  # Ceres' own miniglog (errors only on stderr, as glog prints them by default), no specialised
  # Schur solvers, tests, examples or benchmarks.
  cmake -S "$ceres_src" -B "$deps/ceres-build" "${cross[@]}" -DBUILD_SHARED_LIBS=OFF \
    -DMINIGLOG=ON -DMINIGLOG_MAX_LOG_LEVEL=-2 -DGFLAGS=OFF -DSUITESPARSE=OFF -DCXSPARSE=OFF -DACCELERATESPARSE=OFF \
    -DLAPACK=OFF -DEIGENSPARSE=ON -DSCHUR_SPECIALIZATIONS=OFF -DCUSTOM_BLAS=ON \
    -DUSE_CUDA=OFF -DBUILD_TESTING=OFF -DBUILD_EXAMPLES=OFF -DBUILD_BENCHMARKS=OFF \
    -DBUILD_DOCUMENTATION=OFF -DPROVIDE_UNINSTALL_TARGET=OFF >"$deps/ceres-configure.log"
  build_logged "$deps/ceres-build"
  touch "$prefix/ceres.done"
fi

stage "pugixml for Windows (Debian source)"
if [ ! -f "$prefix/pugixml.done" ]; then
  rm -rf "$deps/pugixml-build"
  # A static library: linked into ncjoule.dll, no DLL of its own to ship.
  cmake -S "$pugixml_src" -B "$deps/pugixml-build" "${cross[@]}" -DBUILD_SHARED_LIBS=OFF \
    -DPUGIXML_BUILD_TESTS=OFF >"$deps/pugixml-configure.log"
  build_logged "$deps/pugixml-build"
  touch "$prefix/pugixml.done"
fi

stage "ncjoule for Windows"
# Statically linked C++ runtime would give each of exe and dll its own copy of the C++ runtime's
# state; the shared runtime DLLs go into the zip instead.
cmake -S "$root" -B "$out/ncjoule" "${cross[@]}" -DNCJOULE_BUILD_TESTS=OFF \
  -DNCJOULE_SOURCE_PROFILES=OFF -U NCJOULE_STAGES -U NCJOULE_COMMANDS >"$out/ncjoule-configure.log" ||
  { cat "$out/ncjoule-configure.log"; exit 1; }
cmake --build "$out/ncjoule" --parallel "$jobs" --target ncjoule ncjoule_shared

stage "dist zip"
version=$(sed -n 's/^project(ncjoule VERSION \([0-9.]*\).*/\1/p' "$root/CMakeLists.txt")
name=ncjoule-$version-win64
pkg=$out/$name
rm -rf "$pkg"
mkdir -p "$pkg/bin" "$pkg/include" "$pkg/share/ncjoule/machines" "$pkg/hooks/fusion360" \
  "$pkg/hooks/generic"
cp "$out/ncjoule/plugin/ncjoule.exe" "$pkg/bin/"
cp "$out/ncjoule/plugin/"*ncjoule*.dll "$pkg/bin/"
# The DLLs the program loads that Windows does not have: found by walking the import tables
# from ncjoule.exe through every DLL it pulls in.
find_dll() {
  local d
  for d in "$prefix/bin" "$(dirname "$($cxx -print-libgcc-file-name)")" \
    /usr/x86_64-w64-mingw32/lib /usr/lib/gcc/x86_64-w64-mingw32/*-posix; do
    [ -f "$d/$1" ] && { echo "$d/$1"; return 0; }
  done
  return 1
}
queue=("$pkg/bin/ncjoule.exe" "$pkg/bin/"*.dll)
while [ "${#queue[@]}" -gt 0 ]; do
  file=${queue[0]}
  queue=("${queue[@]:1}")
  for dll in $(x86_64-w64-mingw32-objdump -p "$file" | sed -n 's/^\s*DLL Name: //p'); do
    [ -f "$pkg/bin/$dll" ] && continue
    if found=$(find_dll "$dll"); then
      cp "$found" "$pkg/bin/"
      queue+=("$pkg/bin/$dll")
    fi
  done
done
x86_64-w64-mingw32-strip --strip-unneeded "$pkg/bin/"*.exe "$pkg/bin/"*.dll
cp "$root/plugin/capi/ncjoule.h" "$pkg/include/"
mkdir -p "$pkg/lib"
cp "$out/ncjoule/plugin/libncjoule.dll.a" "$pkg/lib/" # the import library, for MinGW users
cp "$root/samples/machines/"*.toml "$pkg/share/ncjoule/machines/"
cp "$root/postprocessor-templates/fusion360/"* "$pkg/hooks/fusion360/"
cp "$root/postprocessor-templates/generic/ncjoule-hook.cmd" \
  "$root/postprocessor-templates/generic/README.md" "$pkg/hooks/generic/"
cp "$root/docs/windows.md" "$pkg/README.md"
# Text files with Windows line ends, so that Notepad of older Windows shows them right.
for f in "$pkg/README.md" "$pkg/hooks/"*/*.md "$pkg/hooks/generic/ncjoule-hook.cmd"; do
  sed -i 's/\r$//; s/$/\r/' "$f"
done
mkdir -p "$root/dist"
rm -f "$root/dist/$name.zip"
(cd "$out" && zip -qr "$root/dist/$name.zip" "$name")
echo "wrote dist/$name.zip ($(du -h "$root/dist/$name.zip" | cut -f1)):" >&2
(cd "$out" && find "$name" -type f | sort) >&2
