# Post-processor hooks (postprocessor-templates/): hostile settings and file names must never run
# a command or reach a file they do not name. Sourced by scripts/attack.sh: uses case_, check_, $N, $M,
# $P and $root, runs in its folder, adds to $failures.
hook="$root/postprocessor-templates/generic/ncjoule-hook.sh"

# strips_to FILE ORIGINAL: FILE is ORIGINAL annotated (changed, and strip gives it back).
strips_to() { ! cmp -s -- "$1" "$2" && "$N" strip -- "$1" 2> /dev/null | cmp -s - "$2"; }
# holds TEXT FILE: FILE holds exactly TEXT.
holds() { printf '%s' "$1" | cmp -s - "$2"; }
tiny=$'G0 X0\nM2\n'

# NCJOULE_ARGS is split at blanks, never evaluated: ncjoule refuses the stray words, and
# --strict says the file was not annotated.
cp "$P" hook_args.ngc
# shellcheck disable=SC2016 # the $( ) and backticks are the attack: they must stay text
case_ "hook: NCJOULE_ARGS '; touch X'" 1 "not annotated" -- \
  env NCJOULE_ARGS='--no-removal; touch X $(touch X) `touch X`' \
  bash "$hook" --strict --ncjoule "$N" --machine "$M" hook_args.ngc
check_ "hook: ... ran no command" test ! -e X
check_ "hook: ... left the file alone" cmp -s "$P" hook_args.ngc

# A link in a watched folder to a file outside it: never followed, the target unchanged.
mkdir hook_watch
cp "$P" hook_outside.ngc
ln -s ../hook_outside.ngc hook_watch/passwd.ngc
case_ "hook: link out of a watched folder" 1 "symbolic link" -- \
  env NCJOULE_QUIET=0 bash "$hook" --strict --ncjoule "$N" --machine "$M" \
  --watch hook_watch --once --interval 0.2
check_ "hook: ... its target unchanged" cmp -s "$P" hook_outside.ngc
check_ "hook: ... the link still a link" test -L hook_watch/passwd.ngc

# A post's file named like an option is a file.
cp "$P" ./-x.ngc
case_ "hook: a file named -x.ngc" 0 "" -- bash "$hook" --strict --ncjoule "$N" --machine "$M" -x.ngc
check_ "hook: ... annotated" strips_to -x.ngc "$P"

# A name with a quote, as a Fusion post may write it, beside the name without it: each file is
# its own (a hook that dropped the quote rewrote the other one).
cp "$P" 'part"v2.nc'
printf '%s' "$tiny" > partv2.nc
case_ "hook: a name with a quote" 0 "" -- bash "$hook" --strict --ncjoule "$N" --machine "$M" 'part"v2.nc'
check_ "hook: ... the other file untouched" holds "$tiny" partv2.nc
check_ "hook: ... its own file annotated" strips_to 'part"v2.nc' "$P"

# The same through the Fusion hook, with execute() run by a shell as on macOS and Linux.
if command -v node > /dev/null 2>&1; then
  # shellcheck disable=SC2016 # the $( ) is part of the name
  quoted='fusion "q" $(touch X) it'\''s.nc'
  # shellcheck disable=SC2016
  bystander='fusion q $(touch X) it'\''s.nc'
  cp "$P" "$quoted"
  printf '%s' "$tiny" > "$bystander"
  cat > fusion_post.js << 'END'
// A post engine that runs the hook on one file: execute() goes through /bin/sh.
const cp = require("child_process"), fs = require("fs"), vm = require("vm");
const [hook, program, machine, out] = process.argv.slice(2);
const warnings = [];
const engine = {
  getOutputPath: () => out, getPlatform: () => "LINUX", warning: (m) => warnings.push(m), log() {},
  getProperty: (n) => ({ncjoulePath: program, ncjouleMachine: machine})[n],
  execute: (p, args) => cp.spawnSync("/bin/sh", ["-c", 'exec "$0" ' + args, p]).status,
  FileSystem: {isFile: (p) => fs.existsSync(p), getFolderPath: () => "."},
};
vm.runInContext(fs.readFileSync(hook, "utf8"), vm.createContext(engine));
engine.onTerminate();
if (warnings.length) { console.error(warnings.join("\n")); process.exit(1); }
END
  case_ "fusion hook: quotes, \$(), blanks" 0 "" -- node fusion_post.js \
    "$root/postprocessor-templates/fusion360/ncjoule-hook.cps.js" "$N" "$M" "$quoted"
  check_ "fusion hook: ... ran no command" test ! -e X
  check_ "fusion hook: ... the other file untouched" holds "$tiny" "$bystander"
  check_ "fusion hook: ... its own file annotated" strips_to "$quoted" "$P"
fi
