#!/usr/bin/python3
"""Turek-Hron FSI2/FSI3: accuracy of the periodic state vs wall time per
simulated second (issue: speed chart of the partitioned FSI solver).

Each configuration (case, h, h_i, dt) runs `fsai_turek_hron` on 2 MPI ranks
(size-stiffened ALE, as FSI2/FSI3 need) unless its run folder already holds
a summary.json (then it is only evaluated; --rerun forces a run). The
periodic statistics over the last WINDOW seconds (mean = (max+min)/2,
amplitude = (max-min)/2, frequency from the upward mean crossings) are
compared with the FeatFlow refined values (Turek et al. 2010; FeatFlow
benchmark pages, level 4+0, FSI2 dt = 0.0005, FSI3 dt = 0.00025; the FSI3
2006-paper values are printed too). Writes bench/results/fsi_accuracy.csv
and fsi_accuracy.png.

usage: bench/fsi_accuracy.py [BUILD_DIR] [--rerun] [--only FSI3]
"""
import argparse
import csv
import json
import os
import subprocess

from turek_hron_stats import REF, load_series, periodic_stats

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--rerun", action="store_true")
ap.add_argument("--only", default="")
args = ap.parse_args()
out = os.path.join(here, "results")

REF_FSI3_2006 = {"uy_A_m": (0.00148, 0.03438, 5.3), "drag_N_per_m": (457.3, 22.66, 10.9)}

# The fluid's fieldsplit preconditioner kept for 10 solves, the Krylov
# solve tightened so that the coupling residual does not see its error
# (runs tagged _lag10; the untagged FSI3 runs rebuilt it for every solve
# at ksp_rtol 1e-8, and all runs factorised the solid
# with MUMPS across the ranks instead of PETSc's LU on every rank)
LAG = ["--fluid.pc_lag", "10", "--fluid.ksp_rtol", "1e-10"]

# case, h, h_i, dt, t_end, window, extra flags
CONFIGS = [
    ("FSI2", 0.04, 0.004, 0.005, 12.0, 1.5, ["--fluid.solver", "direct"]),
    ("FSI2", 0.03, 0.003, 0.005, 12.0, 1.5, ["--fluid.solver", "direct"]),
    ("FSI2", 0.03, 0.003, 0.0025, 12.0, 1.5, ["--fluid.solver", "direct"]),
    ("FSI3", 0.04, 0.004, 0.005, 7.0, 1.0, []),
    ("FSI3", 0.04, 0.004, 0.0025, 6.0, 1.0, []),
    ("FSI3", 0.03, 0.003, 0.005, 6.0, 1.0, []),
    ("FSI3", 0.04, 0.004, 0.005, 7.0, 1.0, LAG),
    ("FSI3", 0.04, 0.004, 0.0025, 6.0, 1.0, LAG),
    ("FSI3", 0.03, 0.003, 0.005, 6.0, 1.0, LAG),
]
# (--solid.newton_reuse, the solid's modified Newton, is not used here: on
# FSI3 at dt = 0.005 the IQN-ILS loop stalled at t = 0.445 s with a relative
# interface residual of 2.4e-5 after 50 iterations — whether the Jacobian is
# refreshed depends on the iteration history, so the solid's response is
# no longer a smooth function of the load at the coupling tolerance)


rows = []
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
for case, h, hi, dt, t_end, window, extra in CONFIGS:
    if args.only and case != args.only:
        continue
    tag = "_reuse" if "--solid.newton_reuse" in extra else ""
    tag += "_lag10" if extra == LAG else ""
    run = os.path.join(out, f"run_fsi_acc_{case}_hi{hi}_dt{dt}{tag}")
    if args.rerun or not os.path.exists(os.path.join(run, "summary.json")):
        cmd = ["mpirun", "-n", "2", os.path.join(args.build, "demos", "fsai_turek_hron"),
               "--case", case, "--h", str(h), "--h_i", str(hi), "--dt", str(dt),
               "--t_end", str(t_end), "--write_every", "0", "--ale.stiffening", "size",
               "--ale.chi", "1", "--fluid.solver", "iterative", "--fluid.velocity_pc", "ilu",
               "--output", run] + extra
        print(" ".join(cmd), flush=True)
        subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(run, "summary.json")) as f:
        summ = json.load(f)
    series = load_series(run)
    row = {"case": case, "h": h, "h_i": hi, "dt": dt,
           "solid_newton": "modified" if "_reuse" in tag else "full",
           "pc_lag": summ["parameters"]["fluid"].get("pc_lag", 1),
           "ranks": summ.get("mpi_size", ""),
           "solver": summ["parameters"]["fluid"]["solver"],
           "wall_per_sim_s": summ["wall_per_sim_s"],
           "its_mean": summ["coupling_iterations_mean"]}
    for key, (rm, ra, rf) in REF[case].items():
        m, a, fr = periodic_stats(series, key, window)
        short = key.split("_")[0] + ("" if key.startswith("drag") or key.startswith("lift")
                                     else "_" + key.split("_")[1])
        row[f"{short}_mean"] = m
        row[f"{short}_amp_err_pct"] = 100 * (a / ra - 1)
        row[f"{short}_freq_err_pct"] = 100 * (fr / rf - 1)
        if key == "drag_N_per_m":
            row["drag_mean_err_pct"] = 100 * (m / rm - 1)
    if case == "FSI3":
        m, a, fr = periodic_stats(series, "uy_A_m", window)
        row["uy_amp_err_2006_pct"] = 100 * (a / REF_FSI3_2006["uy_A_m"][1] - 1)
        row["uy_freq_err_2006_pct"] = 100 * (fr / REF_FSI3_2006["uy_A_m"][2] - 1)
    rows.append(row)

keys = []
for r in rows:
    keys += [k for k in r if k not in keys]
with open(os.path.join(out, "fsi_accuracy.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=keys)
    w.writeheader()
    w.writerows(rows)
print("| case | h_i | Δt | ranks | solver | pc lag | wall s / sim s | its | uy amp | "
      "uy freq | drag mean | drag amp |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for r in rows:
    print(f"| {r['case']} | {r['h_i']} | {r['dt']} | {r['ranks']} | {r['solver']} | "
          f"{r['pc_lag']} | "
          f"{r['wall_per_sim_s']:.1f} | {r['its_mean']:.2f} | {r['uy_A_amp_err_pct']:+.1f} % | "
          f"{r['uy_A_freq_err_pct']:+.1f} % | {r['drag_mean_err_pct']:+.1f} % | "
          f"{r['drag_amp_err_pct']:+.1f} % |")
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    groups = (("FSI2", "o", "FSI2", lambda r: r["case"] == "FSI2"),
              ("FSI3", "s", "FSI3, pc_lag 10",
               lambda r: r["case"] == "FSI3" and r["pc_lag"] != 1),
              ("FSI3", "x", "FSI3, preconditioner every solve, solid MUMPS",
               lambda r: r["case"] == "FSI3" and r["pc_lag"] == 1))
    for case, mk, label, sel in groups:
        rr = [r for r in rows if sel(r)]
        for i, (key, lab) in enumerate((("uy_A_amp_err_pct", "uy(A) amplitude"),
                                        ("uy_A_freq_err_pct", "uy(A) frequency"))):
            ax[i].scatter([r["wall_per_sim_s"] for r in rr], [abs(r[key]) for r in rr],
                          marker=mk, label=label)
            if mk == "x":
                continue  # the same (h_i, dt) as the labelled squares
            for r in rr:
                ax[i].annotate(f"{r['h_i']}/{r['dt']}", (r["wall_per_sim_s"], abs(r[key])),
                               fontsize=7, xytext=(4, 4), textcoords="offset points")
            ax[i].set(xlabel="wall s per simulated s (2 ranks); labels h_i/Δt",
                      ylabel=f"|error| {lab} [%]")
    for a in ax:
        a.axhline(5, color="r", lw=0.5, ls=":")
        a.axvline(66, color="g", lw=0.5, ls=":")
        a.legend(fontsize=7)
    fig.suptitle("Turek-Hron FSI: accuracy vs cost (FeatFlow refined reference; "
                 "green: 5x faster than turtleFSI on FSI3)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fsi_accuracy.png"), dpi=110)
except ImportError:
    print("matplotlib missing: no chart")
