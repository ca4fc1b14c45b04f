# FreeCAD's CAM Adaptive operation on a pocket with islands, run headless, posted for LinuxCNC.
#
# Run (FreeCAD 0.20.2 from Debian: `apt-get install freecad-python3`):
#
#     FC_OUTLINE=tests/data/freecad/islands.txt FC_OUT=tests/data/freecad/islands.ngc \
#         HOME=$(mktemp -d) freecadcmd scripts/freecad-adaptive.py
#
# What it reproduces: the program FreeCAD 0.20.2 itself writes for an Adaptive clearing
# operation on the pocket. Nothing of the Adaptive operation is re-implemented here: the script
# builds the part, a Job, a tool controller and an Adaptive operation with FreeCAD's own Path
# workbench classes (PathJob, PathToolBit, PathToolController, PathAdaptive), recomputes the
# document (PathAdaptive.Execute: libarea's Adaptive2d engine, then GenerateGCode: a helix per
# region and level, the engine's paths at each level's depth) and writes the operation through
# FreeCAD's own LinuxCNC post-processor (`linuxcnc_post`).
#
# The part: the outline file FC_OUTLINE, in the format `trochoplan pocket --polygon` reads
# ("x,y" per line; the boundary first, then each island after an empty line). FreeCAD gets a
# solid block 100 × 80 × 20 (the outline's bounding box grown by 10 mm on every side, from the
# stock top Z0 down to Z−20) less the pocket: the face with holes extruded from Z−FC_DEPTH to Z0,
# the islands standing to the stock top. The operation's base is the pocket's floor face at
# Z−FC_DEPTH; its inner wires are the islands, which PathAdaptive hands to Adaptive2d as loops of
# the same geometry (every edge discretized, joined by the engine).
#
# Settings (the values of the other FreeCAD comparison, docs/freecad-comparison.md; environment
# variables override the first four):
#   FC_STEPOVER   StepOver, whole percent of D (default 25: a_e 2.5 mm of D 10, read by
#                 Adaptive2d as 2.5 mm² of material per mm of travel)
#   FC_DEPTH      final depth below the stock top (default 12 mm)
#   FC_STEPDOWN   StepDown (default 4 mm: levels at −4, −8, −12)
#   FC_DIAMETER   tool diameter (default 10 mm; an `endmill` ToolBit)
# fixed: StartDepth 0, FinishDepth 0, ClearanceHeight 5, SafeHeight 3; Tolerance 0.1,
# KeepToolDownRatio 3, StockToLeave 0, ForceInsideOut off, FinishingProfile on, OperationType
# Clearing, Side Inside, UseOutline off, LiftDistance 0, HelixAngle 5°, HelixConeAngle 0,
# UseHelixArcs on, HelixDiameterLimit 0 (the engine's 0.75·D); the Job's stock a box equal to
# the model's bounding box (extents 0); tool controller T1, 2000 rpm clockwise, horizontal and
# vertical feed 600 mm/min. Post-processor `linuxcnc_post` with `--no-header` (its header holds
# the time of output) and `--precision 4` (the other comparison programs' 4 decimals).
#
# The same run gives the same program byte for byte (rand() seeded: see below).

import ctypes
import os
import sys

import FreeCAD
import Part
import PathScripts.PathAdaptive as PathAdaptive
import PathScripts.PathJob as PathJob
from PathScripts.post import linuxcnc_post

OUTLINE = os.environ.get("FC_OUTLINE", "tests/data/freecad/islands.txt")
OUT = os.environ.get("FC_OUT", "tests/data/freecad/islands.ngc")
STEPOVER = int(os.environ.get("FC_STEPOVER", "25"))
DEPTH = float(os.environ.get("FC_DEPTH", "12"))
STEPDOWN = float(os.environ.get("FC_STEPDOWN", "4"))
DIAMETER = float(os.environ.get("FC_DIAMETER", "10"))
MARGIN = 10.0


def read_loops(path):
    """The loops of a point-list file: lists of (x, y), separated by empty lines."""
    loops, cur = [], []
    for line in open(path, encoding="utf-8"):
        line = line.split("#", 1)[0].strip()
        if not line:
            if cur:
                loops.append(cur)
            cur = []
            continue
        x, y = line.split(",")
        cur.append((float(x), float(y)))
    if cur:
        loops.append(cur)
    return loops


def fail(msg):
    sys.stderr.write("freecad-adaptive: %s\n" % msg)
    sys.exit(1)


loops = read_loops(OUTLINE)
if not loops:
    fail("no loop in %s" % OUTLINE)
wires = [Part.makePolygon([FreeCAD.Vector(x, y, -DEPTH) for x, y in l + [l[0]]]) for l in loops]
face = Part.Face(wires[0])
for w in wires[1:]:
    face = face.cut(Part.Face(w))
if len(face.Faces) != 1 or len(face.Faces[0].Wires) != len(loops):
    fail("the loops of %s do not make one face with %d holes" % (OUTLINE, len(loops) - 1))
face = face.Faces[0]

xs = [x for l in loops for x, _ in l]
ys = [y for l in loops for _, y in l]
x0, y0 = min(xs) - MARGIN, min(ys) - MARGIN
x1, y1 = max(xs) + MARGIN, max(ys) + MARGIN
block = Part.makeBox(x1 - x0, y1 - y0, DEPTH + 8.0, FreeCAD.Vector(x0, y0, -DEPTH - 8.0))
solid = block.cut(face.extrude(FreeCAD.Vector(0, 0, DEPTH)))

doc = FreeCAD.newDocument("pocket")
part = doc.addObject("Part::Feature", "Part")
part.Shape = solid
doc.recompute()

floors = [
    "Face%d" % (i + 1)
    for i, f in enumerate(part.Shape.Faces)
    if abs(f.BoundBox.ZMin + DEPTH) < 1e-9 and abs(f.BoundBox.ZMax + DEPTH) < 1e-9
]
if len(floors) != 1:
    fail("expected one floor face at Z-%g, found %d" % (DEPTH, len(floors)))

job = PathJob.Create("Job", [part], None)
job.GeometryTolerance.Value = 0.001
stock = job.Stock
for ext in ("ExtXneg", "ExtXpos", "ExtYneg", "ExtYpos", "ExtZneg", "ExtZpos"):
    setattr(stock, ext, 0.0)
doc.recompute()

tc = job.Tools.Group[0]
tc.Tool.Diameter = DIAMETER
tc.ToolNumber = 1
tc.SpindleSpeed = 2000.0
tc.SpindleDir = "Forward"
tc.HorizFeed = FreeCAD.Units.Quantity("600 mm/min")
tc.VertFeed = FreeCAD.Units.Quantity("600 mm/min")

op = PathAdaptive.Create("Adaptive")
op.Base = [(job.Model.Group[0], floors)]
op.ToolController = tc
for prop, value in (
    ("StartDepth", 0.0),
    ("FinalDepth", -DEPTH),
    ("StepDown", STEPDOWN),
    ("FinishDepth", 0.0),
    ("ClearanceHeight", 5.0),
    ("SafeHeight", 3.0),
):
    op.setExpression(prop, None)
    setattr(op, prop, value)
op.OperationType = "Clearing"
op.Side = "Inside"
op.StepOver = STEPOVER
op.Tolerance = 0.1
op.KeepToolDownRatio = 3.0
op.StockToLeave = 0.0
op.ForceInsideOut = False
op.FinishingProfile = True
op.UseOutline = False
op.LiftDistance = 0.0
op.HelixAngle = 5.0
op.HelixConeAngle = 0.0
op.UseHelixArcs = True
op.HelixDiameterLimit = 0.0
# Adaptive2d draws angles from the C library's rand() where its search has too few points, and
# in freecadcmd that generator starts in another state each run (unseeded, two runs give two
# different programs): seeded here to 1, the state a plain C program starts in, so that a run
# gives the same program again.
ctypes.CDLL(None).srand(1)
doc.recompute()

if len(op.Path.Commands) < 10:
    fail("the Adaptive operation made no path")
sb = stock.Shape.BoundBox
print(
    "stock box (%g, %g, %g)-(%g, %g, %g); depths %s to %s step %s; D %s, T%d, %s rpm"
    % (sb.XMin, sb.YMin, sb.ZMin, sb.XMax, sb.YMax, sb.ZMax, op.StartDepth, op.FinalDepth, op.StepDown,
       tc.Tool.Diameter, tc.ToolNumber, tc.SpindleSpeed)
)
linuxcnc_post.export([tc, op], OUT, "--no-header --no-show-editor --precision 4")
print("wrote %s (%d commands)" % (OUT, len(op.Path.Commands)))
