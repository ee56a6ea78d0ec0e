#!/usr/bin/python3
"""How the FE glottis step's cost grows with the flow unknowns and the
ranks, and which part grows fastest.

The preset demos/glottis/closing_cycle.toml (Δt 1e-5, quadrature degree 2)
on five flow meshes, h_gap = 0.07 … 0.0175 mm with h_far = 10 h_gap (8k to
120k flow unknowns), each run for DURATION from rest on 1 and on 2 ranks:

  [mpirun -n R] fsai_glottis --config demos/glottis/closing_cycle.toml
      --fe.h_gap H --fe.h_far 10H --duration D --write_every 0 --output DIR

The first millisecond is the start-up (the fold at rest, the flow
accelerating); the timers cover the whole time loop, so the cost per
simulated ms is the loop's wall time over the duration. The breakdown is
each timer's share of the loop on rank 0 (summary.json's timings; the
collective parts include the wait for the other rank): the flow's linear
solve (one MUMPS factorisation and solve per coupling iteration), its
assembly, the mesh motion (ALE extension solve and move), the fold's forces
and the rest (porous marking, coupling, the fold, I/O).

usage: bench/glottis_cost.py [BUILD_DIR] [--duration 0.003] [--ranks 1 2]
       [--levels 0.07 0.05 0.035 0.025 0.0175] [--rerun]
writes bench/results/glottis_cost.csv and glottis_cost.png
"""
import argparse
import json
import os
import subprocess

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from benchlib import MPI_ENV, results_dir, print_markdown_table, write_rows

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..")
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(root, "build"))
ap.add_argument("--duration", type=float, default=0.003)
ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
ap.add_argument("--levels", type=float, nargs="+", default=[0.07, 0.05, 0.035, 0.025, 0.0175])
ap.add_argument("--rerun", action="store_true")
args = ap.parse_args()
out = results_dir()
env = MPI_ENV
exe = os.path.join(args.build, "demos", "fsai_glottis")
preset = os.path.join(root, "demos", "glottis", "closing_cycle.toml")
PARTS = {"solve": ["fluid: solve"], "assembly": ["fluid: assemble"],
         "mesh motion": ["ale: move", "ale: extension"], "forces": ["fluid: force"]}
LOOP = "glottis: time loop"

rows = []
for ranks in args.ranks:
    for h in args.levels:
        run = os.path.join(out, f"run_glottis_cost_h{h}_n{ranks}")
        summary = os.path.join(run, "summary.json")
        if args.rerun or not os.path.exists(summary):
            cmd = (["mpirun", "-n", str(ranks)] if ranks > 1 else []) + [
                exe, "--config", preset, "--fe.h_gap", f"{h}e-3", "--fe.h_far", f"{10 * h:.4g}e-3",
                "--duration", str(args.duration), "--write_every", "0", "--output", run]
            print(" ".join(cmd), flush=True)
            subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL)
        s = json.load(open(summary))
        t = s["timings"]
        loop = t[LOOP]["wall_s"]
        row = {"h_gap_mm": h, "ranks": ranks, "flow_dofs": s["flow_dofs"],
               "wall_per_ms_s": loop / (1e3 * args.duration),
               "steps": round(args.duration / 1e-5),
               "coupling_iterations_mean": s["coupling_iterations_mean"]}
        for part, timers in PARTS.items():
            row[part + "_share"] = sum(t[k]["wall_s"] for k in timers if k in t) / loop
        row["other_share"] = 1 - sum(row[p + "_share"] for p in PARTS)
        rows.append(row)
write_rows(os.path.join(out, "glottis_cost.csv"), rows)

print_markdown_table([
    ("h_gap [mm]", lambda r: f"{r['h_gap_mm']}"), ("ranks", lambda r: str(r["ranks"])),
    ("flow unknowns", lambda r: str(r["flow_dofs"])),
    ("wall per simulated ms [s]", lambda r: f"{r['wall_per_ms_s']:.1f}"),
    ("solve", lambda r: f"{100 * r['solve_share']:.0f} %"),
    ("assembly", lambda r: f"{100 * r['assembly_share']:.0f} %"),
    ("mesh motion", lambda r: f"{100 * r['mesh motion_share']:.1f} %"),
    ("forces", lambda r: f"{100 * r['forces_share']:.1f} %"),
    ("other", lambda r: f"{100 * r['other_share']:.0f} %")], rows)

# Growth exponents: cost ∝ unknowns^p, fitted per part over the levels
print()
for ranks in args.ranks:
    rr = [r for r in rows if r["ranks"] == ranks]
    if len(rr) < 2:
        continue
    n = np.log([r["flow_dofs"] for r in rr])
    fits = []
    for part in list(PARTS) + ["other"]:
        c = np.log([r[part + "_share"] * r["wall_per_ms_s"] for r in rr])
        fits.append(f"{part} {np.polyfit(n, c, 1)[0]:.2f}")
    total = np.polyfit(n, np.log([r["wall_per_ms_s"] for r in rr]), 1)[0]
    print(f"{ranks} rank(s): cost ∝ unknowns^p, p = {total:.2f} in all; " + ", ".join(fits))
for h in args.levels:
    by = {r["ranks"]: r for r in rows if r["h_gap_mm"] == h}
    if 1 in by and 2 in by:
        print(f"h_gap {h} mm: 2 ranks {by[1]['wall_per_ms_s'] / by[2]['wall_per_ms_s']:.2f}x "
              "faster than 1")

fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
for ranks, marker in zip(args.ranks, "os^"):
    rr = [r for r in rows if r["ranks"] == ranks]
    n = [r["flow_dofs"] for r in rr]
    a1.loglog(n, [r["wall_per_ms_s"] for r in rr], marker + "-", label=f"{ranks} rank(s): total")
    if ranks == max(args.ranks):
        for part in list(PARTS) + ["other"]:
            a1.loglog(n, [r[part + "_share"] * r["wall_per_ms_s"] for r in rr], marker + ":",
                      label=f"{ranks} ranks: {part}")
a1.set_xlabel("flow unknowns")
a1.set_ylabel("wall time per simulated ms [s]")
a1.set_title("FE glottis step, Δt 1e-5")
a1.legend(fontsize=7)
a1.grid(True, which="both", alpha=0.3)
rr = [r for r in rows if r["ranks"] == max(args.ranks)]
bottom = np.zeros(len(rr))
x = np.arange(len(rr))
for part in list(PARTS) + ["other"]:
    v = np.array([100 * r[part + "_share"] for r in rr])
    a2.bar(x, v, bottom=bottom, label=part)
    bottom += v
a2.set_xticks(x, [f"{r['flow_dofs'] // 1000}k" for r in rr])
a2.set_xlabel(f"flow unknowns ({max(args.ranks)} ranks)")
a2.set_ylabel("share of the time loop [%]")
a2.legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(out, "glottis_cost.png"), dpi=90)
