"""A real FreeCAD Job's stock, end to end, in real FreeCAD (headless): a Part box, a Job around it
(PathScripts.PathJob, its tool controller and stock as FreeCAD makes them) with a CreateBox stock
and with FreeCAD's default ExtendedBoundBox stock, one facing operation in the Job, posted through
the wrapper post (postprocessor-templates/freecad/ncjoule_post.py, around FreeCAD's linuxcnc
post). Checks that

  - the wrapper passes the Job's stock (--stock-from=freecad) and the annotated header says
    FROM=hook-freecad with that box;
  - ncjoule reads the same stock back from the saved document beside the program, without the
    hook: stock_from "freecad-job", the same box;
  - a CreateCylinder stock beside the program is named in a warning and the next source is used.

Usage: NCJOULE=path/to/ncjoule NCJOULE_SOURCE_DIR=repo freecadcmd freecad_stock_test.py
"""
import json
import os
import re
import subprocess
import sys
import tempfile
import traceback

import FreeCAD
import Path
import PathScripts.PathJob as PathJob
import PathScripts.PathStock as PathStock

ROOT = os.environ.get("NCJOULE_SOURCE_DIR") or os.path.dirname(os.path.dirname(
    os.path.dirname(os.path.abspath(globals().get("__file__", sys.argv[0])))))
NCJOULE = os.environ.get("NCJOULE", "ncjoule")
MACHINE = os.path.join(ROOT, "samples", "machines", "generic-3axis.toml")
sys.path.insert(0, os.path.join(ROOT, "postprocessor-templates", "freecad"))
import ncjoule_post  # noqa: E402

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL " + message)


def G(code, **params):
    return Path.Command(code, {k.upper(): float(v) for k, v in params.items()})


def job_document(name, stock):
    """A document with a 60 x 40 x 10 body (top at Z0) and a Job with `stock` ("box",
    "extended" or "cylinder") and one facing operation; returns (doc, [objects to post])."""
    doc = FreeCAD.newDocument(name)
    body = doc.addObject("Part::Box", "Body")
    body.Length, body.Width, body.Height = 60, 40, 10
    body.Placement.Base = FreeCAD.Vector(0, 0, -10)
    doc.recompute()
    job = PathJob.Create("Job", [body], None)
    if stock == "box":
        doc.removeObject(job.Stock.Name)
        job.Stock = PathStock.CreateBox(job)
        job.Stock.Length, job.Stock.Width, job.Stock.Height = 70, 50, 12
        job.Stock.Placement.Base = FreeCAD.Vector(-5, -5, -11)
    elif stock == "cylinder":
        doc.removeObject(job.Stock.Name)
        job.Stock = PathStock.CreateCylinder(job)
        job.Stock.Radius, job.Stock.Height = 40, 12
        job.Stock.Placement.Base = FreeCAD.Vector(30, 20, -12)  # X -10..70, Y -20..60, Z -12..0
    tc = job.Tools.Group[0]
    body_path = [Path.Command("(Facing)"), G("G0", z=5), G("G0", x=-8, y=2), G("G1", z=-0.5, f=5)]
    y, right = 2.0, True
    while y <= 38.0 + 1e-9:
        body_path.append(G("G1", x=68 if right else -8, y=y, z=-0.5, f=20))
        y += 4.0
        if y <= 38.0 + 1e-9:
            body_path.append(G("G1", x=68 if right else -8, y=y, z=-0.5, f=20))
        right = not right
    body_path.append(G("G0", z=5))
    op = doc.addObject("Path::FeaturePython", "Facing")
    op.addProperty("App::PropertyLink", "ToolController", "Path")
    op.addProperty("App::PropertyBool", "Active", "Path")
    op.addProperty("App::PropertyString", "CoolantMode", "Path")
    op.ToolController = tc
    op.Active = True
    op.CoolantMode = "None"
    op.Path = Path.Path(body_path)
    job.Operations.addObject(op)
    doc.recompute()
    return doc, [tc, op]


def header_stock(text):
    return next((l for l in text.splitlines() if "NCJ STOCK" in l), "")


def estimate(program, *more, config=None):
    r = subprocess.run([NCJOULE, "estimate", "--json", "--machine=" + MACHINE] + list(more) +
                       [program],
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       env=dict(os.environ, NCJOULE_CONFIG=config or os.path.join(ROOT, "no-such.toml")))
    check(r.returncode == 0, "ncjoule estimate %s failed: %s" % (program, r.stderr.decode()))
    return (json.loads(r.stdout) if r.stdout else {}), r.stderr.decode()


def close_to_within(values, expected, tolerance):
    return len(values) == 6 and all(abs(a - b) <= tolerance for a, b in zip(values, expected))


def close_to(values, expected):
    return close_to_within(values, expected, 1e-6)


def run():
    with tempfile.TemporaryDirectory(prefix="ncjoule-freecad-stock-") as folder:
        for kind, box in (("box", (-5, -5, -11, 65, 45, 1)), ("extended", (-1, -1, -11, 61, 41, 1))):
            doc, objects = job_document("part_" + kind, kind)
            document = os.path.join(folder, "part_%s.FCStd" % kind)
            doc.saveAs(document)
            out = os.path.join(folder, "part_%s.ngc" % kind)
            ncjoule_post.export(objects, out, " ".join([
                "--post=linuxcnc", "--machine=" + MACHINE, "--ncjoule=" + NCJOULE,
                "--no-header", "--no-show-editor"]))
            with open(out) as f:
                text = f.read()
            stock = header_stock(text)
            check("FROM=hook-freecad" in stock, "%s: the header names the hook's stock: %s" % (kind, stock))
            expected = "BOX_MM=" + ",".join("%g" % v for v in box)
            check(expected in stock, "%s: the header's box is the Job's (%s): %s" % (kind, expected, stock))
            # Without the hook: the same stock read back from the document beside the program.
            result, _ = estimate(out)
            setup = (result.get("setups") or [{}])[0]
            check(result.get("stock_from") == "freecad-job",
                  "%s: stock_from %r, not freecad-job" % (kind, result.get("stock_from")))
            check(close_to(setup.get("stock_box_mm", []), box),
                  "%s: stock box %r read back, not %r" % (kind, setup.get("stock_box_mm"), box))
            check("part_%s.FCStd" % kind in setup.get("stock_origin", ""),
                  "%s: stock_origin %r" % (kind, setup.get("stock_origin")))
            FreeCAD.closeDocument(doc.Name)
        # A cylinder stock through the wrapper: its shape as an STL in the program's units (its
        # bounding box would hold material the cylinder has not), in a mm and an inch program.
        doc, objects = job_document("round", "cylinder")
        for units in ("mm", "inch"):
            out = os.path.join(folder, "round-%s.ngc" % units)
            ncjoule_post.export(objects, out, " ".join(
                ["--post=linuxcnc", "--machine=" + MACHINE, "--ncjoule=" + NCJOULE, "--no-header",
                 "--no-show-editor"] + (["--inches"] if units == "inch" else [])))
            with open(out) as f:
                text = f.read()
            check(("G20" in text) == (units == "inch"), "%s: the post wrote %s" % (units, units))
            stock = header_stock(text)
            check("FROM=hook-freecad" in stock, "cylinder %s: the hook's stock: %s" % (units, stock))
            box = re.search(r"BOX_MM=([-0-9.,]+)", stock)
            values = [float(v) for v in box.group(1).split(",")] if box else []
            check(close_to_within(values, (-10, -20, -12, 70, 60, 0), 0.05),
                  "cylinder %s: the STL's box is the cylinder's: %s" % (units, stock))
            # The cylinder holds less of the facing than its bounding box: the facing's corners
            # lie outside it.
            removed = re.search(r"VOL_MM3=([0-9.e+]+)", text)
            in_box, _ = estimate(out, "--stock=box:-10mm,-20mm,-12mm,70mm,60mm,0mm",
                                 *ncjoule_post._job_tools(objects))
            print("cylinder %s: removed %s, in its box %r" % (units, removed and removed.group(1), in_box.get("removed_mm3")))
            check(removed is not None and 0 < float(removed.group(1)) < 0.97 * in_box.get(
                "removed_mm3", 0), "cylinder %s: removes less than its box (%s, %r)" % (
                units, removed and removed.group(1), in_box.get("removed_mm3")))
        FreeCAD.closeDocument(doc.Name)
        # A cylinder stock beside the program: named, and the next source (here the user
        # config's stock) used.
        doc, objects = job_document("part_cylinder", "cylinder")
        doc.saveAs(os.path.join(folder, "part_cylinder.FCStd"))
        program = os.path.join(folder, "part_cylinder.ngc")
        ncjoule_post.export(objects, program, " ".join([
            "--post=linuxcnc", "--no-ncjoule", "--no-header", "--no-show-editor"]))
        config = os.path.join(folder, "config.toml")
        with open(config, "w") as f:
            f.write('stock = "box:-40,-40,-12,40,40,0"\n')
        result, err = estimate(program, config=config)
        check(result.get("stock_from") == "user-config",
              "cylinder: stock_from %r, not the next source's" % result.get("stock_from"))
        check(re.search(r"part_cylinder\.FCStd/Document\.xml:\d+: warning: .*cylinder stock", err)
              is not None, "cylinder: no warning naming the cylinder stock: " + err)
        FreeCAD.closeDocument(doc.Name)


try:
    run()
except Exception:
    traceback.print_exc()
    failures.append("exception")
print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
