#!/usr/bin/env python3
"""`ncjoule measure` end to end: the trapezoidal energy of a known log, the idle power taken off
(given, or the mean of the log's first seconds), kW columns, and clear failures."""
import os
import re
import subprocess
import sys
import tempfile

NCJOULE = os.environ["NCJOULE"]
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def run(*args):
    return subprocess.run([NCJOULE, *args], capture_output=True, text=True)


def number(text, label):
    """The first number after `label` at the start of a line of measure's report."""
    m = re.search(r"^" + re.escape(label) + r"\s+(-?[0-9.]+)", text, re.M)
    return float(m.group(1)) if m else float("nan")


def trapezoid(samples):
    return sum(0.5 * (p0 + p1) * (t1 - t0) for (t0, p0), (t1, p1) in zip(samples, samples[1:]))


# Idle at 100 W for a second, a 300 W run, idle again: 1100 J over 5 s.
SAMPLES = [(0.0, 100.0), (0.5, 100.0), (1.0, 100.0), (2.0, 300.0), (4.0, 300.0), (5.0, 100.0)]
ENERGY = trapezoid(SAMPLES)
DURATION = SAMPLES[-1][0] - SAMPLES[0][0]

with tempfile.TemporaryDirectory() as tmp:
    log = os.path.join(tmp, "run.csv")
    with open(log, "w") as f:
        f.write("# a meter's export\ntime_s,power_w\n")
        f.writelines(f"{t},{p}\n" for t, p in SAMPLES)

    r = run("measure", log)
    check(r.returncode == 0, f"measure exits 0 (got {r.returncode}: {r.stderr[:200]})")
    check(abs(number(r.stdout, "energy") - ENERGY) < 0.05,
          f"energy is the trapezoid {ENERGY:.1f} J (got {number(r.stdout, 'energy')})")
    check(abs(number(r.stdout, "duration") - DURATION) < 1e-3, "duration 5 s")
    check(abs(number(r.stdout, "mean power") - ENERGY / DURATION) < 0.05,
          "mean power is energy over duration")
    check(abs(number(r.stdout, "peak power") - 300) < 0.05, "peak power 300 W")
    check("net energy" not in r.stdout, "no net energy without an idle power")

    r = run("measure", log, "--idle-w", "100")
    net = ENERGY - 100 * DURATION
    check(r.returncode == 0, "measure --idle-w exits 0")
    check(abs(number(r.stdout, "net energy") - net) < 0.05,
          f"--idle-w 100 takes 100 W x 5 s off: {net:.1f} J (got {number(r.stdout, 'net energy')})")

    r = run("measure", log, "--idle-from-first", "1")
    check(r.returncode == 0, "measure --idle-from-first exits 0")
    check(abs(number(r.stdout, "idle power") - 100) < 0.05,
          f"the first second idles at 100 W (got {number(r.stdout, 'idle power')})")
    check(abs(number(r.stdout, "net energy") - net) < 0.05, "and the same net energy")

    r = run("measure", log, "--idle-w", "100", "--idle-from-first", "1")
    check(r.returncode == 1, f"--idle-w and --idle-from-first exclude each other: exit 1 "
          f"(got {r.returncode})")

    kw = os.path.join(tmp, "run-kw.csv")
    with open(kw, "w") as f:
        f.write("t_s;power_kw\n")
        f.writelines(f"{t};{p / 1000}\n" for t, p in SAMPLES)
    r = run("measure", kw)
    check(r.returncode == 0 and abs(number(r.stdout, "energy") - ENERGY) < 0.05,
          "a power_kw column with ';' separators gives the same energy in J")

    # Errors name the file, the line and the column.
    bad = os.path.join(tmp, "bad.csv")
    with open(bad, "w") as f:
        f.write("time_s,power_w\n0,100\n0.1,1o0\n0.2,100\n")
    r = run("measure", bad)
    check(r.returncode == 2, f"a cell that is not a number: exit 2 (got {r.returncode})")
    check(f"{bad}:3:5:" in r.stderr, f"names {bad}:3:5 (got {r.stderr.strip()[:200]})")

    backwards = os.path.join(tmp, "backwards.csv")
    with open(backwards, "w") as f:
        f.write("time_s,power_w\n0,100\n0.2,100\n0.1,100\n")
    r = run("measure", backwards)
    check(r.returncode == 2, f"time that goes backwards: exit 2 (got {r.returncode})")
    check(f"{backwards}:4:" in r.stderr, f"names line 4 (got {r.stderr.strip()[:200]})")

    # Powers or times no meter gives, a negative power: exit 2 at the cell, and no figures
    # (1e308 printed inf and 309-digit energies; -50 W was taken).
    for name, text, cell in (("huge.csv", "time_s,power_w\n0,100\n1,1e308\n2,100\n", ":3:3:"),
                             ("kw.csv", "time_s,power_kw\n0,0.1\n1,1e300\n2,0.1\n", ":3:3:"),
                             ("negative.csv", "time_s,power_w\n0,100\n1,-50\n2,100\n", ":3:3:"),
                             ("late.csv", "time_s,power_w\n0,100\n1e308,100\n2e308,1\n", ":3:1:")):
        path = os.path.join(tmp, name)
        with open(path, "w") as f:
            f.write(text)
        r = run("measure", path)
        check(r.returncode == 2 and path + cell in r.stderr and "energy" not in r.stdout
              and "inf" not in r.stdout,
              f"{name}: exit 2 at {cell}, no figures (got {r.returncode}: {r.stdout[:100]!r} "
              f"{r.stderr.strip()[:200]})")
    r = run("measure", log, "--idle-w", "1e308")
    check(r.returncode == 1, f"--idle-w 1e308: refused (got {r.returncode})")

    r = run("measure", os.path.join(tmp, "missing.csv"))
    check(r.returncode == 1, f"a log that does not exist: exit 1 (got {r.returncode})")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("all checks passed")
