#!/usr/bin/python3
"""Charts of an fsai_demo run: gap g(t) and glottal flow Q(t), the
microphone pressure, and the sound's spectrum with the harmonics of f0 and
the tract's transfer-function formants marked.

usage: scripts/plot_voice.py RUN_DIR   (writes RUN_DIR/voice.png)
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
col = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
t = col["t_s"]
with open(os.path.join(run, "summary.json")) as f:
    s = json.load(f)
f0 = s.get("f0_hz") or float("nan")
tf = s.get("tract_formants_hz", [])
lpc = s.get("formants_from_sound_hz", [])
fig, ax = plt.subplots(3, 1, figsize=(8, 10))
a2 = ax[0].twinx()
ax[0].plot(t * 1e3, col["gap_m"] * 1e3, lw=0.8, label="g")
a2.plot(t * 1e3, col["Q_m3s"] * 1e3, lw=0.8, color="C1", label="Q")
ax[0].axhline(0, color="k", lw=0.5)
ax[0].set(xlabel="t [ms]", ylabel="half-gap g [mm]",
          title=f"glottis: f0 (fold) = {s.get('f0_fold_hz', float('nan')):.1f} Hz")
a2.set_ylabel("Q [l/s]", color="C1")
ax[1].plot(t * 1e3, col["p_mic_pa"], lw=0.6, label="microphone")
ax[1].plot(t * 1e3, col["p_lips_pa"], lw=0.6, alpha=0.6, label="lips")
ax[1].set(xlabel="t [ms]", ylabel="p' [Pa]", title="acoustic pressure")
ax[1].legend(loc="upper left")
with open(os.path.join(run, "spectrum.csv")) as f:
    sp = list(csv.DictReader(f))
fr = np.array([float(r["f_hz"]) for r in sp])
lv = np.array([float(r["level_db"]) for r in sp])
ax[2].plot(fr, lv, lw=0.8)
if np.isfinite(f0) and f0 > 0:
    for k in range(1, int(5000 / f0) + 1):
        ax[2].axvline(k * f0, color="0.6", lw=0.4, ls=":")
for i, F in enumerate(tf):
    ax[2].axvline(F, color="r", lw=1.0, ls="--", label="tract formants (1D)" if i == 0 else None)
for i, F in enumerate(lpc[:4]):
    ax[2].axvline(F, color="g", lw=1.0, ls="-.", label="LPC of the sound" if i == 0 else None)
ax[2].set_xlim(0, 5000)
ax[2].set(xlabel="f [Hz]", ylabel="level [dB re 20 µPa]",
          title=f"sound at the microphone: f0 = {f0:.1f} Hz, SPL {s.get('spl_db', float('nan')):.1f} dB, vowel {s.get('vowel')}")
ax[2].legend(loc="upper right", fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(run, "voice.png"), dpi=110)
