#!/usr/bin/env bash
# Configures and builds ncjoule in build/ (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DNCJOULE_STAGES="gcode;machine;kinematics;removal;energy;estimate;annotate;report" -DNCJOULE_COMMANDS=""
cmake --build build --parallel "$(nproc)"
