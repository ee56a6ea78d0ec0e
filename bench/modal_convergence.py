#!/usr/bin/python3
"""Mesh convergence and cost of fsai_modal (3D vocal fold, E = 8 kPa,
nu = 0.4, rho = 1000 kg/m3): f1..f4 for P1 and P2 over mesh sizes, the
change between the two finest P2 meshes, and f1 error vs wall time
(error against the finest P2 run).

usage: bench/modal_convergence.py [BUILD_DIR] [--ranks 2] [--layers 1]
writes bench/results/modal_convergence.csv and .png
"""
import argparse
import csv
import json
import os
import subprocess

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--ranks", type=int, default=2)
ap.add_argument("--layers", type=int, default=1)
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_modal")
out = os.path.join(here, "results")
os.makedirs(out, exist_ok=True)
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")

runs = [(1, h) for h in (2.0, 1.4, 1.0, 0.7)] + [(2, h) for h in (2.0, 1.4, 1.0, 0.7)]
rows = []
for order, h in runs:
    run = os.path.join(out, f"run_modal_p{order}_{h}")
    cmd = ["mpirun", "-n", str(args.ranks)] if args.ranks > 1 else []
    cmd += [exe, "--order", str(order), "--fold.h", str(h * 1e-3), "--layers",
            str(args.layers), "--output", run]
    subprocess.run(cmd, check=True, env=env, stdout=subprocess.DEVNULL)
    with open(os.path.join(run, "summary.json")) as f:
        s = json.load(f)
    rows.append(dict(order=order, h=h, dofs=s["dofs"], wall=s["wall_s"],
                     f=s["frequencies_hz"][:4]))
    print(f"P{order} h {h} mm dofs {s['dofs']:7d} wall {s['wall_s']:6.2f} s "
          f"f1-4 = {[round(x, 2) for x in s['frequencies_hz'][:4]]}", flush=True)

ref = rows[-1]["f"]
p2 = [r for r in rows if r["order"] == 2]
change = [abs(a - b) / b * 100 for a, b in zip(p2[-2]["f"], p2[-1]["f"])]
print("change between the two finest P2 meshes [%]:", [round(c, 3) for c in change])
path = os.path.join(out, f"modal_convergence_layers{args.layers}.csv")
with open(path, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["order", "h_mm", "dofs", "wall_s", "f1", "f2", "f3", "f4", "f1_err_percent"])
    for r in rows:
        r["err"] = abs(r["f"][0] - ref[0]) / ref[0] * 100
        w.writerow([r["order"], r["h"], r["dofs"], f"{r['wall']:.2f}",
                    *[f"{x:.3f}" for x in r["f"]], f"{r['err']:.4f}"])
for r in rows:
    print(f"| P{r['order']} | {r['h']} | {r['dofs']} | {r['wall']:.1f} | "
          + " | ".join(f"{x:.2f}" for x in r["f"]) + f" | {r['err']:.3f} |")
fig, ax = plt.subplots(figsize=(6, 4))
for order in (1, 2):
    rr = [r for r in rows if r["order"] == order and r is not rows[-1]]
    ax.loglog([r["wall"] for r in rr], [max(r["err"], 1e-4) for r in rr], "o-",
              label=f"P{order}")
    for r in rr:
        ax.annotate(f"{r['h']} mm", (r["wall"], max(r["err"], 1e-4)), fontsize=7)
ax.set_xlabel(f"wall time [s] ({args.ranks} ranks)")
ax.set_ylabel("f1 error vs finest P2 [%]")
ax.set_title(f"fsai_modal, {args.layers}-layer fold: f1 error vs cost")
ax.legend()
ax.grid(alpha=0.3, which="both")
fig.tight_layout()
fig.savefig(path.replace(".csv", ".png"), dpi=120)
