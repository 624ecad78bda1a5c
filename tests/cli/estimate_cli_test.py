#!/usr/bin/env python3
"""`ncjoule estimate` end to end: the JSON names docs/json.md promises, totals that add up, and
clear failures (undefined tool, bad profile, unreadable file) with exit code 2."""
import json
import math
import os
import re
import subprocess
import sys
import tempfile

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
SAMPLE = os.path.join(ROOT, "samples/programs/bracket-linuxcnc.ngc")
ZHOU = os.path.join(ROOT, "samples/machines/zhou2017-anziani2025.toml")
STOCK = "box:0,0,-20,100,60,0"
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def run(*args, stdin=None):
    return subprocess.run([NCJOULE, *args], capture_output=True, text=True, input=stdin)


r = run("estimate", SAMPLE, "--machine", ZHOU, "--stock", STOCK, "--json")
check(r.returncode == 0, f"estimate --json exits 0 (got {r.returncode}: {r.stderr[:200]})")
doc = json.loads(r.stdout)
blocks = doc["blocks"]
for key in ["time_s", "energy_j", "removed_mm3", "sec_j_mm3", "co2_kg", "cost", "components",
            "warnings", "machine"]:
    check(key in doc, f"program has '{key}'")
for key in ["line", "kind", "time_s", "entry_speed_mm_s", "exit_speed_mm_s", "removed_mm3",
            "mrr_mm3_s", "mrr_peak_mm3_s", "power_w", "power_peak_w", "energy_j", "components"]:
    check(all(key in b for b in blocks), f"every block has '{key}'")
check(abs(sum(b["time_s"] for b in blocks) - doc["time_s"]) < 1e-6 * doc["time_s"],
      "block times add up to the program time")
# Lines that issue no command (G90 G94 G17, G54) start when the line before them has run, so the
# start times, read down the file, never go back (a straight program: no subprograms).
starts = [b["start_s"] for b in blocks]
check(all(a <= b + 1e-9 for a, b in zip(starts, starts[1:])) and starts[-1] > 0,
      f"start_s never goes back down the file ({starts[:12]}...)")
# A line that restates the modes in force issues no command at all: it is read when the line
# before it has run.
r = run("estimate", "-", "--machine", ZHOU, "--no-removal", "--json",
        stdin="G21 G90 G17\nG0 X0 Y0 Z5\nG1 X10 F600\nG17 G90\nG1 X20\nM30\n")
lines = {b["line"]: b for b in json.loads(r.stdout)["blocks"]}
check(4 in lines and lines[4]["commands"] == 0 and
      abs(lines[4]["start_s"] - (lines[3]["start_s"] + lines[3]["time_s"])) < 1e-9 and
      lines[5]["start_s"] >= lines[4]["start_s"],
      f"a line issuing no command starts when the line before it has run ({lines.get(4)})")
check(abs(sum(b["energy_j"] for b in blocks) - doc["energy_j"]) < 1e-6 * doc["energy_j"],
      "block energies add up to the program energy")
check(abs(sum(doc["components"].values()) - doc["energy_j"]) < 1e-6 * doc["energy_j"],
      "components add up to the program energy")
check(abs(sum(b["removed_mm3"] for b in blocks) - doc["removed_mm3"]) < 1e-6 * doc["removed_mm3"],
      "block volumes add up to the removed volume")
check(abs(doc["sec_j_mm3"] - doc["energy_j"] / doc["removed_mm3"]) < 1e-9 * doc["sec_j_mm3"],
      "SEC is energy over removed volume")
# The 100 x 60 facing pass at 1 mm depth removes 6000 mm^3 of the box's top.
facing = [b for b in blocks if 13 <= b["line"] <= 26 and b["kind"] == "feed"]
check(abs(sum(b["removed_mm3"] for b in facing) - 6000) < 0.002 * 6000,
      f"facing removes 6000 mm^3 within 0.2% (got {sum(b['removed_mm3'] for b in facing):.1f})")
rapids = [b for b in blocks if b["kind"] == "rapid"]
check(all(b["removed_mm3"] == 0 for b in rapids), "rapids remove nothing")
check(all(b["components"]["cutting"] == 0 for b in blocks if b["removed_mm3"] == 0),
      "no cutting energy where nothing is removed")

# A tool that is used but described nowhere is a warning naming the tool and the ways to describe
# it; its moves are timed but remove nothing, and the JSON lists it as not simulated.
with tempfile.TemporaryDirectory() as tmp:
    bare = os.path.join(tmp, "bare.ngc")
    with open(bare, "w") as f:
        f.write("G21 G90\nT7 M6\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X50\nM30\n")
    r = run("estimate", bare, "--machine", ZHOU, "--json")
    doc = json.loads(r.stdout) if r.returncode == 0 else None
    check(doc is not None and "T7" in r.stderr and "--tool" in r.stderr,
          f"undefined tool T7: exit 0, a warning names it and --tool ({r.stderr[:160]!r})")
    check(doc is not None and doc["unsimulated_tools"] == [7] and doc["time_s"] > 0
          and doc["removed_mm3"] == 0, "T7's moves are timed, remove nothing, and are listed")
    r = run("estimate", bare, "--machine", ZHOU, "--tool", "7:flat:6", "--json")
    check(r.returncode == 0 and json.loads(r.stdout)["unsimulated_tools"] == []
          and json.loads(r.stdout)["tools"][0]["diameter_mm"] == 6, "--tool 7:flat:6 describes it")
    tbl = os.path.join(tmp, "tool.tbl")
    with open(tbl, "w") as f:
        f.write("T7 P7 Z25 D8 ;8mm ball end mill\n")
    r = run("estimate", bare, "--machine", ZHOU, "--tool-table", tbl, "--stock",
            "box:-10,-10,-5,60,10,0", "--json")
    doc = json.loads(r.stdout) if r.returncode == 0 else None
    check(doc is not None and doc["tools"][0]["shape"] == "ball end mill"
          and doc["tools"][0]["diameter_mm"] == 8 and doc["removed_mm3"] > 0,
          "--tool-table gives T7 its size and shape")
    r = run("estimate", bare, "--machine", ZHOU, "--no-removal", "--json")
    check(r.returncode == 0 and json.loads(r.stdout)["removed_mm3"] == 0,
          "--no-removal estimates without tools")
    bad = os.path.join(tmp, "bad.toml")
    with open(ZHOU) as f:
        text = f.read()
    with open(bad, "w") as f:
        f.write(text.replace("accel_mm_s2 = 1000", "accel_mm_s2 = -1", 1))
    r = run("estimate", bare, "--machine", bad, "--no-removal")
    check(r.returncode == 2 and "accel" in r.stderr and "bad.toml" in r.stderr,
          f"negative acceleration refused with file and key ({r.stderr.strip()[:160]!r})")
    r = run("estimate", os.path.join(tmp, "missing.ngc"), "--machine", ZHOU)
    check(r.returncode == 2 and "missing.ngc" in r.stderr, "unreadable input: exit 2, named")

# Progress for other programs: NCJOULE_PROGRESS=lines gives "PROGRESS n" lines, in order, to 100.
env = dict(os.environ, NCJOULE_PROGRESS="lines")
r = subprocess.run([NCJOULE, "estimate", SAMPLE, "--machine", ZHOU, "--json"], capture_output=True,
                   text=True, env=env)
percents = [int(l.split()[1]) for l in r.stderr.splitlines() if l.startswith("PROGRESS ")]
check(r.returncode == 0 and len(percents) >= 3 and percents == sorted(percents)
      and percents[-1] == 100 and percents[0] == 0, f"progress lines in order to 100 ({percents})")

# The same problem on every feed move (a FreeCAD tool controller with no feed rate) is one
# message with its count and the next lines, not one line per block.
zero_feed = "G21 G90\nT1 M6\nS1000 M3\nG0 X0 Y0 Z1\n" + "".join(
    f"G1 X{k} Y{k % 3}\n" for k in range(1, 61)) + "M2\n"
r = run("estimate", "-", "--machine", ZHOU, "--no-removal", stdin=zero_feed)
lines = [l for l in r.stderr.splitlines() if "no feed rate" in l]
check(r.returncode == 2 and len(lines) == 1 and "(59 more times: line 6, 7, 8, 9, 10, ...)" in lines[0],
      f"a repeated error is printed once with its count ({lines[:2]})")

# The control's own programs: a G65/M98 call to a macro not in the file runs the one in a
# --macro-dir folder (named O9810.NC, 9811 or O09812.min), else in the profile's macro_dirs
# (relative to the profile); with neither, the call is skipped with a warning.
with tempfile.TemporaryDirectory() as tmp:
    macros = os.path.join(tmp, "macros")
    os.mkdir(macros)
    for name, number, x in [("O9810.NC", 9810, 10), ("9811", 9811, 20), ("O09812.min", 9812, 30)]:
        with open(os.path.join(macros, name), "w") as f:
            f.write(f"%\nO{number}\nG1 X{x}. F600.\nM99\n%\n")
    prog = os.path.join(tmp, "main.nc")
    with open(prog, "w") as f:
        f.write("O0001\nG21 G90 G0 X0 Y0 Z5\nG65 P9810\nM98 P9811\nG65 P9812\nM30\n")

    def feed_time(*extra):
        r = run("estimate", prog, "--machine", ZHOU, "--no-removal", "--json", *extra)
        doc = json.loads(r.stdout)
        return r, sum(b["time_s"] for b in doc["blocks"] if b["line"] in (3, 4, 5))

    r, t = feed_time("--macro-dir", macros)
    # 30 mm of feed at 600 mm/min is 3 s; the profile's acceleration adds a little.
    check(r.returncode == 0 and 3.0 <= t < 3.5 and "not in this file" not in r.stderr,
          f"--macro-dir runs the three macros ({t:.3f} s, {r.stderr.strip()[:120]!r})")
    r, t = feed_time()
    check(r.returncode == 0 and t < 0.01 and r.stderr.count("not in this file") == 3,
          f"without the folder the calls are skipped with a warning each ({t:.3f} s)")
    profile = os.path.join(tmp, "machine.toml")
    with open(ZHOU) as f:
        text = f.read()
    with open(profile, "w") as f:
        f.write(text + '\n[setup]\nmacro_dirs = ["macros"]\n')
    r = run("estimate", prog, "--machine", profile, "--no-removal", "--json")
    t = sum(b["time_s"] for b in json.loads(r.stdout)["blocks"] if b["line"] in (3, 4, 5))
    check(r.returncode == 0 and 3.0 <= t < 3.5, f"the profile's macro_dirs, relative to it ({t:.3f} s)")
    r = run("estimate", prog, "--machine", ZHOU, "--macro-dir", os.path.join(tmp, "nope"))
    check(r.returncode != 0 and "nope" in r.stderr, "a --macro-dir that does not exist is refused")

# Shipped machine classes: `ncjoule profiles` lists every one (each loads), --machine finds them
# by name, and a router job at 24,000 rpm idles at the router spindle's power, not a VMC's.
r = subprocess.run([NCJOULE, "profiles"], capture_output=True, text=True)
listed = [l.split()[0] for l in r.stdout.splitlines() if l.strip()]
shipped = sorted(f[:-5] for f in os.listdir(os.path.join(ROOT, "samples/machines")) if f.endswith(".toml"))
check(r.returncode == 0 and listed == shipped and "cannot be read" not in r.stdout,
      f"ncjoule profiles lists the shipped profiles ({listed})")
router_job = ("G21 G90\n(T1 D=6. CR=0. - ZMIN=-1. - FLAT END MILL)\nT1 M6\nS24000 M3\nG4 P10\n"
              "G0 X0 Y0 Z5\nM5\nM30\n")
def spindle_w(machine):
    r = run("estimate", "-", "-m", machine, "--no-removal", "--json", stdin=router_job)
    doc = json.loads(r.stdout)
    dwell = [b for b in doc["blocks"] if b["line"] == 5][0]
    return r, dwell["components"]["spindle"] / dwell["time_s"]
r, w = spindle_w("router-2.2kw")
# The profile's line: 0.007 W/rpm x 24,000 rpm = 168 W (its estimate of a 2.2 kW spindle's
# no-load input); the generic VMC's extrapolated line gives over 5 kW.
check(r.returncode == 0 and abs(w - 168) < 1, f"router-2.2kw (prefix) idles at 168 W at 24,000 rpm ({w:.0f} W)")
r, w_generic = spindle_w("generic-3axis")
# The generic VMC's spindle tops out at 10,000 rpm: S24000 is run (and counted) at that, 2.2 kW
# on its line (91.67 + 0.21 x 10,000), and both the clamp and the line's extrapolation past its
# measured 3000-6700 rpm are said.
check(abs(w_generic - 2191.67) < 1 and "above the spindle's maximum of 10000 rpm" in r.stderr
      and "measured at 3000-6700 rpm" in r.stderr and "1.5x above" in r.stderr,
      f"the generic VMC clamps S24000 to its 10,000 rpm and says so ({w_generic:.0f} W)")
# A class profile says in the summary what of it is an estimate, not a measurement; the VF-0
# Pavanaskar measured says nothing of the kind.
r = run("estimate", "-", "-m", "router-2.2kw", stdin=router_job)
check(r.returncode == 0 and "estimated   this profile's power, timing and rates are estimates "
      "for its class of machine" in r.stdout, f"the router's summary says it is estimated ({r.stdout[:400]!r})")
r = run("estimate", "-", "-m", "haas-vf2", stdin=router_job)
check("estimated   this profile's power and timing" in r.stdout, "the VF-2's summary names its planner")
r = run("estimate", "-", "-m", "haas-vf0", stdin=router_job)
check(r.returncode == 0 and "estimated   " not in r.stdout, "a measured profile says nothing of it")
r = run("estimate", "-", "-m", "haas-vf9", stdin=router_job)
check(r.returncode != 0 and "haas-vf2" in r.stderr and "shipped profiles" in r.stderr,
      "an unknown profile name lists the shipped ones")

# The Zhou/Anziani profile's rates are placeholders (1000 mm/min): a program feeding faster is
# told that its time is no prediction; one within them is not.
for feed, warned in ((3000, True), (600, False)):
    r = run("estimate", "-", "--machine", ZHOU, "--no-removal", "--json",
            stdin=f"G21 G90\nG0 X0 Y0 Z5\nG1 X100 F{feed}\nM30\n")
    messages = [w["message"] for w in json.loads(r.stdout)["warnings"]]
    said = any("placeholders" in m and "3000 mm/min" in m for m in messages)
    check(said == warned, f"F{feed} on the Zhou profile: placeholder rates said: {said} ({messages})")

# The Zhou/Anziani machine's spindle is not described by its sources: its rating and maximum
# speed are placeholders, and the warnings they raise say so rather than predict a stall. A
# 20 mm end mill slotting 20 mm deep at F3000 asks some 100 kW of the placeholder 5.5 kW; on the
# generic profile, whose rating is a typical small VMC's, the same cut is read as a stall.
heavy = ("G21 G90\n(T1 D=20. - FLAT END MILL)\nT1 M6\nS{rpm} M3\nG0 X-15 Y0 Z5\nG0 Z-20\n"
         "G1 X100 F3000\nG0 Z5\nM30\n")
for machine, placeholder in ((ZHOU, True), ("generic-3axis", False)):
    r = run("estimate", "-", "--machine", machine, "--json", "--stock", "box:0,-20,-30,100,20,0",
            stdin=heavy.format(rpm=12000))
    messages = [w["message"] for w in json.loads(r.stdout)["warnings"]]
    load = [m for m in messages if "more than its rated power" in m]
    top = [m for m in messages if "above the spindle's maximum of 10000 rpm" in m]
    check(len(load) == 1 and ("placeholder" in load[0]) == placeholder
          and ("would stall" in load[0]) != placeholder,
          f"{machine}: the overload is read as {'a placeholder' if placeholder else 'a stall'} "
          f"({load})")
    check(len(top) == 1 and ("placeholder" in top[0]) == placeholder,
          f"{machine}: S12000 is clamped to 10000 rpm, the placeholder said: {placeholder} ({top})")

# An inch program's summary reads in in^3 and in^3/min (the mm^3 follow), its operations in
# in^3; the JSON stays in SI. A 0.25 in slot 0.1 in deep along 2 in of a 3 x 1 x 0.5 in block:
# about 0.25 * 0.1 * 2 = 0.05 in^3 plus the tool's round front.
with tempfile.TemporaryDirectory() as tmp:
    inch = os.path.join(tmp, "slot-inch.nc")
    with open(inch, "w") as f:
        f.write("%\nO1000 (SLOT)\n(T1 D=0.25 CR=0. - ZMIN=-0.1 - flat end mill)\nG20 G90 G17\n"
                "T1 M6\nS8000 M3\n(SLOT1)\nG0 X-0.5 Y0.5 Z0.2\nG1 Z-0.1 F10.\nG1 X2. F20.\n"
                "G0 Z0.2\nM5\nM30\n%\n")
    box = "box:0in,0in,-0.5in,3in,1in,0in"
    r = run("estimate", inch, "--stock", box, "--json")
    doc = json.loads(r.stdout)
    mm3 = doc["removed_mm3"]
    in3 = mm3 / 25.4 ** 3
    check(0.05 < in3 < 0.05 + 0.0125, f"the slot removes 0.05 in^3 and its front ({in3:.4f})")
    r = run("estimate", inch, "--stock", box)
    removed = [l for l in r.stdout.splitlines() if l.strip().startswith("removed")]
    check(len(removed) == 1 and f"{in3:.3f} in^3 ({mm3:.0f} mm^3)" in removed[0]
          and "in^3/min" in removed[0] and "J/in^3" in removed[0],
          f"the summary in in^3, in^3/min and J/in^3 ({removed})")
    rate = in3 / (doc["time_s"] / 60)
    check(f"mean MRR {rate:.3f} in^3/min" in removed[0], f"mean MRR {rate:.3f} in^3/min")
    check(" in^3 " in r.stdout.split("by operation:")[1].splitlines()[1],
          "the operations' volume column is in in^3")
    check("mm^3" in run("estimate", SAMPLE, "--machine", ZHOU, "--stock", STOCK).stdout,
          "a mm program's summary stays in mm^3")
    # The annotated slot's MRR is in in^3/min too. The block cuts the stock from X0 to X2 full
    # width (0.25 x 0.1 x 2 in) and the tool's round front past X2 (half a 0.25 in disc, 0.1 in
    # deep): 0.0525 in^3 over its time T (the spindle's run-up to S8000 included).
    block = [l for l in run("annotate", inch, "--stock", box).stdout.splitlines()
             if l.startswith("G1 X2. F20.")]
    fields = re.search(r" T=([0-9.]+)S .* MRR=([0-9.]+)", block[0], re.I) if len(block) == 1 else None
    expected = (0.25 * 0.1 * 2 + math.pi / 2 * 0.125 ** 2 * 0.1) / (float(fields.group(1)) / 60) \
        if fields else 0
    check(fields is not None and abs(float(fields.group(2)) / expected - 1) < 0.02,
          f"the slot block's MRR is {expected:.3f} in^3/min ({block})")

# A comment holding a terminal's escape sequences (a window title, a colour) names an operation:
# every text output shows it escaped (\x1b, \x07), never raw; JSON escapes it its own way.
with tempfile.TemporaryDirectory() as tmp:
    # The file name holds one too, but for Windows (NCJOULE_EXE: the tests under Wine), whose
    # file names cannot hold control characters.
    windows = bool(os.environ.get("NCJOULE_EXE"))
    hostile = os.path.join(tmp, "esc.ngc" if windows else "esc\x1b[31m.ngc")
    with open(hostile, "wb") as f:
        f.write(b"G21 G90\n(OP \x1b]0;title\x07 \x1b[31mRED)\nT1 M6\nS1000 M3\nG0 X0 Y0 Z5\n"
                b"G1 X10 F100\nM2\n")
    outputs = {
        "summary": [NCJOULE, "estimate", hostile, "--machine", ZHOU, "--no-removal"],
        "csv": [NCJOULE, "estimate", hostile, "--machine", ZHOU, "--no-removal", "--csv"],
        "compare": [NCJOULE, "compare", hostile, hostile, "--machine", ZHOU, "--no-removal"],
    }
    for name, cmd in outputs.items():
        r = subprocess.run(cmd, capture_output=True)
        # compare's table shows the file names, which hold the sequence only off Windows.
        shown = b"\\x1b" in r.stdout or (windows and name == "compare")
        check(r.returncode == 0 and b"\x1b" not in r.stdout and b"\x07" not in r.stdout and shown,
              f"{name}: control bytes escaped on stdout ({r.returncode}: {r.stdout[:300]!r} "
              f"{r.stderr[:200]!r})")

print(f"{len(failures) == 0 and 1 or 0} passed, {len(failures) and 1 or 0} failed")
sys.exit(1 if failures else 0)
