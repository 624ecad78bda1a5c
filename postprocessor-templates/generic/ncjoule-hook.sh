#!/bin/sh
# ncjoule hook for CAM systems that can only run a program after posting, or only write into a
# folder (Mastercam, Vectric, SolidCAM, Estlcam, ...).
#
#   ncjoule-hook.sh [OPTIONS] FILE...            annotate each FILE in place
#   ncjoule-hook.sh [OPTIONS] --watch DIR        annotate every NC file that appears in DIR
#
# Options:
#   --machine PROFILE   machine profile (.toml); default $NCJOULE_MACHINE
#   --ncjoule PATH      the ncjoule program; default $NCJOULE, else ncjoule on the PATH
#   --stock TEXT        ncjoule's --stock text; default $NCJOULE_STOCK (empty: box of the cuts)
#   --ext "LIST"        watched extensions, default "nc ngc tap cnc gcode nci mpf eia" (any case)
#   --interval S        seconds between two looks at the folder (default 2)
#   --once              watch mode: annotate what is in the folder now (once each file has
#                       stopped growing), then exit
#   --timeout S         watch mode: stop after S seconds (default: run until stopped)
#   --strict            exit 1 when a file could not be annotated (default: warn, exit 0)
#   -- ARGS...          further arguments for `ncjoule annotate` (also $NCJOULE_ARGS)
# NCJOULE_DISABLE=1 turns the hook off (it then does nothing and exits 0).
#
# A file is annotated with `ncjoule annotate FILE --machine PROFILE --in-place`, which writes
# through a temporary file: when ncjoule fails or is missing, the file stays exactly as the CAM
# system wrote it, and the hook prints a warning saying why. Files that already carry ncjoule's
# annotations are skipped; in watch mode a file is only taken once its size and time have not
# changed between two looks, so a post still writing it is left alone.
set -u

machine=${NCJOULE_MACHINE:-}
ncjoule=${NCJOULE:-ncjoule}
stock=${NCJOULE_STOCK:-}
exts="nc ngc tap cnc gcode nci mpf eia"
interval=2
once=0
timeout=0
strict=0
watch=""
extra=""
files=""
nl='
'

warn() { printf 'ncjoule-hook: warning: %s\n' "$*" >&2; }
die() { printf 'ncjoule-hook: %s\n' "$*" >&2; exit 2; }

# Quotes one word for the shell, so that file names with spaces and quotes survive eval.
quote() { printf "'%s'" "$(printf '%s' "$1" | sed "s/'/'\\\\''/g")"; }

while [ $# -gt 0 ]; do
  case "$1" in
    --machine) [ $# -ge 2 ] || die "--machine needs a value"; machine=$2; shift 2 ;;
    --ncjoule) [ $# -ge 2 ] || die "--ncjoule needs a value"; ncjoule=$2; shift 2 ;;
    --stock) [ $# -ge 2 ] || die "--stock needs a value"; stock=$2; shift 2 ;;
    --ext) [ $# -ge 2 ] || die "--ext needs a value"; exts=$2; shift 2 ;;
    --interval) [ $# -ge 2 ] || die "--interval needs a value"; interval=$2; shift 2 ;;
    --timeout) [ $# -ge 2 ] || die "--timeout needs a value"; timeout=$2; shift 2 ;;
    --watch) [ $# -ge 2 ] || die "--watch needs a folder"; watch=$2; shift 2 ;;
    --once) once=1; shift ;;
    --strict) strict=1; shift ;;
    -h|--help) sed -n '2,26p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    --) shift; for a in "$@"; do extra="$extra $(quote "$a")"; done; break ;;
    -*) die "unknown option $1 (see --help)" ;;
    *) files="$files$(quote "$1") "; shift ;;
  esac
done
[ -n "${NCJOULE_ARGS:-}" ] && extra="$extra $NCJOULE_ARGS"

case "${NCJOULE_DISABLE:-0}" in 1|yes|true|on) exit 0 ;; esac

if [ -z "$watch" ] && [ -z "$files" ]; then
  die "nothing to do: give FILE... or --watch DIR (see --help)"
fi

failed=0

# True when the file already carries ncjoule's annotations: a (NCJ ... CK=xxxxxx) or ;NCJ ...
# CK=xxxxxx comment.
is_annotated() {
  grep -Eiq '(\(|;)NCJ [^)]* CK=[0-9A-Za-z]+' "$1" 2>/dev/null
}

# Annotates one file in place; warns (and remembers the failure) when it cannot.
annotate() {
  f=$1
  if [ ! -f "$f" ]; then
    warn "$f: no such file; not annotated"
    failed=1
    return 1
  fi
  if [ -z "$machine" ]; then
    warn "$f not annotated: no machine profile (--machine PROFILE or NCJOULE_MACHINE)"
    failed=1
    return 1
  fi
  case "$ncjoule" in
    */*) [ -x "$ncjoule" ] || { warn "$f not annotated: ncjoule not found at $ncjoule"; failed=1; return 1; } ;;
    *) command -v "$ncjoule" >/dev/null 2>&1 || { warn "$f not annotated: $ncjoule is not on the PATH"; failed=1; return 1; } ;;
  esac
  cmd="$(quote "$ncjoule") annotate --machine $(quote "$machine") --in-place"
  [ -n "$stock" ] && cmd="$cmd --stock $(quote "$stock")"
  # "--" before the file: a file named like an option stays a file.
  cmd="$cmd $extra -- $(quote "$f")"
  err=$(eval "$cmd" 2>&1 </dev/null)
  rc=$?
  if [ $rc -eq 2 ] && is_annotated "$f"; then
    # Errors its controller would refuse: annotated all the same, the header lists them.
    warn "$f annotated, with errors: $(printf '%s' "$err" | grep -i 'error' | head -n 3)"
    return 0
  fi
  if [ $rc -ne 0 ]; then
    warn "$f not annotated (ncjoule exit $rc); the file is as it was: $(printf '%s' "$err" | tail -n 3)"
    failed=1
    return 1
  fi
  printf 'ncjoule-hook: annotated %s\n' "$f"
  return 0
}

if [ -z "$watch" ]; then
  eval "set -- $files"
  for f in "$@"; do
    annotate "$f" # a file annotated before gets its annotations replaced
  done
  [ $strict -eq 1 ] && [ $failed -ne 0 ] && exit 1
  exit 0
fi

# ---------------------------------------------------------------------------------------------
# Watch mode
# ---------------------------------------------------------------------------------------------
[ -d "$watch" ] || die "--watch $watch: not a folder"
state=$(mktemp -d "${TMPDIR:-/tmp}/ncjoule-hook.XXXXXX") || die "cannot make a temporary folder"
trap 'rm -rf "$state"' EXIT
trap 'exit 130' INT TERM

wanted() {
  name=$(basename "$1")
  case "$name" in .*) return 1 ;; esac # hidden, and ncjoule's own temporary files
  ext=$(printf '%s' "${name##*.}" | tr 'A-Z' 'a-z')
  [ "$ext" != "$name" ] || return 1
  for e in $exts; do
    [ "$ext" = "$(printf '%s' "$e" | tr 'A-Z' 'a-z')" ] && return 0
  done
  return 1
}

# "size mtime" of a file, or empty.
signature() {
  stat -c '%s %Y' "$1" 2>/dev/null || stat -f '%z %m' "$1" 2>/dev/null
}

# The state of a file: one small file in the state folder, named by a checksum of the path, so
# that no character of a file name (tab, newline, backslash) can confuse it. It holds
# "STATUS SIZE MTIME", STATUS being seen (waiting for it to stop growing), done or failed (not
# tried again until it changes).
state_file() {
  printf '%s/%s' "$state" "$(printf '%s' "$1" | cksum | tr ' ' '_')"
}

# One look at the folder; sets `pending` to the number of files still growing or not yet seen
# twice. Stops early when --timeout has passed.
look() {
  pending=0
  for f in "$watch"/*; do
    if [ "$timeout" != 0 ] && [ $(( $(date +%s) - start )) -ge "$timeout" ]; then return; fi
    [ -f "$f" ] || continue
    wanted "$f" || continue
    sig=$(signature "$f")
    sf=$(state_file "$f")
    old=""
    [ -f "$sf" ] && old=$(cat "$sf")
    old_status=${old%% *}
    old_sig=${old#* }
    status=seen
    if [ -n "$old" ] && [ "$old_sig" = "$sig" ]; then
      case "$old_status" in
        done|failed) status=$old_status ;;
        seen)
          if is_annotated "$f"; then
            status=done
          elif annotate "$f"; then
            status=done
            sig=$(signature "$f")
          else
            status=failed
          fi ;;
      esac
    elif is_annotated "$f"; then
      status=done # annotated already (by us, or before it arrived)
    else
      pending=$((pending + 1))
    fi
    printf '%s %s' "$status" "$sig" > "$sf"
  done
}

start=$(date +%s)
look
while :; do
  if [ "$once" -eq 1 ] && [ "$pending" -eq 0 ]; then break; fi
  if [ "$timeout" != 0 ] && [ $(( $(date +%s) - start )) -ge "$timeout" ]; then break; fi
  sleep "$interval"
  look
done
[ $strict -eq 1 ] && [ $failed -ne 0 ] && exit 1
exit 0
