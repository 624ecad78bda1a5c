"""The FreeCAD post-processor wrapper (postprocessor-templates/freecad/ncjoule_post.py) in real
FreeCAD, headless.

Usage: NCJOULE=path/to/ncjoule NCJOULE_SOURCE_DIR=repo freecadcmd freecad_post_test.py

Builds a small milling job out of Path commands (a tool controller and a facing operation, as
FreeCAD's operations store them), posts it through the wrapper around FreeCAD's linuxcnc, fanuc
and grbl posts, to a file and to "-" (the G-code returned as a string), and checks that the
result carries ncjoule's annotations and that `ncjoule strip` gives back exactly what the wrapped
post writes on its own. Also: a missing ncjoule or a failing one only warns and leaves the post's
output as the post made it; --no-ncjoule turns the wrapper off.
"""
import os
import subprocess
import sys
import tempfile
import traceback

import FreeCAD  # noqa: F401  (freecadcmd provides it)
import Path

from Generators import toolchange_generator
import PathScripts.PathToolController as PathToolController

ROOT = os.environ.get("NCJOULE_SOURCE_DIR") or os.path.dirname(os.path.dirname(
    os.path.dirname(os.path.abspath(globals().get("__file__", sys.argv[0])))))
NCJOULE = os.environ.get("NCJOULE", "ncjoule")
MACHINE = os.path.join(ROOT, "samples", "machines", "generic-3axis.toml")
STOCK = "box:0,0,-10,60,40,0"
sys.path.insert(0, os.path.join(ROOT, "postprocessor-templates", "freecad"))
import ncjoule_post  # noqa: E402

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL " + message)


# ---------------------------------------------------------------------------------------------
# A job: the objects a FreeCAD Job hands its post (operations and tool controllers)
# ---------------------------------------------------------------------------------------------

class Obj:
    def __init__(self, name, label, commands, **props):
        self.Name = name
        self.Label = label
        self.Path = Path.Path(commands)
        self.Active = True
        self.InList = []
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


def G(code, **params):
    return Path.Command(code, {k.upper(): float(v) for k, v in params.items()})


def job(tool=None):
    """The job; `tool` replaces the controller's 6 mm end mill (its label stays "6mm Endmill")."""
    label = "TC: 6mm Endmill"
    tc = Obj("ToolController", label, toolchange_generator.generate(
        1, label, 8000, toolchange_generator.SpindleDirection.CW))
    tc.Proxy = PathToolController.ToolController.__new__(PathToolController.ToolController)
    tc.ToolNumber = 1
    tc.SpindleSpeed = 8000
    tc.SpindleDir = "Forward"
    tc.Tool = tool or Tool(6.0, "EndMill")
    tc.HorizFeed = Quantity(1200 / 60.0)
    tc.VertFeed = Quantity(300 / 60.0)
    tc.HorizRapid = Quantity(0)
    tc.VertRapid = Quantity(0)
    body = [Path.Command("(Facing)"), G("G0", z=5), G("G0", x=-4, y=3, z=5), G("G0", x=-4, y=3, z=3),
            G("G1", x=-4, y=3, z=-0.5, f=5)]
    y, right = 3.0, True
    while y <= 38.0 + 1e-9:
        body.append(G("G1", x=64 if right else -4, y=y, z=-0.5, f=20))
        y += 5.0
        if y <= 38.0 + 1e-9:
            body.append(G("G1", x=64 if right else -4, y=y, z=-0.5, f=20))
        right = not right
    body.append(G("G0", z=5))
    op = Obj("Facing", "Facing", body, ToolController=tc, Tool=tc.Tool, SpindleSpeed=8000)
    return [tc, op]


# ---------------------------------------------------------------------------------------------

def plain(post, objects, folder):
    """What the wrapped post writes on its own (to a file: some posts cannot do "-")."""
    module = ncjoule_post._load_post(post)
    target = os.path.join(folder, "plain-%s.nc" % post)
    module.export(objects, target, "--no-header --no-show-editor")
    with open(target, newline="") as f:
        return f.read()


def strip(text, folder):
    path = os.path.join(folder, "to-strip.nc")
    with open(path, "w", newline="") as f:
        f.write(text)
    r = subprocess.run([NCJOULE, "strip", path], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    check(r.returncode == 0, "ncjoule strip failed: %s" % r.stderr.decode())
    return r.stdout.decode()


def annotated(text):
    import re
    return re.search(r"[(;]NCJ SEAL LINES=", text, re.IGNORECASE) is not None


def args(post, *more):
    words = ["--post=" + post, "--machine=" + MACHINE, "--ncjoule=" + NCJOULE,
             "--stock=" + STOCK, "--no-header", "--no-show-editor"]
    return " ".join(words + list(more))


def removed_mm3(text):
    """The volume the annotation header says was removed."""
    import re
    m = re.search(r"VOL_MM3=([0-9.eE+-]+)", text)
    return float(m.group(1)) if m else None


def run_case(name, body):
    before = len(failures)
    try:
        body()
        print(("ok   " if len(failures) == before else "FAIL ") + name)
    except Exception:
        failures.append(name + ": " + traceback.format_exc())
        print("FAIL " + name + "\n" + traceback.format_exc())


def main():
    objects = job()
    folder = tempfile.mkdtemp(prefix="ncjoule-freecad-")

    for post in ("linuxcnc", "fanuc", "grbl"):
        reference = plain(post, objects, folder)
        check("G1" in reference, "%s: the plain post wrote no G1 moves" % post)

        def to_file(post=post, reference=reference):
            out = os.path.join(folder, "%s.nc" % post)
            result = ncjoule_post.export(objects, out, args(post))
            with open(out, newline="") as f:
                text = f.read()
            check(annotated(text), "%s: file output not annotated:\n%s" % (post, text[:300]))
            # The tool controller's tool reaches ncjoule (grbl's output names none).
            check((removed_mm3(text) or 0) > 0, "%s: nothing removed:\n%s" % (post, text[:300]))
            check(strip(text, folder) == reference, "%s: strip(file) is not the post's output" % post)
            if result is not None:
                check(result == text, "%s: returned text differs from the file written" % post)

        def to_string(post=post, reference=reference):
            here = os.getcwd()
            os.chdir(folder)  # a post that cannot do "-" must not leave a file named "-" here
            try:
                result = ncjoule_post.export(objects, "-", args(post))
            finally:
                os.chdir(here)
            check(isinstance(result, str), "%s: '-' did not return a string" % post)
            check(annotated(result), "%s: '-' output not annotated" % post)
            check(strip(result, folder) == reference, "%s: strip('-' output) is not the post's output" % post)
            check(not os.path.exists(os.path.join(folder, "-")), "%s: a file named '-' was written" % post)

        run_case("%s post through the wrapper to a file" % post, to_file)
        run_case("%s post through the wrapper to '-'" % post, to_string)

    reference = plain("linuxcnc", objects, folder)

    def job_stock_in_mm():
        # FreeCAD's stock box is in mm whatever the post writes: each value says so, so that an
        # inch program reads it right; fixed point, no exponent ncjoule would refuse.
        box = ncjoule_post._stock_box_mm((0.0, -0.0, -25.4, 101.6, 76.2000004, 12345678.5))
        check(box == "box:0mm,0mm,-25.4mm,101.6mm,76.2mm,12345678.5mm", box)
        prog = os.path.join(folder, "inch.nc")
        with open(prog, "w") as f:
            f.write("G20 G90\nT1 M6\nS8000 M3\nG0 X0.5 Y0.5 Z0.2\nG1 Z-0.1 F10\nG1 X3.5 F40\nG0 Z0.2\nM30\n")
        r = subprocess.run([NCJOULE, "estimate", "--machine=" + MACHINE, "--tool=1:flat:0.25in",
                            "--stock=" + ncjoule_post._stock_box_mm((0, 0, -25.4, 101.6, 76.2, 0)), prog],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        out = r.stdout.decode()
        check(r.returncode == 0, "estimate with the job's stock failed: %s" % r.stderr.decode())
        check("mix-up" not in r.stderr.decode(), "an mm stock on an inch program was misread")
        check("0.000,0.000,-25.400" in out, "the stock is not the job's box in mm:\n" + out)

    def missing_ncjoule():
        out = os.path.join(folder, "missing.nc")
        a = args("linuxcnc").replace("--ncjoule=" + NCJOULE, "--ncjoule=" + os.path.join(folder, "nope"))
        result = ncjoule_post.export(objects, out, a)
        with open(out, newline="") as f:
            check(f.read() == reference, "missing ncjoule: the post's file was changed")
        check(result == reference, "missing ncjoule: the returned G-code is not the post's")
        dash = ncjoule_post.export(objects, "-", a)
        check(dash == reference, "missing ncjoule: '-' did not return the post's G-code")

    def failing_ncjoule():
        bad = os.path.join(folder, "bad.toml")
        with open(bad, "w") as f:
            f.write("not = [ a profile\n")
        out = os.path.join(folder, "failing.nc")
        result = ncjoule_post.export(objects, out, args("linuxcnc").replace(MACHINE, bad))
        with open(out, newline="") as f:
            check(f.read() == reference, "failing ncjoule: the post's file was changed")
        check(result == reference, "failing ncjoule: the returned G-code is not the post's")

    def turned_off():
        out = os.path.join(folder, "off.nc")
        result = ncjoule_post.export(objects, out, args("linuxcnc", "--no-ncjoule"))
        with open(out, newline="") as f:
            check(f.read() == reference, "--no-ncjoule: the file is not the post's output")
        check(not annotated(result), "--no-ncjoule: annotated anyway")

    def controller_geometry():
        # A ball end mill whose controller is labelled "6mm Endmill": the wrapper passes the tool
        # itself, so the cut is a ball's (less volume than the flat end mill's at the same path).
        ball = Tool(6.0, "BallEnd")
        ball.ShapeName = "ballend"
        volumes = {}
        for name, objs in (("flat", objects), ("ball", job(ball))):
            out = os.path.join(folder, "geometry-%s.nc" % name)
            ncjoule_post.export(objs, out, args("linuxcnc"))
            with open(out, newline="") as f:
                volumes[name] = removed_mm3(f.read())
        check(None not in volumes.values(), "tool geometry: no volume in the header: %s" % volumes)
        if None not in volumes.values():
            check(0 < volumes["ball"] < 0.9 * volumes["flat"],
                  "tool geometry: the ball removed %s mm^3, the flat %s" % (volumes["ball"],
                                                                          volumes["flat"]))
        check(ncjoule_post._tool_spec(3, ball) == "3:ball:6", "ball spec")
        bull = Tool(6.0, "Bullnose")
        bull.ShapeName, bull.FlatRadius = "bullnose", Quantity(1.5)
        check(ncjoule_post._tool_spec(4, bull) == "4:bullnose:6:1.5", "bullnose spec")
        vbit = Tool(Quantity(10.0), "V-Bit")
        vbit.ShapeName, vbit.CuttingEdgeAngle, vbit.TipDiameter = "v-bit", Quantity(60), Quantity(1)
        check(ncjoule_post._tool_spec(5, vbit) == "5:chamfer:10:60:1", "v-bit spec")
        probe = Tool(2.0, "Probe")
        check(ncjoule_post._tool_spec(6, probe) is None, "a probe is not passed as a tool")

    def option_like_name():
        # A file named like an option goes to ncjoule after "--" (it was refused as an option).
        here = os.getcwd()
        os.chdir(folder)
        try:
            ncjoule_post.export(objects, "-x.nc", args("linuxcnc"))
        finally:
            os.chdir(here)
        with open(os.path.join(folder, "-x.nc"), newline="") as f:
            text = f.read()
        check(annotated(text), "-x.nc: not annotated")
        check(strip(text, folder) == reference, "-x.nc: strip is not the post's output")

    def extra_arguments():
        # "--" and --follow-symlinks in the extra arguments are left out; the rest is passed.
        out = os.path.join(folder, "extra.nc")
        ncjoule_post.export(objects, out, args("linuxcnc", "'--ncjoule-args=-- --follow-symlinks --compact'"))
        with open(out, newline="") as f:
            text = f.read()
        check(annotated(text) and strip(text, folder) == reference, "extra arguments: not annotated")
        cmd = ncjoule_post._Settings(ncjoule_post.parser.parse_known_args(
            ["--machine=-m.toml", "--stock=-s", "--ncjoule-args=-- --compact"])[0], []).command("-f.nc", True)
        check(cmd[1:] == ["annotate", "--machine=-m.toml", "--stock=-s", "--in-place", "--compact", "--", "-f.nc"],
              "command: %r" % cmd)
        # No machine anywhere: none is passed, and ncjoule takes the user config's.
        cmd = ncjoule_post._Settings(ncjoule_post.parser.parse_known_args([])[0], []).command("f.nc")
        check(not any(a.startswith("--machine") for a in cmd), "no machine: %r" % cmd)

    run_case("a file named like an option (-x.nc) is annotated", option_like_name)
    run_case("extra arguments: split, '--' and --follow-symlinks left out", extra_arguments)
    run_case("the tool controller's tool shape and size reach ncjoule", controller_geometry)
    run_case("the job's stock goes to ncjoule in mm, for programs in either unit", job_stock_in_mm)
    run_case("a missing ncjoule only warns", missing_ncjoule)
    run_case("a failing ncjoule only warns", failing_ncjoule)
    run_case("--no-ncjoule posts without annotating", turned_off)

    if failures:
        print("%d failure(s)" % len(failures))
        sys.exit(1)
    print("all FreeCAD wrapper tests passed")
    sys.exit(0)


main()
