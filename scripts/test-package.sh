#!/usr/bin/env bash
# Tests the Debian package on a fresh Debian 12: `apt-get install ./ncjoule_*.deb` must pull its
# dependencies, and then ncjoule doctor, profiles, estimate -m NAME on a bundled sample, the man
# pages and a C program built against ncjoule.h and -lncjoule must work
# (tests/package/check-installed.sh). lintian's findings are printed; they do not fail the test.
#
# Usage: scripts/test-package.sh [DEB]      (default: the newest dist/ncjoule_*.deb)
#   As root with debootstrap: in a minimal bookworm root made by debootstrap and removed
#   afterwards. The debootstrapped root is kept as a tarball in $NCJOULE_CACHE_DIR (default
#   ~/.cache/ncjoule) for the next run; NCJOULE_DEBIAN_MIRROR chooses the mirror.
#   Otherwise, or with NCJOULE_PACKAGE_TEST=prefix, or when no root can be made (no network):
#   `apt-get install --simulate` resolves the package's dependencies on this machine, and the
#   package unpacked (dpkg -x) into a fresh folder is checked from there.
set -euo pipefail
cd "$(dirname "$0")/.."

deb=${1:-$(ls -t dist/ncjoule_*.deb 2>/dev/null | head -n 1)}
[ -n "$deb" ] && [ -f "$deb" ] || { echo "test-package.sh: no package: run scripts/package.sh" >&2; exit 1; }
deb=$(realpath "$deb")
mode=${NCJOULE_PACKAGE_TEST:-chroot}
mirror=${NCJOULE_DEBIAN_MIRROR:-http://deb.debian.org/debian}
cache=${NCJOULE_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/ncjoule}
arch=$(dpkg --print-architecture)
started=$SECONDS
if [ "$mode" = chroot ] && { [ "$(id -u)" -ne 0 ] || ! command -v debootstrap >/dev/null; }; then
  echo "test-package.sh: a chroot needs root and debootstrap: testing in a fresh prefix instead"
  mode=prefix
fi

tmp=
root=
new_tmp() {
  tmp=$(mktemp -d /tmp/ncjoule-package-test.XXXXXX)
  root=$tmp/root
}
cleanup() {
  [ -n "$tmp" ] || return 0
  if [ -n "$root" ] && mountpoint -q "$root/proc" 2>/dev/null; then
    umount "$root/proc" || umount -l "$root/proc"
  fi
  rm -rf --one-file-system "$tmp"
  tmp=
  root=
}
trap cleanup EXIT
new_tmp

# The files the checks use: the script, the C program, a bundled sample and its stock.
stage_checks() {
  mkdir -p "$1"
  cp tests/package/check-installed.sh tests/package/capi_smoke.c "$1/"
  cp samples/programs/bracket-linuxcnc.ngc "$1/sample.ngc"
  cp samples/programs/bracket-linuxcnc.stock "$1/sample.stock"
}

# A minimal Debian 12 root, from the cache when it is there.
make_root() {
  local tarball=$cache/bookworm-minbase-$arch.tar.gz
  mkdir -p "$root"
  if [ -f "$tarball" ]; then
    echo "test-package.sh: fresh Debian 12 root from $tarball"
    tar -C "$root" --numeric-owner -xpzf "$tarball"
    return
  fi
  echo "test-package.sh: debootstrap bookworm (minbase) from $mirror"
  local t0=$SECONDS
  if ! debootstrap --variant=minbase --arch="$arch" bookworm "$root" "$mirror" \
    >"$tmp/debootstrap.log" 2>&1; then
    tail -n 20 "$tmp/debootstrap.log" >&2
    return 1
  fi
  echo "test-package.sh: debootstrap took $((SECONDS - t0)) s"
  rm -rf "$root/var/cache/apt/archives/"*.deb "$root/var/lib/apt/lists/"*
  mkdir -p "$cache"
  tar -C "$root" --numeric-owner -czf "$tarball.part" . && mv "$tarball.part" "$tarball"
}

# Returns 10 when no Debian 12 root can be made here (no network, no mirror), 1 when a check
# fails.
run_chroot() {
  make_root || return 10
  # What a fresh installation has: the release, its updates and its security updates.
  printf 'deb %s bookworm main\ndeb %s bookworm-updates main\n' "$mirror" "$mirror" \
    >"$root/etc/apt/sources.list"
  printf 'deb http://security.debian.org/debian-security bookworm-security main\n' \
    >>"$root/etc/apt/sources.list"
  cp /etc/resolv.conf "$root/etc/resolv.conf"
  mount -t proc proc "$root/proc"
  local work=/root/package-test rc=0 t0=$SECONDS name
  name=$(basename "$deb")
  stage_checks "$root$work"
  cp "$deb" "$root/root/$name"
  local in_root=(chroot "$root" env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root
    DEBIAN_FRONTEND=noninteractive LANG=C.UTF-8)
  if ! "${in_root[@]}" apt-get update -q >"$tmp/apt.log" 2>&1; then
    tail -n 20 "$tmp/apt.log" >&2
    return 10
  fi
  echo "test-package.sh: apt-get install ./$name"
  if ! "${in_root[@]}" sh -c "cd /root && apt-get install -y -q ./$name" >"$tmp/install.log" 2>&1; then
    tail -n 30 "$tmp/install.log" >&2
    echo "test-package.sh: FAIL: the package does not install on a fresh Debian 12" >&2
    return 1
  fi
  echo "test-package.sh: installed with $(grep -c '^Setting up' "$tmp/install.log") packages" \
    "(its dependencies pulled) in $((SECONDS - t0)) s"
  "${in_root[@]}" sh "$work/check-installed.sh" "$work" || rc=1
  # The C API with a compiler, installed after the checks above so that they ran without one.
  t0=$SECONDS
  if "${in_root[@]}" apt-get install -y -q --no-install-recommends gcc libc6-dev \
    >"$tmp/gcc.log" 2>&1; then
    echo "test-package.sh: again with a C compiler (installed in $((SECONDS - t0)) s):"
    if "${in_root[@]}" sh "$work/check-installed.sh" "$work" >"$tmp/check-cc.log" 2>&1; then
      grep -E -A2 'C program' "$tmp/check-cc.log" || true
    else
      cat "$tmp/check-cc.log"
      rc=1
    fi
  else
    echo "note  gcc could not be installed: the C API was checked by its files only"
  fi
  return "$rc"
}

run_prefix() {
  echo "test-package.sh: the dependencies, as apt-get would install them here:"
  if ! apt-get install --simulate -q "$deb" >"$tmp/simulate.log" 2>&1; then
    tail -n 20 "$tmp/simulate.log" >&2
    echo "test-package.sh: FAIL: apt-get cannot resolve the package's dependencies" >&2
    return 1
  fi
  grep -E '^(Inst|Conf) ' "$tmp/simulate.log" | sed 's/^/  /' | head -n 40
  local prefix=$tmp/prefix multiarch
  dpkg -x "$deb" "$prefix"
  stage_checks "$tmp/work"
  multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || gcc -print-multiarch)
  env -i PATH="$prefix/usr/bin:/usr/bin:/bin" LANG=C.UTF-8 PREFIX="$prefix" \
    LD_LIBRARY_PATH="$prefix/usr/lib/$multiarch" sh tests/package/check-installed.sh "$tmp/work"
}

status=0
if [ "$mode" = chroot ]; then
  run_chroot || status=$?
  if [ "$status" -eq 10 ]; then
    echo "test-package.sh: no Debian 12 root could be made here: testing in a fresh prefix instead"
    cleanup
    new_tmp
    mode=prefix
    status=0
  fi
fi
if [ "$mode" = prefix ]; then
  run_prefix || status=$?
fi

if command -v lintian >/dev/null; then
  echo "test-package.sh: lintian (reported; it does not fail the test):"
  lintian --tag-display-limit 0 "$deb" 2>&1 | sed 's/^/  /' || true
fi
echo "test-package.sh: $([ "$status" -eq 0 ] && echo passed || echo FAILED)" \
  "in $((SECONDS - started)) s ($mode)"
exit "$status"
