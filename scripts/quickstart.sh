#!/usr/bin/env bash
# Installs what ncjoule needs (Debian packages), builds it, and runs it on a bundled sample.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
sample=samples/programs/bracket-linuxcnc.ngc
machine=samples/machines/zhou2017-anziani2025.toml
echo "== ncjoule estimate $sample --machine $machine --stock box:0,0,-20,100,60,0"
build/plugin/ncjoule estimate "$sample" --machine "$machine" --stock box:0,0,-20,100,60,0
