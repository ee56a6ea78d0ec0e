#!/usr/bin/python3
"""What a coupling iteration of the elastic fold in the FE flow costs, and
what makes it cheaper: the preset demos/glottis/elastic_fe.toml at 800 Pa
for 30 ms from rest (the first closure at 10 ms and two cycles after it),
2 ranks, one run at a time, in interleaved rounds. Two studies:

--study refine (the default; the settings it was run with pinned:
quadrature degree 4, at most 3 refinements):
- "factorise": every flow solve factorises its operator (MUMPS), as before
  --fluid.refine_rtol;
- "refine": a step's second and later coupling iterates refine the
  factorisation of its first (iterative refinement to 1e-14 |b|,
  docs/model.md E20a) instead of factorising anew;
- "tol 1e-5": factorising, with the coupling tolerance 1e-5 instead of
  1e-6: does a looser coupling save iterations?

--study speed (the preset as it is: quadrature degree 4, at most 6
refinements):
- "preset";
- "degree 2": the flow's cell integrals at quadrature degree 2 (the
  voice's);
- "3 refinements": at most 3 refinements before a fresh factorisation
  (the former cap).

Each run against the round's first run: the largest difference of the
glottal flow Q(t) and of the half-gap over the run (from 5 ms on),
relative to their largest values; coupling iterations per step, the
median first residual, the flow's refined solves and fallbacks, the time
loop and its parts. Writes bench/results/glottis_elastic_<study>.csv and
prints a Markdown table.

usage: bench/glottis_elastic_refine.py [--study refine|speed] [--rounds N]
       [--cached] [BUILD_DIR]
(--cached: the table from the runs already in bench/results)
"""
import os
import sys

import numpy as np

from benchlib import MPI_ENV, print_markdown_table, read_float_rows, results_dir, timed_run, write_rows

study = sys.argv[sys.argv.index("--study") + 1] if "--study" in sys.argv else "refine"
if study not in ("refine", "speed"):
    sys.exit(f"--study: refine or speed, not {study}")
args = [a for a in sys.argv[1:]
        if not a.startswith("--") and not a.isdigit() and a not in ("refine", "speed")]
here = os.path.dirname(os.path.abspath(__file__))
build = args[0] if args else os.path.join(here, "..", "build")
exe = os.path.join(build, "demos", "fsai_glottis")
out = results_dir()
rounds = int(sys.argv[sys.argv.index("--rounds") + 1]) if "--rounds" in sys.argv else 2
common = ["--config", os.path.join(here, "..", "demos", "glottis", "elastic_fe.toml"),
          "--p-sub", "800", "--duration", "0.03"]
if study == "refine":
    common += ["--fluid.quadrature_degree", "4", "--fluid.refine_max_its", "3"]
    variants = [("factorise", ["--fluid.refine_rtol", "0"]),
                ("refine", []),
                ("tol 1e-5", ["--fluid.refine_rtol", "0", "--coupling.tol", "1e-5"])]
else:
    variants = [("preset", []),
                ("degree 2", ["--fluid.quadrature_degree", "2"]),
                ("3 refinements", ["--fluid.refine_max_its", "3"])]


def series(folder):
    r = read_float_rows(os.path.join(folder, "series.csv"))
    return {k: np.array([x[k] for x in r]) for k in ("t_s", "Q_m3s", "gap_m")}


rows = []
for k in range(1, rounds + 1):
    ref = None
    # the refine study's tolerance variant once: it answers its question in
    # one round
    for name, opts in variants if k == 1 or study == "speed" else variants[:2]:
        folder = os.path.join(out, f"run_glottis_elastic_{study}_{name.replace(' ', '')}_{k}")
        if "--cached" in sys.argv and not os.path.exists(os.path.join(folder, "summary.json")):
            continue
        s = timed_run(["mpirun", "-n", "2", exe] + common + opts + ["--output", folder], folder,
                      env=MPI_ENV)
        if s is None:
            continue
        c = read_float_rows(os.path.join(folder, "coupling.csv"))
        x = series(folder)
        ref = ref or x
        n = min(len(x["t_s"]), len(ref["t_s"]))
        w = ref["t_s"][:n] >= 0.005
        timing = {t: s["timings"].get(t, {"wall_s": 0})["wall_s"]
                  for t in ("glottis: time loop", "fluid: assemble", "fluid: solve",
                            "fluid: refine", "ale: move", "solid: step")}
        loop = timing["glottis: time loop"]
        rows.append({"round": k, "variant": name,
                     "iterations_per_step": s["coupling_iterations_mean"],
                     "first_residual_median": float(np.median([r["first_residual"] for r in c[1:]])),
                     "refined_solves": s.get("flow_refined_solves", 0),
                     "refine_fallbacks": s.get("flow_refine_fallbacks", 0),
                     "unconverged": s["coupling_unconverged_steps"],
                     "dq_max_rel": float(np.max(np.abs(x["Q_m3s"][:n] - ref["Q_m3s"][:n])[w])
                                         / np.max(np.abs(ref["Q_m3s"][:n]))),
                     "dgap_max_rel": float(np.max(np.abs(x["gap_m"][:n] - ref["gap_m"][:n])[w])
                                           / np.max(np.abs(ref["gap_m"][:n]))),
                     "time_loop_s": loop,
                     "ms_per_step": 1e3 * loop / len(c),
                     "share_solve": timing["fluid: solve"] / loop,
                     "share_assemble": timing["fluid: assemble"] / loop,
                     "share_ale": timing["ale: move"] / loop,
                     "share_fold": timing["solid: step"] / loop,
                     "wall_s": s["process_wall_s"]})
if not rows:
    sys.exit("no run finished")
# each run against the same round's first run
by = {(r["round"], r["variant"]): r for r in rows}
for r in rows:
    f = by.get((r["round"], variants[0][0]))
    r["speedup"] = f["time_loop_s"] / r["time_loop_s"] if f else float("nan")
write_rows(os.path.join(out, f"glottis_elastic_{study}.csv"), rows)
print_markdown_table([
    ("round", lambda r: f"{r['round']}"),
    ("variant", lambda r: r["variant"]),
    ("its/step", lambda r: f"{r['iterations_per_step']:.2f}"),
    ("first residual (median)", lambda r: f"{r['first_residual_median']:.1e}"),
    ("refined / fallbacks", lambda r: f"{r['refined_solves']} / {r['refine_fallbacks']}"),
    ("max ΔQ / Q_max", lambda r: f"{r['dq_max_rel']:.1e}"),
    ("max Δgap / gap_max", lambda r: f"{r['dgap_max_rel']:.1e}"),
    ("ms/step", lambda r: f"{r['ms_per_step']:.1f}"),
    ("solve / assembly / ALE / fold", lambda r: f"{100 * r['share_solve']:.0f} / "
     f"{100 * r['share_assemble']:.0f} / {100 * r['share_ale']:.0f} / {100 * r['share_fold']:.0f} %"),
    ("time loop [s]", lambda r: f"{r['time_loop_s']:.0f}"),
    (f"vs {variants[0][0]}", lambda r: f"{r['speedup']:.2f}x")], rows)
