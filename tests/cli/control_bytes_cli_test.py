#!/usr/bin/env python3
"""Control bytes from users' files (file names, profile names, CSV and log file names, config
paths) reach no terminal raw: every text printer shows them escaped (\\x1b, \\x07), as the
estimate's summary and compare do (their test is in estimate_cli_test.py). One check a printer:
calibrate's report, calibrate --timing, check-log, report, doctor, profiles."""
import os
import shutil
import subprocess
import sys
import tempfile

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
DATA = os.path.join(ROOT, "tests", "logs", "data")
COVER = os.path.join(DATA, "cover.nc")
DEVICES = os.path.join(DATA, "Devices-Hurco04.xml")
HURCO = os.path.join(ROOT, "samples", "machines", "hurco-vmx24.toml")
GENERIC = os.path.join(ROOT, "samples", "machines", "generic-3axis.toml")
SAMPLE = os.path.join(ROOT, "samples", "programs", "bracket-linuxcnc.ngc")
# A window title (OSC 0 ... BEL) and a colour: what a hostile name would send a terminal.
HOSTILE = "x\x1b]0;title\x07\x1b[31m"
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def run(*args, env=None):
    return subprocess.run([NCJOULE, *args], capture_output=True, env=env)


def escaped(r, stream="stdout"):
    """The output holds the name escaped and no raw ESC or BEL."""
    out = getattr(r, stream)
    return b"\x1b" not in out and b"\x07" not in out and b"\\x1b" in out


with tempfile.TemporaryDirectory() as tmp:
    # calibrate: the fit's report names the table, and "wrote" names the profile.
    table = os.path.join(tmp, f"spindle{HOSTILE}.csv")
    with open(table, "w") as f:
        f.write("rpm,power_w\n1000,560\n2000,770\n3000,980\n4000,1195\n")
    out = os.path.join(tmp, f"fit{HOSTILE}.toml")
    r = run("calibrate", "-m", GENERIC, "--spindle", table, "-o", out)
    check(r.returncode == 0 and escaped(r),
          f"calibrate's report escapes the table's and the profile's names ({r.returncode}: "
          f"{r.stdout[:300]!r} {r.stderr[-200:]!r})")

    # calibrate --timing: "wrote" names the profile.
    out = os.path.join(tmp, f"timing{HOSTILE}.toml")
    r = run("calibrate", "--timing", "-m", HURCO, "--program", COVER, "--log",
            os.path.join(DATA, "cover-run.shdr"), "--devices", DEVICES, "-o", out)
    check(r.returncode == 0 and escaped(r),
          f"calibrate --timing escapes the profile's name ({r.returncode}: {r.stdout[-300:]!r} "
          f"{r.stderr[-200:]!r})")

    # check-log: the logs' summary names the log file.
    log = os.path.join(tmp, f"run{HOSTILE}.shdr")
    shutil.copy(os.path.join(DATA, "cover-run.shdr"), log)
    r = run("check-log", COVER, "-m", "hurco-vmx24", "--log", log, "--devices", DEVICES)
    check(r.returncode == 0 and escaped(r),
          f"check-log escapes the log's name ({r.returncode}: {r.stdout[:300]!r} "
          f"{r.stderr[-200:]!r})")

    # report: "wrote" (stderr) names the page.
    page = os.path.join(tmp, f"page{HOSTILE}.html")
    r = run("report", SAMPLE, "-m", GENERIC, "--no-removal", "-o", page)
    check(r.returncode == 0 and os.path.exists(page) and escaped(r, "stderr"),
          f"report escapes the page's name ({r.returncode}: {r.stderr[-300:]!r})")

    # doctor: the user config NCJOULE_CONFIG names, which does not exist.
    env = dict(os.environ, NCJOULE_CONFIG=os.path.join(tmp, f"config{HOSTILE}.toml"))
    r = run("doctor", env=env)
    check(escaped(r), f"doctor escapes the config's path ({r.returncode}: {r.stdout[:400]!r})")

    # profiles: a profile folder (NCJOULE_DATA_DIR) with a file and a machine named so.
    machines = os.path.join(tmp, "data", "machines")
    os.makedirs(machines)
    with open(GENERIC) as f:
        text = f.read()
    lines = text.splitlines()
    named = [i for i, line in enumerate(lines) if line.startswith("name")]
    check(len(named) >= 1, "the generic profile has a name line")
    lines[named[0]] = 'name = "Evil \\u001b]0;title\\u0007 mill"'
    with open(os.path.join(machines, f"evil{HOSTILE}.toml"), "w") as f:
        f.write("\n".join(lines) + "\n")
    env = dict(os.environ, NCJOULE_DATA_DIR=os.path.join(tmp, "data"))
    r = run("profiles", env=env)
    check(r.returncode == 0 and escaped(r) and b"Evil \\x1b]0;title\\x07 mill" in r.stdout,
          f"profiles escapes a profile's file and machine names ({r.returncode}: "
          f"{r.stdout[:300]!r} {r.stderr[-200:]!r})")

print(f"{len(failures) == 0 and 1 or 0} passed, {len(failures) and 1 or 0} failed")
sys.exit(1 if failures else 0)
