#!/usr/bin/python3
"""DFG 2D-2 (Re = 100) speed vs accuracy for fsai_cylinder: c_D,max,
c_L,max and St against the FeatFlow refined series (3.2274, 0.9866,
0.30184) over mesh levels x time steps, with wall time per simulated
second and its breakdown (assembly, solve, forces, other).

usage: bench/dfg_2d2.py [BUILD_DIR] [--ranks 2] [--levels 0 1 2]
       [--dts 0.005 0.0025] [--t_end 8] [--t_stats 6]
       [--solvers direct iterative-ilu iterative-amg] [--name dfg_2d2]
writes bench/results/NAME.csv and .png
solvers: direct = MUMPS LU; iterative-amg = FGMRES + Schur fieldsplit,
BoomerAMG on both blocks; iterative-ilu = the same with block-Jacobi ILU(0)
on the velocity block; direct-q2 = MUMPS LU with --fluid.quadrature_degree 2
(`--solvers direct direct-q2 --levels 1 --dts 0.005 --name
dfg_2d2_quadrature`)
"""
import argparse
import csv
import json
import os
import re
import subprocess

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--ranks", type=int, default=2)
ap.add_argument("--levels", type=int, nargs="+", default=[0, 1, 2])
ap.add_argument("--dts", type=float, nargs="+", default=[0.005, 0.0025])
ap.add_argument("--t_end", type=float, default=8.0)
ap.add_argument("--t_stats", type=float, default=6.0)
solvers = {"direct": [],
           "iterative-amg": ["--fluid.solver", "iterative"],
           "iterative-ilu": ["--fluid.solver", "iterative", "--fluid.velocity_pc", "ilu"],
           # MUMPS LU with the flow's cell integrals at quadrature degree 2
           "direct-q2": ["--fluid.quadrature_degree", "2"]}
ap.add_argument("--solvers", nargs="+", choices=list(solvers), default=["iterative-ilu"])
ap.add_argument("--name", default="dfg_2d2")
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_cylinder")
out = os.path.join(here, "results")
os.makedirs(out, exist_ok=True)
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
ref = {"cd_max": 3.2274, "cl_max": 0.9866, "strouhal": 0.30184}
rows = []
path = os.path.join(out, args.name + ".csv")
for solver, level, dt in [(s, l, d) for s in args.solvers for l in args.levels for d in args.dts]:
    run = os.path.join(out, f"run_dfg_{solver}_l{level}_dt{dt}")
    cmd = (["mpirun", "-n", str(args.ranks)] if args.ranks > 1 else []) + [
        exe, "--case", "2D-2", "--level", str(level), "--dt", str(dt),
        "--t_end", str(args.t_end), "--t_stats", str(args.t_stats),
        "--write_every", "0", "--output", run] + solvers[solver]
    log = subprocess.run(cmd, check=True, env=env, capture_output=True, text=True).stdout
    with open(os.path.join(run, "summary.json")) as f:
        s = json.load(f)
    timing = {}
    for name in ("fluid: assemble", "fluid: solve", "fluid: force", "fluid: step"):
        m = re.search(re.escape(name) + r"\s+\d+\s+([0-9.]+)", log)
        timing[name] = float(m.group(1)) if m else float("nan")
    r = dict(solver=solver, level=level, dt=dt, dofs=s["dofs"], wps=s["wall_per_sim_s"],
             **{k: s[k] for k in ref},
             asm=timing["fluid: assemble"] / args.t_end,
             solve=timing["fluid: solve"] / args.t_end,
             force=timing["fluid: force"] / args.t_end)
    r["other"] = r["wps"] - r["asm"] - r["solve"] - r["force"]
    for k in ref:
        r["err_" + k] = 100 * (r[k] / ref[k] - 1)
    rows.append(r)
    print(f"{solver} level {level} dt {dt} dofs {r['dofs']} wall/sim-s {r['wps']:.1f} "
          f"(assembly {r['asm']:.1f}, solve {r['solve']:.1f}, forces {r['force']:.1f}, other {r['other']:.1f}) "
          f"cd_max {r['cd_max']:.4f} ({r['err_cd_max']:+.2f}%) "
          f"cl_max {r['cl_max']:.4f} ({r['err_cl_max']:+.2f}%) "
          f"St {r['strouhal']:.4f} ({r['err_strouhal']:+.2f}%)", flush=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

fig, ax = plt.subplots(1, 2, figsize=(10, 4))
for solver, dt in [(s, d) for s in args.solvers for d in args.dts]:
    rr = [r for r in rows if r["dt"] == dt and r["solver"] == solver]
    if not rr:
        continue
    ax[0].loglog([r["wps"] for r in rr], [abs(r["err_cl_max"]) for r in rr], "o-", label=f"{solver} dt={dt}")
    ax[1].loglog([r["wps"] for r in rr], [abs(r["err_strouhal"]) for r in rr], "o-", label=f"{solver} dt={dt}")
    for r in rr:
        ax[0].annotate(f"L{r['level']}", (r["wps"], abs(r["err_cl_max"])), fontsize=8)
ax[0].axhline(3, color="k", ls=":", lw=0.8)
ax[1].axhline(1, color="k", ls=":", lw=0.8)
for a, t in zip(ax, ("|c_L,max error| [%]", "|St error| [%]")):
    a.axvline(90, color="r", ls=":", lw=0.8)
    a.set_xlabel(f"wall s per simulated s ({args.ranks} ranks)")
    a.set_ylabel(t)
    a.grid(alpha=0.3, which="both")
    a.legend(fontsize=8)
fig.suptitle("DFG 2D-2, fsai_cylinder (P1/P1 SUPG/PSPG, BDF2 Oseen)")
fig.tight_layout()
fig.savefig(path.replace(".csv", ".png"), dpi=120)
