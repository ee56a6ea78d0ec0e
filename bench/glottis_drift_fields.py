#!/usr/bin/python3
"""Why the closing cycle's flow still drifts at 0.2 s.

The closing cycle (bench/glottis_closure_converged.py, ζ = 0.02) settles in
its fold motion by 0.13 s, but its cycle-mean glottal flow keeps falling,
about −0.4 % per 25 ms at the same opening (bench/glottis_cycle_peaks.py).
The reduced (Bernoulli) model, which has no flow memory, does not drift. So
the memory is the FE flow's, and the candidate is the slow flow away from
the jet: the supraglottal channel's recirculation.

This script compares the cycle-mean flow fields of one mesh level (h_gap
0.025 mm, Δt 0.7e-5: the level with checkpoints at both times) in its
cycle after t = 0.098 s (the step-14000 checkpoint of
run_glottis_h025_dt07_z02_c75) and after t = 0.196 s (the step-28000
checkpoint of run_glottis_h025_dt07_z02_c75_02s):

1. --run: each checkpoint folder is copied to WORK (the copies' flow.xdmf
   files are hundreds of MB; they stay out of the repository) and
   continued for one period and a bit (`--restart`, `--write_every 10`:
   a frame every 0.07 ms).
2. One period from the checkpoint (the mean period of the 3 cycles before
   it, between upward crossings of g = 0.05 mm in series.csv) is averaged:
   ParaView's Python averages the frames in it at the mesh nodes
   (bench/pv_cycle_mean.py).
3. Printed and written: the cycle-mean flow Q, the cycle-mean pressure on
   the axis at stations from the inlet to the outlet, and the cycle-mean
   axial velocity on the axis and near the wall downstream; a picture of
   both mean fields and their difference.

usage: bench/glottis_drift_fields.py [BUILD_DIR] [--run] [--work DIR] [--np N]
writes bench/results/glottis_drift_fields.csv and .png (the fields) and
glottis_drift_cycles.csv (the cycles)
"""
import argparse
import json
import os
import shutil
import subprocess

import numpy as np
from benchlib import read_float_rows, upward_crossings, write_rows

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--run", action="store_true", help="(re)run the two restarts")
ap.add_argument("--work", default="/tmp/fsai_drift_fields")
ap.add_argument("--np", type=int, default=1, help="MPI ranks of the restarts")
args = ap.parse_args()
res = os.path.join(here, "results")
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
# The runs' options (case h025_dt07_z02_c75 of glottis_closure_converged.py)
OPTS = ["--flow", "fe", "--fe.h_gap", "0.025e-3", "--fe.h_far", "0.25e-3", "--dt", "0.7e-5",
        "--vf.zeta1", "0.02", "--vf.zeta2", "0.02"]
SPAN = 0.0068  # > one period (6.5 ms)
CASES = {"early": "run_glottis_h025_dt07_z02_c75",
         "late": "run_glottis_h025_dt07_z02_c75_02s"}
G_OPEN = 0.05e-3


def checkpoint_time(folder):
    with open(os.path.join(folder, "checkpoint.json")) as f:
        return json.load(f)["t"]


if args.run:
    exe = os.path.join(args.build, "demos", "fsai_glottis")
    for name, src in CASES.items():
        out = os.path.join(args.work, name)
        shutil.rmtree(out, ignore_errors=True)
        shutil.copytree(os.path.join(res, src), out)
        t = checkpoint_time(out) + SPAN
        cmd = (["mpirun", "-n", str(args.np), exe] + OPTS
               + ["--duration", f"{t:.6f}", "--write_every", "10", "--restart", out])
        print(" ".join(cmd), flush=True)
        with open(os.path.join(out, "run_drift_fields.log"), "w") as f:
            subprocess.run(cmd, env=env, stdout=f, stderr=subprocess.STDOUT, check=True)

# 0. From the series alone: is it the flow through a given opening that
# drifts, or the opening? Per cycle (every 2nd after 0.09 s): the largest
# and the mean open half-gap (g clipped at 0), the mean flow and their ratio
rows, means, cycle_rows = [], {}, []
for run in ("run_glottis_h035_dt1_z02_c75_02s", "run_glottis_h025_dt07_z02_c75_02s"):
    path = os.path.join(res, run, "series.csv")
    if not os.path.exists(path):
        continue
    r = read_float_rows(path)
    up = [r[i]["t_s"] for i in upward_crossings([x["gap_m"] for x in r], G_OPEN)
          if r[i]["t_s"] > 0.09]
    print(f"{run}, cycle by cycle:")
    print("| cycle from [s] | largest half-gap [mm] | mean open half-gap [mm] | mean Q [l/s] "
          "| mean Q / mean open half-gap [m²/s] | mean h [mm] | mean lift [N] |")
    print("|---|---|---|---|---|---|---|")
    for a, b in list(zip(up, up[1:]))[::2]:
        c = [x for x in r if a <= x["t_s"] < b]
        g_max = max(x["gap_m"] for x in c)
        g_open = sum(max(x["gap_m"], 0) for x in c) / len(c)
        q = sum(x["Q_m3s"] for x in c) / len(c)
        print(f"| {a:.4f} | {1e3 * g_max:.4f} | {1e3 * g_open:.4f} | "
              f"{1e3 * q:.4f} | {q / g_open:.4f} | {1e3 * sum(x['h_m'] for x in c) / len(c):.4f} | "
              f"{sum(x['lift_N'] for x in c) / len(c):.5f} |")
        cycle_rows.append({"run": run, "cycle_start_s": a, "max_half_gap_mm": 1e3 * g_max,
                           "mean_open_half_gap_mm": 1e3 * g_open, "mean_q_ls": 1e3 * q,
                           "q_per_open_gap_m2s": q / g_open})
    print()
write_rows(os.path.join(res, "glottis_drift_cycles.csv"), cycle_rows)

for name in CASES:
    out = os.path.join(args.work, name)
    t_ck = checkpoint_time(out)
    r = read_float_rows(os.path.join(out, "series.csv"))
    # The period: the mean of the last 3 cycles before the checkpoint
    up = [r[i]["t_s"] for i in upward_crossings([x["gap_m"] for x in r], G_OPEN)
          if r[i]["t_s"] <= t_ck]
    t0, t1 = t_ck, t_ck + (up[-1] - up[-4]) / 3
    if r[-1]["t_s"] < t1:
        raise SystemExit(f"{name}: no full period after t = {t_ck:.4f} s (run with --run)")
    cyc = [x for x in r if t0 < x["t_s"] <= t1]
    npz = os.path.join(out, "cycle_mean.npz")
    subprocess.run(["pvpython", os.path.join(here, "pv_cycle_mean.py"),
                    os.path.join(out, "flow.xdmf"), str(t0), str(t1), npz], check=True)
    m = dict(np.load(npz))
    m["Q"] = np.mean([x["Q_m3s"] for x in cyc])
    m["Q_peak"] = max(x["Q_m3s"] for x in cyc)
    m["g_max"] = max(x["gap_m"] for x in cyc)
    m["t0"], m["t1"] = t0, t1
    means[name] = m
    print(f"{name}: period {t0:.5f} ... {t1:.5f} s ({1 / (t1 - t0):.2f} Hz), mean Q "
          f"{1e3 * m['Q']:.4f} l/s, peak Q {1e3 * m['Q_peak']:.4f} l/s, "
          f"largest half-gap {1e3 * m['g_max']:.4f} mm, {int(m['frames'])} frames "
          f"({m['t_first']:.5f} ... {m['t_last']:.5f} s)")

# The same nodes in both (one mesh): check, then compare node by node
e, l = means["early"], means["late"]
if e["x"].shape != l["x"].shape or np.abs(e["x"] - l["x"]).max() > 1e-12:
    raise SystemExit("the two restarts' meshes differ")
x, y = e["x"][:, 0], e["x"][:, 1]
H = y.max()
axis = np.where(y < 1e-9)[0]
print("\ncycle-mean pressure and axial velocity on the axis (y = 0)")
print("| x [mm] | p early [Pa] | p late [Pa] | Δp [Pa] | u early [m/s] | u late [m/s] |")
print("|---|---|---|---|---|---|")
stations = [-20, -10, -2, 0, 3, 5.5, 7, 9, 10, 12, 15, 20, 30, 40, 49]
for xs in stations:
    i = axis[np.argmin(np.abs(x[axis] - 1e-3 * xs))]
    pe, pl = e["pressure"][i], l["pressure"][i]
    ue, ul = e["velocity"][i, 0], l["velocity"][i, 0]
    print(f"| {1e3 * x[i]:.2f} | {pe:.1f} | {pl:.1f} | {pl - pe:+.1f} | {ue:.3f} | {ul:.3f} |")
    rows.append({"where": "axis", "x_mm": 1e3 * x[i], "y_mm": 0.0, "p_early_pa": pe,
                 "p_late_pa": pl, "ux_early_ms": ue, "ux_late_ms": ul})

# Near the wall y = H downstream: the recirculation's return flow
print("\ncycle-mean axial velocity and pressure at y = 7 mm (1 mm below the wall), downstream")
print("| x [mm] | u early [m/s] | u late [m/s] | p early [Pa] | p late [Pa] |")
print("|---|---|---|---|---|")
for xs in [10, 12, 15, 20, 25, 30, 40, 49]:
    d = (x - 1e-3 * xs) ** 2 + (y - (H - 1e-3)) ** 2
    i = np.argmin(d)
    print(f"| {1e3 * x[i]:.2f} | {e['velocity'][i, 0]:.3f} | {l['velocity'][i, 0]:.3f} | "
          f"{e['pressure'][i]:.1f} | {l['pressure'][i]:.1f} |")
    rows.append({"where": "near wall", "x_mm": 1e3 * x[i], "y_mm": 1e3 * y[i],
                 "p_early_pa": e["pressure"][i], "p_late_pa": l["pressure"][i],
                 "ux_early_ms": e["velocity"][i, 0], "ux_late_ms": l["velocity"][i, 0]})
write_rows(os.path.join(res, "glottis_drift_fields.csv"), rows)

# Pictures: mean |v| early and late, and the change of the mean u_x
import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402

tri = Triangulation(1e3 * x, 1e3 * y)
# Delaunay fills the fold's concave region: mask triangles whose centroid
# lies inside the fold (a cell-less region of the mesh: long edges there)
xy = np.c_[1e3 * x, 1e3 * y][tri.triangles]
edge = np.max(np.linalg.norm(xy - np.roll(xy, 1, axis=1), axis=2), axis=1)
tri.set_mask(edge > 1.0)
fig, ax = plt.subplots(3, 1, figsize=(12, 7), sharex=True)
speed = {n: np.linalg.norm(m["velocity"], axis=1) for n, m in means.items()}
vmax = max(s.max() for s in speed.values())
for a, n in zip(ax[:2], ("early", "late")):
    c = a.tripcolor(tri, speed[n], shading="gouraud", vmin=0, vmax=vmax, cmap="viridis")
    a.set_title(f"cycle-mean |v| [m/s], cycle from t = {means[n]['t0']:.4f} s")
    fig.colorbar(c, ax=a)
du = l["velocity"][:, 0] - e["velocity"][:, 0]
lim = np.abs(du).max()
c = ax[2].tripcolor(tri, du, shading="gouraud", vmin=-lim, vmax=lim, cmap="RdBu_r")
ax[2].set_title("late − early, cycle-mean u_x [m/s]")
fig.colorbar(c, ax=ax[2])
for a in ax:
    a.set_aspect("equal")
    a.set_ylabel("y [mm]")
ax[2].set_xlabel("x [mm] (fold from 0 to 9 mm)")
fig.tight_layout()
png = os.path.join(res, "glottis_drift_fields.png")
fig.savefig(png, dpi=110)
print(f"\nwrote {png}")
