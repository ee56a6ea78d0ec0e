#!/usr/bin/env pvbatch
"""Render PNG snapshots of a run folder's XDMF files with ParaView, headless.

usage: xvfb-run -a pvbatch scripts/render_paraview.py RUN_DIR [--time T]
                                                   [--width PIXELS]

For every `*.xdmf` in RUN_DIR, at the last time written (or the one nearest
--time), writes RUN_DIR/<name>.png:
- DOLFINx writes each function as its own grid on the same mesh;
  scripts/paraview_xdmf.py joins their arrays on the one mesh.
- A mesh displacement field ("mesh_displacement" or "displacement") moves
  the reference mesh to the current one (Warp By Vector, scale 1: the ALE
  meshes are written in the reference configuration).
- Colour: the magnitude of the velocity ("velocity"), else the first
  point scalar (e.g. the acoustic pressure p', with a range symmetric
  about 0), else the first cell array.
Prints one line per image: file, field, time, range. Exit status 2 when
RUN_DIR holds no XDMF file.
"""
import argparse
import builtins
import glob
import os
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction,
                             Hide, Render, ResetCamera, SaveScreenshot, Show,
                             WarpByVector)
from paraview_xdmf import joined

ap = argparse.ArgumentParser()
ap.add_argument("run")
ap.add_argument("--time", type=float, default=None)
ap.add_argument("--width", type=int, default=1400)
args = ap.parse_args()

files = sorted(glob.glob(os.path.join(args.run, "*.xdmf")))
if not files:
    print(f"render_paraview: no .xdmf file in '{args.run}'", file=sys.stderr)
    sys.exit(2)

view = GetActiveViewOrCreate("RenderView")
view.OrientationAxesVisibility = 0
view.InteractionMode = "2D"
for path in files:
    reader, data = joined(path)
    times = list(reader.TimestepValues) if reader.TimestepValues else [0.0]
    t = times[-1] if args.time is None else builtins.min(times, key=lambda s: abs(s - args.time))
    data.UpdatePipeline(t)
    point = {n: data.PointData[n].GetNumberOfComponents() for n in data.PointData.keys()}
    cell = list(data.CellData.keys())
    disp = next((n for n in ("mesh_displacement", "displacement") if n in point), None)
    shown = data
    if disp:
        shown = WarpByVector(Input=data, Vectors=["POINTS", disp], ScaleFactor=1.0)
        shown.UpdatePipeline(t)
    view.ViewTime = t
    # Picture shaped like the domain (width fixed), so it fills the image
    b = shown.GetDataInformation().GetBounds()
    aspect = (b[1] - b[0]) / builtins.max(b[3] - b[2], 1e-30)
    size = [args.width, int(builtins.min(builtins.max(args.width / aspect * 1.25, 200), 1200))]
    view.ViewSize = size
    rep = Show(shown, view)
    field, rng = None, None
    if "velocity" in point:
        field = "velocity"
        ColorBy(rep, ("POINTS", field, "Magnitude"))
        rng = shown.PointData[field].GetRange(-1)
        GetColorTransferFunction(field).RescaleTransferFunction(rng[0], builtins.max(rng[1], rng[0] + 1e-12))
    else:
        scalars = [n for n in point if point[n] == 1 and n != disp]
        if scalars:
            field = scalars[0]
            ColorBy(rep, ("POINTS", field))
            rng = shown.PointData[field].GetRange(0)
            m = builtins.max(abs(rng[0]), abs(rng[1])) or 1.0
            lut = GetColorTransferFunction(field)
            lut.ApplyPreset("Cool to Warm", True)
            lut.RescaleTransferFunction(-m, m)
        elif cell:
            field = cell[0]
            ColorBy(rep, ("CELLS", field))
            rng = shown.CellData[field].GetRange(0)
    if field:
        rep.SetScalarBarVisibility(view, True)
    ResetCamera(view)
    view.CameraParallelScale = 0.55 * (b[3] - b[2]) if aspect < size[0] / size[1] else \
        0.55 * (b[1] - b[0]) * size[1] / size[0]
    Render(view)
    png = os.path.splitext(path)[0] + ".png"
    SaveScreenshot(png, view, ImageResolution=size)
    print(f"{png}: {field or '(geometry)'} at t = {t:g}, range {rng}"
          + (f", mesh moved by {disp}" if disp else ""), flush=True)
    Hide(shown, view)
