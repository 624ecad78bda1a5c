#!/usr/bin/env bash
# ncjoule hook for CAM systems that can only run a program after posting, or only write into a
# folder (Mastercam, Vectric, SolidCAM, Estlcam, ...).
#
#   ncjoule-hook.sh [OPTIONS] [--] FILE...       annotate each FILE in place
#   ncjoule-hook.sh [OPTIONS] --watch DIR        annotate every NC file that appears in DIR
#
# Options:
#   --machine PROFILE   machine profile: a .toml file or a shipped profile's name; default
#                       $NCJOULE_MACHINE, else what ncjoule itself takes (the job file's
#                       machine, the user config's `machine = ...`, else its generic profile)
#   --ncjoule PATH      the ncjoule program; default $NCJOULE, else ncjoule on the PATH
#   --stock TEXT        ncjoule's --stock text; default $NCJOULE_STOCK (empty: box of the cuts)
#   --arg ARGUMENT      one more argument for `ncjoule annotate`, passed as it is (repeatable)
#   --ext "LIST"        watched extensions, default "nc ngc tap cnc gcode nci mpf eia" (any case)
#   --interval S        seconds between two looks at the folder (default 2)
#   --quiet S           a file is taken once its size and time have not changed for S whole
#                       seconds by the clock (default 3; $NCJOULE_QUIET)
#   --once              watch mode: annotate what is in the folder now (once each file is
#                       quiet), then exit; a file that keeps changing is given up after
#                       --give-up seconds
#   --give-up S         with --once: how long a file may keep changing before it is left
#                       unannotated with a warning (default 60; $NCJOULE_GIVE_UP)
#   --timeout S         watch mode: stop after S seconds (default: run until stopped)
#   --strict            exit 1 when any file was not annotated (default: warn, exit 0)
#   --                  the arguments after it are files, whatever they look like
# An argument that starts with '-' and is none of these options is a file when a file of that
# name exists (a post's "-x.ngc"); otherwise it is refused as an unknown option.
#
# NCJOULE_ARGS holds further arguments for `ncjoule annotate`: it is split at blanks (spaces,
# tabs, newlines) and never evaluated, so quotes, $, `, ;, * and \ reach ncjoule as they are
# written; an argument with a blank in it goes in --arg. "--" and --follow-symlinks are not
# passed on. NCJOULE_DISABLE=1 turns the hook off (it then does nothing and exits 0).
#
# A file is annotated with `ncjoule annotate [--machine=PROFILE] --in-place [...] -- FILE`, which
# writes through a temporary file: when ncjoule fails or is missing, the file stays exactly as
# the CAM system wrote it, and the hook prints a warning saying why. Whether a file was annotated
# is decided from ncjoule's exit status and its last line on stderr, never from the file's
# contents. Watch mode never follows a symbolic link (each one is named once on stderr and left
# alone) and only takes regular files in the folder itself.
set -u

machine=${NCJOULE_MACHINE:-}
ncjoule=${NCJOULE:-ncjoule}
stock=${NCJOULE_STOCK:-}
ext_list=${NCJOULE_EXT:-"nc ngc tap cnc gcode nci mpf eia"}
interval=${NCJOULE_INTERVAL:-2}
quiet=${NCJOULE_QUIET:-3}
give_up=${NCJOULE_GIVE_UP:-60}
once=0
timeout=0
strict=0
watch=""
files=()
arg_options=()
extra=() # what ncjoule gets besides the machine, the stock and the file
# In --once mode a file another program keeps writing is tried this many times, then given up.
busy_tries=5
newline=$'\n'

# A name or a message as one printable line: control characters (a newline in a file name, an
# escape sequence) become '?', so that they cannot forge lines or drive the terminal.
show() { printf '%s' "${1//[[:cntrl:]]/?}"; }
warn() { printf 'ncjoule-hook: warning: %s\n' "$(show "$*")" >&2; }
say() { printf 'ncjoule-hook: %s\n' "$(show "$*")"; }
die() { printf 'ncjoule-hook: %s\n' "$(show "$*")" >&2; exit 2; }
usage() { awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"; exit 0; }

# Numbers are checked by their characters before any use: bash evaluates a variable's text as
# an expression in $(( )), and an expression can run commands.
whole_number() {
  case $2 in '' | *[!0-9]*) die "$1 must be a whole number of seconds, not '$2'" ;; esac
}
seconds() {
  case $2 in '' | . | *[!0-9.]* | *.*.*) die "$1 must be a number of seconds, not '$2'" ;; esac
}

# One more argument for ncjoule, unless it would break the hook's guarantees: the file must be
# the one argument after the hook's own "--", and a link is never followed.
add_extra() {
  case $1 in
    --) warn "'--' among the extra arguments is not passed on (the file follows the hook's own)" ;;
    --follow-symlinks | --follow-symlinks=*) warn "--follow-symlinks is not passed on: the hook never replaces what a link points to" ;;
    *) extra+=("$1") ;;
  esac
}

while [ $# -gt 0 ]; do
  case $1 in
    --machine | --ncjoule | --stock | --ext | --interval | --quiet | --timeout | --watch | --arg | --give-up)
      [ $# -ge 2 ] || die "$1 needs a value"
      case $1 in
        --machine) machine=$2 ;;
        --ncjoule) ncjoule=$2 ;;
        --stock) stock=$2 ;;
        --ext) ext_list=$2 ;;
        --interval) interval=$2 ;;
        --quiet) quiet=$2 ;;
        --timeout) timeout=$2 ;;
        --watch) watch=$2 ;;
        --arg) arg_options+=("$2") ;;
        --give-up) give_up=$2 ;;
      esac
      shift 2 ;;
    --once) once=1; shift ;;
    --strict) strict=1; shift ;;
    -h | --help) usage ;;
    --) shift; files+=("$@"); break ;;
    -?*)
      # A post may well name its file "-x.ngc": an existing file is a file.
      if [ -e "$1" ] || [ -L "$1" ]; then files+=("$1"); shift
      else die "unknown option $1 (and no file of that name; see --help)"
      fi ;;
    *) files+=("$1"); shift ;;
  esac
done
seconds --interval "$interval"
whole_number --quiet "$quiet"
whole_number --timeout "$timeout"
whole_number --give-up "$give_up"

# Split at blanks without a shell: read neither expands nor evaluates anything; globbing is off
# all the same, in case a later change puts the words through the shell again.
if [ -n "${NCJOULE_ARGS:-}" ]; then
  set -f
  IFS=$' \t\n' read -r -d '' -a words <<<"$NCJOULE_ARGS"
  set +f
  for w in ${words[@]+"${words[@]}"}; do add_extra "$w"; done
fi
for w in ${arg_options[@]+"${arg_options[@]}"}; do add_extra "$w"; done # after NCJOULE_ARGS
set -f
IFS=$' \t\n' read -r -d '' -a exts <<<"$ext_list"
set +f

case "${NCJOULE_DISABLE:-0}" in 1 | yes | true | on) exit 0 ;; esac

if [ -z "$watch" ] && [ ${#files[@]} -eq 0 ]; then
  die "nothing to do: give FILE... or --watch DIR (see --help)"
fi

failed=0 # set when a file was not annotated (--strict exits 1 then)

# Why no file can be annotated (no ncjoule), or nothing. Without a machine profile ncjoule takes
# the job file's or the user config's, as on the command line.
not_ready() {
  if [[ $ncjoule == */* ]]; then
    [ -x "$ncjoule" ] || printf 'ncjoule not found at %s' "$ncjoule"
  elif ! command -v "$ncjoule" >/dev/null 2>&1; then
    printf '%s is not on the PATH (--ncjoule PATH or NCJOULE)' "$ncjoule"
  fi
}

# The last lines ncjoule printed, on one line.
last_lines() {
  local line out=""
  while IFS= read -r line; do out="$out${out:+ | }$line"; done < <(printf '%s\n' "$1" | tail -n 3)
  show "$out"
}

# Runs `ncjoule annotate --in-place` on one file and sets `outcome` from its exit status and its
# status line (its last line on stderr): annotated, unchanged (already annotated this way),
# errors (annotated, with errors its controller would refuse), busy (still being written or
# changed while read: nothing written, try later), link (a symbolic link: refused) or failed.
# `detail` holds the end of what ncjoule said. Every value is one argument; nothing is evaluated.
# ncjoule prints the name in its status line escaped (a newline as \x0a), and it was given this
# one file: the form of the line is what counts.
take() {
  local f=$1 err rc last
  # Even after "--", a lone "-" means standard input to ncjoule: a file of that name is ./-.
  [ "$f" = - ] && f=./-
  err=$("$ncjoule" annotate ${machine:+"--machine=$machine"} --in-place ${stock:+"--stock=$stock"} \
    ${extra[@]+"${extra[@]}"} -- "$f" 2>&1 >/dev/null </dev/null)
  rc=$?
  last=${err##*"$newline"}
  detail=$(last_lines "$err")
  outcome=failed
  case $rc:$last in
    "0:ncjoule: "*" unchanged: already annotated this way") outcome=unchanged ;;
    "0:ncjoule: annotated "*) outcome=annotated ;;
    0:*) detail="exit 0 without 'ncjoule: annotated FILE' (an older ncjoule?): $detail" ;;
    "2:ncjoule: annotated "*", with errors"* | "2:ncjoule: "*" unchanged: already annotated this way, with errors"*)
      outcome=errors ;;
    3:*"still being written"* | 3:*"changed while"*) outcome=busy ;;
    3:*"symbolic link"*) outcome="link" ;;
  esac
  [ $rc -eq 0 ] || detail="ncjoule exit $rc: $detail"
}

# Says what became of a file; remembers a file that was not annotated.
report() {
  local f=$1
  case $outcome in
    annotated) say "annotated $f" ;;
    unchanged) say "$f unchanged: already annotated this way" ;;
    errors) warn "$f annotated, with errors its controller would refuse: $detail" ;;
    *) warn "$f not annotated; the file is as it was ($detail)"; failed=1 ;;
  esac
}

# File mode: each file named on the command line.
annotate_file() {
  local f=$1
  if [ -L "$f" ]; then
    warn "$f not annotated: it is a symbolic link (name the file it points to)"
    failed=1
    return
  fi
  if [ ! -f "$f" ]; then
    warn "$f not annotated: no such file"
    failed=1
    return
  fi
  take "$f"
  if [ "$outcome" = busy ]; then
    # Still being written: once more after a quiet period.
    sleep "$quiet"
    take "$f"
  fi
  report "$f"
}

problem=$(not_ready)

if [ -z "$watch" ]; then
  for f in "${files[@]}"; do
    if [ -n "$problem" ]; then
      warn "$f not annotated: $problem"
      failed=1
    else
      annotate_file "$f" # a file annotated before gets its annotations replaced
    fi
  done
  [ $strict -eq 1 ] && [ $failed -ne 0 ] && exit 1
  exit 0
fi

# ---------------------------------------------------------------------------------------------
# Watch mode
# ---------------------------------------------------------------------------------------------
[ -d "$watch" ] || die "--watch $watch: not a folder"
[ -z "$problem" ] || die "--watch $watch: $problem"
state=$(mktemp -d "${TMPDIR:-/tmp}/ncjoule-hook.XXXXXX") || die "cannot make a temporary folder"
trap 'rm -rf "$state"' EXIT
trap 'exit 130' INT TERM

# True when the name has one of the watched extensions (any case) and is not hidden (ncjoule's
# own temporary files are hidden).
wanted() {
  local name=$1 ext e
  case $name in .*) return 1 ;; esac
  ext=${name##*.}
  [ "$ext" != "$name" ] || return 1
  shopt -s nocasematch
  for e in ${exts[@]+"${exts[@]}"}; do
    if [[ $ext == "$e" ]]; then shopt -u nocasematch; return 0; fi
  done
  shopt -u nocasematch
  return 1
}

# "size mtime inode" of a file (not of what a link points to), or nothing: a post that writes a
# new file and renames it over the old one changes the inode.
signature() {
  stat -c '%s %y %i' -- "$1" 2>/dev/null || stat -f '%z %m %i' -- "$1" 2>/dev/null
}

# The state of a file: one small file in the state folder, named by a checksum of the name, so
# that no character of a name (tab, newline, backslash) can confuse it. It holds
# "STATUS SINCE TRIES FIRST SIGNATURE": STATUS is seen (waiting to be quiet), done, failed (both
# left alone until the file changes) or link; SINCE the clock ($SECONDS) when the signature was
# first seen; TRIES how often ncjoule found it still being written; FIRST the clock when the file
# was first seen changing (--once gives it up after --give-up seconds).
state_file() {
  local sum
  sum=$(printf '%s' "$1" | cksum)
  printf '%s/%s' "$state" "${sum// /_}"
}

save() { printf '%s %s %s %s %s\n' "$2" "$3" "$4" "$5" "$6" >"$1"; }

# Timed out (--timeout)?
over() { [ "$timeout" != 0 ] && [ "$SECONDS" -ge "$timeout" ]; }

# One file of the folder at one look: recorded while it changes, taken once it has been quiet
# for more than --quiet whole seconds (so at least that long, whatever the clock's rounding).
consider() {
  local f=$1 sf status="" since=0 tries=0 first=0 old="" sig
  sf=$(state_file "${f##*/}")
  [ -f "$sf" ] && read -r status since tries first old <"$sf"
  if [ -L "$f" ]; then
    # Never followed: a link in a watched folder can point at any file of the user's.
    [ "$status" = link ] || warn "$f is a symbolic link; it is not followed and not annotated"
    [ "$status" = link ] || failed=1
    save "$sf" link 0 0 0 -
    return
  fi
  [ -f "$f" ] || return
  sig=$(signature "$f") || return
  if [ "$status" = link ] || [ "$sig" != "$old" ]; then
    # Given up on (--once): it stays so, however it goes on changing.
    if [ $once -eq 1 ] && [ "$status" = failed ] && [ "$first" != 0 ]; then
      save "$sf" failed 0 0 "$first" "$sig"
      return
    fi
    # Changing: from when it was first seen so, unless it had been taken (done, failed) since.
    case $status in seen) ;; *) first=$SECONDS ;; esac
    if [ $once -eq 1 ] && [ $((SECONDS - first)) -ge "$give_up" ]; then
      warn "$f not annotated: it kept changing for $give_up s (a program still writing it?)"
      failed=1
      save "$sf" failed 0 0 "$first" "$sig"
      return
    fi
    save "$sf" seen "$SECONDS" 0 "$first" "$sig"
    pending=$((pending + 1))
    return
  fi
  case $status in done | failed) return ;; esac
  if [ $((SECONDS - since)) -le "$quiet" ]; then
    pending=$((pending + 1))
    return
  fi
  take "$f"
  sig=$(signature "$f")
  if [ "$outcome" = busy ]; then
    tries=$((tries + 1))
    if [ $once -eq 0 ] || [ $tries -lt $busy_tries ]; then
      save "$sf" seen "$SECONDS" "$tries" "$first" "$sig" # later, once quiet again
      pending=$((pending + 1))
      return
    fi
  fi
  report "$f"
  case $outcome in
    annotated | unchanged | errors) save "$sf" "done" 0 0 0 "$sig" ;;
    *) save "$sf" failed 0 0 0 "$sig" ;;
  esac
}

# One look at the folder; `pending` counts the files not yet quiet or to be tried again.
look() {
  local f
  pending=0
  for f in "$watch"/*; do
    over && return
    wanted "${f##*/}" || continue
    consider "$f"
  done
}

# Files still changing when the hook stops were not annotated.
left_over() {
  local f status rest
  for f in "$watch"/*; do
    wanted "${f##*/}" || continue
    [ -f "$(state_file "${f##*/}")" ] || continue
    read -r status rest <"$(state_file "${f##*/}")"
    if [ "$status" = seen ]; then
      warn "$f not annotated: it changed less than $quiet s before the hook stopped"
      failed=1
    fi
  done
}

SECONDS=0
look
while :; do
  if [ $once -eq 1 ] && [ $pending -eq 0 ]; then break; fi
  if over; then left_over; break; fi
  sleep "$interval"
  look
done
[ $strict -eq 1 ] && [ $failed -ne 0 ] && exit 1
exit 0
