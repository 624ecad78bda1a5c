"""The generic hook (postprocessor-templates/generic/ncjoule-hook.sh): a file given as argument is
annotated in place; a failure only warns and leaves the file as it was; in folder mode (--watch
with --once or --timeout) every new NC file is annotated once it has been quiet for --quiet
seconds, links, hidden files and files of other kinds are left alone. Nothing the user gives
(NCJOULE_ARGS, option values, file names) is ever evaluated; whether a file was annotated is
decided from ncjoule's exit status and status line (a stand-in ncjoule tests the hook's side of
that contract, the real one the rest).

Usage: NCJOULE=path/to/ncjoule NCJOULE_SOURCE_DIR=repo python3 generic_hook_test.py
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.environ.get("NCJOULE_SOURCE_DIR",
                      os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
NCJOULE = os.path.abspath(os.environ.get("NCJOULE", "ncjoule"))
HOOK = os.path.join(ROOT, "postprocessor-templates", "generic", "ncjoule-hook.sh")
MACHINE = os.path.join(ROOT, "samples", "machines", "haas-vf0-pavanaskar2014.toml")
SAMPLES = os.path.join(ROOT, "samples", "programs")
A = "pavanaskar-facing-x"
B = "pavanaskar-pocket-spiral-out"

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL " + message)
    return condition


def stock(name):
    with open(os.path.join(SAMPLES, name + ".stock")) as f:
        return f.read().strip()


def read(path):
    with open(path, "rb") as f:
        return f.read()


def annotated(data):
    return re.search(rb"[(;]NCJ SEAL LINES=", data, re.I) is not None


def strip(path):
    r = subprocess.run([NCJOULE, "strip", path], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    check(r.returncode == 0, "ncjoule strip failed: %s" % r.stderr.decode())
    return r.stdout


def hook(*args, env=None, timeout=120, cwd=None):
    e = {k: v for k, v in os.environ.items() if not k.startswith("NCJOULE")}
    e.update(env or {})
    return subprocess.run(["bash", HOOK] + list(args), stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, env=e, timeout=timeout, cwd=cwd)


def stub(folder, body):
    """A stand-in ncjoule (sh): `body` runs with $f the file (the last argument) and $log a file
    beside the stub; each call is logged first as "SIZE TIME" (the file's size, the clock)."""
    path = os.path.join(folder, "ncjoule-stub")
    with open(path, "w") as f:
        f.write(STUB_HEAD + body + "\n")
    os.chmod(path, 0o755)
    if os.path.exists(path + ".log"):
        os.remove(path + ".log")
    return path


STUB_HEAD = r"""#!/bin/sh
for f; do :; done
log="$0.log"
printf '%s %s\n' "$(wc -c < "$f")" "$(date +%s.%N)" >> "$log"
"""


def stub_calls(path):
    """(size, time) of each call the stub logged."""
    if not os.path.exists(path + ".log"):
        return []
    with open(path + ".log") as f:
        return [(int(a), float(b)) for a, b in (line.split() for line in f)]


def lines(output, prefix):
    return [line for line in output.decode().splitlines() if line.startswith(prefix)]


def case(name):
    print("--- " + name)


def main():
    folder = tempfile.mkdtemp(prefix="ncjoule-hook-")
    for test in (file_mode, no_evaluation, status_from_ncjoule, watch_mode, watch_links,
                 quiet_period, still_being_written):
        test(os.path.join(folder, test.__name__))
    shutil.rmtree(folder, ignore_errors=True)
    if failures:
        print("%d failure(s)" % len(failures))
        return 1
    print("all generic hook checks passed")
    return 0


def copy_sample(name, path):
    shutil.copyfile(os.path.join(SAMPLES, name + ".ngc"), path)
    return read(path)


def file_mode(folder):
    os.makedirs(folder)
    a = os.path.join(folder, "O2001 facing.nc")  # a space in the name, as Windows CAM writes them
    a_original = copy_sample(A, a)

    case("file argument: annotated in place, strip gives the posted file back")
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "--stock", stock(A), a)
    check(r.returncode == 0, "exit %d: %s" % (r.returncode, r.stderr.decode()))
    check(annotated(read(a)), "not annotated")
    check(strip(a) == a_original, "strip does not give the original back")
    check(lines(r.stdout, "ncjoule-hook: annotated ") == ["ncjoule-hook: annotated " + a],
          "stdout: %r" % r.stdout.decode())

    case("again with the same settings: nothing written, and the hook says so (new CLI)")
    first = read(a)
    mtime = os.stat(a).st_mtime_ns
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "--stock", stock(A), a)
    check(r.returncode == 0 and read(a) == first and os.stat(a).st_mtime_ns == mtime,
          "re-annotating changed the file")
    check(lines(r.stdout, "ncjoule-hook: ") == ["ncjoule-hook: %s unchanged: already annotated "
                                                "this way" % a], "stdout: %r" % r.stdout.decode())

    case("settings from the environment; other settings: the annotations are replaced")
    r = hook(a, env={"NCJOULE": NCJOULE, "NCJOULE_MACHINE": MACHINE, "NCJOULE_STOCK": stock(A),
                     "NCJOULE_ARGS": "--no-removal  --compact"})
    check(r.returncode == 0 and annotated(read(a)) and read(a) != first,
          "env settings: %s" % r.stderr.decode())
    check(strip(a) == a_original, "env settings: strip differs")

    case("a file named like an option is a file: -x.ngc alone and after --")
    for args in (["-x.ngc"], ["--", "-y.ngc"], ["--", "--strict.nc"]):
        path = os.path.join(folder, args[-1])
        original = copy_sample(A, path)
        r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "--strict", *args, cwd=folder)
        check(r.returncode == 0 and annotated(read(path)) and strip(path) == original,
              "%r: exit %d %r" % (args, r.returncode, r.stderr.decode()))
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "-z.ngc", cwd=folder)
    check(r.returncode == 2 and "unknown option -z.ngc" in r.stderr.decode(),
          "a missing -z.ngc is an unknown option: %d %r" % (r.returncode, r.stderr.decode()))

    case("missing ncjoule: a warning, exit 0, file untouched; --strict exits 1")
    a_original = copy_sample(A, a)
    missing = os.path.join(folder, "no-ncjoule")
    r = hook("--ncjoule", missing, "--machine", MACHINE, a)
    check(r.returncode == 0, "missing ncjoule: exit %d" % r.returncode)
    check("warning" in r.stderr.decode() and "not found" in r.stderr.decode(),
          "missing ncjoule: %r" % r.stderr.decode())
    check(read(a) == a_original, "missing ncjoule: file changed")
    r = hook("--strict", "--ncjoule", missing, "--machine", MACHINE, a)
    check(r.returncode == 1, "--strict: exit %d" % r.returncode)

    case("ncjoule failing (bad profile): a warning with the reason, file untouched, --strict 1")
    bad = os.path.join(folder, "bad.toml")
    with open(bad, "w") as f:
        f.write("not = [ a profile\n")
    r = hook("--strict", "--ncjoule", NCJOULE, "--machine", bad, a)
    check(r.returncode == 1 and "exit 2" in r.stderr.decode(), "bad profile: %r" % r.stderr.decode())
    check(read(a) == a_original, "bad profile: file changed")

    case("a symbolic link named as the file is not followed")
    link = os.path.join(folder, "link.nc")
    os.symlink(a, link)
    r = hook("--strict", "--ncjoule", NCJOULE, "--machine", MACHINE, link)
    check(r.returncode == 1 and "symbolic link" in r.stderr.decode() and read(a) == a_original,
          "link: %d %r" % (r.returncode, r.stderr.decode()))

    case("no machine given: ncjoule takes the user config's, as on the command line")
    config = os.path.join(folder, "config")
    os.makedirs(os.path.join(config, "ncjoule"))
    with open(os.path.join(config, "ncjoule", "config.toml"), "w") as f:
        f.write('machine = "haas-vf2"\n')
    c = os.path.join(folder, "config-machine.nc")
    shutil.copyfile(os.path.join(SAMPLES, A + ".ngc"), c)
    r = hook("--strict", "--ncjoule", NCJOULE, c, env={"XDG_CONFIG_HOME": config})
    check(r.returncode == 0 and re.search(rb"NCJ MACHINE NAME=\S+ PROFILE=haas-vf2\.toml", read(c), re.I),
          "no --machine: not annotated with the config's machine: %d %r" % (r.returncode, r.stderr.decode()))

    case("NCJOULE_DISABLE=1: nothing happens")
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, a, env={"NCJOULE_DISABLE": "1"})
    check(r.returncode == 0 and read(a) == a_original, "disabled: file changed")


def no_evaluation(folder):
    os.makedirs(folder)
    a = os.path.join(folder, "a.nc")
    a_original = copy_sample(A, a)

    case("NCJOULE_ARGS is split at blanks and never evaluated")
    for text in ("--no-removal; touch X", "--no-removal $(touch X)", "--no-removal `touch X`",
                 "--no-removal\ntouch X", "--no-removal && touch X", "'; touch X; '"):
        r = hook("--strict", "--ncjoule", NCJOULE, "--machine", MACHINE, a, cwd=folder,
                 env={"NCJOULE_ARGS": text})
        check(not os.path.exists(os.path.join(folder, "X")), "NCJOULE_ARGS %r ran a command" % text)
        # ncjoule refuses the stray words: nothing written, and --strict says so.
        check(r.returncode == 1 and read(a) == a_original,
              "NCJOULE_ARGS %r: exit %d, file changed: %s" % (text, r.returncode, read(a) != a_original))

    case("numbers are checked before bash evaluates them")
    for option, value in (("--quiet", "a[$(touch X)]"), ("--timeout", "x[$(touch X)]+1"),
                          ("--interval", "1; touch X")):
        r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, option, value, "--watch", folder,
                 "--once", cwd=folder)
        check(r.returncode == 2 and option in r.stderr.decode(), "%s %r: %d %r" % (
            option, value, r.returncode, r.stderr.decode()))
        check(not os.path.exists(os.path.join(folder, "X")), "%s %r ran a command" % (option, value))
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "--watch", folder, "--once", cwd=folder,
             env={"NCJOULE_QUIET": "a[$(touch X)]"})
    check(r.returncode == 2 and not os.path.exists(os.path.join(folder, "X")), "NCJOULE_QUIET")

    case("file names with quotes, $(), backticks, ; and newlines reach ncjoule as they are")
    odd = ["a'b\".nc", "$(touch X).nc", "`touch X`.nc", "x; touch X.nc", "new\nline.nc"]
    for name in odd:
        copy_sample(A, os.path.join(folder, name))
    r = hook("--strict", "--ncjoule", NCJOULE, "--machine", MACHINE, "--", *odd, cwd=folder)
    check(r.returncode == 0, "odd names: %d %r" % (r.returncode, r.stderr.decode()))
    check(all(annotated(read(os.path.join(folder, n))) for n in odd), "odd names: not all annotated")
    check(not os.path.exists(os.path.join(folder, "X")), "an odd name ran a command")


def status_from_ncjoule(folder):
    """The hook believes ncjoule's exit status and status line, not the look of the file."""
    os.makedirs(folder)
    a = os.path.join(folder, "a.nc")
    with open(a, "w") as f:
        f.write("(NCJ note CK=ABC123)\nG0 X0\nM30\n")  # looks annotated to a grep; it is not

    case("exit 0 without a status line: not annotated (an older ncjoule), --strict exits 1")
    s = stub(folder, "exit 0")
    r = hook("--strict", "--ncjoule", s, "--machine", MACHINE, a)
    check(r.returncode == 1 and "not annotated" in r.stderr.decode() and not r.stdout,
          "silent ncjoule: %d %r %r" % (r.returncode, r.stdout, r.stderr))

    case("unchanged: said as such, never 'annotated'")
    s = stub(folder, 'echo "ncjoule: $f unchanged: already annotated this way" >&2')
    r = hook("--strict", "--ncjoule", s, "--machine", MACHINE, a)
    check(r.returncode == 0 and lines(r.stdout, "ncjoule-hook:") == [
        "ncjoule-hook: %s unchanged: already annotated this way" % a], "unchanged: %r" % r.stdout)

    case("exit 2 with errors but annotated: a warning, not a failure; other exit 2: a failure")
    s = stub(folder, 'echo "ncjoule: annotated $f, with errors a controller would refuse" >&2; exit 2')
    r = hook("--strict", "--ncjoule", s, "--machine", MACHINE, a)
    check(r.returncode == 0 and "with errors" in r.stderr.decode(), "errors: %r" % r.stderr)
    s = stub(folder, 'echo "ncjoule: $f:3:1: error: bad" >&2; exit 2')
    r = hook("--strict", "--ncjoule", s, "--machine", MACHINE, a)
    check(r.returncode == 1 and "not annotated" in r.stderr.decode(), "exit 2: %r" % r.stderr)

    case("only the last line counts, and only in its own form")
    for body in ('echo "ncjoule: annotated $f" >&2; echo "ncjoule: something after it" >&2',
                 'echo "ncjoule: wrote $f" >&2', 'echo "ncjoule: annotated $f" >&2; exit 3'):
        s = stub(folder, body)
        r = hook("--strict", "--ncjoule", s, "--machine", MACHINE, a)
        check(r.returncode == 1 and "not annotated" in r.stderr.decode(), "%r: exit %d" % (body, r.returncode))

    case("a user's own (NCJ ... CK=...) comment does not stop the real ncjoule (watch mode)")
    watch = os.path.join(folder, "out")
    os.makedirs(watch)
    b = os.path.join(watch, "b.nc")
    with open(b, "wb") as f:
        f.write(b"(NCJ note CK=ABC123)\n" + read(os.path.join(SAMPLES, A + ".ngc")))
    b_original = read(b)
    r = hook("--strict", "--ncjoule", NCJOULE, "--machine", MACHINE, "--interval", "0.5",
             "--watch", watch, "--once", env={"NCJOULE_QUIET": "1"})
    check(r.returncode == 0 and annotated(read(b)) and read(b) != b_original and
          strip(b) == b_original, "user comment: %d %r" % (r.returncode, r.stderr.decode()))

    case("stale annotations (other settings) are replaced in watch mode")
    c = os.path.join(watch, "c.nc")
    copy_sample(A, c)
    subprocess.run([NCJOULE, "annotate", c, "--machine", MACHINE, "--in-place", "--no-removal"],
                   stderr=subprocess.DEVNULL, check=True)
    stale = read(c)
    r = hook("--strict", "--ncjoule", NCJOULE, "--machine", MACHINE, "--interval", "0.5",
             "--watch", watch, "--once", env={"NCJOULE_QUIET": "1"})
    check(r.returncode == 0 and read(c) != stale and annotated(read(c)),
          "stale annotations were kept: %r" % r.stderr.decode())
    check(lines(r.stdout, "ncjoule-hook: annotated ") == ["ncjoule-hook: annotated " + c],
          "stale: stdout %r" % r.stdout.decode())


def watch_mode(folder):
    case("folder, --once: new NC files annotated; hidden and other files left alone, a file "
         "annotated this way already is not rewritten (new CLI)")
    os.makedirs(folder)
    n1 = os.path.join(folder, "O2001.NC")  # upper-case extension
    n2 = os.path.join(folder, "O3001.tap")
    done = os.path.join(folder, "O2002.nc")
    other = os.path.join(folder, "setup-sheet.txt")
    hidden = os.path.join(folder, ".O2003.nc")
    copy_sample(A, n1)
    copy_sample(B, n2)
    copy_sample(A, done)
    subprocess.run([NCJOULE, "annotate", done, "--machine", MACHINE, "--in-place"],
                   stderr=subprocess.DEVNULL, check=True)
    done_before = read(done)
    os.utime(done, (time.time() - 100, time.time() - 100))
    mtime_done = os.stat(done).st_mtime
    with open(other, "w") as f:
        f.write("G1 X1 F100\n")
    copy_sample(A, hidden)
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "--interval", "1", "--watch", folder,
             "--once", "--strict")
    check(r.returncode == 0, "watch --once: exit %d: %s" % (r.returncode, r.stderr.decode()))
    check(annotated(read(n1)), "watch: O2001.NC not annotated")
    check(annotated(read(n2)), "watch: O3001.tap not annotated")
    check(strip(n2) == read(os.path.join(SAMPLES, B + ".ngc")), "watch: strip(O3001.tap) differs")
    check(read(done) == done_before and os.stat(done).st_mtime == mtime_done,
          "watch: an annotated file was rewritten")
    check(read(other) == b"G1 X1 F100\n", "watch: a .txt file was touched")
    check(not annotated(read(hidden)), "watch: a hidden file was annotated")
    check(sorted(lines(r.stdout, "ncjoule-hook: annotated ")) == sorted(
        "ncjoule-hook: annotated " + p for p in (n1, n2)), "watch: stdout %r" % r.stdout.decode())

    case("folder with --timeout: a file still being written is taken only once it stopped growing")
    watch2 = os.path.join(folder, "out2")
    os.makedirs(watch2)
    growing = os.path.join(watch2, "O3001.nc")
    whole = read(os.path.join(SAMPLES, B + ".ngc"))
    chunks = 10

    def writer():
        # the program in ten pieces, 0.3 s apart, as a slow post (or a network copy) writes it
        with open(growing, "wb") as f:
            for i in range(chunks):
                f.write(whole[i * len(whole) // chunks:(i + 1) * len(whole) // chunks])
                f.flush()
                time.sleep(0.3)

    t = threading.Thread(target=writer)
    t.start()
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "--interval", "1", "--watch", watch2,
             "--timeout", "12")
    t.join()
    check(r.returncode == 0, "watch --timeout: exit %d: %s" % (r.returncode, r.stderr.decode()))
    check(annotated(read(growing)), "watch --timeout: the file was not annotated")
    check(strip(growing) == whole,
          "watch --timeout: annotated a partial file (strip differs from the whole program)")
    check(len(lines(r.stdout, "ncjoule-hook: annotated ")) == 1,
          "watch --timeout: annotated %r" % r.stdout.decode())

    case("folder: names with a tab, a newline and a backslash; --once ends, --timeout holds")
    watch3 = os.path.join(folder, "out3")
    os.makedirs(watch3)
    odd = [os.path.join(watch3, n) for n in ("O 4\t1.nc", "O4\n2.nc", "O4\\3.nc")]
    for path in odd:
        copy_sample(A, path)
    started = time.time()
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "--interval", "1", "--watch", watch3,
             "--once", timeout=60)
    check(r.returncode == 0 and all(annotated(read(p)) for p in odd),
          "odd names: not all annotated: %r" % r.stdout.decode())
    check(time.time() - started < 40, "odd names: --once took %.0f s" % (time.time() - started))
    started = time.time()
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "--interval", "1", "--watch", watch3,
             "--timeout", "3", timeout=60)
    check(r.returncode == 0 and time.time() - started < 15,
          "--timeout 3 stopped after %.1f s" % (time.time() - started))


def watch_links(folder):
    case("watch mode never follows a symbolic link out of the folder")
    os.makedirs(folder)
    outside = os.path.join(folder, "elsewhere")
    watch = os.path.join(folder, "out")
    os.makedirs(outside)
    os.makedirs(watch)
    victim = os.path.join(outside, "passwd")
    with open(victim, "wb") as f:
        f.write(read(os.path.join(SAMPLES, A + ".ngc")))  # a G-code file ncjoule would annotate
    victim_before = read(victim)
    os.symlink(victim, os.path.join(watch, "evil.nc"))
    os.symlink(os.path.join(watch, "real.nc"), os.path.join(watch, "inner.ngc"))  # inside, too
    real = os.path.join(watch, "real.nc")
    copy_sample(B, real)
    sub = os.path.join(watch, "sub.nc")
    os.makedirs(sub)
    copy_sample(A, os.path.join(sub, "deep.nc"))
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "--interval", "0.5", "--watch", watch,
             "--timeout", "6", "--strict", env={"NCJOULE_QUIET": "1"})
    err = r.stderr.decode()
    check(read(victim) == victim_before, "the file a link points to was changed")
    check(os.path.islink(os.path.join(watch, "evil.nc")), "the link was replaced")
    check(err.count("evil.nc is a symbolic link") == 1 and err.count("inner.ngc is a symbolic link") == 1,
          "each link is not named exactly once: %r" % err)
    check(annotated(read(real)), "the regular file beside the links was not annotated")
    check(not annotated(read(os.path.join(sub, "deep.nc"))), "a file in a subfolder was annotated")
    check(r.returncode == 1, "--strict: links are files not annotated: exit %d" % r.returncode)

    case("... not even with an ncjoule that would follow it (the hook's own check)")
    s = stub(folder, 'printf "(written through)\\n" >> "$f"; echo "ncjoule: annotated $f" >&2')
    r = hook("--ncjoule", s, "--machine", MACHINE, "--interval", "0.5", "--watch", watch, "--once",
             env={"NCJOULE_QUIET": "0"})
    check(read(victim) == victim_before, "the hook handed a link to ncjoule")
    check(len(stub_calls(s)) == 1, "the stub ran %d times, for the one regular file" % len(stub_calls(s)))


def quiet_period(folder):
    case("a file is taken only after --quiet seconds without change, by the clock")
    os.makedirs(folder)
    watch = os.path.join(folder, "out")
    os.makedirs(watch)
    s = stub(folder, 'echo "ncjoule: annotated $f" >&2')
    path = os.path.join(watch, "slow.nc")
    whole = read(os.path.join(SAMPLES, A + ".ngc"))
    finished = []

    def writer():
        # half, a pause of 2 s with the file closed (no writer to be seen), then the rest
        with open(path, "wb") as f:
            f.write(whole[:len(whole) // 2])
        time.sleep(2)
        with open(path, "ab") as f:
            f.write(whole[len(whole) // 2:])
        finished.append(time.time())

    t = threading.Thread(target=writer)
    t.start()
    # Looks 0.2 s apart: counting looks instead of the clock would take the half file.
    r = hook("--ncjoule", s, "--machine", MACHINE, "--interval", "0.2", "--watch", watch,
             "--timeout", "12", env={"NCJOULE_QUIET": "3"})
    t.join()
    calls = stub_calls(s)
    check(r.returncode == 0 and len(calls) == 1, "calls %r: %r" % (calls, r.stderr.decode()))
    if len(calls) == 1 and finished:
        check(calls[0][0] == len(whole), "taken at %d of %d bytes" % (calls[0][0], len(whole)))
        check(calls[0][1] - finished[0] >= 3, "taken %.2f s after the last write" % (
            calls[0][1] - finished[0]))

    case("NCJOULE_QUIET sets the quiet period too")
    s = stub(folder, 'echo "ncjoule: annotated $f" >&2')
    started = time.time()
    r = hook("--ncjoule", s, "--machine", MACHINE, "--interval", "0.2", "--watch", watch,
             "--once", env={"NCJOULE_QUIET": "5"})
    calls = stub_calls(s)
    check(len(calls) == 1 and calls[0][1] - started >= 5, "NCJOULE_QUIET=5: %r" % calls)


def still_being_written(folder):
    os.makedirs(folder)
    watch = os.path.join(folder, "out")
    os.makedirs(watch)
    path = os.path.join(watch, "busy.nc")
    copy_sample(A, path)
    busy = 'echo "ncjoule: $f is still being written by process 1 (post); $f is untouched" >&2; exit 3'

    case("watch mode: ncjoule's 'still being written' (exit 3): tried again later, then annotated")
    s = stub(folder, '[ "$(wc -l < "$log")" -ge 2 ] || { %s; }\necho "ncjoule: annotated $f" >&2' % busy)
    r = hook("--strict", "--ncjoule", s, "--machine", MACHINE, "--interval", "0.2", "--watch",
             watch, "--once", env={"NCJOULE_QUIET": "0"})
    check(len(stub_calls(s)) == 2 and r.returncode == 0 and
          lines(r.stdout, "ncjoule-hook:") == ["ncjoule-hook: annotated " + path],
          "busy then done: %d calls, %d %r" % (len(stub_calls(s)), r.returncode, r.stderr.decode()))

    case("watch --once: a file that stays busy is given up after a few tries")
    s = stub(folder, busy)
    r = hook("--strict", "--ncjoule", s, "--machine", MACHINE, "--interval", "0.2", "--watch",
             watch, "--once", env={"NCJOULE_QUIET": "0"}, timeout=120)
    check(len(stub_calls(s)) == 5 and r.returncode == 1 and "still being written" in r.stderr.decode(),
          "always busy: %d calls, exit %d" % (len(stub_calls(s)), r.returncode))

    case("watch --once: a file another program keeps appending to is given up after --give-up")
    growing = os.path.join(watch, "growing.nc")
    with open(growing, "w") as f:
        f.write("G21 G90\n")
    writer = subprocess.Popen([sys.executable, "-c",
                               "import sys, time\n"
                               "for k in range(300):\n"
                               "    open(sys.argv[1], 'a').write('G1 X%d F100\\n' % k)\n"
                               "    time.sleep(0.1)\n", growing])
    s = stub(folder, 'echo "ncjoule: annotated $f" >&2')
    started = time.time()
    r = hook("--strict", "--ncjoule", s, "--machine", MACHINE, "--interval", "0.2", "--watch",
             watch, "--once", "--give-up", "2", env={"NCJOULE_QUIET": "1"}, timeout=60)
    took = time.time() - started
    writer.kill()
    writer.wait()
    check(r.returncode == 1 and "kept changing for 2 s" in r.stderr.decode() and took < 20,
          "growing file: exit %d after %.1f s %r" % (r.returncode, took, r.stderr.decode()[-300:]))
    # busy.nc, quiet, is taken once; the growing file never.
    check(len(stub_calls(s)) == 1, "growing file: ncjoule was run on it: %r" % stub_calls(s))
    os.remove(growing)

    case("file mode: tried once more after the quiet period, then a warning")
    s = stub(folder, busy)
    started = time.time()
    r = hook("--strict", "--ncjoule", s, "--machine", MACHINE, "--quiet", "1", path)
    calls = stub_calls(s)
    check(len(calls) == 2 and calls[1][1] - calls[0][1] >= 1 and r.returncode == 1 and
          "not annotated" in r.stderr.decode(), "file mode busy: %r %d" % (calls, r.returncode))
    check(time.time() - started < 30, "file mode busy took %.0f s" % (time.time() - started))


if __name__ == "__main__":
    sys.exit(main())
