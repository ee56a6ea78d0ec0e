#!/usr/bin/python3
"""Convergence of the FE glottis model (fsai_glottis --flow fe, p_sub =
1200 Pa): f0 and peak glottal flow over t in [0.025, 0.05] s for the
default run (Delta t = 2e-5 s, h_gap = 0.05 mm, h_far = 0.5 mm; its first
0.05 s), Delta t halved, and the mesh refined by 1/0.7 (h_gap = 0.035 mm,
h_far = 0.35 mm). f0 from the upward crossings of the mean gap, as
fsai_glottis computes it. The runs (2 ranks) are made by

  mpirun -n 2 fsai_glottis --flow fe --duration 0.1  --output bench/results/run_glottis_fe_default
  mpirun -n 2 fsai_glottis --flow fe --duration 0.05 --dt 1e-5 --output .../run_glottis_conv_dt1e-5
  mpirun -n 2 fsai_glottis --flow fe --duration 0.05 --fe.h_gap 0.035e-3 --fe.h_far 0.35e-3 \\
      --output .../run_glottis_conv_fine

usage: bench/glottis_fe_convergence.py   (writes bench/results/glottis_fe_convergence.csv)
"""
import csv
import os

here = os.path.dirname(os.path.abspath(__file__))
res = os.path.join(here, "results")
T0, T1 = 0.025, 0.05


def stats(run):
    with open(os.path.join(res, run, "series.csv")) as f:
        r = [{k: float(v) for k, v in x.items()} for x in csv.DictReader(f)]
    w = [x for x in r if T0 <= x["t_s"] <= T1 + 1e-12]
    g = [x["gap_m"] for x in w]
    t = [x["t_s"] for x in w]
    mean = sum(g) / len(g)
    cross = [t[i - 1] + (t[i] - t[i - 1]) * (mean - g[i - 1]) / (g[i] - g[i - 1])
             for i in range(1, len(g)) if g[i - 1] < mean <= g[i]]
    f0 = (len(cross) - 1) / (cross[-1] - cross[0])
    return f0, max(x["Q_m3s"] for x in w), len(cross) - 1


rows = []
base = None
for name, run in (("default", "run_glottis_fe_default"), ("dt/2", "run_glottis_conv_dt1e-5"),
                  ("h/1.43", "run_glottis_conv_fine")):
    if not os.path.exists(os.path.join(res, run, "series.csv")):
        continue
    f0, qp, n = stats(run)
    if base is None:
        base = (f0, qp)
    rows.append({"run": name, "f0_hz": f0, "q_peak_ls": 1e3 * qp, "cycles": n,
                 "f0_change_pct": 100 * (f0 / base[0] - 1),
                 "q_peak_change_pct": 100 * (qp / base[1] - 1)})
    print(f"| {name} | {f0:.2f} Hz | {1e3 * qp:.4f} l/s | {n} | "
          f"{rows[-1]['f0_change_pct']:+.2f} % | {rows[-1]['q_peak_change_pct']:+.2f} % |")
with open(os.path.join(res, "glottis_fe_convergence.csv"), "w", newline="") as f:
    wr = csv.DictWriter(f, fieldnames=list(rows[0]))
    wr.writeheader()
    wr.writerows(rows)
