#!/usr/bin/python3
"""The 3D fold in 3D flow (fsai_fold3d, docs/fold3d.md): what a step costs
and what the fold does in the first milliseconds from rest.

Each case is fsai_fold3d with a few options on 2 ranks:

  mpirun -n 2 fsai_fold3d --p-sub P --duration D --write_every 0 [options]
      --output DIR

The scaling cases run the same 2 ms on 1 and on 2 ranks, interleaved
(1, 2, 1, 2), for the speed-up and each rank's peak memory; fine_memory
the peak memory on the finer flow mesh.

Per case: flow and fold unknowns, coupling iterations per step, Krylov
iterations per flow solve, the per-step cost split (flow solve, flow
assembly, fold step, mesh motion: summary.json's timers), wall time per
simulated ms, and from series.csv the medial displacement's swing and the
smallest half-gap.

usage: bench/fold3d.py [BUILD_DIR] [--cases ...] [--rerun]
writes bench/results/fold3d.csv
"""
import argparse
import math
import os

import numpy as np

from benchlib import MPI_ENV, print_markdown_table, read_float_rows, results_dir, timed_run, write_rows

here = os.path.dirname(os.path.abspath(__file__))
# case: (options, duration [s][, ranks (default 2)])
ITERATIVE = ["--fluid.solver", "iterative"]
DIRECT = ["--fluid.solver", "direct"]
FINE = ["--channel.h_gap", "0.2e-3", "--channel.h_far", "1e-3"]
NO_MODES = ["--modes", "0"]
CASES = {
    # the scene's defaults (MUMPS) at 800 Pa: the start-up, 20 ms
    "p800": (["--p-sub", "800"], 0.02),
    # MUMPS against the iterative path (PCD) on two flow meshes
    "p800_direct": (["--p-sub", "800", *DIRECT], 0.004),
    "p800_iterative": (["--p-sub", "800", *ITERATIVE], 0.004),
    "p800_fine": (["--p-sub", "800", *FINE, *ITERATIVE], 0.002),
    "p800_fine_direct": (["--p-sub", "800", *FINE, *DIRECT], 0.002),
    # strong scaling: the defaults (without the modal projection) on 1 and
    # 2 ranks, interleaved
    "ranks1_a": (["--p-sub", "800", *NO_MODES], 0.002, 1),
    "ranks2_a": (["--p-sub", "800", *NO_MODES], 0.002, 2),
    "ranks1_b": (["--p-sub", "800", *NO_MODES], 0.002, 1),
    "ranks2_b": (["--p-sub", "800", *NO_MODES], 0.002, 2),
    # memory on the finer flow mesh: two steps (the peak is the first
    # factorisations)
    "fine_memory": (["--p-sub", "800", *FINE, *NO_MODES], 1e-4),
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
        options, duration, ranks = (*CASES[name], 2)[:3]
        folder = os.path.join(out, "fold3d", name)
        cmd = ["mpirun", "-n", str(ranks), demo, "--duration", str(duration), "--write_every", "0", *options, "--output", folder]
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
            "ranks": ranks,
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
            "peak_mib_per_rank": round(max(s.get("peak_memory_mib_per_rank", [0.0])), 0),
        })
    if rows:
        write_rows(os.path.join(out, "fold3d.csv"), rows)
        print_markdown_table([(k, lambda r, k=k: str(r[k])) for k in rows[0]], rows)
        cost_model({r["case"]: r for r in rows}, out)


def power_law(n, y):
    """(c, a) of y = c n^a through two points"""
    a = math.log(y[1] / y[0]) / math.log(n[1] / n[0])
    return y[0] / n[0] ** a, a


def cost_model(rows, out):
    """Per-step cost as power laws of the unknowns, fitted to the two mesh
    levels (2 ranks), and the 1 -> 2 rank speed-up: the wall time of a
    cycle on finer meshes. Needs the cases p800_direct, p800_fine_direct,
    p800_iterative, p800_fine and ranks1_a/b, ranks2_a/b."""
    need = ["p800_direct", "p800_fine_direct", "p800_iterative", "p800_fine",
            "ranks1_a", "ranks2_a", "ranks1_b", "ranks2_b"]
    if any(k not in rows for k in need):
        return
    lv = [rows["p800_direct"], rows["p800_fine_direct"]]
    it = [rows["p800_iterative"], rows["p800_fine"]]
    nf = [r["flow_dofs"] for r in lv]
    ns = [r["solid_dofs"] for r in lv]

    def per_solve(r, share):  # s per flow solve (one per coupling iteration)
        return r["s_per_step"] * r[share] / r["coupling_its_per_step"]
    parts = {
        "flow solve, MUMPS": (nf, [per_solve(r, "flow_solve_share") for r in lv]),
        "flow solve, PCD": (nf, [per_solve(r, "flow_solve_share") for r in it]),
        "flow assembly": (nf, [per_solve(r, "flow_assembly_share") for r in lv]),
        "mesh motion": (nf, [per_solve(r, "mesh_motion_share") for r in lv]),
        "fold": (ns, [per_solve(r, "fold_share") for r in lv]),
    }
    speedup = [rows[f"ranks1_{k}"]["s_per_step"] / rows[f"ranks2_{k}"]["s_per_step"] for k in "ab"]
    model = []
    for name, (n, y) in parts.items():
        c, a = power_law(n, y)
        model.append({"part": name, "per": "coupling iteration", "c": c, "exponent": round(a, 2),
                      "at_level_1_s": round(y[0], 3), "at_level_2_s": round(y[1], 3)})
    write_rows(os.path.join(out, "fold3d_cost_model.csv"), model)
    print(f"\n1 -> 2 ranks speed-up per step: {speedup[0]:.2f}, {speedup[1]:.2f}")
    print_markdown_table([(k, lambda r, k=k: str(r[k])) for k in model[0]], model)
    # A cycle (10 ms at Δt 5e-5: 200 steps, 2.5 coupling iterations each)
    # on meshes refined by r in every direction (unknowns r^3 x)
    coef = {m["part"]: (m["c"], m["exponent"]) for m in model}
    print("\n| refinement | flow / fold unknowns | MUMPS h per cycle | PCD h per cycle |")
    print("|---|---|---|---|")
    for r in (1.0, 1.5, 2.0, 3.0):
        f, s = nf[0] * r ** 3, ns[0] * r ** 3
        steps = 200 * r  # Δt with the cells (the jet CFL)
        rest = sum(coef[k][0] * f ** coef[k][1] for k in ("flow assembly", "mesh motion")) \
            + coef["fold"][0] * s ** coef["fold"][1]
        hours = [steps * 2.5 * (coef[k][0] * f ** coef[k][1] + rest) / 3600
                 for k in ("flow solve, MUMPS", "flow solve, PCD")]
        print(f"| {r:g} | {f:.3g} / {s:.3g} | {hours[0]:.2g} | {hours[1]:.2g} |")


if __name__ == "__main__":
    main()
