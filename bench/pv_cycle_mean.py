#!/usr/bin/env pvpython
"""Time mean of a run's flow.xdmf over [t0, t1) at the mesh nodes, for
bench/glottis_drift_fields.py (runs in ParaView's Python, which reads XDMF;
Debian's Python has no HDF5 module).

usage: pvpython bench/pv_cycle_mean.py FLOW_XDMF T0 T1 OUT_NPZ

Writes OUT_NPZ with the nodes' reference coordinates `x` (N × 2), the mean
`velocity` (N × 2), `pressure` and `mesh_displacement` (N × 2), and the
number of frames `frames`. Frames are equally spaced (--write_every), so
the mean over the frames of one period is the cycle mean.
"""
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import Xdmf3ReaderS
from vtk.util.numpy_support import vtk_to_numpy

path, t0, t1, out = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
reader = Xdmf3ReaderS(FileName=[path])
reader.UpdatePipelineInformation()
times = [t for t in reader.TimestepValues if t0 - 1e-12 <= t < t1 - 1e-12]
if len(times) < 2:
    sys.exit(f"pv_cycle_mean: {len(times)} frames of '{path}' in [{t0}, {t1})")
names = {"velocity": 2, "pressure": 1, "mesh_displacement": 2}
acc, x = {}, None
for t in times:
    reader.UpdatePipeline(t)
    # DOLFINx writes each function as its own grid on one mesh: the blocks
    # share the points, so take each array from the block that has it
    data = servermanager.Fetch(reader)
    it = data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        ds = it.GetCurrentDataObject()
        if x is None:
            x = vtk_to_numpy(ds.GetPoints().GetData())[:, :2].copy()
        pd = ds.GetPointData()
        for n, c in names.items():
            a = pd.GetArray(n)
            if a is not None:
                v = vtk_to_numpy(a).reshape(len(x), -1)[:, :c]
                v = v[:, 0] if c == 1 else v
                acc[n] = acc.get(n, 0) + v
        it.GoToNextItem()
missing = [n for n in names if n not in acc]
if missing:
    sys.exit(f"pv_cycle_mean: '{path}' has no {missing}")
np.savez(out, x=x, frames=len(times), t_first=times[0], t_last=times[-1],
         **{n: acc[n] / len(times) for n in names})
print(f"{out}: {len(times)} frames, t = {times[0]:.6f} ... {times[-1]:.6f} s")
