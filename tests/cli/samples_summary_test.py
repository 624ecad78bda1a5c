"""Every bundled sample program against its checked summary.

Usage: NCJOULE=path/to/ncjoule NCJOULE_SOURCE_DIR=repo python3 samples_summary_test.py
           [--update] [programs|freecad ...]

For each sample in samples/programs/ (*.ngc) and samples/freecad/ (*.nc) this runs
`ncjoule estimate SAMPLE --machine PROFILE --stock STOCK --json`, where STOCK is the text of the
sample's .stock sidecar, and compares the program's time_s, energy_j and removed_mm3 with
tests/cli/expected/<name>.json to 1e-6 relative. Samples in samples/freecad/ are named
freecad-<post> there.

The expected files are not taken on trust: for every family of samples the test also checks
numbers it works out itself from the geometry and the models (MODELS.md), so a golden file that
merely copied a wrong output would fail:
- anziani-table2-N: the cut line's steady MRR equals depth*width*feed/60 (Table 2), its peak
  power equals the Zhou model P = c1 + c2*n + c3*n^c4*MRR (Table 1), its time equals its length
  over the feed, and the removed volume equals width*depth*155 plus the crescent the tool's front
  leaves where the cut stops;
- pavanaskar-facing-x/-y: the removed volume is the faced layer 100*60*1 and the feed path is
  the zigzag's length worked out from its passes;
- pavanaskar-pocket-*: the removed volume is the round pocket pi*25^2*3, and the two spirals
  (one the other reversed) have the same feed path length, worked out from their half circles;
- bracket-linuxcnc: the facing lines remove the 100*60*1 top layer;
- freecad-*: the facing operation's feed path is the zigzag of the job
  (scripts/make_freecad_samples.py) and it removes the 60*40*0.5 top layer, and every post of the
  same job removes the same volume (posts that name no tool run with --no-removal).

--update writes the expected files from the current output (after the checks above pass);
review the differences before committing them.
"""
import glob
import json
import math
import os
import re
import subprocess
import sys
import tomllib

NCJOULE = os.environ.get("NCJOULE", "ncjoule")
ROOT = os.environ.get("NCJOULE_SOURCE_DIR",
                      os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
EXPECTED = os.path.join(ROOT, "tests", "cli", "expected")
MACHINES = os.path.join(ROOT, "samples", "machines")
REL_TOL = 1e-6

failures = []


def fail(name, message):
    failures.append("%s: %s" % (name, message))
    print("FAIL %s: %s" % (name, message))


def close(a, b, rel):
    return abs(a - b) <= rel * max(abs(a), abs(b), 1e-12)


def check_close(name, what, got, want, rel):
    if not close(got, want, rel):
        fail(name, "%s is %.9g, expected %.9g (relative tolerance %g)" % (what, got, want, rel))


# ------------------------------------------------------------------------------------------
# Which samples, on which machine, with which stock
# ------------------------------------------------------------------------------------------

def machine_for(name):
    """The profile each sample is meant for: the machine of the paper it comes from."""
    if name.startswith("anziani-"):
        return "zhou2017-anziani2025.toml"
    if name.startswith("pavanaskar-"):
        return "haas-vf0-pavanaskar2014.toml"
    if name == "bracket-linuxcnc":
        return "zhou2017-anziani2025.toml"  # as scripts/quickstart.sh runs it
    return "generic-3axis.toml"


# FreeCAD's posts write for different controllers; tests/gcode/freecad_samples_test.py explains
# each entry. The dialect each post writes for:
FREECAD_DIALECT = {"fanuc": "fanuc", "grbl": "grbl", "jtech": "grbl", "marlin": "reprap",
                   "rrf": "reprap", "smoothie": "reprap", "mach3_mach4": "mach3", "uccnc": "mach3",
                   "philips": "fanuc"}
# Posts whose output does not say which tool cuts: estimated with --no-removal.
FREECAD_NO_REMOVAL = {"grbl", "jtech", "marlin", "rrf", "fablin", "nccad", "philips", "centroid",
                      "comparams"}


def extra_arguments(name):
    if not name.startswith("freecad-"):
        return []
    post = name[len("freecad-"):]
    args = ["--dialect", FREECAD_DIALECT.get(post, "linuxcnc")]
    if post in FREECAD_NO_REMOVAL:
        args.append("--no-removal")
    return args


# Samples without a .stock sidecar: the stock their header comments describe.
STOCK_FALLBACK = {
    "bracket-linuxcnc": "box:0,0,-20,100,60,0",  # "Stock 100 x 60 x 20 mm, top at Z0"
}


def samples(groups):
    found = []
    if "programs" in groups:
        for path in sorted(glob.glob(os.path.join(ROOT, "samples", "programs", "*.ngc"))):
            found.append((os.path.splitext(os.path.basename(path))[0], path))
    if "freecad" in groups:
        for path in sorted(glob.glob(os.path.join(ROOT, "samples", "freecad", "*.nc"))):
            found.append(("freecad-" + os.path.splitext(os.path.basename(path))[0], path))
    return found


def stock_for(name, path):
    sidecar = os.path.splitext(path)[0] + ".stock"
    if os.path.exists(sidecar):
        with open(sidecar) as f:
            return f.read().strip()
    return STOCK_FALLBACK.get(name)


def estimate(name, path, stock):
    cmd = [NCJOULE, "estimate", path, "--machine", os.path.join(MACHINES, machine_for(name)),
           "--json"] + extra_arguments(name)
    if stock:
        cmd += ["--stock", stock]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        errors = [l for l in r.stderr.splitlines() if "error" in l] or r.stderr.splitlines()[-3:]
        fail(name, "ncjoule estimate exited %d: %s" % (r.returncode, " | ".join(errors[:3])))
        return None
    return json.loads(r.stdout)


# ------------------------------------------------------------------------------------------
# Independent checks
# ------------------------------------------------------------------------------------------

def source_lines(path):
    with open(path) as f:
        return f.read().split("\n")


def block_at(doc, line):
    for b in doc["blocks"]:
        if b["line"] == line:
            return b
    return None


def blocks_between(doc, first, last):
    return [b for b in doc["blocks"] if first <= b["line"] <= last]


# Table 2 of the Anziani thesis: test -> (n rpm, depth mm, width mm, feed mm/min, MRR mm^3/s)
TABLE2 = {1: (500, 3.0, 0.5, 120, 3.0), 2: (1300, 6.0, 1.5, 120, 18.0),
          3: (2100, 9.0, 2.0, 120, 36.0), 4: (2100, 6.0, 0.5, 180, 9.0),
          5: (500, 9.0, 1.5, 180, 40.5), 6: (1300, 3.0, 2.0, 180, 18.0),
          7: (1300, 9.0, 0.5, 240, 18.0), 8: (2100, 3.0, 1.5, 240, 18.0),
          9: (500, 6.0, 2.0, 240, 48.0)}
# Zhou et al. power model with the Anziani Table 1 constants (kW, rpm, mm^3/s), as the profile
# carries them (to the digits Table 2's model powers give; tests/energy checks that they round to
# the printed 0.78, 0.00017, 8.06e-7, 1.13).
with open(os.path.join(ROOT, "samples", "machines", "zhou2017-anziani2025.toml"), "rb") as f:
    _ZHOU = tomllib.load(f)["power"]["zhou"]
C1, C2, C3, C4 = _ZHOU["c1_kw"], _ZHOU["c2_kw_per_rpm"], _ZHOU["c3"], _ZHOU["c4"]
TOOL_R = 6.0


def crescent_area(r, w):
    """Area of the part of a disc of radius r within w of one edge of it: the crescent the
    tool's front leaves in a strip of width w where a side cut stops."""
    def F(u):
        return 0.5 * (u * math.sqrt(max(r * r - u * u, 0.0)) + r * r * math.asin(u / r))
    return F(-r + w) - F(-r)


def check_anziani(name, path, doc):
    test = int(name.rsplit("-", 1)[1])
    n, depth, width, feed, mrr_table = TABLE2[test]
    text = "\n".join(source_lines(path))
    # The program is the row it claims to be.
    mrr = depth * width * feed / 60.0
    check_close(name, "Table 2 MRR (depth*width*feed/60)", mrr, mrr_table, 1e-9)
    zmin = re.search(r"\(T1 D=12\. CR=0\. - ZMIN=(-?[0-9.]+) - FLAT END MILL\)", text)
    if not zmin or float(zmin.group(1)) != -depth:
        fail(name, "tool header does not describe a 12 mm flat end mill to ZMIN=-%g" % depth)
    if not re.search(r"\bS%d M3\b" % n, text):
        fail(name, "program does not run the spindle at S%d" % n)
    y = re.search(r"G0 X-7\. Y([0-9.]+)", text)
    if not y or float(y.group(1)) != 40 + TOOL_R - width:
        fail(name, "tool centre is not at Y = 40 + 6 - width (the stock edge is Y40)")
    # The cut: the line "X155." from X-7 at feed `feed`, the tool 6 mm wide of the stock edge.
    lines = source_lines(path)
    cut_line = next(i + 1 for i, l in enumerate(lines) if re.search(r"\bX155\.", l))
    cut = block_at(doc, cut_line)
    if cut is None:
        fail(name, "no block for the cut line %d" % cut_line)
        return
    check_close(name, "cut length", cut["length_mm"], 162.0, 1e-9)
    check_close(name, "cut time (length/feed)", cut["time_s"], 162.0 / (feed / 60.0), 5e-3)
    check_close(name, "steady MRR (peak over the cut)", cut["mrr_peak_mm3_s"], mrr, 5e-3)
    p_model_w = 1000 * (C1 + C2 * n + C3 * n ** C4 * mrr)
    check_close(name, "steady cutting power (Zhou model)", cut["power_peak_w"], p_model_w, 5e-3)
    volume = width * depth * 155.0 + depth * crescent_area(TOOL_R, width)
    check_close(name, "removed volume (cut)", cut["removed_mm3"], volume, 2e-3)
    check_close(name, "removed volume (program)", doc["removed_mm3"], volume, 2e-3)


def feed_length(doc):
    return sum(b["length_mm"] for b in doc["blocks"] if b["kind"] in ("feed", "arc"))


def check_facing(name, path, doc):
    check_close(name, "faced volume 100*60*1", doc["removed_mm3"], 100 * 60 * 1.0, 2e-3)
    # Zigzag with a 20 mm tool at 10 mm stepover, 12 mm run-out either side, 6 mm plunge.
    if name.endswith("-x"):
        passes, run, steps = 7, 100 + 24.0, 6
    else:
        passes, run, steps = 11, 60 + 24.0, 10
    check_close(name, "feed path length", feed_length(doc), passes * run + steps * 10.0 + 6.0,
                1e-9)


POCKET_R, POCKET_DEPTH, POCKET_TOOL_R, STEPOVER = 25.0, 3.0, 5.0, 4.0
spiral_lengths = {}


def check_pocket(name, path, doc):
    volume = math.pi * POCKET_R ** 2 * POCKET_DEPTH
    check_close(name, "pocket volume pi*25^2*3", doc["removed_mm3"], volume, 2e-3)
    final = POCKET_R - POCKET_TOOL_R
    plunge = 5.0 + POCKET_DEPTH
    if "spiral" in name:
        # Half circles of radius 1, 3, 5, ... (stepover/2 per half turn) out to the final
        # radius, and one full circle at the final radius.
        radii, k = [], 1
        while k * STEPOVER / 2 <= final + 1e-9:
            radii.append((2 * k - 1) * STEPOVER / 4)
            k += 1
        length = sum(math.pi * r for r in radii) + 2 * math.pi * final + plunge
        spiral_lengths[name] = feed_length(doc)
    else:
        rings = [STEPOVER * k for k in range(1, int(final / STEPOVER) + 1)]
        length = sum(2 * math.pi * r for r in rings) + STEPOVER * len(rings) + plunge
    check_close(name, "feed path length", feed_length(doc), length, 1e-6)


def check_bracket(name, path, doc):
    lines = source_lines(path)
    first = next(i + 1 for i, l in enumerate(lines) if l.startswith("(Facing"))
    last = next(i + 1 for i, l in enumerate(lines) if l.startswith("(Pocket"))
    faced = sum(b["removed_mm3"] for b in blocks_between(doc, first, last))
    check_close(name, "facing volume 100*60*1", faced, 100 * 60 * 1.0, 2e-3)


freecad_volumes = {}


def first_feed_run(doc):
    """The blocks from the first feed move up to the next rapid: the job's first operation."""
    run = []
    for b in doc["blocks"]:
        if b["kind"] in ("feed", "arc"):
            run.append(b)
        elif run and b["kind"] == "rapid":
            break
    return run


def check_freecad(name, path, doc):
    # The job's first operation, facing: a 3.5 mm plunge, then eight 68 mm passes (Y3 to Y38)
    # 5 mm apart, with no rapid in between.
    length = sum(b["length_mm"] for b in first_feed_run(doc))
    check_close(name, "facing feed path 3.5 + 8*68 + 7*5", length, 3.5 + 8 * 68 + 7 * 5, 1e-6)
    if "--no-removal" in extra_arguments(name):
        if doc["removed_mm3"] != 0:
            fail(name, "removal is off, yet %g mm^3 removed" % doc["removed_mm3"])
        return
    faced = sum(b["removed_mm3"] for b in first_feed_run(doc))
    check_close(name, "facing volume 60*40*0.5", faced, 60 * 40 * 0.5, 2e-3)
    freecad_volumes[name] = doc["removed_mm3"]


def independent_checks(name, path, doc):
    if name.startswith("anziani-table2-"):
        check_anziani(name, path, doc)
    elif name.startswith("pavanaskar-facing-"):
        check_facing(name, path, doc)
    elif name.startswith("pavanaskar-pocket-"):
        check_pocket(name, path, doc)
    elif name == "bracket-linuxcnc":
        check_bracket(name, path, doc)
    elif name.startswith("freecad-"):
        check_freecad(name, path, doc)
    else:
        fail(name, "no independent check for this sample: add one to samples_summary_test.py")


# ------------------------------------------------------------------------------------------

FIELDS = ("time_s", "energy_j", "removed_mm3")


def main(argv):
    update = "--update" in argv
    groups = [a for a in argv if not a.startswith("--")] or ["programs", "freecad"]
    found = samples(groups)
    if not found:
        fail("samples", "no sample programs found under %s" % os.path.join(ROOT, "samples"))
    for name, path in found:
        stock = stock_for(name, path)
        if stock is None:
            fail(name, "no .stock sidecar next to %s" % path)
            continue
        doc = estimate(name, path, stock)
        if doc is None:
            continue
        before = len(failures)
        independent_checks(name, path, doc)
        expected_path = os.path.join(EXPECTED, name + ".json")
        if update:
            if len(failures) == before:
                os.makedirs(EXPECTED, exist_ok=True)
                record = {"sample": os.path.relpath(path, ROOT),
                          "machine": "samples/machines/" + machine_for(name), "stock": stock,
                          "arguments": " ".join(extra_arguments(name))}
                record.update({k: doc[k] for k in FIELDS})
                with open(expected_path, "w") as f:
                    json.dump(record, f, indent=1)
                    f.write("\n")
                print("wrote %s" % os.path.relpath(expected_path, ROOT))
            continue
        if not os.path.exists(expected_path):
            fail(name, "no expected summary %s (write it with --update, after checking it)"
                 % os.path.relpath(expected_path, ROOT))
            continue
        with open(expected_path) as f:
            want = json.load(f)
        if want.get("stock") != stock:
            fail(name, "stock '%s' differs from the expected file's '%s'" % (stock, want.get("stock")))
        for k in FIELDS:
            check_close(name, k, doc[k], want[k], REL_TOL)
        print("ok   %-36s time %10.3f s  energy %12.1f J  removed %10.2f mm^3"
              % (name, doc["time_s"], doc["energy_j"], doc["removed_mm3"]))

    # Alternatives that must agree with each other.
    if len(spiral_lengths) == 2:
        a, b = sorted(spiral_lengths.values())
        if not close(a, b, 1e-9):
            fail("pavanaskar-pocket-spiral", "spiral in and out differ in path length: %g, %g" % (a, b))
    if freecad_volumes:
        reference = freecad_volumes.get("freecad-linuxcnc", next(iter(freecad_volumes.values())))
        for name, v in sorted(freecad_volumes.items()):
            if not close(v, reference, 5e-3):
                fail(name, "removes %.3f mm^3, the linuxcnc post of the same job %.3f" % (v, reference))

    if failures:
        print("%d failure(s)" % len(failures))
        return 1
    print("all %d samples agree with their expected summaries" % len(found))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
