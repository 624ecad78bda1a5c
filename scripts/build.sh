#!/usr/bin/env bash
# Configures and builds ncjoule in build/ (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
# Every stage and command: -U drops a partial list an earlier configure may have cached, so the
# defaults in core/CMakeLists.txt and plugin/CMakeLists.txt (the only lists) apply.
# Through ccache when it is there: the package's build (scripts/package.sh) compiles the same
# libraries again, and takes them from the cache.
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -U NCJOULE_STAGES -U NCJOULE_COMMANDS \
  "${launcher[@]}"
cmake --build build --parallel "$(nproc)"
