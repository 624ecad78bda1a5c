# ncjoule post-processor for FreeCAD CAM/Path: wraps one of FreeCAD's own posts (linuxcnc, grbl,
# fanuc, ...) and annotates what it writes with ncjoule's predicted time, MRR, power and energy
# per block. See README.md next to this file.
#
# The wrapped post does all the work; this script only runs
#     ncjoule annotate [--machine=PROFILE] --in-place [...] -- FILE   (output to a file), or
#     ncjoule annotate [--machine=PROFILE] [...] -- -                 (FreeCAD asks for a string: "-")
# on its output, with a --tool N:TYPE:DIAMETER for each tool controller's tool (its shape and
# sizes as FreeCAD holds them). When ncjoule is missing, not configured or fails, the post's output is returned
# and written exactly as the wrapped post made it, with a warning in the report view saying why:
# the wrapper never makes a post fail.
import argparse
import importlib
import os
import shlex
import shutil
import subprocess
import sys
import tempfile

TOOLTIP = """Posts with one of FreeCAD's post-processors (--post, default linuxcnc) and annotates
the G-code with ncjoule's predicted time, MRR, power and energy per block."""

parser = argparse.ArgumentParser(prog="ncjoule", add_help=False)
parser.add_argument("--post", help="FreeCAD post to wrap: linuxcnc, grbl, fanuc, ... "
                    "(default: $NCJOULE_POST or linuxcnc)")
parser.add_argument("--machine", help="ncjoule machine profile (.toml or a shipped profile's name); "
                    "default $NCJOULE_MACHINE, else the user config's machine, else ncjoule's generic one")
parser.add_argument("--ncjoule", help="the ncjoule program; default $NCJOULE or ncjoule on the PATH")
parser.add_argument("--stock", help="ncjoule --stock text (box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX or an "
                    ".stl); default $NCJOULE_STOCK, else the job's stock bounding box")
parser.add_argument("--ncjoule-args", default="", help="further arguments for ncjoule annotate")
parser.add_argument("--no-ncjoule", action="store_true", help="post without annotating")
TOOLTIP_ARGS = parser.format_help() + "\nAll other arguments go to the wrapped post."

ANNOTATE_TIMEOUT_S = 600


def _warn(message):
    text = "ncjoule: %s\n" % message
    try:
        import FreeCAD
        FreeCAD.Console.PrintWarning(text)
    except Exception:
        sys.stderr.write(text)


def _log(message):
    text = "ncjoule: %s\n" % message
    try:
        import FreeCAD
        FreeCAD.Console.PrintMessage(text)
    except Exception:
        sys.stderr.write(text)


def _load_post(name):
    """The wrapped post's module, freshly loaded so that its settings start from its defaults."""
    module_name = name if name.endswith("_post") else name + "_post"
    if module_name == __name__.rsplit(".", 1)[-1]:
        raise ValueError("ncjoule_post cannot wrap itself; choose --post linuxcnc, grbl, fanuc, ...")
    for candidate in (module_name, "PathScripts.post." + module_name):
        try:
            module = importlib.import_module(candidate)
        except ImportError:
            continue
        return importlib.reload(module)
    raise ImportError("no FreeCAD post named '%s' (looked for %s)" % (name, module_name))


def _handles_dash(module):
    """True when the post returns the G-code without writing a file for the filename "-"."""
    try:
        import inspect
        source = inspect.getsource(module.export)
    except (OSError, TypeError):
        return False
    return '"-"' in source or "'-'" in source


def _stock_box_mm(values):
    """box:... of six lengths in mm (FreeCAD's internal unit), each value saying so: a program
    posted in inches reads them right. Fixed point, never an exponent."""
    words = []
    for v in values:
        text = ("%.6f" % v).rstrip("0").rstrip(".")
        words.append(("0" if text in ("-0", "") else text) + "mm")
    return "box:" + ",".join(words)


def _job_stock(objectslist):
    """The stock of the job the objects belong to: (box:... , None) when it is a box along the
    axes (CreateBox, ExtendedBoundBox), (None, its shape) when it is not (a cylinder, a solid):
    that one goes to ncjoule as an STL, its bounding box would hold material it has not.
    (None, None) without a job or a stock."""
    try:
        import PathScripts.PathUtils as PathUtils
        for obj in objectslist:
            job = PathUtils.findParentJob(obj)
            if job is not None and getattr(job, "Stock", None) is not None:
                shape = job.Stock.Shape
                b = shape.BoundBox
                box = b.XLength * b.YLength * b.ZLength
                if box > 0 and abs(shape.Volume - box) <= 1e-6 * box:
                    return _stock_box_mm((b.XMin, b.YMin, b.ZMin, b.XMax, b.YMax, b.ZMax)), None
                return None, shape
    except Exception:
        pass
    return None, None


def _program_in_inches(gcode):
    """Whether the G-code selects inches (G20) before any G21, comments left out."""
    import re
    code = re.sub(r"\([^)]*\)|;[^\n]*", "", gcode or "")
    found = re.search(r"(?<![0-9.])G0*2([01])(?![0-9.])", code, re.IGNORECASE)
    return found is not None and found.group(1) == "0"


def _stock_stl(shape, folder, inch):
    """The stock's shape as an STL in `folder`, in the program's units (ncjoule reads an STL in
    the program's units); None when it cannot be meshed."""
    try:
        import FreeCAD
        import MeshPart
        mesh = MeshPart.meshFromShape(Shape=shape, LinearDeflection=0.01, AngularDeflection=0.05)
        if inch:
            scale = FreeCAD.Matrix()
            scale.scale(1 / 25.4, 1 / 25.4, 1 / 25.4)
            mesh.transform(scale)
        path = os.path.join(folder, "stock.stl")
        mesh.write(path)
        return path
    except Exception as e:  # a shape FreeCAD cannot mesh
        _warn("the job's stock could not be written as an STL (%s); ncjoule is given none" % e)
        return None


# FreeCAD tool bit shapes (ShapeName, or the file name of the bit's shape) and the tool types of
# its legacy tools, as ncjoule --tool names them.
_TOOL_SHAPES = {
    "endmill": "flat", "ballend": "ball", "bullnose": "bullnose", "torus": "bullnose",
    "drill": "drill", "centerdrill": "drill", "countersink": "chamfer", "chamfer": "chamfer",
    "v-bit": "chamfer", "vbit": "chamfer", "engraver": "chamfer", "chamfermill": "chamfer",
    "ballendmill": "ball", "slotcutter": "flat", "reamer": "flat", "flycutter": "flat",
}


def _number(value):
    """A float from a FreeCAD Quantity (its Value, in mm or degrees), a number, or "6.0 mm"."""
    value = getattr(value, "Value", value)
    if isinstance(value, str):
        value = value.split()[0] if value.split() else ""
    return float(value)


def _tool_spec(number, tool):
    """--tool N:TYPE:DIAMETER[:EXTRA...] for a tool controller's tool, or None when its shape is
    one ncjoule does not model (a probe, a thread mill, a slitting saw): the program's comments
    and the profile then speak for it."""
    name = getattr(tool, "ShapeName", "") or os.path.splitext(
        os.path.basename(str(getattr(tool, "BitShape", ""))))[0] or getattr(tool, "ToolType", "")
    shape = _TOOL_SHAPES.get(str(name).lower().replace("_", "").replace(" ", ""))
    if shape is None:
        return None
    try:
        diameter = _number(tool.Diameter)
        if not diameter > 0:
            return None
        spec = "%d:%s:%g" % (number, shape, diameter)
        if shape == "bullnose":
            corner = diameter / 2 - _number(getattr(tool, "FlatRadius", diameter / 2))
            spec = spec + ":%g" % corner if corner > 0 else "%d:flat:%g" % (number, diameter)
        elif shape == "drill" and hasattr(tool, "TipAngle"):
            spec += ":%g" % _number(tool.TipAngle)
        elif shape == "chamfer" and hasattr(tool, "CuttingEdgeAngle"):
            spec += ":%g" % _number(tool.CuttingEdgeAngle)
            if hasattr(tool, "TipDiameter"):
                spec += ":%g" % _number(tool.TipDiameter)
    except (AttributeError, TypeError, ValueError, IndexError):
        return None
    return spec


def _job_tools(objectslist):
    """--tool arguments for the tool controllers of the posted objects: their shapes and sizes as
    FreeCAD holds them, so ncjoule need not read them back from the labels ("TC: 6mm Endmill")."""
    specs = {}
    for obj in objectslist:
        controller = getattr(obj, "ToolController", None) or (
            obj if hasattr(obj, "ToolNumber") and hasattr(obj, "Tool") else None)
        if controller is None:
            continue
        try:
            number = int(controller.ToolNumber)
        except (AttributeError, TypeError, ValueError):
            continue
        spec = _tool_spec(number, getattr(controller, "Tool", None))
        if spec and number not in specs:
            specs[number] = spec
    args = []
    for number in sorted(specs):
        args += ["--tool", specs[number]]
    return args


def _extra_arguments(text):
    """--ncjoule-args / NCJOULE_ARGS as words (a shell's splitting, never a shell), less "--" and
    --follow-symlinks: the file must be the one argument after the wrapper's own "--", and the
    wrapper never replaces what a link points to."""
    try:
        words = shlex.split(text)
    except ValueError as e:  # an unclosed quote
        _warn("extra arguments %r left out: %s" % (text, e))
        return []
    kept = [w for w in words if w not in ("--", "--follow-symlinks")
            and not w.startswith("--follow-symlinks=")]
    if len(kept) != len(words):
        _warn("'--' and --follow-symlinks in the extra arguments are not passed on")
    return kept


class _Settings:
    def __init__(self, known, objectslist):
        self.post = known.post or os.environ.get("NCJOULE_POST") or "linuxcnc"
        self.machine = known.machine or os.environ.get("NCJOULE_MACHINE") or ""
        self.program = known.ncjoule or os.environ.get("NCJOULE") or "ncjoule"
        self.stock = known.stock or os.environ.get("NCJOULE_STOCK") or ""
        # The job's own stock is named as the hook's (ncjoule --stock-from, docs/stock.md): a
        # box as its box in mm, another shape as an STL written when the program's units are
        # known (stock_for).
        self.stock_from = ""
        self.stock_shape = None
        self.scratch = None
        if not self.stock:
            box, self.stock_shape = _job_stock(objectslist)
            self.stock = box or ""
            self.stock_from = "freecad" if box or self.stock_shape is not None else ""
        self.tools = _job_tools(objectslist)
        self.extra = _extra_arguments(known.ncjoule_args or os.environ.get("NCJOULE_ARGS", ""))
        self.enabled = not known.no_ncjoule and os.environ.get("NCJOULE_DISABLE", "") not in (
            "1", "yes", "true", "on")

    def problem(self):
        """Why ncjoule cannot run, or None."""
        if os.sep in self.program or (os.altsep and os.altsep in self.program):
            if not os.path.isfile(self.program):
                return "ncjoule not found at %s" % self.program
        elif shutil.which(self.program) is None:
            return "%s is not on the PATH (--ncjoule PATH)" % self.program
        return None

    def stock_for(self, gcode):
        """Writes the job's non-box stock as an STL in the program's units, for command()."""
        if self.stock_shape is None or self.stock:
            return
        self.scratch = tempfile.mkdtemp(prefix="ncjoule-stock-")
        self.stock = _stock_stl(self.stock_shape, self.scratch, _program_in_inches(gcode)) or ""
        if not self.stock:
            self.stock_from = ""

    def cleanup(self):
        if self.scratch:
            shutil.rmtree(self.scratch, ignore_errors=True)
            self.scratch = None

    def command(self, source, in_place=False):
        """ncjoule annotate for `source` (a file, or "-" for standard input), every value one
        argument, and the file after "--": a file named like an option ("-x.nc") stays a file."""
        # Without a machine ncjoule takes the user config's, else its generic profile.
        cmd = [self.program, "annotate"] + (["--machine=" + self.machine] if self.machine else [])
        if self.stock:
            cmd.append("--stock=" + self.stock)
        if self.stock_from:
            cmd.append("--stock-from=" + self.stock_from)
        if in_place:
            cmd.append("--in-place")
        return cmd + self.tools + self.extra + ["--", source]


def _run(cmd, text=None):
    """(exit status, stdout text, stderr text); (None, "", reason) when it could not run."""
    try:
        r = subprocess.run(cmd, input=None if text is None else text.encode("utf-8", "surrogateescape"),
                           stdin=subprocess.DEVNULL if text is None else None,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=ANNOTATE_TIMEOUT_S)
    except (OSError, subprocess.SubprocessError) as e:
        return None, "", str(e)
    return (r.returncode, r.stdout.decode("utf-8", "surrogateescape"),
            r.stderr.decode("utf-8", "replace").strip())


def _in_place_outcome(status, err, filename):
    """What `ncjoule annotate --in-place` did, from its exit status and its status line (its
    last line on stderr, where it names the file escaped): "annotated FILE", "FILE unchanged:
    ...", or None when it did not annotate the file. Never from the look of the file."""
    last = err.splitlines()[-1] if err else ""
    unchanged = " unchanged: already annotated this way"
    if status == 0 and last.startswith("ncjoule: ") and last.endswith(unchanged):
        return filename + unchanged
    if status == 0 and last.startswith("ncjoule: annotated "):
        return "annotated " + filename
    if status == 2 and ((last.startswith("ncjoule: annotated ") and ", with errors" in last)
                        or unchanged + ", with errors" in last):
        return "annotated " + filename
    return None


def _why(status, err):
    if status is None:
        return "could not run ncjoule: %s" % err
    return "ncjoule exited %d%s" % (status, (": " + err.splitlines()[-1]) if err else "")


def export(objectslist, filename, argstring):
    known, rest = parser.parse_known_args(shlex.split(argstring or ""))
    settings = _Settings(known, objectslist)
    post = _load_post(settings.post)
    post_args = " ".join(shlex.quote(a) for a in rest)

    if filename != "-":
        result = post.export(objectslist, filename, post_args)
        if not settings.enabled:
            return result
        problem = settings.problem()
        if problem:
            _warn("%s; %s is not annotated" % (problem, filename))
            return result
        if not os.path.isfile(filename):
            _warn("the %s post wrote no %s; nothing to annotate" % (settings.post, filename))
            return result
        try:
            with open(filename, encoding="utf-8", errors="surrogateescape") as f:
                settings.stock_for(f.read())
            status, _, err = _run(settings.command(filename, in_place=True))
        finally:
            settings.cleanup()
        done = _in_place_outcome(status, err, filename)
        if done is None:
            _warn("%s; %s is as the %s post wrote it" % (_why(status, err), filename, settings.post))
            return result
        if status == 2:
            _warn("%s was annotated; it has errors its controller would refuse: %s" % (
                filename, err.splitlines()[0] if err else ""))
        _log(done)
        if isinstance(result, str):
            with open(filename, encoding="utf-8", errors="surrogateescape", newline="") as f:
                return f.read()
        return result

    # "-": the G-code is wanted as a string.
    if _handles_dash(post):
        gcode = post.export(objectslist, "-", post_args)
    else:
        # This post always writes a file: let it write one where nobody looks, and read it back.
        with tempfile.TemporaryDirectory(prefix="ncjoule-post-") as folder:
            scratch = os.path.join(folder, "program.nc")
            returned = post.export(objectslist, scratch, post_args)
            if os.path.isfile(scratch):
                with open(scratch, encoding="utf-8", errors="surrogateescape", newline="") as f:
                    gcode = f.read()
            else:
                gcode = returned
    if not isinstance(gcode, str) or not settings.enabled:
        return gcode
    problem = settings.problem()
    if problem:
        _warn("%s; the program is not annotated" % problem)
        return gcode
    try:
        settings.stock_for(gcode)
        status, annotated, err = _run(settings.command("-"), gcode)
    finally:
        settings.cleanup()
    if status != 0:
        _warn("%s; the program is as the %s post made it" % (_why(status, err), settings.post))
        return gcode
    if gcode.strip() and not annotated.strip():
        _warn("ncjoule returned nothing; the program is as the %s post made it" % settings.post)
        return gcode
    return annotated
