#!/usr/bin/python3
"""Mesh convergence of the FE glottal flow at a fixed glottis
(fsai_glottis --flow fe --fold static, 2 MPI ranks).

The self-oscillating scene's peak flow changed by -30 % on a finer mesh
(bench/glottis_fe_convergence.py) while f0 did not move: the oscillation
amplitude near onset is very sensitive to the flow's losses. This study
takes the oscillation out: the 2-DOF profile is held at h = h0 (half-gap
g = g0 - h0, flat medial surface 4 mm long) and the flow rate Q through the
glottis at p_sub = 1200 Pa is measured on a sequence of meshes (h_gap on
the fold, h_far = 10 h_gap away from it, as the scene's default 0.05 /
0.5 mm). Two gaps: 0.15 mm (the default start) and 0.55 mm (near the
limit cycle's widest opening, where its peak flow is taken).

Reported per run: Q mean and its spread (max - min) over the last 40 % of
the run (after the 5 ms pressure ramp), the discharge coefficient
C_d = Q / (2 g L_g sqrt(2 p_sub / rho)) (ideal Bernoulli flow through the
minimum section), dofs and wall time; and per gap the change of Q from
each mesh to the next finer one.

usage: bench/glottis_static_flow.py [BUILD_DIR] [--duration 0.012] [--rerun]
       [--gaps MM,.. --dt S,.. --h_gap MM,..]  (another study than the stored one)
writes bench/results/glottis_static_flow.csv (and .png)
"""
import argparse
import csv
import json
import math
import os
import subprocess

from benchlib import read_float_rows

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--duration", type=float, default=0.012)
ap.add_argument("--rerun", action="store_true")
ap.add_argument("--h_gap", help="mesh sizes on the fold [mm] (default: the study below)")
ap.add_argument("--gaps", help="half-gaps [mm]")
ap.add_argument("--dt", help="time steps [s] (each with every mesh)")
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_glottis")
out = os.path.join(here, "results")
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
P_SUB, RHO, DEPTH, G0 = 1200.0, 1.2, 18e-3, 0.2e-3

rows = []
# The study: both gaps on six meshes at the scene's Δt; the wide gap also
# at Δt/2 and Δt/4 on the three meshes about the default (CFL at the
# glottis ~18 at the default Δt and mesh)
ALL, MID = [0.1, 0.07, 0.05, 0.035, 0.025, 0.0175], [0.05, 0.035, 0.025]
cases = [(0.15, 2e-5, ALL), (0.55, 2e-5, ALL), (0.55, 1e-5, MID), (0.55, 5e-6, MID)]
if args.h_gap or args.gaps or args.dt:
    hs = [float(x) for x in (args.h_gap or "0.05,0.035,0.025").split(",")]
    cases = [(g, dt, hs) for g in [float(x) for x in (args.gaps or "0.55").split(",")]
             for dt in [float(x) for x in (args.dt or "2e-5").split(",")]]
for gap_mm, dt, h_list in cases:
    prev = None
    for h_mm in h_list:
        run = os.path.join(out, f"run_glottis_static_g{gap_mm:g}_h{h_mm:g}"
                           + ("" if dt == 2e-5 else f"_dt{dt:g}"))
        h0 = G0 - gap_mm * 1e-3
        if args.rerun or not os.path.exists(os.path.join(run, "summary.json")):
            cmd = ["mpirun", "-n", "2", exe, "--flow", "fe", "--fold", "static",
                   "--vf.h0", repr(h0), "--p-sub", str(P_SUB),
                   "--duration", str(args.duration), "--dt", repr(dt),
                   "--fe.h_gap", repr(h_mm * 1e-3),
                   "--fe.h_far", repr(10 * h_mm * 1e-3), "--write_every", "0",
                   "--output", run]
            print(" ".join(cmd), flush=True)
            with open(run + ".log", "w") as f:
                rc = subprocess.run(cmd, env=env, stdout=f, stderr=subprocess.STDOUT).returncode
            if rc != 0:
                print(f"  failed (exit {rc}), see {run}.log", flush=True)
                continue
        with open(os.path.join(run, "summary.json")) as f:
            s = json.load(f)
        r = read_float_rows(os.path.join(run, "series.csv"))
        t_end = r[-1]["t_s"]
        q = [x["Q_m3s"] for x in r if x["t_s"] >= 0.6 * t_end]
        q_mean = sum(q) / len(q)
        late = [x for x in r if x["t_s"] >= 0.6 * t_end]
        lift = sum(x["lift_N"] for x in late) / len(late)
        moment = sum(x["moment_Nm"] for x in late) / len(late)
        ideal = 2 * gap_mm * 1e-3 * DEPTH * math.sqrt(2 * P_SUB / RHO)
        row = {"gap_mm": gap_mm, "dt": dt, "h_gap_mm": h_mm, "flow_dofs": s["flow_dofs"],
               # convective Courant number at the glottis: ideal jet speed
               "cfl": math.sqrt(2 * P_SUB / RHO) * dt / (h_mm * 1e-3),
               "q_mean_ls": 1e3 * q_mean, "q_spread_pct": 100 * (max(q) - min(q)) / q_mean,
               "c_d": q_mean / ideal, "lift_N": lift, "moment_mNm": 1e3 * moment,
               "wall_s": s["wall_s"],
               "change_from_coarser_pct": (100 * (q_mean / prev[0] - 1) if prev else float("nan")),
               "lift_change_pct": (100 * (lift / prev[1] - 1) if prev else float("nan")),
               "moment_change_pct": (100 * (moment / prev[2] - 1) if prev else float("nan"))}
        prev = (q_mean, lift, moment)
        rows.append(row)
        print(row, flush=True)

keys = ["gap_mm", "dt", "cfl", "h_gap_mm", "flow_dofs", "q_mean_ls", "q_spread_pct", "c_d", "lift_N",
        "moment_mNm", "wall_s", "change_from_coarser_pct", "lift_change_pct",
        "moment_change_pct"]
with open(os.path.join(out, "glottis_static_flow.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=keys)
    w.writeheader()
    w.writerows(rows)
print(f"p_sub {P_SUB:g} Pa, Q over the last 40 % of {args.duration:g} s")
print("| half-gap [mm] | Δt [s] | CFL | h_gap [mm] | flow dofs | Q [l/s] | spread | C_d | lift [N] | "
      "moment [mN m] | Q, lift, moment change from coarser | wall [s] |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for r in rows:
    print(f"| {r['gap_mm']:g} | {r['dt']:g} | {r['cfl']:.1f} | {r['h_gap_mm']:g} | {r['flow_dofs']} | {r['q_mean_ls']:.4f} | "
          f"{r['q_spread_pct']:.2f} % | {r['c_d']:.3f} | {r['lift_N']:.4f} | "
          f"{r['moment_mNm']:.4f} | {r['change_from_coarser_pct']:+.2f} / "
          f"{r['lift_change_pct']:+.2f} / {r['moment_change_pct']:+.2f} % | {r['wall_s']:.0f} |")

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    for gap, dt in sorted({(r["gap_mm"], r["dt"]) for r in rows}):
        rr = [r for r in rows if r["gap_mm"] == gap and r["dt"] == dt]
        ax.errorbar([r["h_gap_mm"] for r in rr], [r["c_d"] for r in rr],
                    yerr=[0.5 * r["q_spread_pct"] / 100 * r["c_d"] for r in rr],
                    fmt="o-", capsize=3, label=f"half-gap {gap:g} mm, Δt {dt:g} s")
    ax.axvline(0.05, color="grey", ls=":", label="scene default h_gap")
    ax.set_xscale("log")
    ax.set_xlabel("mesh size on the fold h_gap [mm]")
    ax.set_ylabel("discharge coefficient Q / Q_Bernoulli")
    ax.set_title(f"static glottis, p_sub {P_SUB:g} Pa")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "glottis_static_flow.png"), dpi=120)
except ImportError:
    pass
