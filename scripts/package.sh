#!/usr/bin/env bash
# Builds the Debian package dist/ncjoule_VERSION_ARCH.deb from this source tree:
#   /usr/bin/ncjoule, libncjoule.so (+ its soname link) in the multiarch library folder, its header
#   /usr/include/ncjoule.h, the machine profiles in /usr/share/ncjoule/machines (found by name),
#   the post-processor hooks in /usr/share/ncjoule/hooks, the documentation in
#   /usr/share/doc/ncjoule, and man pages made from --help by help2man (ncjoule(1) and one per
#   subcommand, ncjoule-estimate(1), ...). Depends comes from the shared libraries the program
#   and the library use (dpkg-shlibdeps).
# Usage: scripts/package.sh    (the packages scripts/setup.sh installs; builds in build-pkg/)
#   NCJOULE_MAINTAINER="Name <mail>" sets the Maintainer field.
# Install with: apt-get install ./dist/ncjoule_*.deb ; scripts/test-package.sh tests that.
set -euo pipefail
cd "$(dirname "$0")/.."
umask 022

build=build-pkg
dist=dist
maintainer=${NCJOULE_MAINTAINER:-"ncjoule maintainers <ncjoule@packages.invalid>"}
for tool in cmake ninja help2man dpkg-deb dpkg-shlibdeps; do
  command -v "$tool" >/dev/null || { echo "package.sh: $tool is missing: run scripts/setup.sh" >&2; exit 1; }
done

started=$SECONDS
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
# Only what is installed is built; the installed program looks for its profiles only where it
# is installed (share/ncjoule/machines next to its bin folder), not in this source tree. Linked
# --as-needed, as Debian's packages are: no dependency on a library nothing is used from.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
  -DNCJOULE_BUILD_TESTS=OFF -DNCJOULE_SOURCE_PROFILES=OFF -U NCJOULE_STAGES -U NCJOULE_COMMANDS \
  "${launcher[@]}" \
  -DCMAKE_EXE_LINKER_FLAGS=-Wl,--as-needed -DCMAKE_SHARED_LINKER_FLAGS=-Wl,--as-needed >/dev/null
cmake --build "$build" --target ncjoule ncjoule_shared

# The package's tree: debian/ncjoule under a folder of its own, the layout dpkg-shlibdeps knows
# (a library found there belongs to the package and needs no dependency).
pkgdir=$build/deb
root=$pkgdir/debian/ncjoule
rm -rf "$pkgdir"
mkdir -p "$root"
DESTDIR="$PWD/$root" cmake --install "$build" --strip >/dev/null

arch=$(dpkg --print-architecture)
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH)
libdir=$root/usr/lib/$multiarch
[ -d "$libdir" ] || { echo "package.sh: the library is not in usr/lib/$multiarch" >&2; exit 1; }
run_installed() { LD_LIBRARY_PATH="$PWD/$libdir" PATH="$PWD/$root/usr/bin:$PATH" "$@"; }
version=$(run_installed ncjoule --version | awk '{print $2}')
[ -n "$version" ] || { echo "package.sh: the built ncjoule does not say its version" >&2; exit 1; }

# Man pages from --help: ncjoule(1), and ncjoule-SUBCOMMAND(1) through a wrapper of that name,
# so that each page is named and titled as man expects.
mandir=$root/usr/share/man/man1
mkdir -p "$mandir"
wrappers=$(mktemp -d)
trap 'rm -rf "$wrappers"' EXIT
subcommands=$(run_installed ncjoule --help | awk '/^Subcommands:/ {s = 1; next} s && /^  [a-z]/ {print $1}')
see_also=$(for s in $subcommands; do printf '.BR ncjoule-%s (1)\n' "$s"; done | paste -sd ',' - |
  sed 's/,/,\n/g')
printf '[SEE ALSO]\n%s\n' "$see_also" >"$wrappers/main.h2m"
printf '[SEE ALSO]\n.BR ncjoule (1)\n' >"$wrappers/sub.h2m"
run_installed help2man --no-info --section=1 --version-string="$version" \
  --name="predict the time and energy of a CNC milling program before it runs" \
  --include="$wrappers/main.h2m" --output="$mandir/ncjoule.1" ncjoule
for s in $subcommands; do
  printf '#!/bin/sh\nexec ncjoule %s "$@"\n' "$s" >"$wrappers/ncjoule-$s"
  chmod +x "$wrappers/ncjoule-$s"
  # The page's name: the subcommand's one-line description, as --help gives it.
  description=$(run_installed ncjoule --help | awk -v s="$s" '$1 == s {sub(/^  [a-z]+ +/, ""); print; exit}' |
    sed 's/ (.*//; s/[.:;].*//; s/^\(.\)/\L\1/')
  PATH="$wrappers:$PATH" run_installed help2man --no-info --section=1 --version-string="$version" \
    --name="$description" --include="$wrappers/sub.h2m" \
    --output="$mandir/ncjoule-$s.1" "ncjoule-$s"
done
gzip -9n "$mandir"/*.1

# Documentation: the copyright and changelog files every package carries.
docdir=$root/usr/share/doc/ncjoule
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
date=$(date -R -d "@$(git log -1 --format=%ct 2>/dev/null || date +%s)")
cat >"$docdir/copyright" <<EOF
Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/
Upstream-Name: ncjoule
Comment: Built from the ncjoule source tree (commit $commit). The tree states no licence.

Files: *
Copyright: the ncjoule authors
License: unstated
 The source tree states no licence.
EOF
printf 'ncjoule (%s) unstable; urgency=medium\n\n  * Built from the source tree at commit %s.\n\n -- %s  %s\n' \
  "$version" "$commit" "$maintainer" "$date" | gzip -9n >"$docdir/changelog.gz"

# Dependencies of the program and the library, from the packages their shared libraries are in.
mkdir -p "$root/DEBIAN"
printf 'Source: ncjoule\n\nPackage: ncjoule\nArchitecture: any\n' >"$pkgdir/debian/control"
elves=$(find "$root/usr/bin" "$libdir" -type f \( -perm -u+x -o -name '*.so*' \) | sed "s|^$pkgdir/||")
depends=$(cd "$pkgdir" && dpkg-shlibdeps -O -l"debian/ncjoule/usr/lib/$multiarch" $elves |
  sed -n 's/^shlibs:Depends=//p')
[ -n "$depends" ] || { echo "package.sh: dpkg-shlibdeps found no dependencies" >&2; exit 1; }
# The LinuxCNC filter hook (share/ncjoule/hooks/linuxcnc/ncjoule-filter) is a python3 script.
depends="$depends, python3"
rm "$pkgdir/debian/control"

soname=$(objdump -p "$libdir"/libncjoule.so.*.*.* | awk '/SONAME/ {print $2}')
printf 'libncjoule %s ncjoule (>= %s)\n' "${soname#libncjoule.so.}" "$version" >"$root/DEBIAN/shlibs"
printf 'activate-noawait ldconfig\n' >"$root/DEBIAN/triggers"
installed_size=$(du -sk --exclude=DEBIAN "$root" | cut -f1)
cat >"$root/DEBIAN/control" <<EOF
Package: ncjoule
Version: $version
Architecture: $arch
Maintainer: $maintainer
Installed-Size: $installed_size
Depends: $depends
Section: misc
Priority: optional
Description: time and energy estimates for CNC milling programs
 ncjoule reads the G-code a CAM post-processor wrote, plays it on a model of
 the machine (kinematics, stock, tool, power) and tells, block by block, how
 long the machine will take, how much material it removes and how much power
 and energy it draws. It writes the program back with one comment per block,
 compares toolpath alternatives, writes HTML reports and fits a machine's
 power constants from measurements.
 .
 This package holds the ncjoule program, the libncjoule C library and its
 header, machine profiles, and hooks for CAM post-processors (Fusion 360,
 FreeCAD, LinuxCNC and any CAM system that can run a program).
EOF
if [ -n "${NCJOULE_HOMEPAGE:-}" ]; then echo "Homepage: $NCJOULE_HOMEPAGE" >>"$root/DEBIAN/control"; fi
(cd "$root" && find . -type f ! -path './DEBIAN/*' -printf '%P\0' | sort -z | xargs -0 md5sum) \
  >"$root/DEBIAN/md5sums"
chmod 644 "$root/DEBIAN/"*

mkdir -p "$dist"
deb=$dist/ncjoule_${version}_${arch}.deb
dpkg-deb --root-owner-group -Zxz --build "$root" "$deb" >/dev/null
echo "package.sh: $deb ($(du -h "$deb" | cut -f1), built in $((SECONDS - started)) s)"
echo "  Depends: $depends"
