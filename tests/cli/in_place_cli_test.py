#!/usr/bin/env python3
"""`annotate --in-place` and `strip --in-place` never replace a file that is not theirs to replace,
and never take what is not a G-code program for one.

- A post still writing the file (holding it open, or appending between looks): refused, exit 3,
  the file exactly as the writer left it, every line the writer wrote after kept.
- A program without an end is replaced only after a quiet period; one with M2/M30 at once.
- A symbolic link is refused unless --follow-symlinks; then the target is annotated and the link
  stays a link.
- UTF-16 and UTF-32 text, binary data, a passwd-like text, /dev/zero, a file over --input-limit
  and one whose lines need more than --memory-limit: exit 2, nothing written.
- The last line says what was done: 'annotated FILE', 'FILE unchanged', 'with errors'.
Environment: NCJOULE (the program), NCJOULE_SOURCE_DIR (the repository).
"""
import os
import subprocess
import sys
import tempfile
import threading
import time

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
GENERIC = os.path.join(ROOT, "samples/machines/generic-3axis.toml")
failures = []

PROGRAM = b"G21 G90\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X20 Y10\nG1 X40\nG0 Z5\n"
END = b"M2\n"


def check(condition, what):
    if not condition:
        print("FAIL " + what)
        failures.append(what)
    return condition


def run(*args, timeout=120):
    return subprocess.run([NCJOULE, *args], capture_output=True, timeout=timeout)


def annotate(path, *more):
    return run("annotate", path, "-m", GENERIC, "--no-removal", "--in-place", *more)


def read(path):
    with open(path, "rb") as f:
        return f.read()


def write(path, data):
    with open(path, "wb") as f:
        f.write(data)


def last_line(result):
    lines = result.stderr.decode(errors="replace").strip().splitlines()
    return lines[-1] if lines else ""


def test_writer_holding_the_file(d):
    path = os.path.join(d, "held.ngc")
    with open(path, "wb") as post:  # a post that has written half and is still at it
        post.write(PROGRAM)
        post.flush()
        r = annotate(path)
        check(r.returncode == 3, f"held file: exit {r.returncode}, want 3")
        check(b"still being written" in r.stderr, f"held file: says why: {r.stderr!r}")
        post.write(b"G1 X60\n" + END)
    check(read(path) == PROGRAM + b"G1 X60\n" + END, "held file: every byte the post wrote kept")
    r = annotate(path)
    check(r.returncode == 0, f"finished file: annotated, exit {r.returncode} {r.stderr!r}")
    check(last_line(r) == f"ncjoule: annotated {path}", f"status line: {last_line(r)!r}")


def test_writer_appending_between_looks(d):
    # A post that opens, appends and closes its file again and again: no writer is seen at any one
    # moment, but the file keeps changing and has no end yet.
    path = os.path.join(d, "growing.ngc")
    write(path, PROGRAM)
    stop = threading.Event()
    written = [PROGRAM]

    def post():
        k = 0
        while not stop.is_set():
            line = f"G1 X{k % 50} Y{k % 7}\n".encode()
            with open(path, "ab") as f:
                f.write(line)
            written.append(line)
            k += 1
            time.sleep(0.2)

    thread = threading.Thread(target=post)
    thread.start()
    try:
        r = annotate(path)
    finally:
        stop.set()
        thread.join()
    check(r.returncode == 3, f"growing file: exit {r.returncode}, want 3 ({r.stderr!r})")
    check(b"changed while" in r.stderr or b"still being written" in r.stderr,
          f"growing file: says why: {r.stderr!r}")
    check(read(path) == b"".join(written), "growing file: nothing the post appended was lost")


def test_quiet_period(d):
    ended = os.path.join(d, "ended.ngc")
    write(ended, PROGRAM + END)
    t = time.monotonic()
    r = annotate(ended)
    check(r.returncode == 0, f"ended program: exit {r.returncode}")
    check(time.monotonic() - t < 1.8, "a program with M2 is not kept waiting for a quiet period")

    open_ended = os.path.join(d, "open-ended.ngc")
    write(open_ended, PROGRAM)
    t = time.monotonic()
    r = annotate(open_ended)
    waited = time.monotonic() - t
    check(r.returncode == 0, f"program without an end, left alone: exit {r.returncode}")
    check(waited >= 1.5, f"program without an end: waited {waited:.2f} s for the quiet period")
    check(b"(NCJ" in read(open_ended), "program without an end: annotated after the wait")


def test_symbolic_links(d):
    target = os.path.join(d, "target.ngc")
    link = os.path.join(d, "link.ngc")
    write(target, PROGRAM + END)
    os.symlink(target, link)
    r = annotate(link)
    check(r.returncode == 3 and b"symbolic link" in r.stderr, f"link refused: {r.stderr!r}")
    check(read(target) == PROGRAM + END, "link refused: its target is untouched")
    r = run("strip", link, "--in-place")
    check(r.returncode == 3 and b"symbolic link" in r.stderr, f"strip on a link: {r.stderr!r}")
    r = annotate(link, "--follow-symlinks")
    check(r.returncode == 0, f"--follow-symlinks: exit {r.returncode} {r.stderr!r}")
    check(os.path.islink(link), "--follow-symlinks: the link stays a link")
    check(b"(NCJ" in read(target), "--follow-symlinks: the target is annotated")


def test_status_lines(d):
    path = os.path.join(d, "status.ngc")
    write(path, PROGRAM + END)
    annotate(path)
    again = annotate(path)
    check(again.returncode == 0, "annotated twice: exit 0")
    check(last_line(again) == f"ncjoule: {path} unchanged: already annotated this way",
          f"annotated twice: {last_line(again)!r}")
    # An error the controller would refuse (a feed move before any F): annotated all the same.
    bad = os.path.join(d, "no-feed.ngc")
    write(bad, b"G21 G90\nG0 X0 Y0 Z5\nG1 X10\nM2\n")
    r = annotate(bad, "--dialect", "linuxcnc")
    check(r.returncode == 2, f"program with errors: exit {r.returncode}")
    check(last_line(r).startswith(f"ncjoule: annotated {bad}, with errors"),
          f"program with errors: {last_line(r)!r}")
    check(b"(NCJ" in read(bad), "program with errors: annotated")


def test_not_a_program(d):
    cases = {
        "utf16.ngc": ((PROGRAM + END).decode().encode("utf-16"), "UTF-16"),
        "utf16be.ngc": ((PROGRAM + END).decode().encode("utf-16-be"), "UTF-16 (big-endian)"),
        "utf32.ngc": ((PROGRAM + END).decode().encode("utf-32"), "UTF-32"),
        "random.ngc": (os.urandom(20000), "binary"),
        "passwd.ngc": (b"root:x:0:0:root:/root:/bin/bash\n"
                       b"daemon:x:1:1:daemon:/usr/sbin:/usr/sbin/nologin\n", "no G-code"),
        # A setup sheet saved as .ngc, an empty post: comments, '%' and blank lines only.
        "setup-sheet.ngc": (b"(SETUP SHEET)\n(PART 1234 REV B)\n; vise, 2 parallels\n\n",
                            "no block to run"),
        "percent.ngc": (b"%\n%\n", "no block to run"),
        "empty.ngc": (b"", "no block to run"),
    }
    for name, (data, word) in cases.items():
        path = os.path.join(d, name)
        write(path, data)
        r = annotate(path)
        check(r.returncode == 2, f"{name}: exit {r.returncode}, want 2")
        check(word.encode() in r.stderr, f"{name}: names what it is ({word}): {r.stderr!r}")
        check(read(path) == data, f"{name}: untouched")
        r = run("estimate", path, "-m", GENERIC, "--no-removal")
        check(r.returncode == 2, f"{name}: estimate exit {r.returncode}, want 2")

    r = run("estimate", "/dev/zero", "-m", GENERIC, "--input-limit", "1", timeout=60)
    check(r.returncode == 2 and b"larger than 1 MiB" in r.stderr, f"/dev/zero: {r.stderr!r}")
    big = os.path.join(d, "big.ngc")
    write(big, PROGRAM * 30000 + END)  # 1.6 MB
    r = run("estimate", big, "-m", GENERIC, "--input-limit", "1")
    check(r.returncode == 2 and b"--input-limit" in r.stderr, f"over --input-limit: {r.stderr!r}")
    lines = os.path.join(d, "lines.ngc")
    write(lines, b"\n" * 2_000_000 + END)  # 480 MB of per-line results: over a 64 MiB budget
    r = run("annotate", lines, "-m", GENERIC, "--memory-limit", "64", "--in-place")
    check(r.returncode == 2 and b"memory budget" in r.stderr, f"lines over budget: {r.stderr!r}")
    check(os.path.getsize(lines) == 2_000_003, "lines over budget: untouched")


def main():
    with tempfile.TemporaryDirectory() as d:
        for test in (test_writer_holding_the_file, test_writer_appending_between_looks,
                     test_quiet_period, test_symbolic_links, test_status_lines,
                     test_not_a_program):
            test(d)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("in-place and input checks: all passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
