"""The generic hook (postprocessor-templates/generic/ncjoule-hook.sh): a file given as argument is
annotated in place; a failure only warns and leaves the file as it was; in folder mode (--watch
with --once or --timeout) every new NC file is annotated once it has stopped growing, files
already annotated and files of other kinds are left alone.

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
    return re.search(rb"[(;]NCJ [^\n]* CK=", data, re.I) is not None


def strip(path):
    r = subprocess.run([NCJOULE, "strip", path], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    check(r.returncode == 0, "ncjoule strip failed: %s" % r.stderr.decode())
    return r.stdout


def hook(*args, env=None, timeout=120):
    e = dict(os.environ)
    for k in ("NCJOULE", "NCJOULE_MACHINE", "NCJOULE_STOCK", "NCJOULE_ARGS", "NCJOULE_DISABLE"):
        e.pop(k, None)
    e.update(env or {})
    return subprocess.run(["sh", HOOK] + list(args), stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, env=e, timeout=timeout)


def case(name):
    print("--- " + name)


def main():
    folder = tempfile.mkdtemp(prefix="ncjoule-hook-")
    a = os.path.join(folder, "O2001 facing.nc")  # a space in the name, as Windows CAM writes them
    shutil.copyfile(os.path.join(SAMPLES, A + ".ngc"), a)
    a_original = read(a)

    case("file argument: annotated in place, strip gives the posted file back")
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "--stock", stock(A), a)
    check(r.returncode == 0, "exit %d: %s" % (r.returncode, r.stderr.decode()))
    check(annotated(read(a)), "not annotated")
    check(strip(a) == a_original, "strip does not give the original back")

    case("again on the annotated file: the annotations are replaced, not doubled")
    first = read(a)
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "--stock", stock(A), a)
    check(r.returncode == 0 and read(a) == first, "re-annotating changed the file")

    case("settings from the environment")
    shutil.copyfile(os.path.join(SAMPLES, A + ".ngc"), a)
    r = hook(a, env={"NCJOULE": NCJOULE, "NCJOULE_MACHINE": MACHINE, "NCJOULE_STOCK": stock(A)})
    check(r.returncode == 0 and annotated(read(a)), "env settings: %s" % r.stderr.decode())

    case("missing ncjoule: a warning, exit 0, file untouched; --strict exits 1")
    shutil.copyfile(os.path.join(SAMPLES, A + ".ngc"), a)
    missing = os.path.join(folder, "no-ncjoule")
    r = hook("--ncjoule", missing, "--machine", MACHINE, a)
    check(r.returncode == 0, "missing ncjoule: exit %d" % r.returncode)
    check("warning" in r.stderr.decode() and "not found" in r.stderr.decode(),
          "missing ncjoule: %r" % r.stderr.decode())
    check(read(a) == a_original, "missing ncjoule: file changed")
    r = hook("--strict", "--ncjoule", missing, "--machine", MACHINE, a)
    check(r.returncode == 1, "--strict: exit %d" % r.returncode)

    case("ncjoule failing (bad profile): a warning with the reason, file untouched")
    bad = os.path.join(folder, "bad.toml")
    with open(bad, "w") as f:
        f.write("not = [ a profile\n")
    r = hook("--ncjoule", NCJOULE, "--machine", bad, a)
    check(r.returncode == 0 and "exit 2" in r.stderr.decode(), "bad profile: %r" % r.stderr.decode())
    check(read(a) == a_original, "bad profile: file changed")

    case("NCJOULE_DISABLE=1: nothing happens")
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, a, env={"NCJOULE_DISABLE": "1"})
    check(r.returncode == 0 and read(a) == a_original, "disabled: file changed")

    case("folder, --once: new NC files annotated; annotated, hidden and other files left alone")
    watch = os.path.join(folder, "out")
    os.makedirs(watch)
    n1 = os.path.join(watch, "O2001.NC")  # upper-case extension
    n2 = os.path.join(watch, "O3001.tap")
    done = os.path.join(watch, "O2002.nc")
    other = os.path.join(watch, "setup-sheet.txt")
    hidden = os.path.join(watch, ".O2003.nc")
    shutil.copyfile(os.path.join(SAMPLES, A + ".ngc"), n1)
    shutil.copyfile(os.path.join(SAMPLES, B + ".ngc"), n2)
    shutil.copyfile(os.path.join(SAMPLES, A + ".ngc"), done)
    subprocess.run([NCJOULE, "annotate", done, "--machine", MACHINE, "--in-place", "--stock", stock(A)],
                   check=True)
    done_before = read(done)
    os.utime(done, (time.time() - 100, time.time() - 100))
    mtime_done = os.stat(done).st_mtime
    with open(other, "w") as f:
        f.write("G1 X1 F100\n")
    shutil.copyfile(os.path.join(SAMPLES, A + ".ngc"), hidden)
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "--interval", "1", "--watch", watch, "--once")
    check(r.returncode == 0, "watch --once: exit %d: %s" % (r.returncode, r.stderr.decode()))
    check(annotated(read(n1)), "watch: O2001.NC not annotated")
    check(annotated(read(n2)), "watch: O3001.tap not annotated")
    check(strip(n2) == read(os.path.join(SAMPLES, B + ".ngc")), "watch: strip(O3001.tap) differs")
    check(read(done) == done_before and os.stat(done).st_mtime == mtime_done,
          "watch: an annotated file was rewritten")
    check(read(other) == b"G1 X1 F100\n", "watch: a .txt file was touched")
    check(not annotated(read(hidden)), "watch: a hidden file was annotated")
    check(r.stdout.decode().count("annotated") == 2, "watch: expected 2 files annotated: %r" % r.stdout.decode())

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
             "--timeout", "8")
    t.join()
    check(r.returncode == 0, "watch --timeout: exit %d: %s" % (r.returncode, r.stderr.decode()))
    check(annotated(read(growing)), "watch --timeout: the file was not annotated")
    check(strip(growing) == read(os.path.join(SAMPLES, B + ".ngc")),
          "watch --timeout: annotated a partial file (strip differs from the whole program)")
    check(r.stdout.decode().count("annotated") == 1, "watch --timeout: annotated %r" % r.stdout.decode())

    case("folder: names with a tab, a newline and a backslash; --once ends, --timeout holds")
    watch3 = os.path.join(folder, "out3")
    os.makedirs(watch3)
    odd = [os.path.join(watch3, n) for n in ("O 4\t1.nc", "O4\n2.nc", "O4\\3.nc")]
    for path in odd:
        shutil.copyfile(os.path.join(SAMPLES, A + ".ngc"), path)
    started = time.time()
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "--interval", "1", "--watch", watch3,
             "--once", timeout=60)
    check(r.returncode == 0 and all(annotated(read(p)) for p in odd),
          "odd names: not all annotated: %r" % r.stdout.decode())
    check(time.time() - started < 30, "odd names: --once took %.0f s" % (time.time() - started))
    started = time.time()
    r = hook("--ncjoule", NCJOULE, "--machine", MACHINE, "--interval", "1", "--watch", watch3,
             "--timeout", "3", timeout=60)
    check(r.returncode == 0 and time.time() - started < 8,
          "--timeout 3 stopped after %.1f s" % (time.time() - started))

    shutil.rmtree(folder, ignore_errors=True)
    if failures:
        print("%d failure(s)" % len(failures))
        return 1
    print("all generic hook checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
