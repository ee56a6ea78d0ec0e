#!/usr/bin/python3
"""The FE glottis closure model (fsai_glottis --flow fe, 2 MPI ranks): the
closure threshold g_min and the porous penalty sigma_P swept one at a time
about the defaults (g_min = 0.02 mm, sigma_P = 1e7 kg/(m^3 s)) at the
default p_sub = 1200 Pa.

For each run (default p_sub, --duration s, statistics over its second
half): f0, closure in every cycle, peak glottal flow (through the section
at the medial surface's centre), closed-phase leakage (largest |Q| while
the fold is at or across the axis, g <= 0, over the peak; and while
0 < g <= g_min, the approach), coupling iterations, unconverged steps, and
whether the run failed (exit status and the error line). The conditioning
indicator is sigma_P dt / rho: the porous term's weight against the BDF
mass term in the velocity block (1 means equal; the direct solver sees
the ratio of the two as the spread of the diagonal between porous and
free cells).

usage: bench/glottis_closure_sweep.py [BUILD_DIR] [--duration 0.03]
writes bench/results/glottis_closure_sweep.csv (and .png)
"""
import argparse
import csv
import json
import os
import subprocess

from benchlib import read_float_rows

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--duration", type=float, default=0.03)
ap.add_argument("--rerun", action="store_true")
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_glottis")
out = os.path.join(here, "results")
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
RHO, DT = 1.2, 2e-5

# (the defaults g_min = 0.02 mm, sigma_P = 1e7 are the stored default run,
# bench/results/run_glottis_fe_default, 0.1 s)
runs = [(g, 1e7) for g in (0.005e-3, 0.01e-3, 0.04e-3, 0.1e-3)] + \
    [(0.02e-3, s) for s in (1e3, 1e4, 1e5, 1e9)]


def series_stats(run, g_min, t_end, t_from=0.01):
    """From series.csv over [t_from, t_end] (the short runs hold too few
    complete cycles for the demo's own statistics): peak flow, contact
    episodes, max |Q| in contact (g <= 0) and while 0 < g <= g_min, over
    the peak"""
    r = read_float_rows(os.path.join(run, "series.csv"))
    w = [x for x in r if t_from <= x["t_s"] <= t_end + 1e-12]
    qp = max(x["Q_m3s"] for x in w)
    contact = [abs(x["Q_m3s"]) for x in w if x["gap_m"] <= 0]
    near = [abs(x["Q_m3s"]) for x in w if 0 < x["gap_m"] <= g_min]
    episodes = sum(1 for i in range(1, len(w)) if w[i]["gap_m"] <= 0 < w[i - 1]["gap_m"])
    return {"q_peak_ls": 1e3 * qp, "contacts": episodes,
            "leakage_pct": 100 * max(contact) / qp if contact else float("nan"),
            "leakage_below_g_min_pct": 100 * max(near) / qp if near else float("nan")}


rows = [dict(g_min_mm=0.02, sigma_p=1e7, sigma_dt_over_rho=1e7 * DT / RHO, failed="",
             **series_stats(os.path.join(out, "run_glottis_fe_default"), 0.02e-3,
                            args.duration),
             max_penetration_mm=float("nan"), its_mean=float("nan"), unconverged=0,
             wall_per_sim_s=float("nan"))]
for g_min, sigma in runs:
    run = os.path.join(out, f"run_glottis_sweep_g{g_min * 1e3:g}_s{sigma:g}")
    log = os.path.join(run + ".log")
    if args.rerun or not os.path.exists(os.path.join(run, "summary.json")):
        cmd = ["mpirun", "-n", "2", exe, "--flow", "fe", "--duration", str(args.duration),
               "--closure.g_min", str(g_min), "--fluid.sigma_p", str(sigma),
               "--coupling.on_failure", "warn", "--write_every", "0", "--output", run]
        print(" ".join(cmd), flush=True)
        with open(log, "w") as f:
            rc = subprocess.run(cmd, env=env, stdout=f, stderr=subprocess.STDOUT).returncode
    else:
        rc = 0
    row = {"g_min_mm": g_min * 1e3, "sigma_p": sigma, "sigma_dt_over_rho": sigma * DT / RHO}
    if rc == 0 and os.path.exists(os.path.join(run, "summary.json")):
        with open(os.path.join(run, "summary.json")) as f:
            s = json.load(f)
        row.update(failed="", **series_stats(run, g_min, args.duration),
                   max_penetration_mm=1e3 * s["max_penetration_m"],
                   its_mean=s["coupling_iterations_mean"],
                   unconverged=s.get("coupling_unconverged_steps", 0),
                   wall_per_sim_s=s["wall_per_sim_s"])
    else:
        err = ""
        if os.path.exists(log):
            lines = [l.strip() for l in open(log) if "rror" in l]
            err = lines[-1][:160] if lines else f"exit {rc}"
        row.update(failed=err or f"exit {rc}")
    rows.append(row)
    print(row, flush=True)

keys = ["g_min_mm", "sigma_p", "sigma_dt_over_rho", "failed", "q_peak_ls", "contacts",
        "leakage_pct", "leakage_below_g_min_pct", "max_penetration_mm", "its_mean",
        "unconverged", "wall_per_sim_s"]
with open(os.path.join(out, "glottis_closure_sweep.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=keys)
    w.writeheader()
    w.writerows(rows)
print(f"statistics over t in [0.01, {args.duration}] s (first row: the default run's same window)")
print("| g_min [mm] | σ_P | σ_P Δt/ρ | Q_peak [l/s] | contacts | leakage in contact | "
      "leakage 0 < g ≤ g_min | its | unconverged | failed |")
print("|---|---|---|---|---|---|---|---|---|---|")
for r in rows:
    if r["failed"]:
        print(f"| {r['g_min_mm']:g} | {r['sigma_p']:g} | {r['sigma_dt_over_rho']:.3g} | "
              f"| | | | | | {r['failed']} |")
    else:
        print(f"| {r['g_min_mm']:g} | {r['sigma_p']:g} | {r['sigma_dt_over_rho']:.3g} | "
              f"{r['q_peak_ls']:.3f} | {r['contacts']} | {r['leakage_pct']:.2f} % | "
              f"{r['leakage_below_g_min_pct']:.1f} % | {r['its_mean']:.2f} | "
              f"{r['unconverged']} | |")
