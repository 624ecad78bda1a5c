#!/usr/bin/env bash
# Installs everything ncjoule needs to build and test, from Debian's packages.
# Usage: scripts/setup.sh            (run as root, or with sudo available)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  ccache                        # the package's build (scripts/package.sh) reuses build/'s objects
  libeigen3-dev libtbb-dev libceres-dev libspdlog-dev libfmt-dev doctest-dev
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev
  libpugixml-dev                # XML: MTConnect device files and Streams documents (core/logs)
  zlib1g-dev                    # inflates FreeCAD documents (.FCStd, zips) beside a program
  linuxcnc-uspace               # rs274, the reference G-code interpreter used by the tests
  clang libclang-rt-14-dev      # libFuzzer for scripts/fuzz.sh
  clang-format python3 bc time  # bc: arithmetic in the bench/ scripts; time: peak memory
  freecad-python3               # freecadcmd: scripts/make_freecad_samples.py (FreeCAD's posts)
  chromium                      # headless browser: the HTML report's screenshot test
  nodejs                        # node: runs the Fusion 360 post hook under test (tests/hooks)
  # The Debian package (scripts/package.sh, scripts/test-package.sh): dpkg-deb, dpkg-shlibdeps
  # for its Depends, man pages from --help, a fresh Debian 12 root to install it in, its lint.
  dpkg-dev help2man debootstrap lintian
)

. "$(dirname "$0")/lib.sh"
install_packages "${packages[@]}"
