#!/usr/bin/env python3
"""`ncjoule calibrate` from steady-state tables, end to end: the new profile is TOML that loads
(in Python and in ncjoule) and holds the fitted values; --baseline-w is subtracted from the
readings but not written as the tare; CSV errors name file, line and column; exit codes."""
import os
import re
import subprocess
import sys
import tempfile
import tomllib

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
HAAS = os.path.join(ROOT, "samples/machines/haas-vf0-pavanaskar2014.toml")
GENERIC = os.path.join(ROOT, "samples/machines/generic-3axis.toml")
SAMPLE = os.path.join(ROOT, "samples/programs/bracket-linuxcnc.ngc")
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def run(*args):
    return subprocess.run([NCJOULE, *args], capture_output=True, text=True)


def write(path, text):
    with open(path, "w") as f:
        f.write(text)
    return path


def line_fit(xs, ys):
    """Ordinary least squares y = a + b x, computed here independently of ncjoule."""
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return my - b * mx, b


# Pavanaskar's spindle trial: whole-machine 1100/1300/1520 W at 3000/4000/5000 rpm, read above
# a 375 W starting state; his constant power (tare + pump) is 325 W.
RPM, WATTS = [3000, 4000, 5000], [1100, 1300, 1520]
KA, KB = line_fit(RPM, [w - 375 for w in WATTS])
# X moving alone at five feeds, 375 W baseline + 40 W + 0.5 W per mm/s.
FEEDS_MM_MIN = [600, 1200, 2400, 4800, 9000]
AXIS_W = [375 + 40 + 0.5 * f / 60 for f in FEEDS_MM_MIN]

with tempfile.TemporaryDirectory() as tmp:
    spindle = write(os.path.join(tmp, "spindle.csv"),
                    "# Pavanaskar (2014) Sec. 3.3\nrpm,power_w\n" +
                    "".join(f"{n},{w}\n" for n, w in zip(RPM, WATTS)))
    axis_x = write(os.path.join(tmp, "axis-x.csv"),
                   "feed_mm_min,power_w\n" +
                   "".join(f"{f},{w}\n" for f, w in zip(FEEDS_MM_MIN, AXIS_W)))
    out = os.path.join(tmp, "haas-calibrated.toml")
    r = run("calibrate", "--machine", HAAS, "--spindle", spindle, "--axis-x", axis_x,
            "--baseline-w", "375", "-o", out)
    check(r.returncode == 0, f"calibrate from tables exits 0 (got {r.returncode}: {r.stderr[:300]})")
    check(os.path.exists(out), "writes the new profile")
    check(re.search(r"spindle_ka_w\s+[0-9.]+\s+\+-\s+[0-9.]", r.stdout) is not None,
          "prints spindle KA with its standard error")
    check("RMSE" in r.stdout and "R^2" in r.stdout, "prints RMSE and R^2")
    with open(out, "rb") as f:
        doc = tomllib.load(f)
    pav = doc["power"]["pavanaskar"]
    check(abs(pav["spindle_ka_w"] - KA) < 1e-3 * abs(KA),
          f"spindle KA {pav['spindle_ka_w']} = {KA:.3f} W (91.67, Pavanaskar)")
    check(abs(pav["spindle_kb_w_per_rpm"] - KB) < 1e-4 * KB,
          f"spindle KB {pav['spindle_kb_w_per_rpm']} = {KB:.5f} W/rpm (0.21)")
    check(abs(pav["x"]["move_ka_w"] - 40) < 1e-3, f"X move KA 40 W (got {pav['x']['move_ka_w']})")
    check(abs(pav["x"]["move_kb_w_per_mm_s"] - 0.5) < 1e-5,
          f"X move KB 0.5 W/(mm/s) (got {pav['x']['move_kb_w_per_mm_s']})")
    check(pav["tare_w"] == 325, f"the baseline is not written as the tare (tare {pav['tare_w']})")
    check(pav["y"]["move_ka_w"] == 348.57, "constants not fitted keep the base profile's values")
    check(doc["kinematics"]["x"]["rapid_in_min"] == 710, "the base profile's other tables are kept")
    text = open(out).read()
    check("fitted from " + spindle in text and "baseline of 375 W" in text,
          "the profile says where the fitted values came from and above what baseline")
    r = run("estimate", SAMPLE, "--machine", out, "--no-removal")
    check(r.returncode == 0, f"ncjoule loads the new profile (estimate exits {r.returncode}: "
          f"{r.stderr[:200]})")

    # Without --baseline-w the tare is the baseline: the same spindle fit needs --tare-w 375,
    # and then 375 W is what the profile's tare becomes.
    out2 = os.path.join(tmp, "tare375.toml")
    r = run("calibrate", "--machine", HAAS, "--spindle", spindle, "--tare-w", "375", "-o", out2)
    with open(out2, "rb") as f:
        pav2 = tomllib.load(f)["power"]["pavanaskar"]
    check(r.returncode == 0 and abs(pav2["spindle_ka_w"] - KA) < 1e-3 * abs(KA)
          and pav2["tare_w"] == 375, "--tare-w 375 alone: same fit, tare 375 written")

    # --model pavanaskar from a base profile whose cutting term is the material's (the generic
    # one): Pavanaskar's model cuts with its own per-axis lines, so the written profile carries
    # no cutting term, and loads.
    out4 = os.path.join(tmp, "pav.toml")
    r = run("calibrate", "--machine", GENERIC, "--model", "pavanaskar", "--spindle", spindle,
            "-o", out4)
    with open(out4, "rb") as f:
        power4 = tomllib.load(f)["power"]
    check(r.returncode == 0 and power4["model"] == "pavanaskar" and "cutting_term" not in power4,
          f"--model pavanaskar from a material-term base: no cutting_term written ({r.returncode})")
    r = run("estimate", SAMPLE, "--machine", out4, "--no-removal")
    check(r.returncode == 0, f"and ncjoule loads it (estimate exits {r.returncode}: "
          f"{r.stderr[:200]})")

    # Without --machine: the [power] tables alone, to take into a profile (it is no profile by
    # itself, so it is not loaded before it is written).
    out5 = os.path.join(tmp, "power-only.toml")
    r = run("calibrate", "--spindle", spindle, "--baseline-w", "375", "-o", out5)
    with open(out5, "rb") as f:
        doc5 = tomllib.load(f)
    check(r.returncode == 0 and "kinematics" not in doc5
          and abs(doc5["power"]["pavanaskar"]["spindle_ka_w"] - KA) < 1e-3 * abs(KA),
          f"no --machine: the [power] tables alone, with the fit ({r.returncode}: "
          f"{r.stderr[:200]})")

    # A cell that is not a number: file, line and column, exit 2, nothing written.
    bad = write(os.path.join(tmp, "bad.csv"), "rpm,power_w\n3000,1100\n4000,13O0\n5000,1520\n")
    out3 = os.path.join(tmp, "never.toml")
    r = run("calibrate", "--machine", HAAS, "--spindle", bad, "-o", out3)
    check(r.returncode == 2, f"bad cell: exit 2 (got {r.returncode})")
    check(f"{bad}:3:6:" in r.stderr, f"names {bad}:3:6 (got {r.stderr.strip()[:200]})")
    check(not os.path.exists(out3) and not os.path.exists(out3 + ".tmp"), "writes nothing")

    missing = write(os.path.join(tmp, "no-rpm.csv"), "speed,power_w\n3000,1100\n")
    r = run("calibrate", "--machine", HAAS, "--spindle", missing, "-o", out3)
    check(r.returncode == 2 and missing in r.stderr and "rpm" in r.stderr,
          f"a missing column: exit 2 naming the file and the column (got {r.returncode}: "
          f"{r.stderr.strip()[:200]})")

    # Absurd numbers, too few rows, one speed only: exit 2 with the reason, nothing written,
    # never a crash (1e308 once ended in SIGSEGV inside Eigen's SVD; 1e300 wrote
    # spindle_kb = 1e+297 +- nan; one row gave a line).
    for name, text, said in (
            ("huge.csv", "rpm,power_w\n3000,1e308\n4000,1e308\n5000,1e308\n", "huge.csv:2:6:"),
            ("big.csv", "rpm,power_w\n3000,1e300\n4000,1e300\n5000,1e300\n", "beyond"),
            ("negative.csv", "rpm,power_w\n3000,-1100\n4000,1300\n5000,1520\n", "negative"),
            ("one-row.csv", "rpm,power_w\n3000,1100\n", "1 usable row"),
            ("one-speed.csv", "rpm,power_w\n3000,1100\n3000,1110\n3000,1090\n",
             "same spindle speed")):
        path = write(os.path.join(tmp, name), text)
        r = run("calibrate", "--machine", HAAS, "--spindle", path, "-o", out3)
        check(r.returncode == 2 and said in r.stderr and "nan" not in r.stdout
              and not os.path.exists(out3),
              f"{name}: exit 2 saying {said!r} (got {r.returncode}: {r.stderr.strip()[:200]})")
    r = run("calibrate", "--machine", HAAS, "--spindle", spindle, "--tare-w", "1e308", "-o", out3)
    check(r.returncode == 1 and not os.path.exists(out3),
          f"--tare-w 1e308: refused (got {r.returncode})")

    # Exit codes.
    r = run("calibrate", "--machine", HAAS, "-o", out3)
    check(r.returncode == 1, f"nothing to fit: exit 1 (got {r.returncode})")
    r = run("calibrate", "--spindle", spindle)
    check(r.returncode == 1, f"no -o: exit 1 (got {r.returncode})")
    r = run("calibrate", "--spindle", spindle, "--model", "linear", "-o", out3)
    check(r.returncode == 1, f"unknown model: exit 1 (got {r.returncode})")
    broken = write(os.path.join(tmp, "broken.toml"), "name = \"x\"\n[power\n")
    r = run("calibrate", "--machine", broken, "--spindle", spindle, "-o", out3)
    check(r.returncode == 2 and broken in r.stderr,
          f"a profile that does not parse: exit 2 naming it (got {r.returncode})")
    r = run("calibrate", "--machine", HAAS, "--spindle", spindle, "-o",
            os.path.join(tmp, "no-such-dir", "x.toml"))
    check(r.returncode == 3, f"an output that cannot be written: exit 3 (got {r.returncode})")
    r = run("calibrate", "--machine", HAAS, "--log", spindle, "-o", out3)
    check(r.returncode == 1, f"--log without --program: exit 1 (got {r.returncode})")
    check(not os.path.exists(out3), "no profile from any failed run")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("all checks passed")
