#!/usr/bin/env python3
"""`ncjoule estimate` with removal options end to end: --job (stock box or STL relative to the job
file, tool table), --tool overriding header comments, errors that name the file and key, a tool
defined nowhere named in the error, and both engines agreeing on the sample at the same grid."""
import json
import os
import struct
import subprocess
import sys
import tempfile

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
MACHINE = os.path.join(ROOT, "samples/machines/generic-3axis.toml")
failures = []

# A 2 mm deep slot 40 mm long, plunged at feed from the clearance plane Z5, with a tool that
# its header comment says is 6 mm wide.
SLOT = """(T1 D=6. CR=0. - ZMIN=-2. - FLAT END MILL)
G21 G90 G17
T1 M6
S3000 M3
G0 X0 Y0 Z5
G1 Z-2 F200
G1 X40 F600
G0 Z5
M30
"""
PI = 3.141592653589793


def slot_volume(d):  # a slot of width d with round ends, 2 deep, 40 between the ends' centres
    return (40 * d + PI * d * d / 4) * 2


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def run(*args):
    return subprocess.run([NCJOULE, "estimate", *args, "--machine", MACHINE], capture_output=True,
                          text=True)


def removed(r):
    return json.loads(r.stdout)["removed_mm3"] if r.returncode == 0 else None


def box_stl(path, x0, y0, z0, x1, y1, z1):
    v = [(x, y, z) for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)]
    faces = [(0, 2, 1), (1, 2, 3), (4, 5, 6), (5, 7, 6), (0, 1, 4), (1, 5, 4),
             (2, 6, 3), (3, 6, 7), (0, 4, 2), (2, 4, 6), (1, 3, 5), (3, 7, 5)]
    with open(path, "wb") as f:
        f.write(b"\0" * 80 + struct.pack("<I", len(faces)))
        for a, b, c in faces:
            f.write(struct.pack("<3f", 0, 0, 0))
            for k in (a, b, c):
                f.write(struct.pack("<3f", *v[k]))
            f.write(b"\0\0")


with tempfile.TemporaryDirectory() as tmp:
    prog = os.path.join(tmp, "slot.ngc")
    with open(prog, "w") as f:
        f.write(SLOT)
    box = "box:-10,-10,-10,50,10,0"

    r = run(prog, "--stock", box, "--json", "--grid", "0.1")
    v = removed(r)
    check(v is not None and abs(v - slot_volume(6)) < 3e-3 * slot_volume(6),
          f"header comment tool: 6 mm slot volume (got {v}, want {slot_volume(6):.1f})")

    r = run(prog, "--stock", box, "--json", "--grid", "0.1", "--tool", "1:flat:10")
    v = removed(r)
    check(v is not None and abs(v - slot_volume(10)) < 3e-3 * slot_volume(10),
          f"--tool 1:flat:10 overrides the comment (got {v}, want {slot_volume(10):.1f})")

    # A job file in another folder: stock box, tool table; --tool beats the job's tool.
    jobs = os.path.join(tmp, "jobs")
    os.makedirs(os.path.join(jobs, "parts"))
    job = os.path.join(jobs, "slot.toml")
    with open(job, "w") as f:
        f.write(f'stock = "{box}"\n[[tool]]\nnumber = 1\ntype = "flat"\ndiameter_mm = 8\n')
    r = run(prog, "--job", job, "--json", "--grid", "0.1")
    v = removed(r)
    check(v is not None and abs(v - slot_volume(8)) < 3e-3 * slot_volume(8),
          f"--job stock and tool table (got {v}, want {slot_volume(8):.1f}; {r.stderr[:200]})")
    check(r.returncode == 0 and "given" in json.loads(r.stdout).get("stock", ""),
          "the job's stock box is the one used")
    r = run(prog, "--job", job, "--json", "--grid", "0.1", "--tool", "1:flat:10")
    v = removed(r)
    check(v is not None and abs(v - slot_volume(10)) < 3e-3 * slot_volume(10),
          f"--tool overrides the job's tool (got {v})")

    # stock_stl relative to the job file: a box 1 mm thick, 0..-1, so the slot cuts 1 mm of it.
    box_stl(os.path.join(jobs, "parts", "blank.stl"), -10, -10, -1, 50, 10, 0)
    with open(job, "w") as f:
        f.write('stock_stl = "parts/blank.stl"\n[[tool]]\nnumber = 1\ntype = "flat"\n'
                'diameter_mm = 8\n')
    r = run(prog, "--job", job, "--json", "--grid", "0.1")
    v = removed(r)
    check(v is not None and abs(v - slot_volume(8) / 2) < 3e-3 * slot_volume(8),
          f"stock_stl found relative to the job file (got {v}; {r.stderr[:200]})")

    # Mistakes in the job file: exit 2, the file, the line and the key named.
    with open(job, "w") as f:
        f.write('stock = "box:0,0,-20,100,60,0"\n[[tool]]\nnumber = 1\ntype = "flat"\n'
                'diameter_mm = -6\n')
    r = run(prog, "--job", job, "--json")
    check(r.returncode == 2 and "slot.toml:5" in r.stderr and "diameter_mm" in r.stderr
          and r.stdout == "", f"bad diameter: exit 2, file:line and key named ({r.stderr[:200]!r})")
    with open(job, "w") as f:
        f.write('stock = "box:0,0,-20"\n')
    r = run(prog, "--job", job)
    check(r.returncode == 2 and "slot.toml" in r.stderr and "stock" in r.stderr,
          f"bad stock: exit 2, file and key named ({r.stderr[:200]!r})")
    with open(job, "w") as f:
        f.write('stock_stl = "parts/missing.stl"\n')
    r = run(prog, "--job", job)
    check(r.returncode == 2 and "missing.stl" in r.stderr,
          f"missing STL named ({r.stderr[:200]!r})")
    r = run(prog, "--job", os.path.join(tmp, "nojob.toml"))
    check(r.returncode == 2 and "nojob.toml" in r.stderr, "missing job file named")

    r = run(prog, "--tool", "1:square:6")
    check(r.returncode != 0 and "square" in r.stderr, f"bad --tool refused ({r.stderr[:160]!r})")

    # A tool described nowhere is a warning naming it, whatever else is given.
    bare = os.path.join(tmp, "bare.ngc")
    with open(bare, "w") as f:
        f.write(SLOT.replace("T1 M6", "T1 M6\nG0 Z5\nT2 M6").split("\n", 1)[1])
    r = run(bare, "--stock", box, "--tool", "1:flat:6")
    check(r.returncode == 0 and "warning: tool T2" in r.stderr,
          f"undefined T2 named in a warning ({r.stderr[:200]!r})")
    r = run(bare, "--stock", box, "--tool", "1:flat:6", "--tool", "2:ball:6", "--json")
    check(r.returncode == 0, f"both tools on the command line ({r.stderr[:200]!r})")

    # Default stock with feed plunges from Z5: every cut runs below Z0, so Z0 is the top (a post
    # puts Z0 on the stock's top), and the plunges through air do not make a 9 mm stock. The two
    # passes cut the slot 4 mm deep: twice a 2 mm slot's volume.
    deep = os.path.join(tmp, "deep.ngc")
    with open(deep, "w") as f:
        f.write(SLOT.replace("G0 Z5\nM30", "G1 Z-4 F200\nG1 X0 F600\nG0 Z5\nM30"))
    r = run(deep, "--json", "--grid", "0.1")
    doc = json.loads(r.stdout) if r.returncode == 0 else {}
    check("top: Z0" in doc.get("stock", ""), f"default stock rule stated ({doc.get('stock')})")
    v = doc.get("removed_mm3")
    check(v is not None and abs(v - 2 * slot_volume(6)) < 3e-3 * slot_volume(6),
          f"default stock: top at Z0, not the clearance plane (got {v})")
    check("collision" not in r.stderr, "no collision reported")

    # +Z into the work: the slot posted with every Z negated, on a profile that says so, cuts
    # what the slot does from the mirrored STL (1 mm thick, Z0 to 1 in the program's terms).
    down = os.path.join(tmp, "down.ngc")
    with open(down, "w") as f:
        # Twice along the slot: the second crossing is a rapid from a known point.
        f.write(SLOT.replace("Z5", "Z-5").replace("Z-2", "Z2").replace(
            "M30", "G0 X0\nG1 Z2 F200\nG1 X40 F600\nG0 Z-5\nM30"))
    down_machine = os.path.join(tmp, "down.toml")
    with open(MACHINE) as f:
        text = f.read()
    with open(down_machine, "w") as f:
        f.write(text.replace("\ntool_change_s", '\nz_positive = "down"\ntool_change_s', 1))
    box_stl(os.path.join(tmp, "down.stl"), -10, -10, 0, 50, 10, 1)
    r = subprocess.run([NCJOULE, "estimate", down, "--machine", down_machine, "--stock",
                        os.path.join(tmp, "down.stl"), "--json", "--grid", "0.1", "--tool",
                        "1:flat:8"], capture_output=True, text=True)
    doc = json.loads(r.stdout) if r.returncode == 0 else {}
    v = doc.get("removed_mm3")
    check(v is not None and abs(v - slot_volume(8) / 2) < 3e-3 * slot_volume(8),
          f"z_positive = down: a mirrored STL stock cut as its twin (got {v}; {r.stderr[:200]})")
    check(doc.get("removal", {}).get("z_mirrored") is True, "JSON says removal.z_mirrored")
    check("collision" not in r.stderr and "every rapid" not in r.stderr,
          f"no collision, and no guess when the profile says ({r.stderr[:200]!r})")
    # The generic profile reads it from the program's rapids, and says so.
    r = run(down, "--stock", "box:-10,-10,0,50,10,1", "--json", "--grid", "0.1", "--tool",
            "1:flat:8")
    doc = json.loads(r.stdout) if r.returncode == 0 else {}
    check(doc.get("removal", {}).get("z_mirrored") is True and "every rapid" in r.stderr,
          f"z read from the program, with a warning ({r.stderr[:200]!r})")
    v = doc.get("removed_mm3")
    check(v is not None and abs(v - slot_volume(8) / 2) < 3e-3 * slot_volume(8),
          f"a given box in the program's coordinates (got {v})")
    r = run(prog, "--stock", box, "--json")
    check(json.loads(r.stdout)["removal"]["z_mirrored"] is False, "a standard program: not mirrored")

# The sample with both engines at one grid, from its sidecar stock.
sample = os.path.join(ROOT, "samples/programs/bracket-linuxcnc.ngc")
with open(os.path.join(ROOT, "samples/programs/bracket-linuxcnc.stock")) as f:
    stock = f.read().strip()
d = removed(run(sample, "--stock", stock, "--json", "--grid", "0.25"))
v = removed(run(sample, "--stock", stock, "--json", "--grid", "0.25", "--engine", "voxel"))
check(d and v and abs(v - d) < 5e-3 * d, f"bracket: dexel {d} and voxel {v} mm^3 within 0.5%")

print(f"{len(failures) == 0 and 1 or 0} passed, {len(failures) and 1 or 0} failed")
sys.exit(1 if failures else 0)
