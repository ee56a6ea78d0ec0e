#!/usr/bin/python3
"""Speed against accuracy of the converged closing cycle: the preset
demos/glottis/closing_cycle.toml as it was (porous switch, Δt 1e-5) against
the settings that might make it faster.

Each case is the preset plus a few options, run from rest on 2 ranks:

  mpirun -n 2 fsai_glottis --config demos/glottis/closing_cycle.toml
      --duration D --write_every 0 [case options] --output DIR

Accuracy: one run per case for 0.1 s, its limit cycle over the window
[0.05, 0.1] s (the same for every case): f0 and the mean of the cycles'
peak flows (bench/benchlib.glottal_cycles, cycles from g = 0), the open
quotient (share of steps with g > 0), the closed-phase leakage
(summary.json), whether every cycle closes, the coupling steps left
unconverged and the largest one-step change of the glottal flow (t > 20 ms,
share of the peak).

Speed: the cases timed in interleaved rounds of TIMING_DURATION (the
machines here drift in speed between runs; the order reverses from round to
round), compared within a round as ratios of the whole command's wall time.

usage: bench/glottis_speedup.py [BUILD_DIR] [--cases old dt2 ramp_dt2]
       [--rounds 2] [--timing_cases old ramp_dt2] [--timing_duration 0.05]
       [--rerun]
writes bench/results/glottis_speedup.csv and glottis_speedup_timing.csv
"""
import argparse
import json
import os
import re
import subprocess

import numpy as np

from benchlib import MPI_ENV, glottal_cycles, interleaved, print_markdown_table, read_float_rows, results_dir, write_rows

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..")
CASES = {
    "old": ["--closure.porous_ramp", "0"],
    "ramp": ["--closure.porous_ramp", "2e-5"],
    "ramp_dt2": ["--closure.porous_ramp", "2e-5", "--dt", "2e-5"],
    "dt2": ["--closure.porous_ramp", "0", "--dt", "2e-5"],
}
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(root, "build"))
ap.add_argument("--rounds", type=int, default=2)
ap.add_argument("--cases", nargs="+", default=["old", "dt2", "ramp_dt2"])
ap.add_argument("--timing_cases", nargs="+", default=["old", "ramp_dt2"])
ap.add_argument("--timing_duration", type=float, default=0.05)
ap.add_argument("--duration", type=float, default=0.1)
ap.add_argument("--window", type=float, nargs=2, default=[0.05, 0.1])
ap.add_argument("--rerun", action="store_true")
args = ap.parse_args()
out = results_dir()
env = MPI_ENV
exe = os.path.join(args.build, "demos", "fsai_glottis")
preset = os.path.join(root, "demos", "glottis", "closing_cycle.toml")


def wall_of(log):
    m = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (?:(\d+):)?(\d+):([0-9.]+)",
                  open(log).read())
    return 3600 * int(m.group(1) or 0) + 60 * int(m.group(2)) + float(m.group(3))


def run_case(case, run, duration):
    log = run + ".log"
    if args.rerun or not os.path.exists(os.path.join(run, "summary.json")):
        cmd = ["/usr/bin/time", "-v", "mpirun", "-n", "2", exe, "--config", preset,
               "--duration", str(duration), "--write_every", "0", *CASES[case], "--output", run]
        print(" ".join(cmd), flush=True)
        with open(log, "w") as f:
            subprocess.run(cmd, env=env, check=True, stdout=f, stderr=subprocess.STDOUT)
    return json.load(open(os.path.join(run, "summary.json"))), wall_of(log)


rows = []
for case in args.cases:
    run = os.path.join(out, f"run_glottis_speedup_{case}")
    s, wall = run_case(case, run, args.duration)
    series = os.path.join(run, "series.csv")
    t0, t1 = args.window
    cyc = [c for c in glottal_cycles(series, 0.0, t0) if c["t0_s"] + 1 / c["f0_hz"] <= t1 + 1e-9]
    r = read_float_rows(series)
    t = np.array([x["t_s"] for x in r])
    Q = np.array([x["Q_m3s"] for x in r])
    g = np.array([x["gap_m"] for x in r])
    w = (t >= t0) & (t <= t1)
    late = t >= 0.02
    jump = np.abs(np.diff(Q)) * late[1:]
    rows.append({
        "case": case, "dt_s": s["parameters"]["dt"],
        "porous_ramp_m": s["parameters"]["closure"].get("porous_ramp", 0.0),
        "cycles": len(cyc), "f0_hz": float(np.mean([c["f0_hz"] for c in cyc])),
        "q_peak_mean_ls": float(np.mean([c["q_peak_ls"] for c in cyc])),
        "open_quotient": float((g[w] > 0).mean()),
        "leakage_pct": 100 * s["closed_leakage"],
        "closes_every_cycle": s["closes_every_cycle"],
        "coupling_unconverged_steps": s["coupling_unconverged_steps"],
        "coupling_iterations_mean": s["coupling_iterations_mean"],
        "max_jump_pct": 100 * jump.max() / Q[late].max()})
write_rows(os.path.join(out, "glottis_speedup.csv"), rows)
ref = rows[0]


def rel(r, key):
    return 100 * (r[key] / ref[key] - 1)


print_markdown_table([
    ("case", lambda r: r["case"]), ("Δt [s]", lambda r: f"{r['dt_s']:g}"),
    ("ramp [µm]", lambda r: f"{1e6 * r['porous_ramp_m']:g}"),
    ("f0 [Hz]", lambda r: f"{r['f0_hz']:.2f} ({rel(r, 'f0_hz'):+.2f} %)"),
    ("mean cycle peak [l/s]", lambda r: f"{r['q_peak_mean_ls']:.4f} ({rel(r, 'q_peak_mean_ls'):+.2f} %)"),
    ("OQ", lambda r: f"{r['open_quotient']:.3f} ({rel(r, 'open_quotient'):+.2f} %)"),
    ("leakage", lambda r: f"{r['leakage_pct']:.2f} %"),
    ("closes", lambda r: f"{'every cycle' if r['closes_every_cycle'] else 'no'} ({r['cycles']})"),
    ("unconverged steps", lambda r: str(r["coupling_unconverged_steps"])),
    ("coupling its", lambda r: f"{r['coupling_iterations_mean']:.2f}"),
    ("largest ΔQ step", lambda r: f"{r['max_jump_pct']:.1f} %")], rows)

timing = []
for k, case in interleaved(args.timing_cases, args.rounds):
    run = os.path.join(out, f"run_glottis_speedup_timing_{case}_{k}")
    s, wall = run_case(case, run, args.timing_duration)
    timing.append({"case": case, "round": k, "wall_s": wall,
                   "time_loop_s": s["timings"]["glottis: time loop"]["wall_s"]})
if timing:
    write_rows(os.path.join(out, "glottis_speedup_timing.csv"), timing)
    base = {r["round"]: r for r in timing if r["case"] == args.timing_cases[0]}
    print()
    print_markdown_table([
        ("case", lambda r: r["case"]), ("round", lambda r: str(r["round"])),
        ("wall [s]", lambda r: f"{r['wall_s']:.1f}"),
        ("time loop [s]", lambda r: f"{r['time_loop_s']:.1f}"),
        ("speed-up (wall)", lambda r: f"{base[r['round']]['wall_s'] / r['wall_s']:.2f}x")], timing)
