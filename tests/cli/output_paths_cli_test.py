#!/usr/bin/env python3
"""Where ncjoule's output goes, and what a replacement in place survives (output_file.hpp,
in_place.hpp):

- standard output and error by their names (/dev/stdout, /dev/stderr, /dev/fd/N) are written
  where they stand: `-o /dev/stdout >> log` appends, `{ echo a; ncjoule ... -o /dev/stdout;
  echo b; } > f` keeps a and b, for annotate, strip and report;
- a symbolic link another user owns is not followed (report -o, annotate -o);
- --in-place, with ncjoule stopped right before it flushes its new text (pause_io.c): a post
  appending then (open, write, close) keeps every line, and ncjoule refuses; a program opening
  the file for writing while ncjoule renames (the lease) gets the old file back with its line;
  another user's process holding the file open is seen;
- signals that end a program (USR1, ALRM, XCPU, ...) and kill -9 in the middle of a write leave
  no file behind; a temporary a killed run left is removed by the next write in its folder, which
  says so, and by doctor;
- a 250-byte file name is annotated and stripped in place.
Environment: NCJOULE, NCJOULE_SOURCE_DIR, NCJOULE_PAUSE_SHIM (the preloadable pause_io library).
"""
import os
import signal
import subprocess
import sys
import tempfile
import time

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
SHIM = os.environ["NCJOULE_PAUSE_SHIM"]
GENERIC = os.path.join(ROOT, "samples/machines/generic-3axis.toml")
SAMPLE = os.path.join(ROOT, "samples/programs/bracket-linuxcnc.ngc")
failures = []

PROGRAM = b"G21 G90\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X20 Y10\nG1 X40\nG0 Z5\nM2\n"


def check(condition, what):
    if not condition:
        print("FAIL " + what)
        failures.append(what)
    return condition


def read(path):
    with open(path, "rb") as f:
        return f.read()


def write(path, data):
    with open(path, "wb") as f:
        f.write(data)


def sh(script, cwd):
    return subprocess.run(["sh", "-c", script], cwd=cwd, capture_output=True, timeout=120,
                          env=dict(os.environ, N=NCJOULE, M=GENERIC, P=SAMPLE))


def test_standard_streams(d):
    write(os.path.join(d, "log.txt"), b"old log\n")
    r = sh('"$N" annotate "$P" -m "$M" --no-removal -o /dev/stdout >> log.txt', d)
    log = read(os.path.join(d, "log.txt"))
    check(r.returncode == 0, f"-o /dev/stdout >> log: exit {r.returncode} {r.stderr!r}")
    check(log.startswith(b"old log\n") and b"(NCJ " in log, "-o /dev/stdout >> log appends")
    r = sh('{ echo header; "$N" strip "$P" -o /dev/stdout; echo footer; } > out.txt', d)
    check(read(os.path.join(d, "out.txt")) == b"header\n" + read(SAMPLE) + b"footer\n",
          f"strip -o /dev/stdout between echoes keeps both: {r.stderr!r}")
    r = sh('"$N" strip "$P" -o /dev/stderr 2>> log.txt', d)
    log2 = read(os.path.join(d, "log.txt"))
    check(log2.startswith(log) and read(SAMPLE) in log2[len(log):],
          "strip -o /dev/stderr 2>> log appends")
    r = sh('{ echo "<!-- before -->"; "$N" report "$P" -m "$M" --no-removal -o /dev/stdout; } '
           '> page.html', d)
    page = read(os.path.join(d, "page.html"))
    check(page.startswith(b"<!-- before -->\n") and b"</html>" in page,
          f"report -o /dev/stdout after a line keeps it: {r.stderr!r}")
    r = sh('"$N" strip "$P" -o /dev/fd/3 3>> log.txt', d)
    check(read(os.path.join(d, "log.txt")).endswith(read(SAMPLE)), "-o /dev/fd/3 3>> appends")
    check(not [f for f in os.listdir(d) if "ncjoule" in f], "no temporary left in the folder")


def test_links_of_other_users(d):
    if os.geteuid() != 0:
        print("skipped: links of another user need root to make")
        return
    shared = os.path.join(d, "shared")
    os.mkdir(shared)
    os.chmod(shared, 0o1777)  # as /tmp
    victim = os.path.join(d, "root-owned.txt")
    write(victim, b"keep me\n")
    for name, command in (("report.html", ["report", SAMPLE, "-m", GENERIC, "--no-removal"]),
                          ("out.ngc", ["annotate", SAMPLE, "-m", GENERIC, "--no-removal"])):
        link = os.path.join(shared, name)
        os.symlink(victim, link)
        os.lchown(link, 65534, 65534)  # planted by another user
        r = subprocess.run([NCJOULE, *command, "-o", link], capture_output=True, timeout=120)
        check(r.returncode == 3, f"{command[0]} -o another user's link: exit {r.returncode}")
        check(b"symbolic link of another user" in r.stderr, f"... says why: {r.stderr!r}")
        check(read(victim) == b"keep me\n", f"{command[0]}: the link's target untouched")
        check(os.path.islink(link), f"{command[0]}: the link still a link")
    # The user's own link is followed, as before: the file it names gets the text.
    own = os.path.join(d, "own-link.ngc")
    target = os.path.join(d, "own-target.ngc")
    write(target, b"")
    os.symlink(target, own)
    r = subprocess.run([NCJOULE, "strip", SAMPLE, "-o", own], capture_output=True, timeout=60)
    check(r.returncode == 0 and read(target) == read(SAMPLE) and os.path.islink(own),
          f"strip -o the user's own link writes its target: {r.stderr!r}")


def paused(args, at, cwd, extra_env=None):
    """Starts ncjoule with the pause shim; returns (process, flag) once it has stopped at `at`."""
    flag = os.path.join(cwd, ".pause-flag")
    env = dict(os.environ, LD_PRELOAD=SHIM, NCJOULE_PAUSE_AT=at, NCJOULE_PAUSE_FLAG=flag)
    env.update(extra_env or {})
    proc = subprocess.Popen([NCJOULE, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            env=env, cwd=cwd)
    for _ in range(3000):
        if os.path.exists(flag) or proc.poll() is not None:
            break
        time.sleep(0.01)
    return proc, flag


def test_append_while_the_new_text_is_written(d):
    # A post that appends (open, write, close) while ncjoule writes its temporary: the check that
    # comes after the temporary is complete sees it, every time.
    for attempt in range(3):
        path = os.path.join(d, f"appended{attempt}.ngc")
        write(path, PROGRAM)
        os.utime(path, (time.time() - 60, time.time() - 60))
        proc, flag = paused(["annotate", path, "-m", GENERIC, "--no-removal", "--in-place"],
                            "fsync", d)
        check(os.path.exists(flag), f"run {attempt}: ncjoule stopped before its flush")
        with open(path, "ab") as post:
            post.write(b"G1 X99\n")
        os.remove(flag)
        out, err = proc.communicate(timeout=60)
        check(proc.returncode == 3, f"run {attempt}: exit {proc.returncode}, want 3 ({err!r})")
        check(b"changed while" in err, f"run {attempt}: says why: {err!r}")
        check(read(path) == PROGRAM + b"G1 X99\n", f"run {attempt}: the appended line kept")
    check(not [f for f in os.listdir(d) if ".ncjoule-" in f], "no temporary left")


def leases_enabled():
    try:
        with open("/proc/sys/fs/leases-enable") as f:
            return f.read().strip() == "1"
    except OSError:
        return False


def test_writer_opening_during_the_rename(d):
    if not leases_enabled():
        print("skipped: this system grants no leases")
        return
    path = os.path.join(d, "opened.ngc")
    write(path, PROGRAM)
    proc, flag = paused(["annotate", path, "-m", GENERIC, "--no-removal", "--in-place"],
                        "rename", d)
    check(os.path.exists(flag), "ncjoule stopped before its rename")
    # A post that opens the file now (its open waits for ncjoule's lease), then appends.
    writer = subprocess.Popen([sys.executable, "-c",
                               "import sys\nf = open(sys.argv[1], 'ab')\nf.write(b'G1 X77\\n')\n"
                               "f.close()", path])
    time.sleep(0.5)
    os.remove(flag)
    out, err = proc.communicate(timeout=60)
    writer.wait(timeout=60)
    check(proc.returncode == 3, f"opened during the rename: exit {proc.returncode} ({err!r})")
    check(b"put back" in err, f"... says so: {err!r}")
    check(read(path) == PROGRAM + b"G1 X77\n", f"... the old file back, with the line: "
                                                f"{read(path)[-40:]!r}")


def as_user(uid, args, **kw):
    return subprocess.Popen(["setpriv", f"--reuid={uid}", f"--regid={uid}", "--clear-groups",
                             *args], **kw)


def test_another_users_writer(d):
    # ncjoule run by one user, the file held open for writing by another's process, which that
    # user cannot see in /proc: the lease tells.
    if os.geteuid() != 0 or not leases_enabled():
        print("skipped: needs root to run as two users, and leases")
        return
    shared = os.path.join(d, "two-users")
    os.mkdir(shared)
    os.chmod(shared, 0o1777)
    path = os.path.join(shared, "shared.ngc")
    write(path, PROGRAM)
    os.chown(path, 65534, 65534)
    os.chmod(path, 0o666)
    started = os.path.join(shared, "started")
    writer = as_user(65533, [sys.executable, "-c",
                             "import sys, time\nf = open(sys.argv[1], 'ab')\n"
                             "open(sys.argv[2], 'w').close()\ntime.sleep(30)\n", path, started])
    for _ in range(500):
        if os.path.exists(started):
            break
        time.sleep(0.01)
    r = as_user(65534, [NCJOULE, "annotate", path, "-m", GENERIC, "--no-removal", "--in-place"],
                stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    out, err = r.communicate(timeout=60)
    writer.kill()
    writer.wait()
    check(r.returncode == 3, f"another user's writer: exit {r.returncode} ({err!r})")
    check(b"still being written" in err, f"... says why: {err!r}")
    check(read(path) == PROGRAM, "... the file untouched")


def test_signals_and_kill(d):
    for name in ("SIGUSR1", "SIGALRM", "SIGXCPU", "SIGTERM", "SIGKILL"):
        folder = os.path.join(d, name)
        os.mkdir(folder)
        path = os.path.join(folder, "p.ngc")
        write(path, PROGRAM)
        proc, flag = paused(["annotate", path, "-m", GENERIC, "--no-removal", "--in-place"],
                            "fsync", folder)
        proc.send_signal(getattr(signal, name))
        proc.communicate(timeout=60)
        os.remove(flag)
        left = sorted(os.listdir(folder))
        check(left == ["p.ngc"], f"{name} during the write: left {left}")
        check(read(path) == PROGRAM, f"{name}: the program untouched")


def test_stale_temporary(d):
    folder = os.path.join(d, "stale")
    os.mkdir(folder)
    write(os.path.join(folder, "p.ngc"), PROGRAM)
    # A temporary of a run killed before it could remove it: its process (a number no process
    # has) is gone.
    stale = os.path.join(folder, ".p.ngc.ncjoule-999999999-abcdefghijkl")
    write(stale, b"G1 X1\n" * 1000)
    r = subprocess.run([NCJOULE, "annotate", "p.ngc", "-m", GENERIC, "--no-removal", "-o",
                        "out.ngc"], capture_output=True, cwd=folder, timeout=60)
    check(r.returncode == 0, f"write beside a stale temporary: exit {r.returncode}")
    check(not os.path.exists(stale), "the stale temporary removed")
    check(b"removed" in r.stderr and b"interrupted run" in r.stderr, f"... and said: {r.stderr!r}")
    write(stale, b"x")
    r = subprocess.run([NCJOULE, "doctor"], capture_output=True, cwd=folder, timeout=60)
    check(not os.path.exists(stale), "doctor removes one too")
    check(b"interrupted run" in r.stdout + r.stderr, "... and says so")
    check(sorted(os.listdir(folder)) == ["out.ngc", "p.ngc"], "doctor leaves nothing behind")


def test_long_name(d):
    name = "p" * 246 + ".ngc"  # 250 bytes, as ext4 allows
    path = os.path.join(d, name)
    write(path, PROGRAM)
    r = subprocess.run([NCJOULE, "annotate", path, "-m", GENERIC, "--no-removal", "--in-place"],
                       capture_output=True, timeout=60)
    check(r.returncode == 0 and b"(NCJ " in read(path), f"250-byte name annotated: {r.stderr!r}")
    r = subprocess.run([NCJOULE, "strip", path, "--in-place"], capture_output=True, timeout=60)
    check(r.returncode == 0 and read(path) == PROGRAM, f"... and stripped: {r.stderr!r}")


def main():
    with tempfile.TemporaryDirectory() as d:
        os.chmod(d, 0o755)
        for test in (test_standard_streams, test_links_of_other_users,
                     test_append_while_the_new_text_is_written, test_writer_opening_during_the_rename,
                     test_another_users_writer, test_signals_and_kill, test_stale_temporary,
                     test_long_name):
            sub = os.path.join(d, test.__name__)
            os.mkdir(sub)
            os.chmod(sub, 0o755)
            test(sub)
    if failures:
        print(f"{len(failures)} failure(s)")
        return 1
    print("all output path checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
