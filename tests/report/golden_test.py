#!/usr/bin/env python3
"""Golden test: the estimate summary of samples/programs/bracket-linuxcnc.ngc on the Zhou profile
(stock box:0,0,-20,100,60,0) against tests/report/golden/bracket-zhou.json, to 1e-6 relative;
and, independently of the golden file, numbers worked out by hand from the program and the
profile (docs/report.md tells how they were reviewed).

  golden_test.py            compare
  golden_test.py --update   rewrite the golden file (review the diff number by number!)"""
import json
import math
import os
import subprocess
import sys
import tomllib

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
PROGRAM = "samples/programs/bracket-linuxcnc.ngc"
PROFILE = "samples/machines/zhou2017-anziani2025.toml"
STOCK = "box:0,0,-20,100,60,0"
GOLDEN = os.path.join(ROOT, "tests/report/golden/bracket-zhou.json")
REL = 1e-6
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def near(a, b, rel):
    return abs(a - b) <= rel * max(abs(a), abs(b), 1e-9)


# Paths relative to the repository, so the document does not depend on where it was run.
r = subprocess.run([NCJOULE, "estimate", PROGRAM, "--machine", PROFILE, "--stock", STOCK, "--json"],
                   capture_output=True, text=True, cwd=ROOT)
if r.returncode != 0:
    print(r.stderr)
    sys.exit(1)
doc = json.loads(r.stdout)
summary_keys = ["time_s", "removed_mm3", "energy_j", "sec_j_mm3", "co2_kg", "cost", "currency",
                "components"]
op_keys = ["name", "tool", "line", "start_s", "time_s", "removed_mm3", "energy_j", "components"]
summary = {k: doc[k] for k in summary_keys}
summary["operations"] = [{k: op[k] for k in op_keys} for op in doc["operations"]]

if "--update" in sys.argv:
    with open(GOLDEN, "w") as f:
        json.dump(summary, f, indent=1)
        f.write("\n")
    print("wrote", GOLDEN)
    sys.exit(0)


def compare(path, got, want):
    if isinstance(want, dict):
        check(isinstance(got, dict) and set(got) == set(want), f"{path}: same keys")
        for k in want:
            if isinstance(got, dict) and k in got:
                compare(f"{path}.{k}", got[k], want[k])
    elif isinstance(want, list):
        check(isinstance(got, list) and len(got) == len(want), f"{path}: {len(want)} entries")
        for i, (g, w) in enumerate(zip(got or [], want)):
            compare(f"{path}[{i}]", g, w)
    elif isinstance(want, (int, float)) and not isinstance(want, bool):
        check(near(got, want, REL), f"{path} = {got} (golden {want})")
    else:
        check(got == want, f"{path} = {got!r} (golden {want!r})")


with open(GOLDEN) as f:
    compare("summary", summary, json.load(f))

# ---- Independent checks: from the program text and the profile, not from the output ----
with open(os.path.join(ROOT, PROFILE), "rb") as f:
    profile = tomllib.load(f)
zhou = profile["power"]["zhou"]
blocks = {b["line"]: b for b in doc["blocks"]}
ops = {op["name"]: op for op in doc["operations"]}
kwh = doc["energy_j"] / 3.6e6

check(list(ops) == ["Facing", "Pocket 40 x 20, corner radius 8, depth 6 in two steps", "Drilling"], f"operations named after the post's comments: {list(ops)}")
# Passes at Y3..57 with a 12 mm tool cover all of the 100 x 60 stock, 1 mm deep.
check(abs(ops["Facing"]["removed_mm3"] - 6000) < 0.005 * 6000,
      f"facing removes 100 x 60 x 1 mm within 0.5% (got {ops['Facing']['removed_mm3']:.1f})")
check(ops["Facing"]["tool"] == 1 and ops["Drilling"]["tool"] == 2, "T1 then T2")
check(ops["Facing"]["line"] == 8 and ops["Drilling"]["line"] == 45, "at the T1 M6 and T2 M6 lines")
for key in ["time_s", "energy_j", "removed_mm3"]:
    check(near(sum(op[key] for op in doc["operations"]), doc[key], 1e-9),
          f"operations add up to the program's {key}")

# Facing: 100 x 60 face, 1 mm deep -> 6000 mm^3 (the dexel grid is exact in Z, not in X/Y).
facing = sum(blocks[n]["removed_mm3"] for n in range(13, 27) if n in blocks)
check(abs(facing - 6000) < 0.002 * 6000, f"facing removes 100*60*1 = 6000 mm^3 (got {facing:.1f})")

# Drilling: four D6.8 holes with a 118 deg point from the faced top Z-1 to Z-15:
# cone height r / tan(59 deg); cylinder above it.
r_hole = 6.8 / 2
cone_h = r_hole / math.tan(math.radians(59))
hole = math.pi * r_hole ** 2 * ((15 - 1) - cone_h) + math.pi * r_hole ** 2 * cone_h / 3
check(abs(ops["Drilling"]["removed_mm3"] - 4 * hole) < 0.01 * 4 * hole,
      f"drilling removes 4 x {hole:.1f} mm^3 within 1% (got {ops['Drilling']['removed_mm3']:.1f})")

# Tool changes: the profile's tool_change_s each.
tc = [b for b in doc["blocks"] if b["kind"] == "tool_change"]
check(len(tc) == 2 and all(near(b["time_s"], profile["kinematics"]["tool_change_s"], 1e-9) for b in tc),
      f"two tool changes of {profile['kinematics']['tool_change_s']} s each")

# Zhou: c1 is the base power, drawn all the time -> tare energy = c1 * program time.
check(near(doc["components"]["tare"], zhou["c1_kw"] * 1000 * doc["time_s"], 1e-6),
      f"tare = c1 {zhou['c1_kw']} kW x {doc['time_s']:.3f} s")

# Cutting (Zhou): c3 * n^c4 * MRR integrated over time = c3 * n^c4 * volume, per spindle speed.
for name, rpm in [("Facing", 2100), ("Drilling", 1300)]:
    expect = 1000 * zhou["c3"] * rpm ** zhou["c4"] * ops[name]["removed_mm3"]
    check(near(ops[name]["components"]["cutting"], expect, 1e-3),
          f"{name} cutting = c3 * {rpm}^c4 * volume = {expect:.1f} J "
          f"(got {ops[name]['components']['cutting']:.1f})")

# The first facing pass, G1 X108. F480 from X-8: 116 mm at 8 mm/s; accelerating at 1 m/s^2 to
# 8 mm/s costs a few ms.
first_pass = blocks[14]
check(abs(first_pass["time_s"] - 116 / 8) < 0.01 * 116 / 8 and near(first_pass["length_mm"], 116, 1e-9),
      f"first facing pass 116 mm at 8 mm/s ~ 14.5 s (got {first_pass['time_s']:.3f})")

# CO2 and cost from the profile's factors.
check(near(doc["co2_kg"], kwh * profile["power"]["co2_kg_per_kwh"], 1e-9), "CO2 = kWh x factor")
check(near(doc["cost"], kwh * profile["power"]["price_per_kwh"], 1e-9), "cost = kWh x price")
check(near(doc["sec_j_mm3"], doc["energy_j"] / doc["removed_mm3"], 1e-9), "SEC = energy / volume")

print(f"{len(failures)} failed")
sys.exit(1 if failures else 0)
