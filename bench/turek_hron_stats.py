#!/usr/bin/python3
"""Turek-Hron periodic statistics of an fsai_turek_hron run: for ux(A),
uy(A), drag and lift over the last WINDOW seconds, mean = (max + min)/2,
amplitude = (max - min)/2 and frequency from the upward crossings of the
mean (the benchmark's convention), compared with the FeatFlow refined
values (Turek et al. 2010; FeatFlow benchmark pages, level 4+0, FSI2
dt = 0.0005, FSI3 dt = 0.00025; references/turek_hron_results.csv).
bench/fsi_accuracy.py uses the same functions.

usage: bench/turek_hron_stats.py RUN_DIR [--case FSI2|FSI3] [--window 2.0]
"""
import argparse
import os

from benchlib import read_float_rows

# (mean, amplitude, frequency) per quantity
REF = {
    "FSI2": {"uy_A_m": (0.0013, 0.0816, 1.93), "ux_A_m": (-0.01485, 0.0127, 3.86),
             "drag_N_per_m": (215.06, 77.65, 3.86), "lift_N_per_m": (0.61, 237.8, 1.93)},
    "FSI3": {"uy_A_m": (0.00147, 0.03499, 5.46), "ux_A_m": (-0.00288, 0.00272, 10.93),
             "drag_N_per_m": (460.5, 27.74, 10.93), "lift_N_per_m": (2.50, 153.91, 5.46)},
}


def load_series(run):
    return read_float_rows(os.path.join(run, "series.csv"))


def periodic_stats(series, key, window):
    """(mean, amplitude, frequency) of `key` over the last `window` seconds"""
    t_end = series[-1]["t_s"]
    rows = [r for r in series if r["t_s"] >= t_end - window]
    v = [r[key] for r in rows]
    t = [r["t_s"] for r in rows]
    mean, amp = (max(v) + min(v)) / 2, (max(v) - min(v)) / 2
    cross = [t[i - 1] + (t[i] - t[i - 1]) * (mean - v[i - 1]) / (v[i] - v[i - 1])
             for i in range(1, len(v)) if v[i - 1] < mean <= v[i]]
    freq = (len(cross) - 1) / (cross[-1] - cross[0]) if len(cross) >= 2 else float("nan")
    return mean, amp, freq


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("run")
    ap.add_argument("--case", choices=sorted(REF), default="FSI2")
    ap.add_argument("--window", type=float, default=2.0)
    args = ap.parse_args()
    series = load_series(args.run)
    for key, (rm, ra, rf) in REF[args.case].items():
        mean, amp, freq = periodic_stats(series, key, args.window)
        print(f"{key}: mean {mean:.5g} (ref {rm}), amplitude {amp:.5g} (ref {ra}, "
              f"{100 * (amp / ra - 1):+.1f}%), frequency {freq:.4g} Hz (ref {rf}, "
              f"{100 * (freq / rf - 1):+.1f}%)")
