"""Render interface fields of a push-out run as unrolled maps (paper Fig. 8).

Run with ParaView's pvbatch (on a machine without a display, under a virtual
X server: `xvfb-run -a pvbatch ...`; scripts/studies.py starts its own):
  pvbatch scripts/render_interface.py RUN_DIR OUT.png [--fields t_n t_s1]
          [--center X Y] [--time LAST]

Reads RUN_DIR/interface.xdmf (written with output.xdmf = true), unrolls the
tube surface to (arc length s = R theta, z) and draws one map per field,
stacked, at the last (or the given) time step. Units: tractions MPa, s and
z mm. The tube axis is RUN_DIR/scene.toml's geometry.tube_center (the
resolved scene every run writes), unless --center gives it. The seam is at
theta = 225 deg, a block corner's direction and a node line of a centred
tube's mesh; cells are unrolled one by one, and one across the seam is kept whole
(off the centre the node line lies a few degrees away, so s starts up to an
element past 0). The joint elements of
[[crack]] planes, also in interface.xdmf, are left out: a cell is the
interface's where its corners lie on one circle about the axis. Prints
what it drew: the unrolled extent and the cells kept of interface.xdmf's.
"""
import argparse
import sys
import os

from paraview.simple import (AssignViewToLayout, ColorBy, CreateLayout, CreateRenderView,
                             ExtractBlock, GetColorTransferFunction, GetScalarBar, MergeBlocks,
                             ProgrammableFilter, ResetCamera, SaveScreenshot, Show, Text,
                             XDMFReader)

LABELS = {
    "t_n": "normal traction t_n [MPa] (negative: pressure)",
    "t_s1": "axial shear traction t_s1 [MPa]",
    "t_s2": "circumferential shear traction t_s2 [MPa]",
    "w_n": "normal jump w_n [mm]",
    "w_s1": "axial slip w_s1 [mm]",
}

# Runs inside a ProgrammableFilter, whose namespace shadows sum/min/max with
# VTK's array algorithms: use the builtins explicitly.
UNROLL = """
import builtins
import math
from vtkmodules.vtkCommonCore import vtkIdList, vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_QUAD, vtkUnstructuredGrid
src = self.GetInputDataObject(0, 0)
out = self.GetOutputDataObject(0)
cx, cy, seam = {cx!r}, {cy!r}, math.radians(225.0)
pts = vtkPoints()
out.Allocate(src.GetNumberOfCells())
kept = vtkIdList()
for c in range(src.GetNumberOfCells()):
    cell = src.GetCell(c)
    xyz = [src.GetPoint(cell.GetPointId(i)) for i in range(cell.GetNumberOfPoints())]
    radii = [math.hypot(p[0] - cx, p[1] - cy) for p in xyz]
    if builtins.max(radii) - builtins.min(radii) > 1e-6 * builtins.max(radii):
        continue  # a crack plane's joint element, radial: not on the tube
    kept.InsertNextId(c)
    # angle measured from the seam, in (0, 2 pi)
    ang = [(math.atan2(p[1] - cy, p[0] - cx) - seam) % (2 * math.pi) for p in xyz]
    if builtins.max(ang) - builtins.min(ang) > math.pi:  # on the seam: keep the cell whole
        ang = [a if a > math.pi else a + 2 * math.pi for a in ang]
        if builtins.max(ang) - builtins.min(ang) > math.pi:
            ang = [a - 2 * math.pi for a in ang]
    r = builtins.sum(math.hypot(p[0] - cx, p[1] - cy) for p in xyz) / len(xyz)
    ids = []
    for a, p in zip(ang, xyz):
        ids.append(pts.InsertNextPoint(r * a, p[2], 0.0))
    out.InsertNextCell(VTK_QUAD, 4, ids)
out.SetPoints(pts)
data = out.GetCellData()
data.CopyAllocate(src.GetCellData(), kept.GetNumberOfIds())
for i in range(kept.GetNumberOfIds()):
    data.CopyData(src.GetCellData(), kept.GetId(i), i)
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("run_dir")
    ap.add_argument("png")
    ap.add_argument("--fields", nargs="+", default=["t_n", "t_s1"])
    ap.add_argument("--center", nargs=2, type=float, default=None,
                    help="the tube axis x y [mm] (default: RUN_DIR/scene.toml's)")
    ap.add_argument("--time", type=float, default=None)
    ap.add_argument("--title", default="")
    args = ap.parse_args()
    # What it needs, said in one line (ParaView's own errors name its proxies).
    xdmf = os.path.join(args.run_dir, "interface.xdmf")
    try:
        with open(xdmf) as f:
            text = f.read()
    except OSError as e:
        sys.exit(f"render_interface.py: error: cannot read {xdmf} ({e.strerror}): "
                 "run the scene with --set output.xdmf=true")
    missing = [field for field in args.fields if f'Name="{field}"' not in text]
    if missing:
        sys.exit(f"render_interface.py: error: {xdmf} has no field {', '.join(missing)}")
    if args.center is None:
        import tomllib  # Python 3.11 (Debian 12's pvbatch); --center needs none

        scene = os.path.join(args.run_dir, "scene.toml")
        try:
            with open(scene, "rb") as f:
                args.center = tomllib.load(f)["geometry"]["tube_center"]
        except (OSError, ValueError, KeyError) as e:
            sys.exit(f"render_interface.py: error: no tube axis from {scene} ({e}): give --center X Y")

    reader = XDMFReader(FileNames=[xdmf])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues) or [0.0]
    t = times[-1] if args.time is None else args.time

    layout = CreateLayout("interface maps")
    cell = 0
    for i, field in enumerate(args.fields):
        block = MergeBlocks(Input=ExtractBlock(Input=reader, Selectors=["/Root/" + field]))
        flat = ProgrammableFilter(Input=block)
        flat.OutputDataSetType = "vtkUnstructuredGrid"
        flat.Script = UNROLL.format(cx=args.center[0], cy=args.center[1])
        flat.UpdatePipeline(t)
        if i == 0:  # what is drawn: the tube's cells, unrolled
            info = flat.GetDataInformation()
            b = info.GetBounds()
            print(f"unrolled: s {b[0]:.6g} to {b[1]:.6g} mm, z {b[2]:.6g} to {b[3]:.6g} mm, "
                  f"{info.GetNumberOfCells()} of {block.GetDataInformation().GetNumberOfCells()} "
                  "cells (the others on crack planes)")
        view = CreateRenderView()
        view.ViewTime = t
        view.OrientationAxesVisibility = 0
        view.Background = [1, 1, 1]
        if hasattr(view, "UseColorPaletteForBackground"):
            view.UseColorPaletteForBackground = 0
        display = Show(flat, view)
        display.SetRepresentationType("Surface With Edges")
        display.EdgeColor = [0.5, 0.5, 0.5]
        ColorBy(display, ("CELLS", field))
        lut = GetColorTransferFunction(field)
        lut.ApplyPreset("Cool to Warm", True)
        lo, hi = flat.CellData[field].GetRange()
        print(f"coloured {field}: {lo:.6g} to {hi:.6g}")
        if hi - lo < 1e-9 * (abs(hi) if abs(hi) > 1 else 1.0):
            lo, hi = lo - 1e-6, hi + 1e-6
        lut.RescaleTransferFunction(lo, hi)
        display.SetScalarBarVisibility(view, True)
        bar = GetScalarBar(lut, view)
        bar.Title = LABELS.get(field, field)
        bar.ComponentTitle = ""
        bar.TitleColor = bar.LabelColor = [0, 0, 0]
        bar.Orientation = "Horizontal"
        bar.WindowLocation = "Any Location"
        bar.Position = [0.25, 0.02]
        bar.ScalarBarLength = 0.5
        grid = display.DataAxesGrid
        grid.GridAxesVisibility = 1
        grid.XTitle, grid.YTitle = "s = R theta [mm] (from 225 deg)", "z [mm]"
        for a in ("XTitleColor", "YTitleColor", "XLabelColor", "YLabelColor", "GridColor"):
            setattr(grid, a, [0, 0, 0])
        if i == 0 and args.title:
            text = Text(Text=args.title)
            td = Show(text, view)
            td.Color = [0, 0, 0]
            td.WindowLocation = "Upper Center"
        view.InteractionMode = "2D"
        ResetCamera(view)
        view.CameraParallelScale *= 0.75
        if i < len(args.fields) - 1:
            cell = layout.SplitVertical(cell, 1.0 / (len(args.fields) - i))
            AssignViewToLayout(view=view, layout=layout, hint=cell)
            cell += 1
        else:
            AssignViewToLayout(view=view, layout=layout, hint=cell)
    layout.SetSize(1400, 380 * len(args.fields))
    SaveScreenshot(args.png, layout, ImageResolution=[1400, 380 * len(args.fields)])
    print("wrote", args.png, "at time", t)


if __name__ == "__main__":
    main()
