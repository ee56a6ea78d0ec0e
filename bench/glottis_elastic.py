#!/usr/bin/python3
"""The elastic vocal fold with the Bernoulli flow (fsai_glottis --flow
bernoulli --fold elastic): oscillation and closure vs subglottal pressure
and tissue damping, cycle-to-cycle regularity, the convergence of the
default run in mesh and time step, the fold with clamped ends
(--elastic.clamped_ends) against plane strain, and the 2-DOF fold under
the same flow.

Runs of 0.25 s, statistics over the second half (summary.json), two at a
time. Writes bench/results/glottis_elastic.csv and glottis_elastic.png and
prints a Markdown table.

usage: bench/glottis_elastic.py [BUILD_DIR]
"""
import concurrent.futures
import json
import os
import subprocess
import sys

from benchlib import print_markdown_table, write_rows

here = os.path.dirname(os.path.abspath(__file__))
build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "build")
exe = os.path.join(build, "demos", "fsai_glottis")
out = os.path.join(here, "results")

# (label, extra arguments); the elastic fold's defaults: zeta 0.01 at
# 100 Hz (stiffness-proportional), h_surface 0.2 mm, dt 2e-5
cases = [(f"p{p}", ["--fold", "elastic", "--p-sub", str(p)])
         for p in (200, 300, 400, 600, 800, 1200, 1600, 2400)]
cases += [(f"z{z}", ["--fold", "elastic", "--p-sub", "1200", "--elastic.zeta", str(z)])
          for z in (0.02, 0.03, 0.05)]
cases += [(f"c{p}", ["--fold", "elastic", "--elastic.clamped_ends", "--p-sub", str(p)])
          for p in (200, 400, 800, 1200, 1600, 2400)]
cases += [("dt1e-5", ["--fold", "elastic", "--dt", "1e-5"]),
          ("h0.1mm", ["--fold", "elastic", "--elastic.h_surface", "0.1e-3",
                      "--elastic.h_far", "0.5e-3"]),
          ("2dof", ["--fold", "2dof", "--p-sub", "1200"])]


def run(case):
    label, args = case
    folder = os.path.join(out, f"run_glottis_elastic_{label}")
    subprocess.run([exe, "--flow", "bernoulli", "--duration", "0.25",
                    "--output", folder] + args, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(folder, "summary.json")) as f:
        s = json.load(f)
    par = s["parameters"]
    return {"case": label, "fold": par["fold"], "p_sub_Pa": par["p-sub"],
            "zeta": par["elastic"]["zeta"], "dt_s": par["dt"],
            "h_surface_m": par["elastic"]["h_surface"],
            "clamped_ends": int(par["elastic"]["clamped_ends"]),
            "f0_hz": s["f0_hz"], "open_quotient": s["open_quotient"],
            "q_peak_m3s": s["q_peak_m3s"],
            "closes_every_cycle": int(s["closes_every_cycle"]),
            "period_cv": s["period_cv"], "q_peak_cycle_cv": s["q_peak_cycle_cv"],
            "max_penetration_m": s["max_penetration_m"],
            "wall_per_sim_s": s["wall_per_sim_s"]}


with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
    rows = list(pool.map(run, cases))
write_rows(os.path.join(out, "glottis_elastic.csv"), rows)
print_markdown_table([
    ("case", lambda r: r["case"]),
    ("fold", lambda r: r["fold"] + (", clamped" if r["clamped_ends"] else "")),
    ("p_sub [Pa]", lambda r: f"{r['p_sub_Pa']:.0f}"),
    ("ζ", lambda r: f"{r['zeta']:g}"), ("f0 [Hz]", lambda r: f"{r['f0_hz']:.2f}"),
    ("OQ", lambda r: f"{r['open_quotient']:.3f}"),
    ("Q_peak [l/s]", lambda r: f"{1e3 * r['q_peak_m3s']:.3f}"),
    ("closes", lambda r: "yes" if r["closes_every_cycle"] else "no"),
    ("period CV", lambda r: f"{100 * r['period_cv']:.1f} %"),
    ("peak CV", lambda r: f"{100 * r['q_peak_cycle_cv']:.1f} %"),
    ("max δ [µm]", lambda r: f"{1e6 * r['max_penetration_m']:.1f}"),
    ("wall s / sim s", lambda r: f"{r['wall_per_sim_s']:.0f}")], rows)
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(13, 3.8))
    ax[0].axhspan(85, 155, color="0.9", label="male range")
    for prefix, name, ls in (("p", "plane strain", "-"), ("c", "clamped ends", "--")):
        pr = [r for r in rows if r["case"].startswith(prefix)]
        x = [r["p_sub_Pa"] for r in pr]
        ax[0].plot(x, [r["f0_hz"] for r in pr], "o" + ls, label=name)
        ax[1].plot(x, [1e3 * r["q_peak_m3s"] for r in pr], "o" + ls,
                   label=f"peak flow [l/s], {name}")
        ax[1].plot(x, [r["open_quotient"] for r in pr], "s" + ls,
                   label=f"open quotient, {name}")
        ax[2].plot(x, [100 * r["period_cv"] for r in pr], "o" + ls,
                   label=f"period, {name}")
        ax[2].plot(x, [100 * r["q_peak_cycle_cv"] for r in pr], "s" + ls,
                   label=f"peak flow, {name}")
    ax[0].set(xlabel="p_sub [Pa]", ylabel="f0 [Hz]", title="elastic fold, ζ 0.01")
    ax[0].legend()
    ax[1].set(xlabel="p_sub [Pa]", title="flow")
    ax[1].legend(fontsize=7)
    ax[2].set(xlabel="p_sub [Pa]", ylabel="cycle-to-cycle CV [%]",
              title="regularity (0: limit cycle)")
    ax[2].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "glottis_elastic.png"), dpi=110)
except ImportError:
    print("matplotlib missing: no chart")
