#!/usr/bin/python3
"""One-step jumps of the glottal flow at closing and reopening on the FE
glottis scene's default mesh (0.05 mm), and what the porous ramp
(--closure.porous_ramp, docs/model.md G4) does to them there. (On the
preset's 0.035 mm mesh: bench/glottis_speedup.py, cases dt2 and ramp_dt2.)

fsai_glottis --flow fe (h_gap 0.05 mm, Δt 2e-5, p_sub 1200 Pa), run for
DURATION from rest with the porous indicator switched cell-wise (ramp 0)
and ramped over δ:

  [mpirun -n R] fsai_glottis --flow fe --closure.porous_ramp δ
      --duration D --write_every 0 --output DIR

Per run, over t ≥ 20 ms (after the start-up): the largest one-step change
of the glottal flow Q as a share of the peak flow, with its time and the
half-gap there; the number of steps whose change exceeds 10 % of the peak;
the limit-cycle figures of summary.json (f0, open quotient, peak flow,
closed-phase leakage, closed in every cycle) and the coupling iterations.

usage: bench/glottis_clicks.py [BUILD_DIR] [--duration 0.1] [--ranks 1]
       [--ramps 0 2e-5] [--rerun]
writes bench/results/glottis_clicks.csv
"""
import argparse
import json
import os
import subprocess

import numpy as np

from benchlib import MPI_ENV, results_dir, print_markdown_table, read_float_rows, write_rows

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..")
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(root, "build"))
ap.add_argument("--duration", type=float, default=0.1)
ap.add_argument("--ranks", type=int, default=1)
ap.add_argument("--ramps", type=float, nargs="+", default=[0.0, 2e-5])
ap.add_argument("--rerun", action="store_true")
args = ap.parse_args()
out = results_dir()
env = MPI_ENV
exe = os.path.join(args.build, "demos", "fsai_glottis")
T_FROM = 0.02  # [s] after the start-up

rows = []
for scene in ["default"]:
    for ramp in args.ramps:
        run = os.path.join(out, f"run_glottis_clicks_{scene}_ramp{ramp:g}_n{args.ranks}")
        summary = os.path.join(run, "summary.json")
        if args.rerun or not os.path.exists(summary):
            cmd = (["mpirun", "-n", str(args.ranks)] if args.ranks > 1 else []) + [
                exe, "--flow", "fe", "--closure.porous_ramp", f"{ramp:g}",
                "--duration", str(args.duration), "--write_every", "0", "--output", run]
            print(" ".join(cmd), flush=True)
            subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL)
        s = json.load(open(summary))
        r = read_float_rows(os.path.join(run, "series.csv"))
        t = np.array([x["t_s"] for x in r])
        Q = np.array([x["Q_m3s"] for x in r])
        g = np.array([x["gap_m"] for x in r])
        late = t >= T_FROM
        peak = Q[late].max()
        jump = np.abs(np.diff(Q)) * late[1:]
        i = int(np.argmax(jump))
        rows.append({
            "scene": scene, "porous_ramp_um": 1e6 * ramp,
            "max_jump_pct": 100 * jump[i] / peak, "max_jump_t_ms": 1e3 * t[i + 1],
            "max_jump_gap_um": 1e6 * g[i + 1],
            "jumps_over_10pct": int((jump > 0.1 * peak).sum()),
            "f0_hz": s["f0_hz"], "open_quotient": s["open_quotient"],
            "q_peak_ls": 1e3 * s["q_peak_m3s"], "leakage_pct": 100 * s["closed_leakage"],
            "closes_every_cycle": s["closes_every_cycle"],
            "coupling_iterations_mean": s["coupling_iterations_mean"],
            "coupling_iterations_max": s["coupling_iterations_max"],
            "coupling_unconverged_steps": s["coupling_unconverged_steps"],
            "time_loop_s": s["timings"]["glottis: time loop"]["wall_s"]})
write_rows(os.path.join(out, "glottis_clicks.csv"), rows)
print_markdown_table([
    ("scene", lambda r: r["scene"]), ("ramp δ [µm]", lambda r: f"{r['porous_ramp_um']:g}"),
    ("largest one-step ΔQ", lambda r: f"{r['max_jump_pct']:.1f} % at {r['max_jump_t_ms']:.2f} ms "
                                      f"(g {r['max_jump_gap_um']:.1f} µm)"),
    ("steps > 10 %", lambda r: str(r["jumps_over_10pct"])),
    ("f0 [Hz]", lambda r: f"{r['f0_hz']:.2f}"), ("OQ", lambda r: f"{r['open_quotient']:.3f}"),
    ("peak flow [l/s]", lambda r: f"{r['q_peak_ls']:.3f}"),
    ("leakage", lambda r: f"{r['leakage_pct']:.2f} %"),
    ("closes", lambda r: "every cycle" if r["closes_every_cycle"] else "no"),
    ("coupling its mean / max / unconverged",
     lambda r: f"{r['coupling_iterations_mean']:.2f} / {r['coupling_iterations_max']} / "
               f"{r['coupling_unconverged_steps']}"),
    ("time loop [s]", lambda r: f"{r['time_loop_s']:.0f}")], rows)
