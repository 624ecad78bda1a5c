#!/usr/bin/env bash
# Configures and builds ncjoule in build/ (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
# Every stage and command: -U drops a partial list an earlier configure may have cached, so the
# defaults in core/CMakeLists.txt and plugin/CMakeLists.txt (the only lists) apply.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -U NCJOULE_STAGES -U NCJOULE_COMMANDS
cmake --build build --parallel "$(nproc)"
