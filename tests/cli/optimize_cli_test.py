#!/usr/bin/env python3
"""ncjoule optimize end to end (docs/optimize.md): a synthetic program with moves in air beside a
known box stock.
- The optimized program runs the same path under LinuxCNC's own interpreter (rs274 -g): the same
  motion end points in the same order; the motions that differ (a feed at the air feed, a feed
  turned traverse) are exactly the changed blocks; every other motion runs at its original feed.
- It removes the same volume, takes less time, gains no collision (estimate --json on both).
- A guessed stock, --in-place and -o naming the program are refused; the original is
  byte-identical after every run; strip leaves the NCJOPT marks.
- --load-feeds on a program with a heavy slot and a light pass: rs274 runs the same end points;
  the motions that differ are the LOAD-marked blocks, the slot slower, the pass at most 1.3 times
  faster; the time that grows is allowed, and said.
Environment: NCJOULE (the program), NCJOULE_SOURCE_DIR (the repository)."""
import atexit
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
GENERIC = os.path.join(ROOT, "samples/machines/generic-3axis.toml")
STOCK = "box:0,0,-10,40,20,0"
# rs274 keeps its tool table under $HOME: each test run gets its own.
RS274_HOME = tempfile.mkdtemp(prefix="rs274-home-")
atexit.register(shutil.rmtree, RS274_HOME, ignore_errors=True)
failures = []

PROGRAM = """%
(AIR TEST)
G21 G90 G17
(T1 D=6. CR=0. - FLAT END MILL)
T1 M6
S8000 M3
G0 X-10. Y10. Z5.
G1 Z-2. F300.
X45.
G1 Z5.
X50. F1000.
Y12.
G1 Z-3. F200.
X-10.
G0 Z5.
X5 Y-10
G1 Z-4 F250
G1 Y30 F500
Y35
G0 Z5
M5
M30
%
"""

# A 12 mm end mill: a full slot 8 mm deep at F5000 (above 70% of the 5.5 kW rating), a pass 2 mm
# wide at F1000 (far below it), a 0.2 mm skim (a finishing pass) and a link in air at F700.
LOAD_PROGRAM = """%
(LOAD TEST)
G21 G90 G17
(T1 D=12. CR=0. - FLAT END MILL)
T1 M6
S8000 M3
G0 X-10. Y10. Z5.
G1 Z-8. F5000.
X50.
G0 Z5.
G0 X-10. Y-4.
G1 Z-3. F1000.
X20.
X50.
G0 Z5.
G0 X-10. Y15.
G1 Z-0.2 F800.
X50.
G1 Z5.
X60. F700.
G0 Z20.
M30
%
"""


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)
    return condition


def run(*args):
    return subprocess.run([NCJOULE, *args], capture_output=True, text=True, timeout=300,
                          env=dict(os.environ, NCJOULE_PROGRESS="0"))


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


MOTION = re.compile(r"(STRAIGHT_FEED|STRAIGHT_TRAVERSE|ARC_FEED)\(([^)]*)\)")
FEED = re.compile(r"SET_FEED_RATE\(([^)]*)\)")


def motions(path):
    """(kind, end point, feed in force) of every motion rs274 -g prints for the program."""
    r = subprocess.run(["rs274", "-g", path], capture_output=True, text=True,
                       stdin=subprocess.DEVNULL, timeout=120, cwd=os.path.dirname(path),
                       env=dict(os.environ, HOME=RS274_HOME))
    out, feed = [], None
    for line in r.stdout.splitlines():
        f = FEED.search(line)
        if f:
            feed = round(float(f.group(1)), 3)
        m = MOTION.search(line)
        if m:
            values = [round(float(v), 4) for v in m.group(2).split(",")[:3]]
            out.append((m.group(1), tuple(values), feed))
    return r.returncode, out


def estimate(path):
    r = run("estimate", "--json", "--machine", GENERIC, "--stock", STOCK, path)
    return json.loads(r.stdout) if r.returncode == 0 else {}


work = tempfile.mkdtemp(prefix="ncjoule-optimize-")
atexit.register(shutil.rmtree, work, ignore_errors=True)
program = os.path.join(work, "air.ngc")
with open(program, "w") as f:
    f.write(PROGRAM)
before = digest(program)
optimized = os.path.join(work, "air-opt.ngc")

r = run("optimize", program, "--machine", GENERIC, "--stock", STOCK, "-o", optimized)
check(r.returncode == 0, f"optimize exits 0 ({r.returncode}: {r.stderr[-400:]})")
check(digest(program) == before, "the original is byte-identical after optimize")
check(os.path.exists(optimized), "the optimized program is written")
text = open(optimized).read() if os.path.exists(optimized) else ""
changed = len(re.findall(r"\(NCJOPT (?:AIR F|RAPID WAS)", text))
check(changed >= 6, f"moves in air are changed ({changed})")
check("saved" in r.stdout and "time" in r.stdout, "it prints what it saves")
check("by operation" in r.stdout, "it prints the savings by operation")

if shutil.which("rs274"):
    code_a, a = motions(program)
    code_b, b = motions(optimized)
    check(code_a == code_b == 0, f"rs274 runs both ({code_a}, {code_b})")
    check([m[1] for m in a] == [m[1] for m in b], "rs274: the same motion end points in order")
    differ = [i for i, (x, y) in enumerate(zip(a, b)) if x != y]
    check(len(differ) == changed,
          f"rs274: the motions that differ are the changed blocks ({len(differ)} vs {changed})")
    check(all(x[0] == "STRAIGHT_FEED" for x, y in zip(a, b) if x != y),
          "rs274: only feed moves differ")
    check(all(y[0] == "STRAIGHT_TRAVERSE" or y[2] > x[2] for x, y in zip(a, b) if x != y),
          "rs274: a changed feed move is a traverse or runs faster")
    cuts = [(x, y) for x, y in zip(a, b) if x == y and x[0] == "STRAIGHT_FEED"]
    check(len(cuts) >= 3, f"rs274: the cuts run as they were ({len(cuts)})")
else:
    print("skip rs274 comparison: rs274 not installed")

e0, e1 = estimate(program), estimate(optimized)
if check(bool(e0) and bool(e1), "both programs estimate"):
    v0, v1 = e0["removed_mm3"], e1["removed_mm3"]
    check(v0 > 1000 and abs(v1 - v0) <= 0.005 * v0, f"the same volume removed ({v0}, {v1})")
    t0, t1 = e0["time_s"], e1["time_s"]
    check(t1 < t0, f"the optimized program takes less time ({t0} -> {t1})")
    collisions = [d for d in e1.get("warnings", []) if "collision" in d.get("message", "")]
    check(not collisions, "no collision in the optimized program")

# strip takes out only annotate's comments: the optimizer's marks stay.
stripped = os.path.join(work, "stripped.ngc")
r = run("strip", optimized, "-o", stripped)
check(r.returncode == 0 and open(stripped).read() == text, "strip leaves the NCJOPT marks")
# compare reads both.
r = run("compare", "--machine", GENERIC, "--stock", STOCK, program, optimized)
check(r.returncode == 0, "compare ORIGINAL OPTIMIZED runs")
# -o /dev/stdout appended to a log keeps the log, and the program goes there alone: what
# optimize says goes to standard error.
log = os.path.join(work, "log.txt")
with open(log, "w") as f:
    f.write("KEEP ME\n")
with open(log, "a") as f:
    r = subprocess.run([NCJOULE, "optimize", program, "--machine", GENERIC, "--stock", STOCK,
                        "-o", "/dev/stdout"], stdout=f, stderr=subprocess.PIPE, text=True,
                       timeout=300, env=dict(os.environ, NCJOULE_PROGRESS="0"))
logged = open(log).read()
check(r.returncode == 0 and logged == "KEEP ME\n" + text,
      "-o /dev/stdout >> log: the log kept, then the optimized program alone")
check("saved" in r.stderr, "with the program on standard output, the savings go to stderr")
# The HTML report lists the changed blocks of an optimized program, and none of the original.
page = os.path.join(work, "optimized.html")
r = run("report", optimized, "--machine", GENERIC, "--stock", STOCK, "-o", page)
html = open(page, encoding="utf-8").read() if r.returncode == 0 else ""
marked = [l for l in text.splitlines() if "NCJOPT" in l and not l.lstrip().startswith("(")]
rows = re.findall(r'<tr data-line="(\d+)"><td>\d+</td><td>([A-Z]+)</td>', html)
check("Blocks changed by ncjoule optimize" in html and len(rows) == len(marked) >= changed,
      f"the report lists every changed block ({len(rows)} rows, {len(marked)} marked lines)")
lines = text.splitlines()
check(all("NCJOPT" in lines[int(n) - 1] for n, _ in rows), "each listed line carries the mark")
original_page = os.path.join(work, "original.html")
r = run("report", program, "--machine", GENERIC, "--stock", STOCK, "-o", original_page)
check(r.returncode == 0 and "Blocks changed by ncjoule optimize" not in
      open(original_page, encoding="utf-8").read(), "the original's report lists no changed block")

# Refusals: nothing written, the original as it was.
refused = os.path.join(work, "refused.ngc")
r = run("optimize", program, "--machine", GENERIC, "-o", refused)
check(r.returncode == 2 and "guessed" in r.stderr and "--stock" in r.stderr,
      f"a guessed stock is refused with the reason and how to give one ({r.returncode})")
check(not os.path.exists(refused), "nothing is written for a guessed stock")
r = run("optimize", program, "--machine", GENERIC, "--stock", STOCK, "--in-place")
check(r.returncode == 1 and "in-place" in r.stderr, "--in-place is refused")
r = run("optimize", program, "--machine", GENERIC, "--stock", STOCK, "-o", program)
check(r.returncode == 1, "-o naming the program is refused")
r = run("optimize", program, "--machine", GENERIC, "--stock", STOCK)
check(r.returncode == 1, "no -o is refused")
check(digest(program) == before, "the original is byte-identical after every run")
leftovers = [n for n in os.listdir(work) if n.startswith(".")]
check(not leftovers, f"no temporary file is left ({leftovers})")

# Rule c, feeds to a load target, with the other rules off.
load_program = os.path.join(work, "load.ngc")
with open(load_program, "w") as f:
    f.write(LOAD_PROGRAM)
load_before = digest(load_program)
loaded = os.path.join(work, "load-opt.ngc")
r = run("optimize", load_program, "--machine", GENERIC, "--stock", STOCK, "--no-air-feeds",
        "--no-rapid-links", "--load-feeds", "--json", "-o", loaded)
check(r.returncode == 0, f"optimize --load-feeds exits 0 ({r.returncode}: {r.stderr[-400:]})")
check(digest(load_program) == load_before, "the original is byte-identical after --load-feeds")
try:
    doc = json.loads(r.stdout)
except ValueError:
    doc = {}
load = doc.get("load_feeds", {})
check(load.get("lowered") == 1 and load.get("raised") == 2 and load.get("share") == 0.7,
      f"--json: one feed lowered, two raised, at 70% ({load})")
check(load.get("finishing_passes", 0) >= 1 and load.get("over_share") == 0,
      f"--json: the skim is a finishing pass; nothing left above the share ({load})")
times = doc.get("time_s", [0, 0])
check(times[1] > times[0], f"the slower slot makes it longer, and it is written ({times})")
text = open(loaded).read() if os.path.exists(loaded) else ""
marked = len(re.findall(r"\(NCJOPT LOAD F", text))
check(marked == 3, f"three blocks marked LOAD ({marked})")
check("(NCJOPT LOAD - 3 CUTTING FEEDS SCALED, 1 LOWERED, 2 RAISED" in text,
      "the header lists the rule")
check("X50. (NCJOPT LOAD F1300. WAS F1000.)" in text,
      "a block at the same scaled feed as the one before writes no F of its own")
if shutil.which("rs274"):
    code_a, a = motions(load_program)
    code_b, b = motions(loaded)
    check(code_a == code_b == 0, f"rs274 runs both ({code_a}, {code_b})")
    check([m[1] for m in a] == [m[1] for m in b], "rs274: the same motion end points in order")
    # A traverse runs at the rapid rate whatever feed is in force.
    differ = [(x, y) for x, y in zip(a, b)
              if x != y and not (x[0] == y[0] == "STRAIGHT_TRAVERSE")]
    check(len(differ) == marked, f"rs274: the motions that differ are the LOAD blocks ({differ})")
    check(all(x[0] == y[0] == "STRAIGHT_FEED" for x, y in differ), "rs274: only feeds differ")
    check(all(y[2] <= 1.3 * x[2] + 1e-9 for x, y in differ),
          "rs274: no feed above 1.3 times the programmed one")
    check(any(y[2] < x[2] for x, y in differ), "rs274: the heavy slot runs slower")
e0, e1 = estimate(load_program), estimate(loaded)
if check(bool(e0) and bool(e1), "both load programs estimate"):
    v0, v1 = e0["removed_mm3"], e1["removed_mm3"]
    check(abs(v1 - v0) <= 0.005 * v0, f"the same volume removed ({v0}, {v1})")
r = run("optimize", load_program, "--machine", GENERIC, "--stock", STOCK, "--no-air-feeds",
        "--no-rapid-links", "--load-feeds", "-o", loaded)
check(r.returncode == 0 and "the time grew" in r.stdout and "rating" in r.stdout,
      f"it says the time grew and why ({r.stdout[-600:]})")
# Without the spindle's rating there is no load target: refused, nothing written.
no_rating = os.path.join(work, "no-rating.toml")
with open(GENERIC) as f, open(no_rating, "w") as g:
    g.writelines(line for line in f if not line.startswith("spindle_rated_w"))
unrated = os.path.join(work, "unrated.ngc")
r = run("optimize", load_program, "--machine", no_rating, "--stock", STOCK, "--load-feeds", "-o",
        unrated)
check(r.returncode == 2 and "spindle_rated_w" in r.stderr and not os.path.exists(unrated),
      f"--load-feeds without a spindle rating is refused ({r.returncode}: {r.stderr[-300:]})")

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
print("all optimize checks passed")
