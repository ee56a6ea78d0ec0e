#!/usr/bin/python3
"""Where does the FE glottis scene need its fine mesh? Cost against accuracy.

The converged closing cycle (h_gap = 0.035 mm on all of the
fold, h_far = 0.35 mm, Δt = 1e−5, ζ1 = ζ2 = 0.02, 1200 Pa:
bench/results/run_glottis_h035_dt1_z02_c75) takes 21.5 min per 0.1 s on
2 ranks, 2.1× the scene's 10 min target. Most of its 31.5k flow unknowns
are not in the glottis: the fold's upper flanks (8 mm of its surface each
side, where the air is nearly at rest) are meshed at h_gap, and the
far field at 0.35 mm fills a 69 mm × 8 mm channel. This study keeps the
glottis's own resolution (h_gap 0.035 mm within `--fe.fine_height` of the
axis, growing over `--fe.grading`) and coarsens the rest, then compares
the limit cycle (summary.json: t ≥ 0.051 s) with that reference run.

Each case is one run of
  mpirun -n 2 fsai_glottis --flow fe --duration 0.1 --write_every 0
      --dt 1e-5 --vf.zeta1 0.02 --vf.zeta2 0.02 --fe.h_gap 0.035e-3 [case]
stored in bench/results/run_glottis_<case>/ (series.csv, summary.json,
run.log).

usage: bench/glottis_mesh_layout.py [BUILD_DIR] [--run CASE,..]
writes bench/results/glottis_mesh_layout.csv and .png
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
ap.add_argument("--run", help="cases to (re)run now, comma-separated")
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_glottis")
res = os.path.join(here, "results")
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
COMMON = ["--flow", "fe", "--duration", "0.1", "--write_every", "0", "--dt", "1e-5",
          "--vf.zeta1", "0.02", "--vf.zeta2", "0.02", "--fe.h_gap", "0.035e-3"]

# case: (run folder, options)
REFERENCE = "h035_dt1_z02_c75"
CASES = {
    # the converged run (bench/glottis_closure_converged.py)
    REFERENCE: ("run_glottis_h035_dt1_z02_c75", ["--fe.h_far", "0.35e-3"]),
    # h_gap within 1.5 mm of the axis, graded over 3 mm, far field 0.5 mm
    "band_fh15_g3_hf05": ("run_glottis_band_fh15_g3_hf05",
                          ["--fe.h_far", "0.5e-3", "--fe.fine_height", "1.5e-3",
                           "--fe.grading", "3e-3"]),
    # the same band with the reference's far field (0.35 mm): the band alone
    "band_fh15_g3_hf035": ("run_glottis_band_fh15_g3_hf035",
                           ["--fe.h_far", "0.35e-3", "--fe.fine_height", "1.5e-3",
                            "--fe.grading", "3e-3"]),
    # the band, 0.35 mm in the jet region (y ≤ 4 mm downstream of x = 0),
    # 0.7 mm elsewhere
    "band_jet035_hf07": ("run_glottis_band_jet035_hf07",
                         ["--fe.h_far", "0.7e-3", "--fe.h_jet", "0.35e-3",
                          "--fe.jet_height", "4e-3", "--fe.fine_height", "1.5e-3",
                          "--fe.grading", "3e-3"]),
}

for case in (args.run.split(",") if args.run else []):
    folder, opts = CASES[case]
    out = os.path.join(res, folder)
    cmd = ["mpirun", "-n", "2", exe] + COMMON + opts + ["--output", out]
    print(" ".join(cmd), flush=True)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "run.log"), "w") as f:
        subprocess.run(cmd, env=env, stdout=f, stderr=subprocess.STDOUT)

QUANTITIES = [("f0_hz", "f0 [Hz]", 1), ("q_peak_m3s", "peak flow [l/s]", 1e3),
              ("open_quotient", "OQ", 1), ("closed_leakage", "closed-phase leakage", 1)]
rows = []
ref = None
for case, (folder, opts) in CASES.items():
    path = os.path.join(res, folder, "summary.json")
    if not os.path.exists(path):
        print(f"{case}: not run ({path} missing)")
        continue
    with open(path) as f:
        s = json.load(f)
    tim = s["timings"]
    row = {"case": case, "options": " ".join(opts), "flow_dofs": s["flow_dofs"],
           "time_loop_s": tim["glottis: time loop"]["wall_s"],
           "solve_s": tim["fluid: solve"]["wall_s"],
           "assemble_s": tim["fluid: assemble"]["wall_s"],
           "ale_s": tim["ale: move"]["wall_s"], "force_s": tim["fluid: force"]["wall_s"],
           "closes_every_cycle": s["closes_every_cycle"],
           "unconverged_steps": s["coupling_unconverged_steps"]}
    for key, _, scale in QUANTITIES:
        row[key] = s[key] * scale
    if case == REFERENCE:
        ref = row
    for key, _, _ in QUANTITIES[:3]:
        row[key + "_change_pct"] = (100 * (row[key] / ref[key] - 1) if ref else float("nan"))
    rows.append(row)

print("| case | flow unknowns | time loop [s] | solve / assembly / ALE / force [s] | "
      + " | ".join(label for _, label, _ in QUANTITIES) + " | closes every cycle |")
print("|---" * (5 + len(QUANTITIES)) + "|")
for r in rows:
    cells = []
    for key, _, _ in QUANTITIES:
        c = f"{r[key]:.4g}"
        if key + "_change_pct" in r and r["case"] != REFERENCE:
            c += f" ({r[key + '_change_pct']:+.2f} %)"
        cells.append(c)
    print(f"| {r['case']} | {r['flow_dofs']} | {r['time_loop_s']:.0f} | "
          f"{r['solve_s']:.0f} / {r['assemble_s']:.0f} / {r['ale_s']:.0f} / {r['force_s']:.0f} | "
          + " | ".join(cells) + f" | {'yes' if r['closes_every_cycle'] else 'no'} |")



def cycle_peaks(folder, t_from=0.03):
    """Peak flow [l/s] of each cycle after t_from (cycles from one opening,
    the half-gap crossing 0 upwards, to the next)"""
    r = [(x["t_s"], x["gap_m"], x["Q_m3s"])
         for x in read_float_rows(os.path.join(res, folder, "series.csv"))]
    ups = [r[i][0] for i in range(1, len(r)) if r[i - 1][1] <= 0 < r[i][1] and r[i][0] > t_from]
    return [1e3 * max(q for t, _, q in r if a <= t < b) for a, b in zip(ups, ups[1:])]


print("\npeak flow per cycle after 30 ms [l/s] (the reference's cycle is slowly modulated)")
for r in rows:
    print(f"  {r['case']:20s} " + " ".join(f"{q:.3f}" for q in cycle_peaks(CASES[r['case']][0])))

out_csv = os.path.join(res, "glottis_mesh_layout.csv")
with open(out_csv, "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()) if rows else ["case"])
    w.writeheader()
    w.writerows(rows)
print("wrote", out_csv)

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    plt = None
if plt and len(rows) > 1:
    fig, ax = plt.subplots(figsize=(6, 4))
    for key, label, _ in QUANTITIES[:3]:
        ax.plot([r["time_loop_s"] for r in rows[1:]],
                [abs(r[key + "_change_pct"]) for r in rows[1:]], "o", label=label)
    for r in rows[1:]:
        ax.annotate(f"{r['case']}\n{r['flow_dofs']} dofs", (r["time_loop_s"], abs(r["q_peak_m3s_change_pct"])),
                    fontsize=7, xytext=(6, -4), textcoords="offset points")
    ax.axvline(600, color="k", ls=":", lw=1)
    ax.axvline(ref["time_loop_s"], color="grey", ls="--", lw=1)
    ax.text(ref["time_loop_s"], ax.get_ylim()[1] * 0.9, " reference", color="grey")
    ax.text(600, ax.get_ylim()[1] * 0.8, " 10 min", color="k")
    ax.set_xlabel("wall time per 0.1 s on 2 ranks [s]")
    ax.set_ylabel("|change| from the 0.035 mm reference [%]")
    ax.set_title("FE glottis: mesh layouts (Δt 1e-5, ζ 0.02, 1200 Pa)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(res, "glottis_mesh_layout.png"), dpi=120)
