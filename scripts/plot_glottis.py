#!/usr/bin/python3
"""Charts of an fsai_glottis run: gap g(t), flow Q(t) and the spectrum of Q.

usage: scripts/plot_glottis.py RUN_DIR   (writes RUN_DIR/glottis.png)
"""
import csv
import json
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

run = sys.argv[1]
with open(os.path.join(run, "series.csv")) as f:
    rows = list(csv.DictReader(f))
t = np.array([float(r["t_s"]) for r in rows])
g = np.array([float(r["gap_m"]) for r in rows])
Q = np.array([float(r["Q_m3s"]) for r in rows])
f0 = float("nan")
try:
    with open(os.path.join(run, "summary.json")) as f:
        f0 = json.load(f).get("f0_hz", float("nan"))
except (OSError, KeyError, ValueError):
    pass
fig, ax = plt.subplots(3, 1, figsize=(8, 9))
ax[0].plot(t * 1e3, g * 1e3, lw=0.8)
ax[0].axhline(0, color="k", lw=0.5)
ax[0].set(xlabel="t [ms]", ylabel="half-gap g [mm]", title="glottal gap")
ax[1].plot(t * 1e3, Q * 1e3, lw=0.8)
ax[1].set(xlabel="t [ms]", ylabel="Q [l/s]", title="glottal flow")
half = t >= t[-1] / 2
if half.sum() > 16:
    q = Q[half] - Q[half].mean()
    dt = np.diff(t[half]).mean()
    spec = np.abs(np.fft.rfft(q * np.hanning(len(q))))
    fr = np.fft.rfftfreq(len(q), dt)
    ax[2].semilogy(fr, spec / max(spec.max(), 1e-300) + 1e-12, lw=0.8)
    ax[2].set_xlim(0, 2000)
    if np.isfinite(f0) and f0 > 0:
        for k in range(1, int(2000 / f0) + 1):
            ax[2].axvline(k * f0, color="r", lw=0.4, ls=":")
ax[2].set(xlabel="f [Hz]", ylabel="|Q| (normalised)",
          title=f"spectrum of Q (second half), f0 = {f0:.1f} Hz")
fig.tight_layout()
fig.savefig(os.path.join(run, "glottis.png"), dpi=110)
