# Shell functions the scripts share (sourced, not run).

# Installs the Debian packages given that are not installed yet (as root, or with sudo).
install_packages() {
  local sudo_cmd=() missing=() p
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ "${#missing[@]}" -gt 0 ]; then
    export DEBIAN_FRONTEND=noninteractive
    "${sudo_cmd[@]}" apt-get update
    "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
  fi
}

# Timed stages: `stage NAME` ends the stage before and starts this one; print_stage_times TITLE
# ends the last one and prints every stage's seconds and the total to stderr.
stage_names=()
stage_times=()
stage_start=0
stage() {
  stage_end
  stage_names+=("$1")
  stage_start=$(date +%s.%N)
  echo "== $1" >&2
}
stage_end() {
  if [ "${#stage_names[@]}" -gt "${#stage_times[@]}" ]; then
    stage_times+=("$(echo "$(date +%s.%N) - $stage_start" | bc)")
  fi
}
print_stage_times() {
  stage_end
  echo "$1 stage times:" >&2
  local total=0 k
  for k in "${!stage_times[@]}"; do
    printf '  %-48s %7.1f s\n' "${stage_names[$k]}" "${stage_times[$k]}" >&2
    total=$(echo "$total + ${stage_times[$k]}" | bc)
  done
  printf '  %-48s %7.1f s\n' "total" "$total" >&2
}

# The Windows build's folder ($NCJOULE_WIN_DIR, default build-win), made if need be, as an
# absolute path: what build-windows.sh writes and test-windows.sh reads.
windows_build_dir() {
  local dir=${NCJOULE_WIN_DIR:-build-win}
  mkdir -p "$dir"
  (cd "$dir" && pwd)
}
