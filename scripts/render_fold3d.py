#!/usr/bin/env pvbatch
"""One ParaView picture of a fsai_fold3d run: the fold (moved by its
displacement, coloured by |u|) and the flow on the mid-length plane
z = L/2 (the moved mesh, coloured by |v|), seen obliquely from above
and from the midline.

usage: xvfb-run -a pvbatch scripts/render_fold3d.py RUN_DIR [--time T]
                                                   [--out PNG] [--width PIXELS]

RUN_DIR holds fold.xdmf and flow.xdmf (fsai_fold3d with --write_every > 0).
At the frame nearest --time (default the last), writes --out (default
RUN_DIR/fold3d.png) and prints the time and the ranges shown.
"""
import argparse
import builtins
import os
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction, GetScalarBar,
                             Render, ResetCamera, SaveScreenshot, Show, Slice, WarpByVector)
from paraview_xdmf import joined

ap = argparse.ArgumentParser()
ap.add_argument("run")
ap.add_argument("--time", type=float, default=None)
ap.add_argument("--out", default=None)
ap.add_argument("--width", type=int, default=1400)
args = ap.parse_args()
for name in ("fold.xdmf", "flow.xdmf"):
    if not os.path.exists(os.path.join(args.run, name)):
        sys.exit(f"render_fold3d: no '{name}' in '{args.run}' (run fsai_fold3d with --write_every > 0)")

fold_reader, fold = joined(os.path.join(args.run, "fold.xdmf"))
times = list(fold_reader.TimestepValues) or [0.0]
t = times[-1] if args.time is None else builtins.min(times, key=lambda s: abs(s - args.time))
_, flow = joined(os.path.join(args.run, "flow.xdmf"))
view = GetActiveViewOrCreate("RenderView")
view.ViewTime = t
view.ViewSize = [args.width, int(args.width * 0.7)]


def show_magnitude(source, field, preset, title):
    """Show source coloured by |field| from 0 to its largest value at t;
    return that value"""
    source.UpdatePipeline(t)
    rep = Show(source, view)
    ColorBy(rep, ("POINTS", field, "Magnitude"))
    top = builtins.max(source.PointData[field].GetRange(-1)[1], 1e-12)
    lut = GetColorTransferFunction(field)
    lut.ApplyPreset(preset, True)
    lut.RescaleTransferFunction(0.0, top)
    rep.SetScalarBarVisibility(view, True)
    GetScalarBar(lut, view).Title = title
    return top


fold.UpdatePipeline(t)
moved_fold = WarpByVector(Input=fold, Vectors=["POINTS", "displacement"], ScaleFactor=1.0)
u_top = show_magnitude(moved_fold, "displacement", "Viridis (matplotlib)", "|u| [m]")
fb = moved_fold.GetDataInformation().GetBounds()
zc = 0.5 * (fb[4] + fb[5])
flow.UpdatePipeline(t)
plane = Slice(Input=WarpByVector(Input=flow, Vectors=["POINTS", "mesh_displacement"], ScaleFactor=1.0))
plane.SliceType = "Plane"
plane.SliceType.Origin = [0.0, 0.0, zc]
plane.SliceType.Normal = [0.0, 0.0, 1.0]
v_top = show_magnitude(plane, "velocity", "Cool to Warm", "|v| [m/s]")

# Oblique: from the midline (+x), above (+y) and in front (+z)
cx, cy = 0.5 * (fb[0] + fb[1]), 0.5 * (fb[2] + fb[3])
span = builtins.max(fb[1] - fb[0], fb[3] - fb[2], fb[5] - fb[4])
view.CameraFocalPoint = [cx, cy, zc]
view.CameraPosition = [cx + 1.6 * span, cy + 1.2 * span, zc + 2.2 * span]
view.CameraViewUp = [0.0, 1.0, 0.0]
ResetCamera(view)
Render(view)
png = args.out or os.path.join(args.run, "fold3d.png")
SaveScreenshot(png, view, ImageResolution=view.ViewSize)
print(f"{png}: t = {t:g} s, fold |u| up to {u_top:.3e} m, flow |v| on z = {zc:.4g} m "
      f"up to {v_top:.3g} m/s", flush=True)
