"""Makes the FreeCAD documents the stock readers are tested on (tests/projects/data/*.FCStd), in
real FreeCAD: each a Part box 60 x 40 x 10 mm (its top at Z0) and a Path Job around it, with the
Job's stock made as FreeCAD's own stock dialog makes it.

  box.FCStd       a CreateBox stock, 70 x 50 x 12 at (-5, -5, -11)
  extended.FCStd  an ExtendedBoundBox stock (the model's box and FreeCAD's default 1 mm
                  allowances): (-1, -1, -11) to (61, 41, 1)
  cylinder.FCStd  a CreateCylinder stock, radius 40, height 12 (not modelled: named only)
  twojobs.FCStd   two Jobs, their PostProcessorOutputFile "%d-top.nc" and "bottom.nc", with
                  CreateBox stocks 70 x 50 x 12 and 80 x 60 x 14 at (-10, -10, -13)

Usage: [NCJOULE_FCSTD_DIR=FOLDER] freecadcmd scripts/make_freecad_stock_documents.py
(default folder: tests/projects/data)
"""
import os
import sys

import FreeCAD
import PathScripts.PathJob as PathJob
import PathScripts.PathStock as PathStock

here = os.path.dirname(os.path.abspath(globals().get("__file__", sys.argv[0])))
folder = os.environ.get("NCJOULE_FCSTD_DIR") or os.path.join(here, "..", "tests", "projects",
                                                             "data")
os.makedirs(folder, exist_ok=True)


def document(name):
    doc = FreeCAD.newDocument(name)
    body = doc.addObject("Part::Box", "Body")
    body.Length, body.Width, body.Height = 60, 40, 10
    body.Placement.Base = FreeCAD.Vector(0, 0, -10)
    doc.recompute()
    return doc, body


def box_stock(job, size, at):
    job.Document.removeObject(job.Stock.Name)
    job.Stock = PathStock.CreateBox(job)
    job.Stock.Length, job.Stock.Width, job.Stock.Height = size
    job.Stock.Placement.Base = FreeCAD.Vector(*at)


def save(doc, name):
    doc.recompute()
    doc.saveAs(os.path.join(folder, name + ".FCStd"))
    FreeCAD.closeDocument(doc.Name)


doc, body = document("box")
job = PathJob.Create("Job", [body], None)
box_stock(job, (70, 50, 12), (-5, -5, -11))
save(doc, "box")

doc, body = document("extended")
PathJob.Create("Job", [body], None)  # FreeCAD's default stock: the model's box, 1 mm around
save(doc, "extended")

doc, body = document("cylinder")
job = PathJob.Create("Job", [body], None)
doc.removeObject(job.Stock.Name)
job.Stock = PathStock.CreateCylinder(job)
job.Stock.Radius, job.Stock.Height = 40, 12
save(doc, "cylinder")

doc, body = document("twojobs")
top = PathJob.Create("Top", [body], None)
top.PostProcessorOutputFile = "%D/%d-top.nc"
box_stock(top, (70, 50, 12), (-5, -5, -11))
bottom = PathJob.Create("Bottom", [body], None)
bottom.PostProcessorOutputFile = "/somewhere/else/bottom.nc"
box_stock(bottom, (80, 60, 14), (-10, -10, -13))
save(doc, "twojobs")
print("made box, extended, cylinder and twojobs .FCStd in " + folder)
