#!/usr/bin/python3
"""Why the body-cover fold's closed phases take many coupling iterations.

In the FE flow the body-cover fold (--elastic.layers 2, cover 2 kPa on an
8 kPa body) on the elastic preset (demos/glottis/elastic_fe.toml) takes
about three times the homogeneous fold's coupling iterations per step in its
closed phases, and its contact depth changes from step to step nine times
as much. This script asks whether the fold side makes it: the fold's
numerical dissipation (generalised-alpha rho_inf 0.5 and 0, the preset
0.8) and the contact penalty (--elastic.contact_factor 2.5, which puts
k_c at 10 E/h of the cover instead of the body), and whether the flow's
closure does: the porous ramp twice as wide (40 um, the preset 20 um:
the flow's load changes less steeply as the surface nears the axis), or
the coupling: IQN-ILS without the columns of earlier steps
(--coupling.reuse 0, the preset 8).
Each case runs 800 Pa from rest on 2 ranks, the cover for 0.03 s (its
first three closed phases, about 10 min each), the homogeneous fold for
0.045 s (it closes later):

  mpirun -n 2 fsai_glottis --config demos/glottis/elastic_fe.toml --p-sub 800
      --duration D [--elastic.layers 2] [case options] --output DIR

Per case, over the steps whose fold touches the axis (closed) and the
others (open): coupling iterations per step, the mean step-to-step change
of the contact depth (penetration) and its maximum, unconverged steps
(accepted at the last step cut, logged), and the run's wall time.

--long adds 0.2 s of the cover and of the homogeneous fold, both with the
wider ramp (about 80 and 45 min), and the cover's first 0.1 s (35 min) as
a repeat of its start-up, and compares their cycles from 50 to 100 ms and
from 100 to 200 ms (f0, peak and mean flow, open quotient,
closings, the closed phases' leakage, the flow's subharmonic ratio) with
the homogeneous fold's preset run over the same windows
(bench/glottis_pod.py --fe: its folder pod_fe_preset800).

usage: bench/glottis_cover_closure.py [BUILD_DIR] [--rerun] [--long] [--cached]
  --cached: the tables from the runs already in bench/results
writes bench/results/glottis_cover_closure.csv (and with --long
glottis_cover_closure_cycles.csv)
"""
import argparse
import os

import numpy as np

from benchlib import (MPI_ENV, glottal_cycles, pair_sem, print_markdown_table, read_float_rows,
                      results_dir, subharmonic_ratio, timed_run, write_rows)

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--rerun", action="store_true")
ap.add_argument("--long", action="store_true")
ap.add_argument("--cached", action="store_true")
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_glottis")
out = results_dir()

BC = ["--elastic.layers", "2"]
# (label, duration, extra options); the homogeneous fold closes later
cases = [("homogeneous", 0.045, []),
         ("cover", 0.03, BC),
         ("cover_rho_inf0.5", 0.03, BC + ["--elastic.rho_inf", "0.5"]),
         ("cover_rho_inf0", 0.03, BC + ["--elastic.rho_inf", "0"]),
         ("cover_contact2.5", 0.03, BC + ["--elastic.contact_factor", "2.5"]),
         ("cover_ramp4e-5", 0.03, BC + ["--closure.porous_ramp", "4e-5"]),
         ("cover_reuse0", 0.03, BC + ["--coupling.reuse", "0"])]
# --long: 0.2 s of the cover and of the homogeneous fold with the wider
# ramp, and the cover's first 0.1 s again (a repeat of the same command up
# to 0.1 s: how far its start-up cycles are reproducible)
RAMP = ["--closure.porous_ramp", "4e-5"]
LONG = [("cover_ramp4e-5_0.2s", 0.2, BC + RAMP), ("homogeneous_ramp4e-5_0.2s", 0.2, RAMP),
        ("cover_ramp4e-5_0.1s", 0.1, BC + RAMP)]
if args.long:
    cases += LONG


def folder(label):
    return os.path.join(out, f"cover_closure_{label}")


def analyse(label):
    d = folder(label)
    series = read_float_rows(os.path.join(d, "series.csv"))
    coupling = read_float_rows(os.path.join(d, "coupling.csv"))
    # One row per step in both (a cut step is one row: its parts' iterations)
    n = min(len(series), len(coupling))
    closed = [series[i]["closed"] == 1 for i in range(n)]
    depth = [series[i]["penetration_m"] for i in range(n)]
    its = [coupling[i]["iterations"] for i in range(n)]
    with open(os.path.join(d, "process_wall_s")) as f:
        wall_s = float(f.read())
    steps_closed = [i for i in range(n) if closed[i]]
    steps_open = [i for i in range(n) if not closed[i]]
    jumps = [abs(depth[i + 1] - depth[i]) for i in range(n - 1) if closed[i] and closed[i + 1]]
    return {"case": label,
            "steps": n,
            "closed_steps": len(steps_closed),
            "iterations_closed": sum(its[i] for i in steps_closed) / len(steps_closed),
            "iterations_open": sum(its[i] for i in steps_open) / len(steps_open),
            "depth_change_um": 1e6 * sum(jumps) / len(jumps),
            "depth_max_um": 1e6 * max(depth),
            "unconverged": sum(1 for r in coupling[:n] if r["converged"] != 1),
            "wall_s": wall_s}


def cycles(label, d, a, b):
    """The cycles starting in [a, b) s of the run in folder d, the closed
    phases' leakage over them (the summary's definition: the largest |Q|
    while the fold touches the axis, over the largest Q) and the glottal
    flow's subharmonic ratio (docs/model.md A10) over them"""
    path = os.path.join(d, "series.csv")
    cyc = [c for c in glottal_cycles(path, None, a) if c["t0_s"] < b]
    r = read_float_rows(path)
    t, q, g = (np.array([x[k] for x in r]) for k in ("t_s", "Q_m3s", "gap_m"))
    end = cyc[-1]["t0_s"] + 1 / cyc[-1]["f0_hz"]
    window = (t >= cyc[0]["t0_s"]) & (t < end)
    touching = window & (g <= 0)

    def mean(k):
        return float(np.mean([c[k] for c in cyc]))
    return {"case": label, "window_ms": f"{1e3 * a:.0f}-{1e3 * b:.0f}", "cycles": len(cyc),
            "f0_hz": mean("f0_hz"), "q_peak_ls": mean("q_peak_ls"),
            "q_peak_sem_ls": pair_sem([c["q_peak_ls"] for c in cyc]), "q_mean_ls": mean("q_mean_ls"),
            "open_quotient": mean("open_quotient"),
            "closings": sum(c["closings"] for c in cyc),
            "closed_leakage": float(np.abs(q[touching]).max() / q[window].max()),
            "shr_flow": subharmonic_ratio(t, q, [c["t0_s"] for c in cyc] + [end])}


rows = []
for label, duration, extra in cases:
    if not args.cached:
        timed_run(["mpirun", "-n", "2", exe, "--config", os.path.join(here, "..", "demos", "glottis", "elastic_fe.toml"),
                   "--p-sub", "800", "--duration", str(duration), "--output", folder(label)] + extra,
                  folder(label), rerun=args.rerun, env=MPI_ENV)
    if os.path.exists(os.path.join(folder(label), "process_wall_s")):  # finished
        rows.append(analyse(label))
write_rows(os.path.join(out, "glottis_cover_closure.csv"), rows)
print_markdown_table([("case", lambda r: r["case"]),
                      ("closed steps", lambda r: f"{r['closed_steps']} of {r['steps']}"),
                      ("iterations per step closed / open",
                       lambda r: f"{r['iterations_closed']:.2f} / {r['iterations_open']:.2f}"),
                      ("contact depth change per step", lambda r: f"{r['depth_change_um']:.2f} µm"),
                      ("max depth", lambda r: f"{r['depth_max_um']:.1f} µm"),
                      ("unconverged", lambda r: str(r["unconverged"])),
                      ("wall", lambda r: f"{r['wall_s']:.0f} s")], rows)
if args.long and all(os.path.exists(os.path.join(folder(c[0]), "process_wall_s")) for c in LONG):
    # the homogeneous fold's preset run (porous ramp 20 um) beside the two
    # runs with the 40 um ramp, over the start-up and the later cycles
    runs = [("homogeneous, ramp 20 um (preset)", os.path.join(out, "pod_fe_preset800")),
            ("homogeneous, ramp 40 um", folder(LONG[1][0])),
            ("body-cover, ramp 40 um", folder(LONG[0][0]))]
    # the start-up window also from the cover's run to 0.1 s (the repeat)
    windows = {(0.05, 0.1): runs + [("body-cover, ramp 40 um (run to 0.1 s)", folder(LONG[2][0]))],
               (0.1, 0.2): runs}
    rows = [cycles(label, d, a, b) for (a, b), in_window in windows.items() for label, d in in_window]
    write_rows(os.path.join(out, "glottis_cover_closure_cycles.csv"), rows)
    print_markdown_table([("case", lambda r: r["case"]),
                          ("cycles from", lambda r: f"{r['cycles']} in {r['window_ms']} ms"),
                          ("f0", lambda r: f"{r['f0_hz']:.2f} Hz"),
                          ("mean cycle peak (standard error) / mean flow",
                           lambda r: f"{r['q_peak_ls']:.3f} ({100 * r['q_peak_sem_ls'] / r['q_peak_ls']:.1f} %)"
                           f" / {r['q_mean_ls']:.3f} l/s"),
                          ("OQ", lambda r: f"{r['open_quotient']:.3f}"),
                          ("closings", lambda r: str(r["closings"])),
                          ("leakage", lambda r: f"{100 * r['closed_leakage']:.2f} %"),
                          ("SHR flow", lambda r: f"{r['shr_flow']:.3f}")], rows)
