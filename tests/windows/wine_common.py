"""What the Windows tests share: the programs they run and Windows paths of Linux files.

Environment (scripts/test-windows.sh sets it):
  NCJOULE          runs the Windows ncjoule.exe under Wine (a wrapper script)
  NCJOULE_EXE      the Windows program itself (a Linux path), for `wine cmd` and the hooks
  NCJOULE_LINUX    the Linux build of ncjoule, whose results the Windows build must give
  NCJOULE_SOURCE_DIR  the repository
  NCJOULE_WIN_WORK a folder for the tests' files
  WINEPREFIX       the Wine prefix the tests run in (C: is its drive_c)
"""
import json
import math
import os
import subprocess

NCJOULE = os.environ["NCJOULE"]
NCJOULE_EXE = os.environ["NCJOULE_EXE"]
LINUX = os.environ["NCJOULE_LINUX"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
WORK = os.environ["NCJOULE_WIN_WORK"]
MACHINES = os.path.join(ROOT, "samples", "machines")

failures = []


def check(condition, what):
    if not condition:
        print("FAIL " + what, flush=True)
        failures.append(what)
    return condition


def finish(name):
    if failures:
        print("%s: %d failure(s)" % (name, len(failures)))
        raise SystemExit(1)
    print("%s: all passed" % name)


def win(path):
    """The Windows path of a Linux file: Wine's Z: drive is the Linux root."""
    return "Z:" + os.path.abspath(path).replace("/", "\\")


def run_windows(*args, stdin=None, cwd=None, env=None):
    return subprocess.run([NCJOULE, *args], capture_output=True, input=stdin, timeout=600,
                          cwd=cwd, env=env)


def run_linux(*args, stdin=None, cwd=None, env=None):
    return subprocess.run([LINUX, *args], capture_output=True, input=stdin, timeout=600, cwd=cwd,
                          env=env)


def run_wine_cmd(words, cwd=None, env=None):
    """Words run by Wine's cmd.exe (/c), as a CAM system would start them. Wine joins them into
    cmd's command line, in double quotes those with a blank; "call" goes first, so that cmd
    never strips the quotes of a first word that is quoted. No word may hold a double quote."""
    assert not any('"' in w for w in words)
    return subprocess.run(["wine", "cmd", "/c", "call", *words], capture_output=True, timeout=600,
                          cwd=cwd, env=env)


def compare_numbers(a, b, where, rel=1e-9, zero=1e-12, ignore_strings=False):
    """Differences between two JSON documents: numbers beyond `rel` (or, near zero, beyond
    `zero` in their own unit: a speed of 4e-15 mm/s on one system and 0 on the other are both a
    stop, the C libraries round differently), anything else unequal
    (but the names of files, which are written as each system spells them). Returns (differences, how many numbers were compared, of which time or energy)."""
    differences = []
    counts = [0, 0]

    def walk(x, y, path):
        if isinstance(x, bool) or isinstance(y, bool) or x is None or y is None:
            if x != y:
                differences.append("%s: %r != %r" % (path, x, y))
        elif isinstance(x, (int, float)) and isinstance(y, (int, float)):
            counts[0] += 1
            key = path.lower()
            if "time" in key or "energy" in key or key.endswith("_s") or key.endswith("_j"):
                counts[1] += 1
            if not (x == y or (math.isfinite(x) and math.isfinite(y) and
                               abs(x - y) <= max(rel * max(abs(x), abs(y)), zero))):
                differences.append("%s: %.17g != %.17g" % (path, x, y))
        elif isinstance(x, dict) and isinstance(y, dict):
            if sorted(x) != sorted(y):
                differences.append("%s: keys %s != %s" % (path, sorted(x), sorted(y)))
            for k in x:
                if k in y:
                    walk(x[k], y[k], path + "." + k)
        elif isinstance(x, list) and isinstance(y, list):
            if len(x) != len(y):
                differences.append("%s: %d items != %d" % (path, len(x), len(y)))
            for i, (p, q) in enumerate(zip(x, y)):
                walk(p, q, "%s[%d]" % (path, i))
        elif x != y and not (isinstance(x, str) and isinstance(y, str) and
                             (ignore_strings or path.endswith(".file"))):
            differences.append("%s: %r != %r" % (path, x, y))

    walk(a, b, where)
    return differences, counts[0], counts[1]


def parse_json(stdout, what):
    try:
        return json.loads(stdout.decode("utf-8"))
    except (ValueError, UnicodeDecodeError) as e:
        check(False, "%s: not JSON (%s): %r" % (what, e, stdout[:200]))
        return None
