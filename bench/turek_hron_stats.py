#!/usr/bin/python3
"""Turek-Hron periodic statistics of an fsai_turek_hron run: for ux(A),
uy(A), drag and lift over the last WINDOW seconds, mean = (max + min)/2,
amplitude = (max - min)/2 and frequency from the upward crossings of the
mean (the benchmark's convention), compared with the FeatFlow refined
values of FSI2 (shared/references/turek_hron_results.csv).

usage: bench/turek_hron_stats.py RUN_DIR [--window 2.0]
"""
import argparse
import csv
import os

ap = argparse.ArgumentParser()
ap.add_argument("run")
ap.add_argument("--window", type=float, default=2.0)
args = ap.parse_args()
with open(os.path.join(args.run, "series.csv")) as f:
    rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
t_end = rows[-1]["t_s"]
rows = [r for r in rows if r["t_s"] >= t_end - args.window]
ref = {"ux_A_m": (-0.01485, 0.0127, 3.86), "uy_A_m": (0.0013, 0.0816, 1.93),
       "drag_N_per_m": (215.06, 77.65, 3.86), "lift_N_per_m": (0.61, 237.8, 1.93)}
for key, (rm, ra, rf) in ref.items():
    v = [r[key] for r in rows]
    t = [r["t_s"] for r in rows]
    mean, amp = (max(v) + min(v)) / 2, (max(v) - min(v)) / 2
    cross = [t[i - 1] + (t[i] - t[i - 1]) * (mean - v[i - 1]) / (v[i] - v[i - 1])
             for i in range(1, len(v)) if v[i - 1] < mean <= v[i]]
    freq = (len(cross) - 1) / (cross[-1] - cross[0]) if len(cross) >= 2 else float("nan")
    print(f"{key}: mean {mean:.5g} (ref {rm}), amplitude {amp:.5g} (ref {ra}, "
          f"{100 * (amp / ra - 1):+.1f}%), frequency {freq:.4g} Hz (ref {rf}, "
          f"{100 * (freq / rf - 1):+.1f}%)")
