#!/usr/bin/python3
"""One-page report of an fsai_demo run (docs/voice.md): the voice measures
(summary.json's "voice"), the glottal flow and its derivative over the last
cycles, the fold's motion, a spectrogram of the sound at the microphone, and
its spectrum with the tract's transfer function over it.

usage: scripts/plot_voice.py RUN_DIR   (writes RUN_DIR/report.png)
"""
import csv
import json
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def fmt(v, spec):
    return "–" if v is None else format(v, spec)


run = sys.argv[1]
col = read_csv(os.path.join(run, "series.csv"))
with open(os.path.join(run, "summary.json")) as f:
    s = json.load(f)
v = s.get("voice", {})
t, Q = col["t_s"], col["Q_m3s"] * 1e3
dt = t[1] - t[0]
f0 = v.get("f0_hz") or s.get("f0_fold_hz") or float("nan")

fig = plt.figure(figsize=(11, 11))
gs = fig.add_gridspec(3, 2, height_ratios=[1, 1, 1.1])
fig.suptitle(f"fsai_demo: vowel [{s.get('vowel')}], {s.get('fidelity', '')}, "
             f"p_sub {s.get('parameters', {}).get('p-sub', float('nan')):.0f} Pa",
             fontsize=12)

# Measures
ax = fig.add_subplot(gs[0, 0])
ax.axis("off")
lines = [
    ("f0", f"{fmt(v.get('f0_hz'), '.1f')} Hz ({v.get('cycles', 0)} cycles)"),
    ("jitter / shimmer", f"{fmt(v.get('jitter_pct'), '.2f')} % / {fmt(v.get('shimmer_pct'), '.2f')} %"),
    ("HNR", f"{fmt(v.get('hnr_db'), '.1f')} dB"),
    ("flow peak / mean / AC", f"{fmt(v.get('q_peak_ls'), '.3f')} / {fmt(v.get('q_mean_ls'), '.3f')} / {fmt(v.get('q_ac_ls'), '.3f')} l/s"),
    ("OQ / CQ / SQ", f"{fmt(v.get('open_quotient'), '.2f')} / {fmt(v.get('closed_quotient'), '.2f')} / {fmt(v.get('speed_quotient'), '.2f')}"),
    ("MFDR / NAQ", f"{fmt(v.get('mfdr_ls2'), '.0f')} l/s² / {fmt(v.get('naq'), '.3f')}"),
    ("H1–H2", f"{fmt(v.get('h1_h2_db'), '.1f')} dB"),
    ("SPL", f"{fmt(v.get('spl_db'), '.1f')} dB at {fmt(v.get('mic_distance_m'), '.2f')} m"),
    ("formants (sound)", ", ".join(f"{x:.0f}" for x in v.get("formants_hz", [])[:4]) + " Hz"),
    ("bandwidths", ", ".join(f"{x:.0f}" for x in v.get("bandwidths_hz", [])[:4]) + " Hz"),
    ("tract formants (1D)", ", ".join(f"{x:.0f}" for x in s.get("tract_formants_hz", [])[:4]) + " Hz"),
]
for i, (k, val) in enumerate(lines):
    ax.text(0.0, 1 - i * 0.09, k, fontsize=10, weight="bold", va="top")
    ax.text(0.45, 1 - i * 0.09, val, fontsize=10, va="top")
ax.set_title("voice measures (statistics window)", loc="left")

# Glottal flow and its derivative over the last cycles
ax = fig.add_subplot(gs[0, 1])
n_last = int(min(len(t), 4 / f0 / dt)) if np.isfinite(f0) else len(t)
tl = t[-n_last:] * 1e3
ax.plot(tl, Q[-n_last:], lw=1.0, label="Q")
ax.set(xlabel="t [ms]", ylabel="Q [l/s]", title="glottal flow and its derivative")
a2 = ax.twinx()
a2.plot(tl, np.gradient(Q[-n_last:], dt), lw=0.8, color="C1")
a2.set_ylabel("dQ/dt [l/s²]", color="C1")

# Fold motion
ax = fig.add_subplot(gs[1, 0])
ax.plot(t * 1e3, col["gap_m"] * 1e3, lw=0.7, label="half-gap g")
ax.plot(t * 1e3, col["h_m"] * 1e3, lw=0.7, label="translation h")
ax.axhline(0, color="k", lw=0.5)
ax.set(xlabel="t [ms]", ylabel="[mm]", title="fold motion")
ax.legend(loc="upper right", fontsize=8)

# Spectrogram of the sound
ax = fig.add_subplot(gs[1, 1])
p = col["p_mic_pa"] - np.mean(col["p_mic_pa"])
nfft = int(2 ** np.ceil(np.log2(0.02 / dt)))
if len(p) > nfft:
    ax.specgram(p, NFFT=nfft, Fs=1 / dt, noverlap=nfft * 3 // 4, cmap="magma",
                vmin=None)
ax.set_ylim(0, 5000)
ax.set(xlabel="t [s]", ylabel="f [Hz]", title="spectrogram at the microphone")

# Spectrum with the tract's transfer function
ax = fig.add_subplot(gs[2, :])
sp = read_csv(os.path.join(run, "spectrum.csv"))
ax.plot(sp["f_hz"], sp["level_db"], lw=0.8, label="sound at the microphone")
tr_path = os.path.join(run, "tract_response.csv")
if os.path.exists(tr_path):
    tr = read_csv(tr_path)
    # The tract's |P_lips/U_g| in dB, shifted onto the spectrum's top
    shift = np.max(sp["level_db"]) - np.max(tr["level_db"])
    ax.plot(tr["f_hz"], tr["level_db"] + shift, lw=1.0, color="r", alpha=0.7,
            label="tract transfer function (1D, shifted)")
for i, F in enumerate(v.get("formants_hz", [])[:4]):
    ax.axvline(F, color="g", lw=0.8, ls="-.", label="formants of the sound (LPC)" if i == 0 else None)
ax.set_xlim(0, 5000)
top = np.max(sp["level_db"])
ax.set_ylim(top - 80, top + 5)
ax.set(xlabel="f [Hz]", ylabel="level [dB re 20 µPa]",
       title=f"spectrum: H1–H2 {fmt(v.get('h1_h2_db'), '.1f')} dB, SPL {fmt(v.get('spl_db'), '.1f')} dB")
ax.legend(loc="upper right", fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(run, "report.png"), dpi=90)
