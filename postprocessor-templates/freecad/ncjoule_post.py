# ncjoule post-processor for FreeCAD CAM/Path: wraps one of FreeCAD's own posts (linuxcnc, grbl,
# fanuc, ...) and annotates what it writes with ncjoule's predicted time, MRR, power and energy
# per block. See README.md next to this file.
#
# The wrapped post does all the work; this script only runs
#     ncjoule annotate FILE --machine PROFILE --in-place        (output to a file), or
#     ncjoule annotate - --machine PROFILE                       (FreeCAD asks for a string: "-")
# on its output. When ncjoule is missing, not configured or fails, the post's output is returned
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
parser.add_argument("--machine", help="ncjoule machine profile (.toml); default $NCJOULE_MACHINE")
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


def _job_stock(objectslist):
    """box:... of the job's stock, when the objects belong to a job that has one."""
    try:
        import PathScripts.PathUtils as PathUtils
        for obj in objectslist:
            job = PathUtils.findParentJob(obj)
            if job is not None and getattr(job, "Stock", None) is not None:
                b = job.Stock.Shape.BoundBox
                return "box:%g,%g,%g,%g,%g,%g" % (b.XMin, b.YMin, b.ZMin, b.XMax, b.YMax, b.ZMax)
    except Exception:
        pass
    return None


class _Settings:
    def __init__(self, known, objectslist):
        self.post = known.post or os.environ.get("NCJOULE_POST") or "linuxcnc"
        self.machine = known.machine or os.environ.get("NCJOULE_MACHINE") or ""
        self.program = known.ncjoule or os.environ.get("NCJOULE") or "ncjoule"
        self.stock = known.stock or os.environ.get("NCJOULE_STOCK") or _job_stock(objectslist)
        self.extra = shlex.split(known.ncjoule_args or os.environ.get("NCJOULE_ARGS", ""))
        self.enabled = not known.no_ncjoule and os.environ.get("NCJOULE_DISABLE", "") not in (
            "1", "yes", "true", "on")

    def problem(self):
        """Why ncjoule cannot run, or None."""
        if not self.machine:
            return "no machine profile (--machine PROFILE in the job's post-processor arguments, " \
                   "or NCJOULE_MACHINE)"
        if os.sep in self.program or (os.altsep and os.altsep in self.program):
            if not os.path.isfile(self.program):
                return "ncjoule not found at %s" % self.program
        elif shutil.which(self.program) is None:
            return "%s is not on the PATH (--ncjoule PATH)" % self.program
        return None

    def command(self, source):
        cmd = [self.program, "annotate", source, "--machine", self.machine]
        if self.stock:
            cmd += ["--stock", self.stock]
        return cmd + self.extra


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
        status, _, err = _run(settings.command(filename) + ["--in-place"])
        if status != 0:
            _warn("%s; %s is as the %s post wrote it" % (_why(status, err), filename, settings.post))
            return result
        _log("annotated %s" % filename)
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
    status, annotated, err = _run(settings.command("-"), gcode)
    if status != 0:
        _warn("%s; the program is as the %s post made it" % (_why(status, err), settings.post))
        return gcode
    if gcode.strip() and not annotated.strip():
        _warn("ncjoule returned nothing; the program is as the %s post made it" % settings.post)
        return gcode
    return annotated
