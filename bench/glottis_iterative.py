#!/usr/bin/python3
"""Why the iterative flow solver stalled at the glottis's closure, and what
the fixes cost: the converged closing cycle (demos/glottis/closing_cycle.toml)
with MUMPS and with the Schur fieldsplit (FGMRES, BoomerAMG on the velocity
block and on the selfp Schur approximation, or the pressure
convection-diffusion one, --fluid.schur pcd, docs/model.md E20b), with and
without the porous term in SUPG/PSPG's τ_m (--fluid.tau_porous, E20).

Each case is the preset plus a few options, run from rest on 2 ranks:

  mpirun -n 2 fsai_glottis --config demos/glottis/closing_cycle.toml
      --duration D --write_every 0 [case options] --output DIR

The limit cycle over [0.05, 0.1] s as in bench/glottis_speedup.py (f0 and
mean cycle peak of bench/benchlib.glottal_cycles, OQ as the share of steps
with g > 0, summary.json's leakage), the Krylov iterations per solve and
the flow solve's time per solve (summary.json's timers). A case that stops
is listed with where it stopped.

Speed: the direct and iterative solvers (all with the porous τ_m) timed
over TIMING_DURATION (through the first closure) in interleaved rounds, the
order reversed from round to round, compared within a round.

usage: bench/glottis_iterative.py [BUILD_DIR] [--cases ...] [--rounds 2]
       [--timing_duration 0.012] [--rerun]
writes bench/results/glottis_iterative.csv and glottis_iterative_timing.csv
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
ITERATIVE = ["--fluid.solver", "iterative"]
# case: (options, duration [s])
CASES = {
    "direct": ([], 0.1),
    "direct_tau": (["--fluid.tau_porous"], 0.1),
    "iterative": (ITERATIVE, 0.02),
    "iterative_tau": (ITERATIVE + ["--fluid.tau_porous"], 0.1),
    # the same at 800 Pa (a weaker jet): through two closures and reopenings?
    "iterative_tau_800": (ITERATIVE + ["--fluid.tau_porous", "--p-sub", "800"], 0.03),
    # the pressure convection-diffusion Schur approximation (E20b) instead
    # of selfp: only a pressure Laplacian meets AMG
    "iterative_pcd": (ITERATIVE + ["--fluid.tau_porous", "--fluid.schur", "pcd"], 0.1),
    # its Krylov iterations under mesh refinement, through the first
    # closure and the re-forming jet (0.02 s): the scene's mesh, the
    # preset's, and a finer one. On the scene's mesh this fold inverts an
    # ALE cell at 18.57 ms with the direct solver as well, so that level
    # stops at 18 ms
    "iterative_pcd_h0.05": (ITERATIVE + ["--fluid.tau_porous", "--fluid.schur", "pcd",
                                         "--fe.h_gap", "0.05e-3", "--fe.h_far", "0.5e-3"], 0.018),
    "iterative_pcd_h0.035": (ITERATIVE + ["--fluid.tau_porous", "--fluid.schur", "pcd"], 0.02),
    "iterative_pcd_h0.025": (ITERATIVE + ["--fluid.tau_porous", "--fluid.schur", "pcd",
                                          "--fe.h_gap", "0.025e-3", "--fe.h_far", "0.25e-3"], 0.02),
    # the same with an exact (LU) solve of the selfp Schur approximation
    # instead of its AMG V-cycle: is it the approximation or its AMG?
    "iterative_tau_schur_lu": (ITERATIVE + ["--fluid.tau_porous", "-fluid_fieldsplit_p_pc_type", "lu",
                                            "-fluid_fieldsplit_p_pc_factor_mat_solver_type", "mumps"], 0.02),
}
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(root, "build"))
ap.add_argument("--cases", nargs="+", default=list(CASES))
ap.add_argument("--window", type=float, nargs=2, default=[0.05, 0.1])
ap.add_argument("--rounds", type=int, default=2)
ap.add_argument("--timing_cases", nargs="*", default=["direct_tau", "iterative_tau", "iterative_pcd"])
# through the first closure (10.3 ms), before the iterative solver stalls
# in the open phase (13.6 ms)
ap.add_argument("--timing_duration", type=float, default=0.012)
ap.add_argument("--rerun", action="store_true")
args = ap.parse_args()
out = results_dir()
exe = os.path.join(args.build, "demos", "fsai_glottis")
preset = os.path.join(root, "demos", "glottis", "closing_cycle.toml")


def run_case(case, duration=None, tag=""):
    """The case's summary (None if it stopped), its folder and its log's
    text"""
    opts, case_duration = CASES[case]
    duration = duration or case_duration
    run = os.path.join(out, f"run_glottis_iterative_{case}{tag}")
    log = run + ".log"
    if args.rerun or not os.path.exists(log):
        cmd = ["mpirun", "-n", "2", exe, "--config", preset, "--duration", str(duration),
               "--write_every", "0", *opts, "--output", run]
        print(" ".join(cmd), flush=True)
        with open(log, "w") as f:
            subprocess.run(cmd, env=MPI_ENV, stdout=f, stderr=subprocess.STDOUT)
    text = open(log).read()
    summary = os.path.join(run, "summary.json")
    if "error:" in text or not os.path.exists(summary):
        return None, run, text
    return json.load(open(summary)), run, text


rows = []
for case in args.cases:
    s, run, text = run_case(case)
    opts = CASES[case][0]
    row = {"case": case, "solver": "iterative" if "iterative" in opts else "direct",
           "tau_porous": "--fluid.tau_porous" in opts}
    if s is None:
        m = re.search(r"error: (.*?\))", text)
        row["outcome"] = m.group(1) if m else "stopped"
        rows.append(row)
        continue
    tm = s["timings"]
    solves = tm["fluid: solve"]["count"]
    row.update({
        "outcome": "completed", "flow_dofs": s["flow_dofs"],
        "krylov_iterations_mean": s.get("krylov_iterations_mean", 0.0),
        "solve_ms": 1e3 * tm["fluid: solve"]["wall_s"] / solves,
        "assemble_ms": 1e3 * tm["fluid: assemble"]["wall_s"] / solves,
        "time_loop_s": tm["glottis: time loop"]["wall_s"]})
    t0, t1 = args.window
    if CASES[case][1] < t1:
        row["outcome"] = f"completed ({CASES[case][1]:g} s)"
        rows.append(row)
        continue
    series = os.path.join(run, "series.csv")
    cyc = [c for c in glottal_cycles(series, 0.0, t0) if c["t0_s"] + 1 / c["f0_hz"] <= t1 + 1e-9]
    r = read_float_rows(series)
    t = np.array([x["t_s"] for x in r])
    g = np.array([x["gap_m"] for x in r])
    w = (t >= t0) & (t <= t1)
    row.update({
        "cycles": len(cyc),
        "f0_hz": float(np.mean([c["f0_hz"] for c in cyc])),
        "q_peak_mean_ls": float(np.mean([c["q_peak_ls"] for c in cyc])),
        "open_quotient": float((g[w] > 0).mean()),
        "leakage_pct": 100 * s["closed_leakage"],
        "closes_every_cycle": s["closes_every_cycle"],
        "coupling_unconverged_steps": s["coupling_unconverged_steps"]})
    rows.append(row)
KEYS = ["case", "solver", "tau_porous", "outcome", "cycles", "f0_hz", "q_peak_mean_ls",
        "open_quotient", "leakage_pct", "closes_every_cycle", "coupling_unconverged_steps",
        "flow_dofs", "krylov_iterations_mean", "solve_ms", "assemble_ms", "time_loop_s"]
rows = [{k: r.get(k, "") for k in KEYS} for r in rows]
write_rows(os.path.join(out, "glottis_iterative.csv"), rows)
# relative to the preset (direct), or to the first case run
ref = next((r for r in rows if r["case"] == "direct"), rows[0])


def rel(r, key, digits):
    if r[key] == "":
        return "–"
    return f"{r[key]:.{digits}f} ({100 * (r[key] / ref[key] - 1):+.2f} %)"


print_markdown_table([
    ("case", lambda r: r["case"]), ("flow solve", lambda r: r["solver"]),
    ("τ_m with σ_P χ", lambda r: "yes" if r["tau_porous"] else "no"),
    ("outcome", lambda r: r["outcome"]),
    ("f0 [Hz]", lambda r: rel(r, "f0_hz", 2)),
    ("mean cycle peak [l/s]", lambda r: rel(r, "q_peak_mean_ls", 4)),
    ("OQ", lambda r: rel(r, "open_quotient", 3)),
    ("leakage", lambda r: f"{r['leakage_pct']:.2f} %" if r["leakage_pct"] != "" else "–"),
    ("closes", lambda r: f"{'every cycle' if r['closes_every_cycle'] else 'no'} ({r['cycles']})"
     if r["cycles"] != "" else "–"),
    ("unconverged", lambda r: str(r["coupling_unconverged_steps"])),
    ("flow unknowns", lambda r: str(r["flow_dofs"])),
    ("Krylov its", lambda r: f"{r['krylov_iterations_mean']:.1f}" if r["krylov_iterations_mean"] else "–"),
    ("ms per solve (assembly)", lambda r: f"{r['solve_ms']:.1f} ({r['assemble_ms']:.1f})"
     if r["solve_ms"] != "" else "–"),
    ("time loop", lambda r: f"{r['time_loop_s']:.0f} s" if r["time_loop_s"] != "" else "–")], rows)

timing = []
for k, case in interleaved(args.timing_cases, args.rounds):
    s, run, text = run_case(case, args.timing_duration, f"_timing_{k}")
    tm = s["timings"]
    timing.append({"case": case, "round": k,
                   "time_loop_s": tm["glottis: time loop"]["wall_s"],
                   "solve_ms": 1e3 * tm["fluid: solve"]["wall_s"] / tm["fluid: solve"]["count"],
                   "krylov_iterations_mean": s.get("krylov_iterations_mean", 0.0)})
if timing:
    write_rows(os.path.join(out, "glottis_iterative_timing.csv"), timing)
    base = {r["round"]: r for r in timing if r["case"] == args.timing_cases[0]}
    print()
    print_markdown_table([
        ("case", lambda r: r["case"]), ("round", lambda r: str(r["round"])),
        ("time loop [s]", lambda r: f"{r['time_loop_s']:.1f}"),
        ("ms per solve", lambda r: f"{r['solve_ms']:.1f}"),
        ("Krylov its", lambda r: f"{r['krylov_iterations_mean']:.1f}" if r["krylov_iterations_mean"] else "–"),
        ("time loop vs " + args.timing_cases[0],
         lambda r: f"{r['time_loop_s'] / base[r['round']]['time_loop_s']:.2f}")], timing)
