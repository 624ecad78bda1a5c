#!/usr/bin/env bash
# Installs what ncjoule needs (Debian packages), builds it, and runs it on a bundled sample.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
sample=samples/programs/bracket-linuxcnc.ngc
echo "== ncjoule canon $sample (first 20 commands)"
build/plugin/ncjoule canon "$sample" | head -n 20
