#!/usr/bin/env python3
"""`ncjoule compare` on Pavanaskar's X- vs Y-direction facing of the same 100 x 60 face (D20 end
mill, 10 mm stepover, F800) on the Haas VF-0 profile: the direction the profile's axis constants imply wins, the component split
names the axis terms as the reason, and the axis energies agree with the constants worked out by
hand. Also: --csv, --help of every subcommand, the progress bar (quiet unless on a terminal)."""
import csv
import io
import json
import os
import pty
import re
import shutil
import subprocess
import sys
import tempfile
import tomllib

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
PROGRAMS = os.path.join(ROOT, "samples/programs")
HAAS = os.path.join(ROOT, "samples/machines/haas-vf0-pavanaskar2014.toml")
X = os.path.join(PROGRAMS, "pavanaskar-facing-x.ngc")
Y = os.path.join(PROGRAMS, "pavanaskar-facing-y.ngc")
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def run(*args, **kw):
    return subprocess.run([NCJOULE, *args], capture_output=True, text=True, **kw)


def sidecar_stock(program):
    with open(os.path.splitext(program)[0] + ".stock") as f:
        return f.read().strip()


stock = sidecar_stock(X)
check(stock == sidecar_stock(Y), "both alternatives start from the same stock")
with open(HAAS, "rb") as f:
    axes = tomllib.load(f)["power"]["pavanaskar"]
ax, ay = axes["x"], axes["y"]

r = run("compare", Y, X, "--machine", HAAS, "--stock", stock, "--json")
check(r.returncode == 0, f"compare --json exits 0 ({r.stderr[:200]!r})")
doc = json.loads(r.stdout)
progs = doc["programs"]
by_name = {os.path.basename(p["file"]): p for p in progs}
px, py = by_name["pavanaskar-facing-x.ngc"], by_name["pavanaskar-facing-y.ngc"]
check([p["rank"] for p in progs] == [1, 2], "ranks 1, 2")
check(progs[0]["energy_j"] <= progs[1]["energy_j"], "cheapest energy first")

for p in (px, py):
    check(abs(p["removed_mm3"] - 6000) < 0.002 * 6000, f"removes 100*60*1 = 6000 mm^3 ({p['removed_mm3']:.1f})")

# The profile's X move line is below Y's at the passes' F800 (Table 4.1: the Y table carries the X
# axis), so facing along X must be cheaper.
v = 800 / 60
x_lighter = ax["move_ka_w"] + ax["move_kb_w_per_mm_s"] * v < ay["move_ka_w"] + ay["move_kb_w_per_mm_s"] * v
check(x_lighter, "the Haas profile's X move line is below Y's at F800")
expected_best = px if x_lighter else py
check(progs[0]["file"] == expected_best["file"],
      f"the direction the constants favour wins: {os.path.basename(progs[0]['file'])}")
loser = py if x_lighter else px
d = loser["vs_best"]
check(abs(d["energy_j"] - (loser["energy_j"] - expected_best["energy_j"])) < 1e-6 * loser["energy_j"],
      "vs_best.energy_j is the difference to the best")
check(abs(d["energy_pct"] - 100 * d["energy_j"] / expected_best["energy_j"]) < 1e-9 * 100,
      "vs_best.energy_pct is relative to the best")
# One cutting term for every axis: the same volume costs the same to cut either way.
check(d["components"]["axis_y"] > 0 and abs(d["components"]["cutting"]) < 1e-3 * d["energy_j"],
      "the component split shows the reason: the Y axis up, the cutting the same")
check(abs(sum(d["components"].values()) - d["energy_j"]) < 1e-6 * loser["energy_j"],
      "component differences add up to the energy difference")
check("axis_y" in loser["why"], f"'why' names the axis_y term: {loser['why']!r}")

# By hand, block by block: a pass that cuts its full 10 mm width 1 mm deep over the stock (along
# X 100 mm, 1000 mm^3; along Y 60 mm, 600 mm^3). The feeding axis draws its move line throughout,
# so over the block KA_move * t + KB_move * length (the integral of KB * v is KB times the
# distance, ramps and all); the cut draws k_c / efficiency per mm^3 removed, the profile's one
# cutting term.
with open(HAAS, "rb") as f:
    power = tomllib.load(f)["power"]
drawn_j_mm3 = power["profile_material"]["kc_j_mm3"] / power["cutting_efficiency"]
for program, axis, k, run_mm in [(X, "axis_x", ax, 100), (Y, "axis_y", ay, 60)]:
    r = run("estimate", program, "--machine", HAAS, "--stock", stock, "--json")
    volume = 10 * run_mm
    blocks = [b for b in json.loads(r.stdout)["blocks"] if abs(b["removed_mm3"] - volume) < 2]
    check(len(blocks) >= 4, f"{os.path.basename(program)}: passes cutting {volume} mm^3 ({len(blocks)})")
    for b in blocks:
        c = b["components"]
        axis_w = k["move_ka_w"] * b["time_s"] + k["move_kb_w_per_mm_s"] * b["length_mm"]
        cutting = drawn_j_mm3 * b["removed_mm3"]
        check(abs(c[axis] - axis_w) < 1e-3 * axis_w and abs(c["cutting"] - cutting) < 1e-3 * cutting,
              f"{os.path.basename(program)} line {b['line']}: axis {c[axis]:.1f} J = "
              f"{k['move_ka_w']} W x {b['time_s']:.3f} s + {k['move_kb_w_per_mm_s']} x "
              f"{b['length_mm']} mm; cutting {c['cutting']:.1f} J = {drawn_j_mm3:.4f} J/mm^3 x "
              f"{b['removed_mm3']:.0f} mm^3")

# The table for people.
r = run("compare", X, Y, "--machine", HAAS, "--stock", stock)
check(r.returncode == 0 and "best" in r.stdout and "kJ more than" in r.stdout and "axis_y" in r.stdout,
      "the text table ranks, compares and names the reason")
check(doc["warnings"] == [], f"the same part: no warning ({doc['warnings']})")
for p in progs:
    split = p["time_split"]
    check(abs(split["feed_s"] + split["rapid_s"] + split["tool_change_s"] + split["dwell_s"]
              + split["spindle_s"] + split["other_s"] - p["time_s"]) < 1e-6
          and abs(split["cutting_s"] + split["air_cut_s"] - split["feed_s"]) < 1e-6
          and p["peak_power_w"] > 0,
          f"the JSON's time split adds up to the time ({split})")
check(progs[0]["why_in_time"] == "" and progs[1]["why_in_time"] != "",
      f"the JSON says the difference in time ({progs[1]['why_in_time']!r})")
for p in progs:
    check(0 < p["air_cut_s"] < p["time_s"], f"air cutting time per alternative ({p['air_cut_s']:.1f} s)")
check("air cut" in r.stdout, "the table shows air cutting")
check("peak kW" in r.stdout and "time by what it is spent on" in r.stdout
      and "rapids" in r.stdout and ("s longer" in r.stdout or "s shorter" in r.stdout),
      f"the table shows the peak power and the time split ({r.stdout[-600:]!r})")

# Alternatives that do not make the same part: said, in the table and in the JSON.
other = os.path.join(PROGRAMS, "anziani-table2-1.ngc")
r = run("compare", X, other, "--machine", HAAS, "--json")
check(r.returncode == 0 and any("different volumes" in w for w in json.loads(r.stdout)["warnings"]),
      "different volumes: a JSON warning")
r = run("compare", X, other, "--machine", HAAS)
check("warning: the alternatives remove different volumes" in r.stdout, "different volumes: in the table")

# Names are never shortened, and equal file names in two folders are told apart; one time
# format per column.
with tempfile.TemporaryDirectory() as d:
    long_name = os.path.join(d, "a-very-long-program-name-for-the-roughing-alternative.ngc")
    shutil.copy(X, long_name)
    os.mkdir(os.path.join(d, "v2"))
    same = os.path.join(d, "v2", os.path.basename(X))
    shutil.copy(Y, same)
    r = run("compare", long_name, X, same, "--machine", HAAS, "--stock", stock)
    check(r.returncode == 0, f"compare three ({r.stderr[-200:]!r})")
    check(r.stdout.count(os.path.basename(long_name)) >= 3, "a long name is printed whole, in both tables")
    check(same in r.stdout and X in r.stdout, "equal file names: shown with their paths")
    rows = [l for l in r.stdout.splitlines() if l[:3].strip().isdigit()]
    times = [l.split()[3] for l in rows]
    check(len(rows) == 3 and all(":" in t for t in times), f"one time format in the column: {times}")

r = run("compare", X, "--machine", HAAS)
check(r.returncode == 1 and "two or more" in r.stderr, "one program: exit 1, says why")
r = run("compare", X, os.path.join(PROGRAMS, "missing.ngc"), "--machine", HAAS)
check(r.returncode == 2 and "missing.ngc" in r.stderr and r.stdout == "", "missing file: exit 2, named, no table")

# estimate --csv: one row per block, header, numbers that add up.
r = run("estimate", X, "--machine", HAAS, "--stock", stock, "--csv")
rows = list(csv.DictReader(io.StringIO(r.stdout)))
j = json.loads(run("estimate", X, "--machine", HAAS, "--stock", stock, "--json").stdout)
check(r.returncode == 0 and len(rows) == len(j["blocks"]), f"--csv has one row per block ({len(rows)})")
check(abs(sum(float(x["energy_j"]) for x in rows) - j["energy_j"]) < 1e-6 * j["energy_j"],
      "--csv energies add up to the total")
check(all(x["operation"] == "FACE1" for x in rows if x["kind"] == "feed"),
      "--csv names each block's operation")
check([o["name"] for o in j["operations"]] == ["FACE1"], "JSON operations: FACE1 (the post's comment)")
r = run("estimate", X, "--machine", HAAS, "--stock", stock)
check("by operation" in r.stdout and "FACE1" in r.stdout and "kWh" in r.stdout and "kJ" in r.stdout,
      "human summary: kWh, kJ and the operation split")

# --help for every registered subcommand.
top = run("--help").stdout
subs = [line.split()[0] for line in top.split("Subcommands:")[1].splitlines() if line.startswith("  ") and line.split()]
subs = [s for s in subs if s.isidentifier()]
check({"estimate", "compare", "report"} <= set(subs), f"subcommands listed: {subs}")
for s in subs:
    h = run(s, "--help")
    options = [l for l in h.stdout.splitlines() if l.strip().startswith("-")]
    described = all(len(l.split(None, 1)) > 1 for l in options)
    check(h.returncode == 0 and "Usage" in h.stdout and options and described,
          f"{s} --help: usage and every option described")

# Progress: nothing on a pipe; a bar on a terminal, erased at the end.
r = run("estimate", X, "--machine", HAAS, "--stock", stock)
check("\r" not in r.stderr and "\033[" not in r.stderr, "no progress bar when stderr is a pipe")
master, slave = pty.openpty()
env = dict(os.environ, NCJOULE_PROGRESS_DELAY_MS="0", TERM="xterm")
p = subprocess.Popen([NCJOULE, "compare", X, Y, "--machine", HAAS, "--stock", stock],
                     stdout=subprocess.DEVNULL, stderr=slave, env=env)
p.wait()
os.close(slave)
seen = b""
while True:
    try:
        chunk = os.read(master, 4096)
    except OSError:
        break
    if not chunk:
        break
    seen += chunk
os.close(master)
# Wine's console redraws what a Windows program writes: it hides and shows the cursor around
# every write (ESC[?25l, ESC[?25h), moves over blanks (ESC[nC) and clears after words (ESC[K).
# Those are its rendering, not ours: the text and the final erase are what is checked.
seen = re.sub(rb"\x1b\[\?25[hl]", b"", seen)
seen = re.sub(rb"\x1b\[(\d*)C", lambda m: b" " * int(m.group(1) or b"1"), seen)
text = re.sub(rb"\x1b\[K(?!$)", b"", seen)
check(b"estimating [" in text and seen.endswith(b"\r\x1b[K"),
      f"progress bar on a terminal, erased at the end ({seen[-60:]!r})")

# Rank by time or by cost; cost is the electricity plus the time at a machine-hour rate.
def ranked(*extra):
    r = run("compare", X, Y, "--machine", HAAS, "--stock", stock, "--price", "0.2", "--json",
            *extra)
    check(r.returncode == 0, f"compare {' '.join(extra)} exits 0 ({r.stderr[:200]!r})")
    return json.loads(r.stdout)


by_time = ranked("--by", "time")
check(by_time["ranked_by"] == "time_s", "--by time is said in the JSON")
times = [p["time_s"] for p in by_time["programs"]]
check(times == sorted(times), f"--by time: shortest first ({times})")
rate = 90.0
by_cost = ranked("--by", "cost", "--machine-rate", str(rate))
check(by_cost["ranked_by"] == "cost", "--by cost is said in the JSON")
costs = [p["cost"] for p in by_cost["programs"]]
check(costs == sorted(costs), f"--by cost: lowest first ({costs})")
for p in by_cost["programs"]:
    check(abs(p["machine_cost"] - p["time_s"] / 3600 * rate) <= 1e-9 * p["machine_cost"],
          f"machine cost = time x rate ({p['machine_cost']:.6f})")
    electricity = p["energy_j"] / 3.6e6 * 0.2
    check(abs(p["cost"] - (electricity + p["machine_cost"])) <= 1e-9 * p["cost"],
          f"cost = electricity {electricity:.6f} + machine time")
second = by_cost["programs"][1]
check(second["why_by_operation"] != "" and second["currency"] in second["why_by_operation"],
      f"the second's cost difference by operation ({second['why_by_operation']!r})")
check(by_cost["programs"][0]["why_by_operation"] == "", "the best has no 'why'")
# Without a rate, cost is the electricity alone and ranks as energy does.
no_rate = ranked("--by", "cost")
check([p["file"] for p in no_rate["programs"]] == [p["file"] for p in progs],
      "--by cost without a rate ranks as energy does")
check(all(p["machine_cost"] == 0 for p in no_rate["programs"]), "no rate: no machine cost")

r = run("compare", X, Y, "--machine", HAAS, "--stock", stock, "--by", "time")
check(r.returncode == 0 and "shortest time first" in r.stdout, "the table says its order")
check("longer than" in r.stdout and "by operation:" in r.stdout,
      f"the table says how much longer, by operation ({r.stdout[-300:]!r})")
r = run("compare", X, Y, "--machine", HAAS, "--by", "speed")
check(r.returncode != 0 and "speed" in r.stderr, f"--by speed is refused ({r.stderr[:120]!r})")

# The estimate's cost and its operations' costs with a rate: the parts add up.
r = run("estimate", X, "--machine", HAAS, "--stock", stock, "--machine-rate", "90", "--json")
doc = json.loads(r.stdout)
energy = doc.get("energy", doc)
total = energy["cost"]
ops = sum(op["cost"] for op in energy["operations"])
check(abs(ops - total) <= 1e-9 * total, f"operations' costs add up to the total ({ops} vs {total})")
r = run("estimate", X, "--machine", HAAS, "--stock", stock, "--machine-rate", "90")
check("machine time" in r.stdout and "/h" in r.stdout, "the summary splits the cost")

# A misspelt command or option gets the name nearest it, and still exits 1 (usage).
for args, hint in [(["estimat", X], "did you mean 'estimate'?"),
                   (["comapre", X, Y], "did you mean 'compare'?"),
                   (["estimate", X, "--stok", stock], "'--stok' is no option of estimate; did you mean '--stock'?"),
                   (["compare", X, Y, "--bye", "time"], "did you mean '--by'?")]:
    r = run(*args)
    check(r.returncode == 1 and hint in r.stderr, f"{' '.join(args[:1])}...: {hint} ({r.stderr[-120:]!r})")
r = run("frobnicate", X)
check(r.returncode == 1 and "did you mean" not in r.stderr, "nothing near 'frobnicate': no guess")

print(f"{len(failures)} failed")
sys.exit(1 if failures else 0)
