#!/usr/bin/python3
"""Speed vs accuracy of fsai_formants for a vowel (default [u], planar,
Sommerfeld): F1-F3 error against the finest run vs wall time, over mesh
sizes given as elements per wavelength at f_max.

usage: bench/formants_speed_accuracy.py [BUILD_DIR] [--model planar|axisym]
       [--vowel u] [--ranks 1]
writes bench/results/formants_<vowel>_<model>.csv and .png
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
ap.add_argument("--model", default="planar")
ap.add_argument("--vowel", default="u")
ap.add_argument("--radiation", default="sommerfeld")
ap.add_argument("--ranks", type=int, default=1)
args = ap.parse_args()

exe = os.path.join(args.build, "demos", "fsai_formants")
out = os.path.join(here, "results")
os.makedirs(out, exist_ok=True)
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")

# (elements per wavelength at f_max, cells across the narrowest half-width,
# time steps per period of f_max); the last is the reference run. The
# constrictions, not the wavelength, decide the mesh of a vowel like [u].
levels = [(3, 0.5, 10), (4, 0.5, 15), (4, 1, 20), (6, 1, 30), (10, 2, 30),
          (15, 3, 40), (30, 6, 80)]
rows = []
for epw, ca, spp in levels:
    run = os.path.join(out, f"run_{args.vowel}_{args.model}_{epw}")
    cmd = ([] if args.ranks == 1 else ["mpirun", "-n", str(args.ranks)]) + [
        exe, "--vowel", args.vowel, "--model", args.model, "--radiation", args.radiation,
        "--elements_per_wavelength", str(epw), "--pulse.steps_per_period", str(spp),
        "--tract.cells_across", str(ca),
        "--snapshots", "0", "--output", run]
    subprocess.run(cmd, check=True, env=env, stdout=subprocess.DEVNULL)
    with open(os.path.join(run, "summary.json")) as f:
        s = json.load(f)
    rows.append(dict(epw=epw, ca=ca, spp=spp, h_m=s["h_m"], dofs=s["dofs"], steps=s["steps"],
                     wall_s=s["wall_s"], F=s["formants_hz"][:3]))
    print(f"epw {epw:3d} across {ca} spp {spp:3d} h {s['h_m']*1e3:.2f} mm dofs {s['dofs']:6d} "
          f"wall {s['wall_s']:.2f} s F = {[round(x, 1) for x in s['formants_hz'][:3]]}",
          flush=True)

ref = rows[-1]["F"]
path = os.path.join(out, f"formants_{args.vowel}_{args.model}.csv")
with open(path, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["elements_per_wavelength", "cells_across", "steps_per_period", "h_mm", "dofs", "steps",
                "wall_s", "F1_hz", "F2_hz", "F3_hz", "max_err_F1_F3_percent"])
    for r in rows:
        err = max(abs(a - b) / b * 100 for a, b in zip(r["F"], ref))
        r["err"] = err
        w.writerow([r["epw"], r["ca"], r["spp"], f"{r['h_m']*1e3:.3f}", r["dofs"], r["steps"],
                    f"{r['wall_s']:.2f}", *[f"{x:.1f}" for x in r["F"]], f"{err:.3f}"])
print(f"wrote {path}")
for r in rows:
    print(f"| {r['epw']} | {r['ca']} | {r['spp']} | {r['h_m']*1e3:.2f} | {r['dofs']} | {r['wall_s']:.2f} | "
          + " | ".join(f"{x:.1f}" for x in r["F"]) + f" | {r['err']:.2f} |")

fig, ax = plt.subplots(figsize=(6, 4))
pts = rows[:-1]
ax.loglog([r["wall_s"] for r in pts], [max(r["err"], 1e-3) for r in pts], "o-")
for r in pts:
    ax.annotate(f"{r['epw']}/λ, {r['ca']} across, {r['spp']}/T", (r["wall_s"], max(r["err"], 1e-3)), fontsize=8)
ax.axhline(1.0, color="k", ls=":", lw=0.8)
ax.set_xlabel("wall time [s] (%d rank%s)" % (args.ranks, "s" if args.ranks > 1 else ""))
ax.set_ylabel("max |F1..F3 error| vs finest [%]")
ax.set_title(f"fsai_formants [{args.vowel}] {args.model}, {args.radiation}")
ax.grid(alpha=0.3, which="both")
fig.tight_layout()
fig.savefig(path.replace(".csv", ".png"), dpi=120)
