#!/usr/bin/python3
"""The 3D fold in 3D flow (fsai_fold3d, docs/fold3d.md): what a step costs
and what the fold does in the first milliseconds from rest.

Each case is fsai_fold3d with a few options on 2 ranks:

  mpirun -n 2 fsai_fold3d --p-sub P --duration D --write_every 0 [options]
      --output DIR

Per case: flow and fold unknowns, coupling iterations per step, Krylov
iterations per flow solve, the per-step cost split (flow solve, flow
assembly, fold step, mesh motion: summary.json's timers), wall time per
simulated ms, and from series.csv the medial displacement's swing and the
smallest half-gap.

usage: bench/fold3d.py [BUILD_DIR] [--cases ...] [--rerun]
writes bench/results/fold3d.csv
"""
import argparse
import os

import numpy as np

from benchlib import MPI_ENV, print_markdown_table, read_float_rows, results_dir, timed_run, write_rows

here = os.path.dirname(os.path.abspath(__file__))
# case: (options, duration [s])
ITERATIVE = ["--fluid.solver", "iterative"]
DIRECT = ["--fluid.solver", "direct"]
FINE = ["--channel.h_gap", "0.2e-3", "--channel.h_far", "1e-3"]
CASES = {
    # the scene's defaults (MUMPS) at 800 Pa: the start-up, 20 ms
    "p800": (["--p-sub", "800"], 0.02),
    # MUMPS against the iterative path (PCD) on two flow meshes
    "p800_direct": (["--p-sub", "800", *DIRECT], 0.004),
    "p800_iterative": (["--p-sub", "800", *ITERATIVE], 0.004),
    "p800_fine": (["--p-sub", "800", *FINE, *ITERATIVE], 0.002),
    "p800_fine_direct": (["--p-sub", "800", *FINE, *DIRECT], 0.002),
}


def timer(s, name):
    t = s.get("timings", {}).get(name)
    return t["wall_s"] if t else 0.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
    ap.add_argument("--cases", nargs="*", default=list(CASES))
    ap.add_argument("--rerun", action="store_true")
    a = ap.parse_args()
    demo = os.path.join(a.build, "demos", "fsai_fold3d")
    out = results_dir()
    rows = []
    for name in a.cases:
        options, duration = CASES[name]
        folder = os.path.join(out, "fold3d", name)
        cmd = ["mpirun", "-n", "2", demo, "--duration", str(duration), "--write_every", "0", *options, "--output", folder]
        s = timed_run(cmd, folder, a.rerun, env=MPI_ENV)
        if s is None:
            continue
        series = read_float_rows(os.path.join(folder, "series.csv"))
        ux = np.array([r["ux_medial_m"] for r in series])
        steps = len(series)
        loop = timer(s, "fold3d: time loop")
        rows.append({
            "case": name,
            "duration_s": duration,
            "flow_dofs": s["flow_dofs"],
            "solid_dofs": s["solid_dofs"],
            "coupling_its_per_step": round(s["coupling_iterations_mean"], 2),
            "krylov_its_per_solve": round(s["krylov_iterations_mean"], 1),
            "s_per_step": round(loop / steps, 3),
            "flow_solve_share": round(timer(s, "fluid: solve") / loop, 3),
            "flow_assembly_share": round(timer(s, "fluid: assemble") / loop, 3),
            "fold_share": round(timer(s, "solid: step") / loop, 3),
            "mesh_motion_share": round(timer(s, "ale: move") / loop, 3),
            "wall_per_sim_ms_s": round(s["wall_per_sim_s"] / 1000, 1),
            "ux_medial_swing_m": float(ux.max() - ux.min()),
            "gap_min_m": s["gap_min_m"],
            "q_mean_m3s": s["q_mean_m3s"],
            "f0_hz": s["f0_hz"],
            "unconverged_steps": s["coupling_unconverged_steps"],
        })
    if rows:
        write_rows(os.path.join(out, "fold3d.csv"), rows)
        print_markdown_table([(k, lambda r, k=k: str(r[k])) for k in rows[0]], rows)


if __name__ == "__main__":
    main()
