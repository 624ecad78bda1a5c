#!/usr/bin/env python3
"""`ncjoule check-log` and `ncjoule calibrate --timing` end to end, on NIST's cover run
(tests/logs/data): the run found and aligned in both log forms, measured against predicted; a
profile calibrated from the log that loads and names its machine and data; and the refusals:
a device file given as a log, a log with no run of the program, a mapping that does not read,
several power logs without --timing. Nothing is written when nothing can be fitted."""
import json
import os
import subprocess
import sys
import tempfile

NCJOULE = os.environ["NCJOULE"]
SRC = os.environ["NCJOULE_SOURCE_DIR"]
DATA = os.path.join(SRC, "tests", "logs", "data")
COVER = os.path.join(DATA, "cover.nc")
DEVICES = os.path.join(DATA, "Devices-Hurco04.xml")
HURCO = os.path.join(SRC, "samples", "machines", "hurco-vmx24.toml")
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def run(*args):
    return subprocess.run([NCJOULE, *args], capture_output=True, text=True)


def check_json(*args):
    r = run("check-log", *args, "--json")
    try:
        return r, json.loads(r.stdout)
    except ValueError:
        return r, {}


# The cover run, as SHDR through the device file and as the agent's Streams document.
measured = {}
for form, extra in (("SHDR", ["--log", os.path.join(DATA, "cover-run.shdr"), "--devices", DEVICES]),
                    ("Streams", ["--log", os.path.join(DATA, "cover-run.xml")])):
    r, doc = check_json(COVER, "-m", "hurco-vmx24", *extra)
    check(r.returncode == 0, f"check-log on the {form} log exits 0 ({r.stderr[-200:]})")
    runs = doc.get("runs", [])
    check(len(runs) == 1 and runs[0]["usable"], f"{form}: one usable run of the cover")
    prog = (doc.get("programs") or [{}])[0]
    m = prog.get("measured", {}).get("median_s", 0)
    measured[form] = m
    check(abs(m - 80.14) < 0.05, f"{form}: the run took 80.14 s (got {m})")
    check(70 < prog.get("predicted_s", 0) < 80, f"{form}: predicted on the Hurco profile")
    ops = prog.get("operations", [])
    check(len(ops) == 1 and ops[0]["tool"] == 23, f"{form}: one operation, T23")
    worst = prog.get("worst_blocks", [])
    check(worst and worst[0]["first_line"] == 1 and "M6" in worst[0]["text"],
          f"{form}: the worst block is the header with its M6 ({worst[:1]})")
check(abs(measured["SHDR"] - measured["Streams"]) < 1e-6, "both forms measure the same run")

# The text tables.
r = run("check-log", COVER, "-m", "hurco-vmx24", "--log", os.path.join(DATA, "cover-run.shdr"),
        "--devices", DEVICES)
check("by operation" in r.stdout and "worst blocks" in r.stdout and "usable" in r.stdout,
      "check-log prints the runs, the operations and the worst blocks")

# A log of another program: its run is found, fits no program, nothing is compared.
r, doc = check_json(COVER, "-m", "hurco-vmx24", "--log", os.path.join(DATA, "held-run.shdr"),
                    "--devices", DEVICES)
check(r.returncode == 0 and doc.get("runs") == [] and doc.get("other_runs") == 1,
      "a held run of another program is counted apart, not compared")

# Refusals.
r = run("check-log", COVER, "--log", DEVICES)
check(r.returncode == 2 and "give it with --devices" in r.stderr,
      f"a device file given as a log is refused with why (exit {r.returncode})")
with tempfile.TemporaryDirectory() as tmp:
    bad = os.path.join(tmp, "map.toml")
    with open(bad, "w") as f:
        f.write("[items]\nfeedrate = \"F\"\n")
    r = run("check-log", COVER, "--log", os.path.join(DATA, "cover-run.shdr"), "--log-mapping", bad)
    check(r.returncode == 2 and "map.toml:2:" in r.stderr and "unknown signal" in r.stderr,
          "a misspelt mapping is an error at its line")

    # calibrate --timing: a profile that loads, names the machine and the data, and times the
    # cover as the fit says.
    out = os.path.join(tmp, "ours.toml")
    r = run("calibrate", "--timing", "-m", HURCO, "--program", COVER, "--log",
            os.path.join(DATA, "cover-run.shdr"), "--devices", DEVICES, "-o", out)
    check(r.returncode == 0, f"calibrate --timing exits 0 ({r.stderr[-300:]})")
    check("timing fit:" in r.stdout and "left as in the base" in r.stdout,
          "it prints the fit, with the keys left as in the base and why")
    text = open(out).read() if os.path.exists(out) else ""
    check("calibrated by ncjoule calibrate --timing" in text and "for Hurco04" in text,
          "the profile names the machine (the log's device)")
    check("cover-run.shdr" in text and "program cover.nc: 1 usable run of 1" in text,
          "the profile names its data")
    check("# data sheet: 24 hp peak" in text, "the base's comments stay")
    r = run("estimate", COVER, "-m", out, "--no-removal", "--json")
    check(r.returncode == 0 and json.loads(r.stdout or "{}").get("time_s", 0) > 0,
          "the calibrated profile loads and estimates")

    # A log that carries the machine's power: the power model is fitted on the run too (or, when
    # the fit cannot go into a profile that loads, left out with a warning); the timing is
    # written either way.
    powered = os.path.join(tmp, "powered.shdr")
    spindle, last, lines = 0.0, None, []
    for line in open(os.path.join(DATA, "cover-run.shdr")).read().splitlines():
        lines.append(line)
        fields = line.split("|")
        if len(fields) >= 3 and fields[1] == "Spindle_Speed":
            spindle = float(fields[2])
        if fields[0][:19] != last:
            last = fields[0][:19]
            lines.append("%s|kw|%.4f" % (fields[0], (900 + 0.12 * spindle) / 1000))
    with open(powered, "w") as f:
        f.write("\n".join(lines) + "\n")
    mapping = os.path.join(tmp, "power.toml")
    with open(mapping, "w") as f:
        f.write('[items]\npower = "kw"\n[scale]\npower = 1000\n')
    out_power = os.path.join(tmp, "powered.toml")
    r = run("calibrate", "--timing", "-m", HURCO, "--program", COVER, "--log", powered,
            "--devices", DEVICES, "--log-mapping", mapping, "-o", out_power)
    check(r.returncode == 0 and "power fit on run of cover.nc" in r.stdout and
          "logged electrical power" in r.stdout,
          f"a logged power is fitted ({r.stderr[-300:]})")
    check("power = kw (mapping file)" in r.stdout, "the mapping file names the power item")
    check(os.path.exists(out_power) and run("estimate", COVER, "-m", out_power,
                                            "--no-removal").returncode == 0,
          "the profile is written and loads")

    # Nothing usable: nothing written.
    none = os.path.join(tmp, "none.toml")
    r = run("calibrate", "--timing", "-m", HURCO, "--program", COVER, "--log",
            os.path.join(DATA, "held-run.shdr"), "--devices", DEVICES, "-o", none)
    check(r.returncode == 2 and "nothing written" in r.stderr and not os.path.exists(none),
          f"no usable run: exit 2, nothing written (exit {r.returncode})")
    r = run("calibrate", "--timing", "--program", COVER, "--log",
            os.path.join(DATA, "cover-run.shdr"), "-o", none)
    check(r.returncode == 1 and "-m" in r.stderr, "--timing without a base profile is a usage error")
    r = run("calibrate", "-m", HURCO, "--program", COVER, "--program", COVER, "--log",
            os.path.join(DATA, "cover-run.shdr"), "--log", os.path.join(DATA, "cover-run.shdr"),
            "-o", none)
    check(r.returncode == 1 and "several only with --timing" in r.stderr,
          "two power logs without --timing are a usage error")

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
