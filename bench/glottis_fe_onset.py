#!/usr/bin/python3
"""Phonation onset of the FE glottis model (fsai_glottis --flow fe, 2 MPI
ranks): for each subglottal pressure a short run from the small initial
perturbation (h0 = 0.05 mm), and the evolution of the glottal half-gap
g(t): its half peak-to-peak swing in the first 10 ms after the pressure
ramp (5-15 ms) and in the last 10 ms. The oscillation is self-sustained
when the late swing is at least the early one (amplitude ratio >= 1), and
the onset pressure lies between the highest decaying and the lowest
sustained p_sub. The gap, not h, is the measure: the limit cycle is
rotation-dominated (h alone decays at 1200 Pa while the glottis closes in
every cycle). A least-squares growth rate of the gap swings over the run
is also reported; it mixes growth and saturation, so the ratio decides.
The reduced model's onset comes from its linear stability
(bench/glottis_bernoulli.py).

usage: bench/glottis_fe_onset.py [BUILD_DIR] [--pressures 300,450,600]
       [--duration 0.04]
writes bench/results/glottis_fe_onset.csv
"""
import argparse
import json
import math
import os
import subprocess

from benchlib import read_float_rows, write_rows

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--pressures", default="300,450,600")
ap.add_argument("--duration", type=float, default=0.04)
ap.add_argument("--t_from", type=float, default=0.01, help="after the ramp [s]")
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_glottis")
out = os.path.join(here, "results")
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


def growth_rate(t, h, t_from):
    """Least-squares slope of log(half swing between successive extrema)"""
    pts = [(a, b) for a, b in zip(t, h) if a >= t_from]
    ext = []
    for i in range(1, len(pts) - 1):
        if (pts[i][1] - pts[i - 1][1]) * (pts[i + 1][1] - pts[i][1]) < 0:
            ext.append(pts[i])
    swings = [(0.5 * (ext[i][0] + ext[i - 1][0]), 0.5 * abs(ext[i][1] - ext[i - 1][1]))
              for i in range(1, len(ext)) if ext[i][1] != ext[i - 1][1]]
    if len(swings) < 4:
        return float("nan"), len(swings)
    xs, ys = [s[0] for s in swings], [math.log(s[1]) for s in swings]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return slope, len(swings)


rows = []
for ps in [float(p) for p in args.pressures.split(",")]:
    run = os.path.join(out, f"run_glottis_fe_onset_{ps:g}")
    if not os.path.exists(os.path.join(run, "summary.json")):
        cmd = ["mpirun", "-n", "2", exe, "--flow", "fe", "--p-sub", str(ps), "--duration",
               str(args.duration), "--write_every", "0", "--output", run]
        print(" ".join(cmd), flush=True)
        subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL)
    ser = read_float_rows(os.path.join(run, "series.csv"))
    t = [r["t_s"] for r in ser]
    g = [r["gap_m"] for r in ser]
    rate, n = growth_rate(t, g, args.t_from)

    def swing(a, b):
        s = [x for tt, x in zip(t, g) if a <= tt < b]
        return 0.5 * (max(s) - min(s))
    early, late = swing(0.005, 0.015), swing(t[-1] - 0.01, t[-1] + 1)
    with open(os.path.join(run, "summary.json")) as f:
        s = json.load(f)
    rows.append({"p_sub_Pa": ps, "gap_swing_early_m": early, "gap_swing_late_m": late,
                 "amplitude_ratio": late / early, "growth_rate_1_per_s": rate,
                 "half_swings": n, "f0_hz": s["f0_hz"], "wall_s": s["wall_s"]})
    print(rows[-1], flush=True)
write_rows(os.path.join(out, "glottis_fe_onset.csv"), rows)
grow = [r["p_sub_Pa"] for r in rows if r["amplitude_ratio"] >= 1]
decay = [r["p_sub_Pa"] for r in rows if r["amplitude_ratio"] < 1]
print(f"FE onset between {max(decay) if decay else '?'} Pa (decays) and "
      f"{min(grow) if grow else '?'} Pa (sustained)")
