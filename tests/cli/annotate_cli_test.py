#!/usr/bin/env python3
"""`ncjoule annotate` and `ncjoule strip` end to end.

- strip(annotate(x)) == x byte for byte, and annotating the annotated file changes nothing, on
  every program in samples/programs and every .ngc in LinuxCNC's nc_files (--no-removal there:
  their tools are defined nowhere). A program ncjoule cannot read must fail cleanly: exit 2, a
  message, no output file, no temporary file.
- LinuxCNC's own interpreter (`rs274 -g`) runs every annotated file exactly as the original: the
  same canonical commands and MESSAGE lines once the COMMENT lines are set aside.
- Failures: unreadable input, bad profile, a read-only directory, a full disk
  (/dev/full, a full file system, a file size limit): the original is untouched, the message is
  clear, the exit code is non-zero, and no temporary file is left behind.
Environment: NCJOULE (the program), NCJOULE_SOURCE_DIR (the repository), NCFILES (default:
LinuxCNC's install).
"""
import atexit
import os
import re
import resource
import shutil
import signal
import stat
import subprocess
import sys
import tempfile

# rs274 keeps its tool table in a file under $HOME (~/.tool.mmap) that every run truncates: runs
# in parallel (ctest -j) with other tool tables would read each other's. Each test gets its own.
RS274_HOME = tempfile.mkdtemp(prefix="rs274-home-")
atexit.register(shutil.rmtree, RS274_HOME, ignore_errors=True)
RS274_ENV = dict(os.environ, HOME=RS274_HOME)

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
NCFILES = os.environ.get("NCFILES", "/usr/share/linuxcnc/ncfiles")
GENERIC = os.path.join(ROOT, "samples/machines/generic-3axis.toml")
SAMPLE = os.path.join(ROOT, "samples/programs/bracket-linuxcnc.ngc")
failures = []


def check(condition, what):
    if not condition:
        print("FAIL " + what)
        failures.append(what)
    return condition


def run(*args, stdin=None, **kwargs):
    return subprocess.run([NCJOULE, *args], capture_output=True, input=stdin, timeout=300,
                          **kwargs)


def read(path):
    with open(path, "rb") as f:
        return f.read()


def temp_files(directory):
    return [n for n in os.listdir(directory) if ".ncjoule-" in n]


# ---------------------------------------------------------------------------------------------
# Round trips
# ---------------------------------------------------------------------------------------------

def annotate_options(path):
    """Samples define their tools in header comments and have their stock in a .stock file next
    to them; nc_files define neither."""
    if not path.startswith(os.path.join(ROOT, "samples")):
        return ["--no-removal"]
    stock = os.path.splitext(path)[0] + ".stock"
    if os.path.exists(stock):
        with open(stock) as f:
            return ["--stock", f.read().strip()]
    return []


def round_trip(path, workdir):
    """Annotates path into workdir; returns the annotated file or None when ncjoule refused."""
    name = re.sub(r"[^A-Za-z0-9_.-]", "_", os.path.relpath(path, os.path.dirname(path)))
    out = os.path.join(workdir, name)
    options = annotate_options(path)
    r = run("annotate", path, "--machine", GENERIC, *options, "-o", out)
    if r.returncode == 2 and not options:
        options = ["--no-removal"]
        r = run("annotate", path, "--machine", GENERIC, *options, "-o", out)
    original = read(path)
    check(r.returncode in (0, 2), f"{path}: exit 0, or 2 for errors (got {r.returncode})")
    if not os.path.exists(out):
        # Only a program that could not be estimated at all is refused.
        check(r.returncode == 2 and b"nothing was written" in r.stderr,
              f"{path}: refusal says nothing was written")
        check(not temp_files(workdir), f"{path}: refused, and no temporary file")
        return None
    if r.returncode == 2:
        # Errors its controller would refuse: annotated all the same, and the header lists them.
        check(f"ncjoule: wrote {out}, with errors".encode() in r.stderr,
              f"{path}: exit 2 says it was annotated anyway")
    annotated = read(out)
    check(b"NCJ WARN ERROR" in annotated or r.returncode == 0,
          f"{path}: the header lists the errors")
    check(annotated != original, f"{path}: annotate added something")
    s = run("strip", out)
    check(s.returncode == 0 and s.stdout == original, f"{path}: strip(annotate(x)) == x")
    again = run("annotate", out, "--machine", GENERIC, *options)
    check(again.returncode == r.returncode and again.stdout == annotated,
          f"{path}: annotate(annotate(x)) == annotate(x)")
    return out


# Programs that read their own line number (#<_line>): the header moves every line down, so they
# are compared annotated without it.
READS_LINE_NUMBERS = {"roparams.ngc"}

RS274_SEQUENCE = re.compile(rb"^\s*\d+ ")


def rs274(path, cwd):
    """rs274's canonical commands without their sequence numbers and COMMENT lines."""
    r = subprocess.run(["rs274", "-g", path], capture_output=True, stdin=subprocess.DEVNULL,
                       timeout=300, cwd=cwd, env=RS274_ENV)
    lines = [RS274_SEQUENCE.sub(b"", line) for line in r.stdout.splitlines()]
    return r.returncode, [l for l in lines if not l.lstrip().startswith(b"N..... COMMENT(")
                          and b"COMMENT(" not in l]


def same_under_rs274(original, annotated):
    cwd = os.path.dirname(original)
    code_a, lines_a = rs274(original, cwd)
    code_b, lines_b = rs274(annotated, cwd)
    return code_a == code_b and lines_a == lines_b, lines_a


def round_trips():
    programs = sorted(os.path.join(ROOT, "samples/programs", n)
                      for n in os.listdir(os.path.join(ROOT, "samples/programs"))
                      if n.lower().endswith((".ngc", ".nc", ".tap", ".gcode")))
    ncfiles = []
    for root, _, names in os.walk(NCFILES):
        ncfiles += [os.path.join(root, n) for n in names if n.endswith(".ngc")]
    ncfiles.sort()
    check(len(ncfiles) > 50, f"LinuxCNC's nc_files found under {NCFILES} ({len(ncfiles)})")
    have_rs274 = shutil.which("rs274") is not None
    check(have_rs274, "rs274 is installed (linuxcnc-uspace)")
    annotated_count = refused = rs274_same = 0
    with tempfile.TemporaryDirectory() as workdir:
        for path in programs + ncfiles:
            out = round_trip(path, workdir)
            if out is None:
                refused += 1
                continue
            annotated_count += 1
            if have_rs274:
                if os.path.basename(path) in READS_LINE_NUMBERS:
                    same, _ = same_under_rs274(path, out)
                    check(not same, f"{path}: the header moves the line numbers it prints")
                    r = run("annotate", path, "--machine", GENERIC, "--no-removal", "--no-header",
                            "-o", out)
                    check(r.returncode == 0, f"{path}: annotate --no-header")
                same, _ = same_under_rs274(path, out)
                rs274_same += same
                check(same, f"{path}: rs274 runs the annotated file as the original")
    print(f"round trips: {annotated_count} annotated, {refused} refused cleanly; "
          f"rs274 identical on {rs274_same}/{annotated_count}")


# ---------------------------------------------------------------------------------------------
# LinuxCNC's MSG: only the last comment of a line counts
# ---------------------------------------------------------------------------------------------

MSG_PROGRAM = b"""%
(MSG, starting the bracket)
G21 G90 G17
G0 X0 Y0 Z5 (MSG, rapid to start)
G1 Z-1 F100 (plunge) (DEBUG, depth is -1)
G1 X20 F300 ; plain note
G1 Y20 (MSG, one) (MSG, two)
G0 Z5
M2
%
"""


def msg_comments():
    with tempfile.TemporaryDirectory() as d:
        original = os.path.join(d, "msg.ngc")
        with open(original, "wb") as f:
            f.write(MSG_PROGRAM)
        out = os.path.join(d, "msg-annotated.ngc")
        r = run("annotate", original, "--machine", GENERIC, "--no-removal", "-o", out)
        if not check(r.returncode == 0, f"MSG program annotated ({r.stderr[:200]!r})"):
            return
        check(read(out).count(b"(NCJ ") >= 5, "MSG program: the moving blocks are annotated")
        same, lines = same_under_rs274(original, out)
        messages = [l for l in lines if b"MESSAGE(" in l]
        check(len(messages) == 4, f"rs274 shows the 4 MSG/DEBUG messages ({messages})")
        check(any(b"two" in m for m in messages) and not any(b"one" in m for m in messages),
              "rs274 shows only the last comment of a line")
        check(same, "rs274 shows the same messages and moves on the annotated file")


# ---------------------------------------------------------------------------------------------
# Standard input and output, in place, help
# ---------------------------------------------------------------------------------------------

def streams_and_in_place():
    original = read(SAMPLE)
    by_file = run("annotate", SAMPLE, "--machine", GENERIC)
    # The file's stock comes from its .stock file next to it; standard input has none.
    sidecar = os.path.splitext(SAMPLE)[0] + ".stock"
    with open(sidecar) as f:
        stock = f.read().strip()
    by_stdin = run("annotate", "-", "--machine", GENERIC, "--stock", stock, stdin=original)
    check(by_file.returncode == 0 and by_stdin.returncode == 0, "annotate from a file and from -")
    # The same, but for where the stock came from (the header's stock line names it, and the
    # seal's hash covers that line).
    def without_stock_line(text):
        return [l for l in text.splitlines() if b"NCJ STOCK" not in l and b"NCJ SEAL" not in l]
    check(without_stock_line(by_file.stdout) == without_stock_line(by_stdin.stdout),
          "stdin gives the same annotation as the file")
    check(b"FROM=stock-file" in by_file.stdout and b"FROM=option" in by_stdin.stdout,
          "the stock line names each one's source")
    stripped = run("strip", "-", "-o", "-", stdin=by_stdin.stdout)
    check(stripped.returncode == 0 and stripped.stdout == original, "strip - - gives the original")
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "part.ngc")
        shutil.copy(SAMPLE, path)
        shutil.copy(sidecar, os.path.join(d, "part.stock"))
        os.chmod(path, 0o640)
        r = run("annotate", path, "--machine", GENERIC, "--in-place")
        check(r.returncode == 0 and read(path) == by_file.stdout, "annotate --in-place")
        check(stat.S_IMODE(os.stat(path).st_mode) == 0o640, "--in-place keeps the permissions")
        r = run("strip", path, "--in-place")
        check(r.returncode == 0 and read(path) == original, "strip --in-place")
        check(not temp_files(d), "no temporary files after in-place runs")
        r = run("annotate", "-", "--machine", GENERIC, "--in-place", stdin=original)
        check(r.returncode == 1, "--in-place with standard input is a usage error")
        r = run("annotate", path, "--machine", GENERIC, "--in-place", "-o", path)
        check(r.returncode == 1, "--in-place and -o together are a usage error")
    for command in ("annotate", "strip"):
        r = run(command, "--help")
        text = r.stdout.decode()
        check(r.returncode == 0 and "--in-place" in text and "--output" in text,
              f"{command} --help")


# ---------------------------------------------------------------------------------------------
# Failures
# ---------------------------------------------------------------------------------------------

UNKNOWN_TOOL = b"G21 G90\nT7 M6\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X50\nM30\n"


def expect_refusal(result, code, words, what, directory=None, untouched=None):
    err = result.stderr.decode(errors="replace")
    check(result.returncode == code, f"{what}: exit {code} (got {result.returncode}: {err[:200]!r})")
    for w in words:
        check(w in err, f"{what}: the message names {w!r} ({err[:200]!r})")
    if directory:
        check(not temp_files(directory), f"{what}: no temporary file left in {directory}")
    if untouched:
        path, data = untouched
        check(read(path) == data, f"{what}: {os.path.basename(path)} is untouched")


def input_failures():
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "out.ngc")
        missing = os.path.join(d, "missing.ngc")
        expect_refusal(run("annotate", missing, "--machine", GENERIC, "-o", out), 2,
                       ["missing.ngc"], "unreadable input", d)
        expect_refusal(run("annotate", d, "--machine", GENERIC, "-o", out), 2, [d],
                       "a directory as input", d)
        expect_refusal(run("strip", missing, "-o", out), 2, ["missing.ngc"], "strip: unreadable input", d)
        check(not os.path.exists(out), "unreadable input: no output file")

        bad = os.path.join(d, "bad.toml")
        with open(GENERIC) as f:
            profile = f.read()
        with open(bad, "w") as f:
            f.write(profile.replace("accel_mm_s2 = 1000", "accel_mm_s2 = -1", 1))
        program = os.path.join(d, "tool7.ngc")
        with open(program, "wb") as f:
            f.write(UNKNOWN_TOOL)
        expect_refusal(run("annotate", program, "--machine", bad, "--in-place"), 2,
                       ["bad.toml", "accel"], "bad profile", d, (program, UNKNOWN_TOOL))
        # A tool described nowhere is not a refusal: the program is annotated, a warning names
        # the tool, and the header says it was not simulated.
        r = run("annotate", program, "--machine", GENERIC, "-o", out)
        err = r.stderr.decode(errors="replace")
        check(r.returncode == 0 and "tool T7" in err, f"unknown tool: written, T7 named ({err[:160]!r})")
        with open(out, "rb") as f:
            written = f.read()
        check(b"NCJ WARN tools T7 not simulated" in written, "unknown tool: the header says so")
        check(run("strip", out, "-o", "-").stdout == UNKNOWN_TOOL, "unknown tool: strip gives it back")
        os.remove(out)
        # A program its controller would refuse (a feed move with no feed rate) is annotated all
        # the same, its header listing the error, and the exit status says so.
        refused = os.path.join(d, "nofeed.ngc")
        with open(refused, "wb") as f:
            f.write(b"G21 G90\nG0 X0 Y0 Z5\nG1 Z-1\nM30\n")
        r = run("annotate", refused, "--machine", GENERIC, "--no-removal", "-o", out)
        with open(out, "rb") as f:
            written = f.read()
        named = re.search(rb"NCJ WARN ERROR L(\d+) ", written)
        check(r.returncode == 2 and named is not None,
              f"controller error: exit 2, written, listed in the header ({r.returncode})")
        if named:
            # The line it names is the line of the annotated file, header included.
            bad_line = written.splitlines()[int(named.group(1)) - 1]
            check(bad_line.startswith(b"G1 Z-1"), f"the header names the right line ({bad_line!r})")
        os.remove(out)


def mount_tmpfs(directory, options):
    """A small file system of our own (root only); False when it cannot be had."""
    if os.geteuid() != 0:
        return False
    return subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", directory],
                          capture_output=True).returncode == 0


def read_only_directory():
    with tempfile.TemporaryDirectory() as d:
        ro = os.path.join(d, "ro")
        os.mkdir(ro)
        mounted = mount_tmpfs(ro, "size=1m")
        try:
            part = os.path.join(ro, "part.ngc")
            shutil.copy(SAMPLE, part)
            original = read(part)
            if mounted:
                subprocess.run(["mount", "-o", "remount,ro", ro], check=True)
            else:
                os.chmod(ro, 0o555)
            probe = os.path.join(ro, "probe")
            try:
                open(probe, "w").close()
                os.remove(probe)
                print("skip read-only directory: cannot make one here (root without mount)")
                return
            except OSError:
                pass
            expect_refusal(run("annotate", part, "--machine", GENERIC, "--in-place"), 3,
                           ["part.ngc", "untouched"], "in place in a read-only directory", ro,
                           (part, original))
            expect_refusal(run("annotate", SAMPLE, "--machine", GENERIC, "-o",
                               os.path.join(ro, "new.ngc")), 3, ["new.ngc", ro],
                           "output into a read-only directory", ro)
            check(not os.path.exists(os.path.join(ro, "new.ngc")), "read-only: no output file")
        finally:
            if mounted:
                subprocess.run(["umount", ro])
            else:
                os.chmod(ro, 0o755)


def full_disk():
    # /dev/full: a device is written in place, and every write fails with ENOSPC.
    expect_refusal(run("annotate", SAMPLE, "--machine", GENERIC, "-o", "/dev/full"), 3,
                   ["/dev/full", "No space left"], "-o /dev/full")
    with open("/dev/full", "wb") as full:
        r = subprocess.run([NCJOULE, "annotate", SAMPLE, "--machine", GENERIC], stdout=full,
                           stderr=subprocess.PIPE, timeout=300)
    expect_refusal(r, 3, ["standard output"], "standard output on /dev/full")
    with open("/dev/full", "wb") as full:
        r = subprocess.run([NCJOULE, "strip", SAMPLE], stdout=full, stderr=subprocess.PIPE,
                           timeout=300)
    expect_refusal(r, 3, ["standard output"], "strip to /dev/full")
    # Listings and JSON on a full standard output: exit 3, never a quiet success.
    for extra in ([], ["--json"], ["--csv"]):
        with open("/dev/full", "wb") as full:
            r = subprocess.run([NCJOULE, "estimate", SAMPLE, "--machine", GENERIC, *extra],
                               stdout=full, stderr=subprocess.PIPE, timeout=300)
        expect_refusal(r, 3, ["standard output"], "estimate %s to /dev/full" % " ".join(extra))

    with tempfile.TemporaryDirectory() as d:
        # A file size limit: the temporary file cannot grow past the original's size.
        part = os.path.join(d, "part.ngc")
        shutil.copy(SAMPLE, part)
        original = read(part)

        def limit_file_size():
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
            resource.setrlimit(resource.RLIMIT_FSIZE, (len(original), len(original)))

        r = subprocess.run([NCJOULE, "annotate", part, "--machine", GENERIC, "--in-place"],
                           capture_output=True, preexec_fn=limit_file_size, timeout=300)
        expect_refusal(r, 3, ["part.ngc", "untouched"], "in place past a file size limit", d,
                       (part, original))

        # A file system that is really full.
        small = os.path.join(d, "small")
        os.mkdir(small)
        if not mount_tmpfs(small, "size=16k"):
            print("skip full file system: no tmpfs mount here (needs root)")
            return
        try:
            part = os.path.join(small, "part.ngc")
            shutil.copy(SAMPLE, part)
            filler = os.path.join(small, "filler")
            fd = os.open(filler, os.O_WRONLY | os.O_CREAT)
            try:
                while True:
                    os.write(fd, b"x" * 512)
            except OSError:
                pass
            os.close(fd)
            os.truncate(filler, max(0, os.path.getsize(filler) - 4096))  # room for a little
            expect_refusal(run("annotate", part, "--machine", GENERIC, "--in-place"), 3,
                           ["part.ngc", "untouched"], "in place on a full file system", small,
                           (part, original))
            expect_refusal(run("annotate", SAMPLE, "--machine", GENERIC, "-o",
                               os.path.join(small, "new.ngc")), 3, ["new.ngc"],
                           "new file on a full file system", small)
            check(not os.path.exists(os.path.join(small, "new.ngc")), "full disk: no output file")
        finally:
            subprocess.run(["umount", small])


def overload_and_fields():
    # A cut over the spindle's rating: its LOAD field is in the comment (no '%', which ends a
    # Fanuc tape and is not a character a marked comment may hold) and strip still takes it out.
    program = ("(T1 D=40. CR=0. - ZMIN=-10. - FLAT END MILL)\nG21 G90\nT1 M6\nS800 M3\n"
               "G0 X-30 Y20 Z5\nG1 Z-10 F2000\nG1 X130\nG0 Z5\nM30\n").encode()
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "over.ngc")
        with open(path, "wb") as f:
            f.write(program)
        with open(os.path.join(d, "over.stock"), "w") as f:
            f.write("box:0,0,-20,100,40,0\n")
        r = run("annotate", path, "--machine", GENERIC)
        check(r.returncode == 0 and b"LOAD_PCT=" in r.stdout and b"%" not in r.stdout,
              "an overloaded cut says LOAD_PCT, without '%'")
        s = run("strip", "-", "-o", "-", stdin=r.stdout)
        check(s.stdout == program, "strip takes the LOAD field out with its comment")

        # --fields and --compact: fewer bytes, the same round trip.
        full = len(run("annotate", SAMPLE, "--machine", GENERIC).stdout)
        for args, expect, absent in ((["--fields", "T"], b" T=", [b" E=", b" MRR=", b" CUM="]),
                                     (["--compact"], b" MRR=", [b"MRR=0 ", b" P=", b" CUM="])):
            a = run("annotate", SAMPLE, "--machine", GENERIC, *args)
            body = b"\n".join(l for l in a.stdout.split(b"\n") if b"(NCJ " in l and b"NCJ KEYS" not in l
                              and not l.startswith(b"(NCJ "))
            check(a.returncode == 0 and expect in body and not any(x in body for x in absent),
                  "%s: only the fields asked for" % " ".join(args))
            check(len(a.stdout) < full, "%s: smaller than the default (%d < %d bytes)" % (
                " ".join(args), len(a.stdout), full))
            st = run("strip", "-", "-o", "-", stdin=a.stdout)
            check(st.stdout == read(SAMPLE), "%s: strip gives the original" % " ".join(args))
        # The longest move a program may make (X99,999.999 at F0.0001, 1.7e7 hours; a move to
        # X1e29, found by fuzzing, is now out of range): its times are written without an
        # exponent or a '+', so strip still recognises every comment.
        far = b"G21 G90\nG0 X0 Y0 Z0\nG1 X99999.999 F0.0001\nM2\n"
        a = run("annotate", "-", "--machine", GENERIC, "--no-removal", stdin=far)
        st = run("strip", "-", "-o", "-", stdin=a.stdout)
        check(a.returncode == 0 and b"T=16666666h30m00s" in a.stdout and b"+" not in a.stdout
              and st.stdout == far, "a 1.7e7-hour move annotates without '+' and strips back")
        bad = run("annotate", SAMPLE, "--machine", GENERIC, "--fields", "T,WATTS")
        check(bad.returncode == 1 and "WATTS" in bad.stderr.decode(), "--fields with an unknown name")


def in_place_safety():
    with tempfile.TemporaryDirectory() as d:
        original = read(SAMPLE)
        # A file with two names: replacing one would leave the other with the old text.
        path = os.path.join(d, "part.ngc")
        shutil.copy(SAMPLE, path)
        os.link(path, os.path.join(d, "other-name.ngc"))
        r = run("annotate", path, "--machine", GENERIC, "--in-place")
        check(r.returncode == 3 and b"hard links" in r.stderr and read(path) == original,
              "a hard-linked file is refused, untouched")
        os.remove(os.path.join(d, "other-name.ngc"))

        # Owner and group are kept (only root can give a file to another user).
        if os.geteuid() == 0:
            os.chown(path, 4321, 4321)
            r = run("annotate", path, "--machine", GENERIC, "--in-place")
            st = os.stat(path)
            check(r.returncode == 0 and (st.st_uid, st.st_gid) == (4321, 4321),
                  "--in-place keeps the owner and group (%d:%d)" % (st.st_uid, st.st_gid))
            shutil.copy(SAMPLE, path)

        # A file size limit hit while writing, with SIGXFSZ at its default (which would kill the
        # program mid-write): reported as a failed write, the original intact, no temporary left.
        big = os.path.join(d, "big.ngc")
        with open(big, "wb") as f:
            f.write(original * 60)
        before = read(big)
        r = subprocess.run(["bash", "-c", "ulimit -f 16; exec \"$0\" annotate \"$1\" --machine \"$2\" "
                            "--in-place --no-removal", NCJOULE, big, GENERIC], capture_output=True)
        check(r.returncode == 3 and read(big) == before and not temp_files(d),
              "a write cut short by a file size limit leaves the file and no temporary (%d, %r)"
              % (r.returncode, temp_files(d)))


round_trips()
in_place_safety()
overload_and_fields()
msg_comments()
streams_and_in_place()
input_failures()
read_only_directory()
full_disk()
print(f"{'all checks passed' if not failures else str(len(failures)) + ' checks failed'}")
sys.exit(1 if failures else 0)
