"""Posts one small milling job through every G-code post-processor FreeCAD ships.

Usage (from anywhere; needs Debian's freecad-python3, see scripts/setup.sh):

    freecadcmd scripts/make_freecad_samples.py

Writes samples/freecad/<post>.nc, one file per post, and samples/freecad/<post>.stock with the
`--stock` text for `ncjoule estimate`. The job is the same for every post: a 60 x 40 x 10 mm
block (top at Z0), two tools ("TC: 6mm Endmill" T1, "TC: 5mm Drill" T2), and five operations:
facing (zigzag, 0.5 mm deep), a pocket with rounded corners and a helical entry (two 1.5 mm
steps), a profile around the part with arcs at the corners (2 mm deep), drilling with G81 under
G99, and peck drilling with G83 under G98.

The operations are not computed from a solid model (that needs FreeCAD's GUI-side operation
proxies and is fragile headless). Instead each operation's Path is built from Path.Command
objects the way FreeCAD's operations build them: the operation label as a comment, a rapid to
the clearance height, FreeCAD's own generators for tool changes (toolchange_generator), helical
entries (helix_generator) and drilling cycles (drill_generator), and feed rates in mm/s as
PathFeedRate stores them. The posts' export() then turns those objects into text, so every file
is exactly what that post writes for such a job.

Posts that do not write G-code are skipped and named at the end: dxf (drawing exchange),
rml (Roland RML-1), opensbp (ShopBot OpenSBP), heidenhain (Heidenhain conversational "Klartext",
not ISO). Pre-processors (*_pre.py) import files and are not posts.
"""
import importlib
import math
import os
import sys

import FreeCAD
import Part
import Path

from Generators import drill_generator, helix_generator, toolchange_generator
import PathScripts.PathToolController as PathToolController

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(os.path.dirname(HERE), "samples", "freecad")
STOCK = "box:0,0,-10,60,40,0"

# Every post of FreeCAD 0.20 (Mod/Path/PathScripts/post); those that do not write G-code are
# listed in NOT_GCODE.
POSTS = [
    "linuxcnc", "grbl", "fanuc", "mach3_mach4", "centroid", "uccnc", "smoothie", "marlin",
    "dynapath", "rrf", "jtech", "KineticNCBeamicon2", "comparams", "philips", "nccad", "fablin",
]
NOT_GCODE = {
    "opensbp": "ShopBot OpenSBP commands (M3, J2, ...), not G-code",
    "heidenhain": "Heidenhain conversational (Klartext: L X+.. FMAX, TOOL CALL), not ISO G-code",
    "rml": "Roland RML-1, not G-code",
    "dxf": "a DXF drawing, not a program",
}

CLEARANCE = 5.0
SAFE = 3.0
MM_PER_MIN = 1.0 / 60.0  # Path commands hold feed rates in mm/s


class Obj:
    """Stands in for a document object: the posts read Name, Label, Path and a few properties."""

    def __init__(self, name, label, commands, **props):
        self.Name = name
        self.Label = label
        self.Path = Path.Path(commands)
        self.Active = True
        self.InList = []  # no parent Job: posts that look for one use their defaults
        self.CoolantMode = "None"
        for k, v in props.items():
            setattr(self, k, v)


class Quantity:
    def __init__(self, value):
        self.Value = value


class Tool:
    def __init__(self, diameter, tool_type):
        self.Diameter = diameter
        self.ToolType = tool_type
        self.ShapeName = tool_type.lower()
        self.Label = tool_type


def tool_controller(name, label, number, diameter, tool_type, rpm, h_feed, v_feed):
    commands = toolchange_generator.generate(
        number, label, rpm, toolchange_generator.SpindleDirection.CW)
    tc = Obj(name, label, commands)
    # The posts that look for tool controllers test isinstance(obj.Proxy, ToolController).
    tc.Proxy = PathToolController.ToolController.__new__(PathToolController.ToolController)
    tc.ToolNumber = number
    tc.SpindleSpeed = rpm
    tc.SpindleDir = "Forward"
    tc.Tool = Tool(diameter, tool_type)
    tc.HorizFeed = Quantity(h_feed * MM_PER_MIN)
    tc.VertFeed = Quantity(v_feed * MM_PER_MIN)
    tc.HorizRapid = Quantity(0)
    tc.VertRapid = Quantity(0)
    return tc


def G(code, **params):
    return Path.Command(code, {k.upper(): float(v) for k, v in params.items()})


def operation(name, label, tc, body, coolant="None"):
    commands = [Path.Command("(%s)" % label), G("G0", z=CLEARANCE)] + body
    return Obj(name, label, commands, ToolController=tc, Tool=tc.Tool,
               SpindleSpeed=tc.SpindleSpeed, CoolantMode=coolant)


def facing(tc):
    h, v = tc.HorizFeed.Value, tc.VertFeed.Value
    body = [G("G0", x=-4, y=3, z=CLEARANCE), G("G0", x=-4, y=3, z=SAFE),
            G("G1", x=-4, y=3, z=-0.5, f=v)]
    y, direction = 3.0, 1
    while y <= 38.0 + 1e-9:
        x_end = 64.0 if direction > 0 else -4.0
        body.append(G("G1", x=x_end, y=y, z=-0.5, f=h))
        y_next = y + 5.0
        if y_next <= 38.0 + 1e-9:
            body.append(G("G1", x=x_end, y=y_next, z=-0.5, f=h))
        y, direction = y_next, -direction
    body.append(G("G0", z=CLEARANCE))
    return body


def rounded_rectangle(x0, y0, x1, y1, r, z, feed):
    """A closed loop, climb-milled (clockwise inside a pocket would be conventional), starting
    at the middle of the bottom edge; corners are G3 arcs with I/J from the arc start."""
    return [
        G("G1", x=x1 - r, y=y0, z=z, f=feed),
        G("G3", x=x1, y=y0 + r, z=z, i=0, j=r, f=feed),
        G("G1", x=x1, y=y1 - r, z=z, f=feed),
        G("G3", x=x1 - r, y=y1, z=z, i=-r, j=0, f=feed),
        G("G1", x=x0 + r, y=y1, z=z, f=feed),
        G("G3", x=x0, y=y1 - r, z=z, i=0, j=-r, f=feed),
        G("G1", x=x0, y=y0 + r, z=z, f=feed),
        G("G3", x=x0 + r, y=y0, z=z, i=r, j=0, f=feed),
        G("G1", x=(x0 + x1) / 2, y=y0, z=z, f=feed),
    ]


def pocket(tc):
    # A 20 x 14 pocket centred at (30, 20) with 4 mm corner radii; the 6 mm tool's centre runs
    # 3 mm inside the wall. Entry: FreeCAD's helix generator, 2.5 mm helix radius.
    h, v = tc.HorizFeed.Value, tc.VertFeed.Value
    cx, cy = 30.0, 20.0
    body = [G("G0", x=cx + 2.5, y=cy, z=CLEARANCE), G("G0", x=cx + 2.5, y=cy, z=SAFE)]
    top = -0.5
    for depth in (-2.0, -3.5):
        edge = Part.makeLine(FreeCAD.Vector(cx, cy, top), FreeCAD.Vector(cx, cy, depth))
        helix = helix_generator.generate(edge, 5.5, 0.75, 0.5, 6.0, 0.0, "CCW", "Inside")
        for c in helix:
            p = dict(c.Parameters)
            p["F"] = v if c.Name in ("G0", "G1") and "Z" in p and len(p) <= 2 else h
            if c.Name == "G0":
                p.pop("F")
            body.append(Path.Command(c.Name, p))
        inner = [(cx - 4.0, cy - 1.0, cx + 4.0, cy + 1.0, 1.0), (cx - 7.0, cy - 4.0, cx + 7.0,
                                                                  cy + 4.0, 1.0)]
        for x0, y0, x1, y1, r in inner:
            body.append(G("G1", x=(x0 + x1) / 2, y=y0, z=depth, f=h))
            body += rounded_rectangle(x0, y0, x1, y1, r, depth, h)
        body.append(G("G0", z=SAFE))
        body.append(G("G0", x=cx + 2.5, y=cy, z=SAFE))
        top = depth
    body.append(G("G0", z=CLEARANCE))
    return body


def profile(tc):
    # Outside a 50 x 30 part with 5 mm corner radii at (5,5)-(55,35); tool centre 3 mm outside.
    h, v = tc.HorizFeed.Value, tc.VertFeed.Value
    x0, y0, x1, y1, r = 2.0, 2.0, 58.0, 38.0, 8.0
    body = [G("G0", x=30, y=y0, z=CLEARANCE), G("G0", x=30, y=y0, z=SAFE),
            G("G1", x=30, y=y0, z=-2.0, f=v)]
    body += rounded_rectangle(x0, y0, x1, y1, r, -2.0, h)
    body.append(G("G0", z=CLEARANCE))
    return body


def drilling(tc, holes, return_level, peck):
    """The command sequence of FreeCAD 0.20's PathDrilling.circularHoleExecute."""
    v = tc.VertFeed.Value
    body = [Path.Command("(Begin Drilling)"), G("G0", z=CLEARANCE), Path.Command("G90"),
            Path.Command(return_level)]
    start_height = 0.0 + SAFE
    for x, y in holes:
        body.append(G("G0", x=x, y=y))
        body.append(G("G0", z=start_height))
        edge = Part.makeLine(FreeCAD.Vector(x, y, 0.0), FreeCAD.Vector(x, y, -6.0))
        for c in drill_generator.generate(edge, 0.0, peck, 1, 1.0):
            p = dict(c.Parameters)
            p["F"] = v
            body.append(Path.Command(c.Name, p))
    body.append(Path.Command("G80"))
    body.append(G("G0", z=CLEARANCE))
    return body


def job():
    endmill = tool_controller("ToolController", "TC: 6mm Endmill", 1, 6.0, "EndMill", 8000,
                              1200, 300)
    drill = tool_controller("ToolController001", "TC: 5mm Drill", 2, 5.0, "Drill", 3000, 200,
                            150)
    corners = [(8, 8), (52, 8), (52, 32), (8, 32)]
    return [
        endmill,
        operation("MillFace", "Facing", endmill, facing(endmill), coolant="Flood"),
        operation("Pocket_Shape", "Pocket", endmill, pocket(endmill), coolant="Flood"),
        operation("Profile", "Profile", endmill, profile(endmill), coolant="Flood"),
        drill,
        operation("Drilling", "Drilling", drill, drilling(drill, corners, "G99", 0.0)),
        operation("Drilling001", "PeckDrilling", drill,
                  drilling(drill, [(20, 20), (40, 20)], "G98", 2.0)),
    ]


# How each post is called when the defaults do not work headless.
ARGS = {"fablin": "--no-show-editor"}
# jtech writes its file in binary mode with a str (a Python 2 leftover): it is asked for the
# text ("-") and the text is written here, unchanged.
TEXT_ONLY = {"jtech"}
# Module globals set before export(): comparams and philips take no option that keeps their
# editor dialog shut;
# KineticNC and fablin define `pythonopen` (the built-in open) only under Python 2.
GLOBALS = {"comparams": {"SHOW_EDITOR": False}, "philips": {"SHOW_EDITOR": False},
           "KineticNCBeamicon2": {"pythonopen": open}, "fablin": {"pythonopen": open}}


def objects_for(name):
    objects = job()
    if name == "comparams":
        # comparams posts only the first selected object: give it the whole job as one path
        # object, as a Path compound of the tool controllers and operations would be.
        commands = [c for o in objects for c in o.Path.Commands]
        return [Obj("Compound", "Compound", commands)]
    return objects


def main():
    os.makedirs(OUT, exist_ok=True)
    os.chdir(OUT)
    # uccnc and philips read the active document's file name.
    FreeCAD.newDocument("ncjoule_samples")
    written, failed = [], []
    for name in POSTS:
        # Posts print the file name they are given in their headers: give a relative one.
        target = name + ".nc"
        try:
            post = importlib.import_module("PathScripts.post.%s_post" % name)
            for key, value in GLOBALS.get(name, {}).items():
                setattr(post, key, value)
            if os.path.exists(target):
                os.remove(target)
            text = post.export(objects_for(name), "-" if name in TEXT_ONLY else target,
                               ARGS.get(name, ""))
            if not os.path.exists(target) and text:
                with open(target, "w") as f:
                    f.write(text)
            if not os.path.exists(target):
                raise RuntimeError("the post wrote nothing")
            with open(name + ".stock", "w") as f:
                f.write(STOCK + "\n")
            written.append(name)
        except Exception as e:  # report every post, then fail
            failed.append("%s: %s: %s" % (name, type(e).__name__, e))
    print("written:", " ".join(written))
    for name, why in NOT_GCODE.items():
        print("not written: %s (%s)" % (name, why))
    for f in failed:
        print("FAILED:", f)
    if failed:
        sys.exit(1)


main()
