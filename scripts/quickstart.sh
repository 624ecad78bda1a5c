#!/usr/bin/env bash
# Installs what ncjoule needs (Debian packages), builds it, and runs it on a bundled sample.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
sample=samples/programs/bracket-linuxcnc.ngc
machine=samples/machines/zhou2017-anziani2025.toml
stock=box:0,0,-20,100,60,0
echo "== ncjoule estimate $sample --machine $machine --stock $stock"
build/plugin/ncjoule estimate "$sample" --machine "$machine" --stock "$stock"
annotated=$(mktemp "${TMPDIR:-/tmp}/ncjoule-quickstart.XXXXXX")
trap 'rm -f "$annotated"' EXIT
echo
echo "== ncjoule annotate $sample --machine $machine --stock $stock -o $annotated"
build/plugin/ncjoule annotate "$sample" --machine "$machine" --stock "$stock" -o "$annotated"
echo "== the first 25 lines of the annotated program:"
head -n 25 "$annotated"
