#!/usr/bin/python3
"""Does the 2-DOF fold close the glottis on the converged FE mesh?

On the scene's default mesh (h_gap = 0.05 mm) the fold closes in every
cycle at 1200 Pa; on the 0.035 mm mesh, the coarsest whose glottal forces
are converged (bench/glottis_static_flow.py), it settles into a cycle that
does not reach the axis (bench/glottis_fe_convergence.py). This study
varies what the scene leaves free (p_sub, rest gap, modal damping) on that
mesh and reports, per 5 ms window, the smallest and largest half-gap: the
start-up always overshoots into contact, so only the windows after
t_settle (default 30 ms) say whether the cycle closes. The study adds the
time step this mesh needs (Δt = 1e−5, cases dt1_*; dt05_* is Δt/2): with
ζ = 0.02 the cycle closes in every cycle there once the mesh motion's gap
columns stop at g0 + 0.75 R (dt1_z02_c75; the g0 + R runs invert a cell).
h025_dt1_z02_c75 is its mesh check: h_gap 0.025 mm, h_far 0.25 mm;
the cases change one size of the mesh at a time; the next
h025_dt07_z02_c75 refines the mesh as h025 and Δt by 0.7 together (the same
CFL number), continued to 0.1 s from its step-8000 checkpoint (--restart,
log run_restart.log).

Each case is one run of
  mpirun -n 2 fsai_glottis --flow fe --fe.h_gap 0.035e-3 --fe.h_far 0.35e-3
      --write_every 0 --duration D [case options]
stored in bench/results/run_glottis_h035_<case>/ (series.csv, summary.json,
run.log). A run that fails (e.g. an inverted ALE cell) is reported with
its error line.

usage: bench/glottis_closure_converged.py [BUILD_DIR] [--run CASE,..] [--t_settle S]
writes bench/results/glottis_closure_converged.csv
"""
import argparse
import json
import os
import subprocess

from benchlib import read_float_rows, write_rows

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--run", help="cases to (re)run now, comma-separated")
ap.add_argument("--t_settle", type=float, default=0.03)
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_glottis")
res = os.path.join(here, "results")
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
MESH = ["--fe.h_gap", "0.035e-3", "--fe.h_far", "0.35e-3"]
# the closing cycle's time step and damping
CLOSING = ["--dt", "1e-5", "--vf.zeta1", "0.02", "--vf.zeta2", "0.02"]

# case: (duration [s], options). "conv_fine_01_load" is the convergence
# study's run at the scene's defaults (0.1 s, stored under that name)
CASES = {
    # (the runs, made when the algebraic gap columns reached g0 + R)
    "default": (0.1, ["--closure.gap_columns", "1"]),
    "z02": (0.04, ["--vf.zeta1", "0.02", "--vf.zeta2", "0.02", "--closure.gap_columns", "1"]),
    "z02_g15": (0.04, ["--vf.zeta1", "0.02", "--vf.zeta2", "0.02",
                       "--glottis.rest_gap", "0.15e-3", "--closure.gap_columns", "1"]),
    "z02_p16": (0.04, ["--vf.zeta1", "0.02", "--vf.zeta2", "0.02", "--p-sub", "1600",
                       "--closure.gap_columns", "1"]),
    # at the time step this mesh needs (Δt = 1e−5: the jet's CFL ≈ 12)
    "dt1_z02": (0.06, CLOSING + ["--closure.gap_columns", "1"]),
    # the same with the size-stiffened mesh motion (dt1_z02 inverted a cell
    # at the fold's superior edge)
    "dt1_z02_size": (0.06, CLOSING + ["--ale.stiffening", "size", "--closure.gap_columns", "1"]),
    # with the algebraic gap columns up to g0 + 0.75 R (the new default;
    # the two runs above used g0 + R)
    "dt1_z02_c75": (0.1, CLOSING + ["--checkpoint-every", "2000"]),
    # the same configuration again with the faster solvers (OpenBLAS,
    # MUMPS without scaling, superposed mesh motion, wall forces from the
    # wall cells): its wall time, and the run-to-run scatter of 2-rank runs
    "dt1_z02_c75_s26": (0.1, CLOSING),
    # its time-step check (Δt/2, the first 0.06 s)
    "dt05_z02_c75": (0.06, ["--dt", "5e-6", "--vf.zeta1", "0.02", "--vf.zeta2", "0.02"]),
    # its mesh check: h_gap 0.025 mm, h_far 0.25 mm (the later
    # options override MESH), the first 0.06 s; continued to 0.1 s in stop
    # 26 from its step-6000 checkpoint (--restart, log run_restart.log)
    "h025_dt1_z02_c75": (0.1, CLOSING + ["--fe.h_gap", "0.025e-3", "--fe.h_far", "0.25e-3",
                                         "--checkpoint-every", "2000"]),
    # SUPG/PSPG τ without its transient term (2/Δt)² (Hsu et al.
    # 2010; it halved the held glottis's Δt dependence): the first 0.06 s.
    # It failed: coupling stalls near closure, a cell inverted at 26 ms
    "dt1_z02_c75_taus": (0.06, CLOSING + ["--fluid.tau_dt=false", "--checkpoint-every", "2000"]),
    # the cell integrals at quadrature degree 2 (3 points per
    # triangle instead of 6; the Galerkin terms still exact)
    "dt1_z02_c75_q2": (0.1, CLOSING + ["--fluid.quadrature_degree", "2"]),
    # which half of the mesh check moves the peak flow? Each
    # refines one of the two sizes that h025_dt1_z02_c75 refined together
    # (the first 0.06 s, compared in t ∈ [0.03, 0.06] s)
    "hgap025_dt1_z02_c75": (0.06, CLOSING + ["--fe.h_gap", "0.025e-3"]),
    "hfar025_dt1_z02_c75": (0.06, CLOSING + ["--fe.h_far", "0.25e-3"]),
    # the subglottal channel at 0.7 mm from the inlet to 6 mm
    # before the fold (--fe.h_inlet; 28764 instead of 31491 unknowns)
    "dt1_z02_c75_in07": (0.06, CLOSING + ["--fe.h_inlet", "0.7e-3"]),
    # the cheapest variant, both: the subglottal channel at
    # 0.7 mm and the cell integrals at degree 2 (0.1 s)
    "dt1_z02_c75_in07_q2": (0.1, CLOSING + ["--fe.h_inlet", "0.7e-3",
                                            "--fluid.quadrature_degree", "2"]),
    # the jet region (y ≤ 4 mm downstream of the fold's inferior
    # attachment) at 0.25 mm, h_far 0.35 mm elsewhere: is the far field's
    # sensitivity (hfar025 above) the jet's?
    "dt1_z02_c75_jet025": (0.06, CLOSING + ["--fe.h_jet", "0.25e-3"]),
    # mesh and step refined together at the reference's CFL
    # (h_gap 0.025 / h_far 0.25 mm as h025_dt1_z02_c75, Δt 0.7e-5 = 0.7 ×
    # 1e-5 for the sizes' ratio 0.714): refining h alone (h025, −2.6 %) and
    # Δt alone (dt05, +2.5 %) moved the peak flow in opposite directions
    "h025_dt07_z02_c75": (0.06, CLOSING + ["--fe.h_gap", "0.025e-3", "--fe.h_far", "0.25e-3",
                                          "--dt", "0.7e-5", "--checkpoint-every", "2000"]),
    # the third level of that series, h_gap 0.0175 / h_far 0.175 mm
    # (× 0.7 again; 120735 unknowns) at Δt 0.7e-5: the CFL of h025_dt1
    # (≈ 16 at 40 m/s), whose cycle h025_dt07 matched within 0.1 %. Is the
    # 0.025 mm mesh converged where the 0.035 mm one missed by 0.5 point?
    "h0175_dt07_z02_c75": (0.1, CLOSING + ["--fe.h_gap", "0.0175e-3", "--fe.h_far", "0.175e-3",
                                           "--dt", "0.7e-5", "--checkpoint-every", "1000"]),
    # the reference cycle continued to 0.2 s (the same run as
    # dt1_z02_c75, longer): the per-cycle peak flow of every mesh level
    # still swings by ±5 % in [0.05, 0.1] s with the same pattern on all
    # of them, a start-up transient that has not died out (ζ = 0.02)
    "dt1_z02_c75_02s": (0.2, CLOSING + ["--checkpoint-every", "2000"]),
    # h025_dt07_z02_c75 continued from its step-14000 checkpoint
    # (t = 0.098 s) towards 0.2 s, in a copy of its folder (--restart, log
    # run_restart_02s.log), for the settled window
    "h025_dt07_z02_c75_02s": (0.2, CLOSING + ["--fe.h_gap", "0.025e-3", "--fe.h_far", "0.25e-3",
                                             "--dt", "0.7e-5", "--checkpoint-every", "2000"]),
    # the reference's time-step check (Δt/2) to 0.2 s, for the
    # late window [0.13, 0.2] s (dt05_z02_c75 above ran the first 0.06 s)
    "dt05_z02_c75_02s": (0.2, ["--dt", "5e-6", "--vf.zeta1", "0.02", "--vf.zeta2", "0.02",
                               "--checkpoint-every", "4000"]),
    # h0175_dt07_z02_c75 continued from its step-14000
    # checkpoint (t = 0.098 s) to 0.2 s in a copy of its folder (--restart,
    # stopped and continued twice: logs run_restart_02s*.log), for the late
    # window of all three levels
    "h0175_dt07_z02_c75_02s": (0.2, CLOSING + ["--fe.h_gap", "0.0175e-3", "--fe.h_far", "0.175e-3",
                                               "--dt", "0.7e-5", "--checkpoint-every", "1000"]),
    # the finest level to 0.2 s again, from rest (the checkpoint
    # of h0175_dt07_z02_c75_02s was lost with the machine at 0.155 s), now
    # at Δt 0.5e-5: the jet's CFL √(2 p_sub/ρ) Δt / h_gap of the other two
    # levels (12.8 and 12.5; Δt 0.7e-5 gave this mesh 17.9, near the ≈ 20
    # where the held glottis's jet flaps). Does the finest level's
    # cycle-to-cycle variation (6 %, the others' < 3 %) come from that?
    # Longer than a session: its checkpoint files are committed (git add
    # -f; checkpoint* is ignored) and it goes on with --restart
    "h0175_dt05_z02_c75_02s": (0.2, CLOSING + ["--fe.h_gap", "0.0175e-3", "--fe.h_far", "0.175e-3",
                                               "--dt", "0.5e-5", "--checkpoint-every", "2000"]),
    # the reference continued from 0.2 to 0.5 s (a copy of
    # dt1_z02_c75_02s's folder, --restart, log run_restart_05s.log): does
    # the cycle reach a limit cycle? (bench/glottis_limit_cycle.py)
    "dt1_z02_c75_05s": (0.5, CLOSING + ["--checkpoint-every", "5000"]),
}
FOLDER = {"default": "run_glottis_conv_fine_01_load",
          "h025_dt1_z02_c75": "run_glottis_h025_dt1_z02_c75",
          "h025_dt07_z02_c75": "run_glottis_h025_dt07_z02_c75",
          "h0175_dt07_z02_c75": "run_glottis_h0175_dt07_z02_c75",
          "h025_dt07_z02_c75_02s": "run_glottis_h025_dt07_z02_c75_02s",
          "h0175_dt07_z02_c75_02s": "run_glottis_h0175_dt07_z02_c75_02s",
          "h0175_dt05_z02_c75_02s": "run_glottis_h0175_dt05_z02_c75_02s"}


def folder(case):
    return os.path.join(res, FOLDER.get(case, f"run_glottis_h035_{case}"))


for case in (args.run.split(",") if args.run else []):
    duration, opts = CASES[case]
    out = folder(case)
    cmd = (["mpirun", "-n", "2", exe, "--flow", "fe", "--duration", str(duration),
            "--write_every", "0"] + MESH + opts + ["--output", out])
    print(" ".join(cmd), flush=True)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "run.log"), "w") as f:
        subprocess.run(cmd, env=env, stdout=f, stderr=subprocess.STDOUT)

rows = []
print("| case | options | windows of 5 ms: min / max half-gap [mm] | contact after "
      f"{1e3 * args.t_settle:g} ms | f0 | end |")
print("|---|---|---|---|---|---|")
for case, (duration, opts) in CASES.items():
    out = folder(case)
    if not os.path.exists(os.path.join(out, "series.csv")):
        continue
    r = read_float_rows(os.path.join(out, "series.csv"))
    wins, t0 = [], 0.0
    # (not a window of a step or two: a run of Δt 0.7e-5 ends at 0.100002 s)
    while t0 < r[-1]["t_s"] - 1e-4:
        s = [x["gap_m"] for x in r if t0 < x["t_s"] <= t0 + 0.005 + 1e-12]
        wins.append((t0, min(s), max(s)))
        t0 += 0.005
    late = [w for w in wins if w[0] >= args.t_settle - 1e-12]
    contact = [w[1] <= 0 for w in late]
    end, f0 = "completed", ""
    if os.path.exists(os.path.join(out, "summary.json")):
        with open(os.path.join(out, "summary.json")) as f:
            f0 = f"{json.load(f)['f0_hz']:.1f} Hz"
    log = os.path.join(out, "run.log")
    if os.path.exists(log):
        with open(log, errors="replace") as f:
            err = [x.strip() for x in f if "error:" in x]
        if err:
            end = err[0].split("error:", 1)[1].split("[")[0].strip()
    if end == "completed" and r[-1]["t_s"] < duration - 1e-4:
        # stopped without an error (h0175_dt07_z02_c75_02s: its checkpoint
        # was lost at 0.155 s); its summary.json is the run it continued
        end, f0 = f"stopped at t = {r[-1]['t_s']:.4f} s", ""
    verdict = ("every window" if contact and all(contact) else
               "none" if not any(contact) else f"{sum(contact)} of {len(contact)} windows")
    print(f"| {case} | {' '.join(opts) or '(defaults: 1200 Pa, g0 0.2 mm, zeta 0.05)'} | "
          + " ".join(f"{1e3 * a:+.3f}/{1e3 * b:.3f}" for _, a, b in wins)
          + f" | {verdict} | {f0} | {end} |")
    rows.append({"case": case, "options": " ".join(opts), "duration_s": r[-1]["t_s"],
                 "late_min_gap_mm": 1e3 * min(w[1] for w in late) if late else "",
                 "late_max_gap_mm": 1e3 * max(w[2] for w in late) if late else "",
                 "contact_windows_after_settle": sum(contact), "windows_after_settle": len(contact),
                 "end": end})
write_rows(os.path.join(res, "glottis_closure_converged.csv"), rows)
