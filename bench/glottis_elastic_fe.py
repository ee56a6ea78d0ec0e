#!/usr/bin/python3
"""The elastic fold in the FE flow through closure: the preset
demos/glottis/elastic_fe.toml (clamped ends, porous ramp, Newmark γ 0.6,
remeshing, IQN-ILS) for 0.2 s from rest at p_sub 400, 800 and 1200 Pa;
with --check, the 800 Pa run again on the finer mesh (h_gap 0.035 mm) and
at Δt 1e-5.

Runs on 2 ranks, one at a time (each 25-60 min); a run whose summary.json
exists is not repeated. Writes bench/results/glottis_elastic_fe.csv and
prints a Markdown table.

usage: bench/glottis_elastic_fe.py [--check] [BUILD_DIR]
"""
import os
import sys

from benchlib import MPI_ENV, print_markdown_table, results_dir, timed_run, write_rows

args = [a for a in sys.argv[1:] if not a.startswith("--")]
here = os.path.dirname(os.path.abspath(__file__))
build = args[0] if args else os.path.join(here, "..", "build")
exe = os.path.join(build, "demos", "fsai_glottis")
out = results_dir()
common = ["--config", os.path.join(here, "..", "demos", "glottis", "elastic_fe.toml"),
          "--duration", "0.2"]
cases = [(f"p{p}", ["--p-sub", str(p)]) for p in (800, 1200, 400)]
if "--check" in sys.argv:
    cases += [("p800_h0.035", ["--p-sub", "800", "--fe.h_gap", "0.035e-3"]),
              ("p800_dt1e-5", ["--p-sub", "800", "--dt", "1e-5"])]

rows = []
for label, extra in cases:
    folder = os.path.join(out, f"run_glottis_elastic_fe_{label}")
    s = timed_run(["mpirun", "-n", "2", exe] + common + extra + ["--output", folder],
                  folder, env=MPI_ENV)
    if s is None:
        continue
    rows.append({"case": label, "p_sub_Pa": s["parameters"]["p-sub"],
                 "f0_hz": s["f0_hz"], "open_quotient": s["open_quotient"],
                 "q_peak_m3s": s["q_peak_m3s"],
                 "closes_every_cycle": int(s["closes_every_cycle"]),
                 "closed_leakage": s["closed_leakage"],
                 "max_penetration_m": s["max_penetration_m"],
                 "mesh_quality_min": s["mesh_quality_min"],
                 "remeshes": s["remeshes"],
                 "coupling_iterations_mean": s["coupling_iterations_mean"],
                 "coupling_unconverged_steps": s["coupling_unconverged_steps"],
                 "flow_dofs": s["flow_dofs"], "wall_s": s["process_wall_s"]})
write_rows(os.path.join(out, "glottis_elastic_fe.csv"), rows)
print_markdown_table([
    ("case", lambda r: r["case"]),
    ("f0 [Hz]", lambda r: f"{r['f0_hz']:.2f}"),
    ("OQ", lambda r: f"{r['open_quotient']:.3f}"),
    ("Q_peak [l/s]", lambda r: f"{1e3 * r['q_peak_m3s']:.3f}"),
    ("closes", lambda r: "every cycle" if r["closes_every_cycle"] else "no"),
    ("leakage", lambda r: f"{100 * r['closed_leakage']:.2f} %"),
    ("max δ [µm]", lambda r: f"{1e6 * r['max_penetration_m']:.1f}"),
    ("min quality", lambda r: f"{r['mesh_quality_min']:.3f}"),
    ("remeshes", lambda r: f"{r['remeshes']}"),
    ("its/step", lambda r: f"{r['coupling_iterations_mean']:.2f}"),
    ("unconverged", lambda r: f"{r['coupling_unconverged_steps']}"),
    ("wall [s]", lambda r: f"{r['wall_s']:.0f}")], rows)
