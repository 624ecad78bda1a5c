#!/usr/bin/env bash
# Fills DIR with the corpus programs listed in manifest.tsv, each checked against its sha256.
# Needs network access to GitHub (the programs' licences are unknown, so they are not in this
# repository). A directory of bare clones can stand in for the network: MIRROR=/path, holding
# owner+name/repo (as `git clone --bare` of each repository).
#
#   tests/corpus/fetch.sh DIR
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
dir="${1:?usage: fetch.sh DIR}"
mkdir -p "$dir"
cache="${MIRROR:-$dir/.repos}"
failed=0
while IFS=$'\t' read -r id repo path commit sha rest; do
  [ "$id" = id ] && continue
  git_dir="$cache/${repo/\//+}/repo"
  if [ ! -d "$git_dir" ]; then
    mkdir -p "$(dirname "$git_dir")"
    git clone --quiet --bare --filter=blob:none "https://github.com/$repo" "$git_dir" || {
      echo "cannot clone $repo" >&2; failed=$((failed + 1)); continue; }
  fi
  if ! git --git-dir="$git_dir" show "$commit:$path" > "$dir/$id" 2> /dev/null; then
    echo "$id: $repo has no $path at $commit" >&2; failed=$((failed + 1)); rm -f "$dir/$id"; continue
  fi
  if [ "$(sha256sum < "$dir/$id" | cut -d' ' -f1)" != "$sha" ]; then
    echo "$id: sha256 differs from the manifest" >&2; failed=$((failed + 1))
  fi
done < "$here/manifest.tsv"
echo "fetched into $dir; $failed problem(s)"
exit $((failed > 0))
