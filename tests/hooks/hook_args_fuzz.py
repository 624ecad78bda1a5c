"""Randomized property test of the generic hook's argument handling
(postprocessor-templates/generic/ncjoule-hook.sh).

Each run makes files with hostile names (shell metacharacters, quotes, newlines, a leading '-',
unicode, very long names) in a folder of their own, and runs the hook on them with hostile
NCJOULE_ARGS, NCJOULE_STOCK, --arg and --machine values: once naming the files (file mode), once
watching the folder (--watch DIR --once). The ncjoule it runs is a stub that records its
arguments as JSON and answers with one of ncjoule's status lines. Properties:
  - ncjoule gets every file exactly once, its name as one argument, the last one, right after
    the one "--"; the machine, the stock and every extra argument arrive as single arguments,
    NCJOULE_ARGS split at blanks and nothing else ("--" and --follow-symlinks left out);
  - in watch mode only the regular, visible files of the watched extensions are passed: never a
    symbolic link (it points outside, at a file that must not change), a hidden file, a file of
    another extension or one in a subfolder;
  - nothing else appears in the folder or beside it (no command in a name or an argument ran),
    no file outside the folder changes, and the hook prints no raw control character;
  - with --strict the hook exits 1 exactly when a file was not annotated.

Usage: NCJOULE_SOURCE_DIR=repo python3 hook_args_fuzz.py [--runs N] [--seed S]
"""
import argparse
import hashlib
import json
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.environ.get("NCJOULE_SOURCE_DIR",
                      os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
HOOK = os.path.join(ROOT, "postprocessor-templates", "generic", "ncjoule-hook.sh")
WATCHED = ["nc", "NC", "ngc", "Tap", "cnc", "gcode", "nci", "mpf", "eia"]

# The stub ncjoule: records its arguments (one JSON list a line) and answers as STUB_MODE says.
STUB = r'''#!/usr/bin/env python3
import json, os, sys
args = sys.argv[1:]
with open(os.environ["STUB_LOG"], "a") as f:
    f.write(json.dumps(args) + "\n")
# The name as ncjoule prints it: control characters escaped (\x0a).
name = "".join("\\x%02x" % ord(c) if ord(c) < 0x20 or ord(c) == 0x7f else c
               for c in (args[-1] if args else ""))
mode = os.environ.get("STUB_MODE", "annotated")
lines = {
    "annotated": ("ncjoule: annotated %s\n", 0),
    "unchanged": ("ncjoule: %s unchanged: already annotated this way\n", 0),
    "errors": ("ncjoule: annotated %s, with errors a controller would refuse (see above)\n", 2),
    "bad": ("ncjoule: %s could not be estimated (see above); nothing was written\n", 2),
    "silent": ("", 0),
}
text, code = lines[mode]
sys.stderr.buffer.write(os.fsencode(text.replace("%s", name) if "%s" in text else text))
sys.exit(code)
'''

# Pieces of hostile names and arguments. The payloads would create PWNED (in the folder, where
# the hook runs) or a file beside the folder if anything ever evaluated them.
PAYLOADS = ["$(touch PWNED)", "`touch PWNED`", "; touch PWNED", "| touch PWNED", "& touch PWNED",
            "$(touch ../PWNED)", "'; touch PWNED; '", "\"; touch PWNED; \"", "\ntouch PWNED\n",
            "${IFS}touch${IFS}PWNED", ">PWNED", "<PWNED", "$((1+1))", "$HOME", "~", "*", "?",
            "[a-z]", "{a,b}", "!!", "\\", "\\n", "%PATH%", "^&", "#", "\t", "\r", "\x1b[31m"]
PIECES = ["a", "part", "O1001", " ", "  ", "'", "\"", "-", "--", "=", ",", ":", "@", "+", "é",
          "漢字", "Ω", "\u202e", "e\u0301", "🙂", "\u00a0", "\\", "$", "`", ";", "(", ")"]
LEADS = ["-", "--", "-x", "-o", "--stock=", "-h", "--help", " ", "~", "#", "!"]


def hostile_text(rng, max_pieces=6):
    parts = [rng.choice(PAYLOADS + PIECES) for _ in range(rng.randint(1, max_pieces))]
    return "".join(parts)


def hostile_name(rng, ext):
    """A file name with a hostile stem, ending in .ext; never '/', NUL or a hidden name."""
    stem = hostile_text(rng)
    if rng.random() < 0.4:
        stem = rng.choice(LEADS) + stem
    if rng.random() < 0.1:
        stem += "x" * rng.randint(100, 200)  # long: near the 255 bytes a name may have
    stem = stem.replace("/", "_")
    while len(os.fsencode(stem + "." + ext)) > 250:
        stem = stem[:-1]
    if stem.startswith("."):
        stem = "_" + stem
    return stem + "." + ext


def hostile_words(rng):
    """NCJOULE_ARGS: words and payloads with blanks of every kind between them."""
    out = []
    for _ in range(rng.randint(0, 6)):
        out.append(rng.choice(PAYLOADS + PIECES + ["--", "--follow-symlinks", "--no-removal",
                                                   "--follow-symlinks=true", "-o", "/etc/x"]))
        out.append(rng.choice([" ", "\t", "\n", "  ", " \t\n "]))
    return "".join(out)


def expected_extra(ncjoule_args, arg_options):
    """What the hook must pass: NCJOULE_ARGS split at spaces, tabs and newlines only, then the
    --arg values, less "--" and --follow-symlinks."""
    words = [w for w in re.split(r"[ \t\n]+", ncjoule_args) if w] + arg_options
    return [w for w in words
            if w not in ("--", "--follow-symlinks") and not w.startswith("--follow-symlinks=")]


def tree_state(top, skip):
    """Every file under top (not under skip) with its type, bytes and time."""
    state = {}
    for folder, dirs, files in os.walk(top):
        dirs[:] = [d for d in dirs if os.path.join(folder, d) not in skip]
        for name in files + dirs:
            p = os.path.join(folder, name)
            st = os.lstat(p)
            digest = ""
            if os.path.isfile(p) and not os.path.islink(p):
                with open(p, "rb") as f:
                    digest = hashlib.sha256(f.read()).hexdigest()
            state[p] = (st.st_mode, st.st_size, st.st_mtime_ns, digest,
                        os.readlink(p) if os.path.islink(p) else "")
    return state


class Failure(Exception):
    pass


def require(condition, message):
    if not condition:
        raise Failure(message)


def check_calls(calls, expected_files, machine, stock, extra):
    """Every file once, as the one argument after the one "--", the rest as the hook must pass."""
    seen = []
    for argv in calls:
        require(argv.count("--") == 1 and argv[-2] == "--",
                "the file is not the one argument after the one '--': %r" % argv)
        head = ["annotate", "--machine=" + machine, "--in-place"]
        if stock:
            head.append("--stock=" + stock)
        require(argv[:-2] == head + extra, "arguments %r, expected %r" % (argv[:-2], head + extra))
        seen.append(argv[-1])
    require(sorted(seen) == sorted(expected_files),
            "files passed %r, expected %r" % (sorted(seen), sorted(expected_files)))


def printable(output):
    return re.search(rb"[\x00-\x08\x0b-\x1f\x7f]", output) is None


def fresh_name(rng, folder, ext):
    while True:
        name = hostile_name(rng, ext)
        if not os.path.lexists(os.path.join(folder, name)):
            return name


def one_run(rng, work, stub):
    # The watched folder has a hostile name of its own at times.
    folder = os.path.join(work, hostile_name(rng, "d") if rng.random() < 0.5 else "in")
    outside = os.path.join(work, "outside")
    logs = os.path.join(work, "logs")
    for d in (folder, outside, logs):
        os.makedirs(d)
    victim = os.path.join(outside, "passwd.nc")
    with open(victim, "w") as f:
        f.write("root:x:0:0:root:/root:/bin/bash\n")

    names = []
    for _ in range(rng.randint(1, 4)):
        names.append(fresh_name(rng, folder, rng.choice(WATCHED)))
        with open(os.path.join(folder, names[-1]), "w") as f:
            f.write("G0 X0\nG1 X1 F100\nM30\n")
    # What watch mode must leave alone: a link out of the folder, a hidden file, another
    # extension, a folder with an NC name and an NC file inside it.
    os.symlink(victim, os.path.join(folder, fresh_name(rng, folder, "nc")))
    with open(os.path.join(folder, "." + fresh_name(rng, folder, "nc")), "w") as f:
        f.write("G0 X0\n")
    with open(os.path.join(folder, fresh_name(rng, folder, "txt")), "w") as f:
        f.write("setup sheet\n")
    sub = os.path.join(folder, fresh_name(rng, folder, "nc"))
    os.makedirs(sub)
    with open(os.path.join(sub, "inner.nc"), "w") as f:
        f.write("G0 X0\n")

    machine = hostile_text(rng) + ".toml"
    stock = hostile_text(rng) if rng.random() < 0.7 else ""
    ncjoule_args = hostile_words(rng)
    arg_options = [hostile_text(rng, 3) for _ in range(rng.randint(0, 2))]
    mode = rng.choice(["annotated", "annotated", "unchanged", "errors", "bad", "silent"])
    env = {k: v for k, v in os.environ.items() if not k.startswith("NCJOULE")}
    env.update({"NCJOULE_ARGS": ncjoule_args, "NCJOULE_STOCK": stock, "STUB_MODE": mode,
                "LC_ALL": "C.UTF-8"})
    options = ["--ncjoule", stub, "--machine", machine, "--strict"]
    for a in arg_options:
        options += ["--arg", a]
    extra = expected_extra(ncjoule_args, arg_options)
    not_annotated = mode in ("bad", "silent")

    listing = sorted(os.listdir(folder))
    before = tree_state(work, {logs})

    # File mode, run in the folder; names with a leading '-' either alone (an existing file is a
    # file) or after "--".
    env["STUB_LOG"] = os.path.join(logs, "files.jsonl")
    dashed = rng.random() < 0.5
    command = ["bash", HOOK] + options + (["--"] + names if dashed else names)
    r = subprocess.run(command, cwd=folder, env=env, stdin=subprocess.DEVNULL,
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120)
    details = "file mode, exit %d, stderr %r" % (r.returncode, r.stderr[-400:])
    require(r.returncode == (1 if not_annotated else 0), "exit status: " + details)
    require(printable(r.stdout) and printable(r.stderr), "raw control bytes printed: " + details)
    with open(env["STUB_LOG"]) as f:
        calls = [json.loads(line) for line in f]
    check_calls(calls, names, machine, stock, extra)

    # Watch mode, run from elsewhere: only the folder's own visible NC files.
    env["STUB_LOG"] = os.path.join(logs, "watch.jsonl")
    command = ["bash", HOOK] + options + ["--watch", folder, "--once", "--interval", "0.2",
                                          "--quiet", "0"]
    r = subprocess.run(command, cwd=logs, env=env, stdin=subprocess.DEVNULL,
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120)
    details = "watch mode, exit %d, stderr %r" % (r.returncode, r.stderr[-400:])
    # The link is never annotated: --strict says so.
    require(r.returncode == 1, "exit status: " + details)
    require(r.stderr.count(b"symbolic link") == 1, "the link is not named once: " + details)
    require(printable(r.stdout) and printable(r.stderr), "raw control bytes printed: " + details)
    with open(env["STUB_LOG"]) as f:
        calls = [json.loads(line) for line in f]
    check_calls(calls, [os.path.join(folder, n) for n in names], machine, stock, extra)

    require(sorted(os.listdir(folder)) == listing,
            "the folder changed: %r" % sorted(set(os.listdir(folder)) ^ set(listing)))
    after = tree_state(work, {logs})
    changed = sorted(p for p in set(before) | set(after) if before.get(p) != after.get(p))
    require(not changed, "files changed or appeared: %r" % changed)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=40)
    parser.add_argument("--seed", type=int, default=None)
    options = parser.parse_args()
    seed = options.seed if options.seed is not None else random.SystemRandom().randrange(2**32)
    print("seed %d (replay: hook_args_fuzz.py --seed %d --runs %d)" % (seed, seed, options.runs))
    rng = random.Random(seed)
    base = tempfile.mkdtemp(prefix="ncjoule-hook-fuzz-")
    stub = os.path.join(base, "bin", "ncjoule-stub")
    os.makedirs(os.path.dirname(stub))
    with open(stub, "w") as f:
        f.write(STUB)
    os.chmod(stub, 0o755)
    failures = 0
    for run in range(options.runs):
        work = os.path.join(base, "run%d" % run)
        os.makedirs(work)
        try:
            one_run(rng, work, stub)
            shutil.rmtree(work)
        except Failure as e:
            failures += 1
            print("FAIL run %d (kept in %s): %s" % (run, work, e))
    if failures:
        print("%d of %d runs failed (seed %d)" % (failures, options.runs, seed))
        return 1
    shutil.rmtree(base, ignore_errors=True)
    print("all %d runs held" % options.runs)
    return 0


if __name__ == "__main__":
    sys.exit(main())
