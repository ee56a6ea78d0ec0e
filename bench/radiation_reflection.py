#!/usr/bin/python3
"""Reflection of the radiated pulse at the outer boundary of the radiation
region: fsai_formants' microphone signal (3 cm beyond the lips of vowel
[u]) with the boundary at R = 8 cm (plain Sommerfeld, Sommerfeld with the
curvature term, absorbing layer of 2 cm and of 6 cm), against a reference
run with the boundary at R = 50 cm, over the time window before the
reference's own boundary echo can reach the microphone.

reflection = max |p - p_ref| / max |p_ref| over that window

usage: bench/radiation_reflection.py [BUILD_DIR]
writes bench/results/radiation_reflection.csv and .png
"""
import csv
import json
import os
import subprocess
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

here = os.path.dirname(os.path.abspath(__file__))
build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "build")
exe = os.path.join(build, "demos", "fsai_formants")
out = os.path.join(here, "results")
os.makedirs(out, exist_ok=True)
c0, mic, R_ref, T = 343.0, 0.03, 0.5, 0.006

cases = [("reference R=50cm", ["--radiation", "sommerfeld", "--tract.radius", str(R_ref)]),
         ("Sommerfeld (plain)", ["--radiation", "sommerfeld", "--curvature=false"]),
         ("Sommerfeld + curvature", ["--radiation", "sommerfeld"]),
         ("absorbing layer 2 cm", ["--radiation", "pml", "--layer", "0.02"]),
         ("absorbing layer 6 cm", ["--radiation", "pml", "--layer", "0.06"])]


def series(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [float(r["t_s"]) for r in rows], [float(r["p_mic_pa"]) for r in rows]


results = []
for model in ("planar", "axisym"):
    sig = {}
    for name, opts in cases:
        run = os.path.join(out, f"refl_{model}_{len(sig)}")
        subprocess.run([exe, "--vowel", "u", "--model", model, "--pulse.duration", str(T),
                        "--mic_distance", str(mic), "--snapshots", "0", "--output", run] + opts,
                       check=True, stdout=subprocess.DEVNULL)
        with open(os.path.join(run, "summary.json")) as f:
            wall = json.load(f)["wall_s"]
        sig[name] = (series(os.path.join(run, "time_series.csv")), wall)
    (t, pref), _ = sig[cases[0][0]]
    # Direct sound passes the mic at ~ t_pulse + L/c + mic/c; the reference's
    # echo needs a further (2 R_ref - mic)/c
    t_end = 4 * 0.84 / 5000 + 0.1825 / c0 + mic / c0 + (2 * R_ref - 2 * mic) / c0
    idx = [i for i, ti in enumerate(t) if ti <= min(t_end, T)]
    peak = max(abs(pref[i]) for i in idx)
    fig, ax = plt.subplots(figsize=(7, 4))
    for name, _ in cases:
        (ti, p), wall = sig[name]
        err = max(abs(p[i] - pref[i]) for i in idx) / peak
        if name != cases[0][0]:
            results.append((model, name, err, wall))
            print(f"{model:7s} {name:24s} reflection {err:.4f} ({20 * __import__('math').log10(err):.1f} dB) wall {wall:.2f} s")
        ax.plot([x * 1e3 for x in ti], p, lw=0.8, label=name)
    ax.set_xlim(0, T * 1e3)
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("p' at the microphone [Pa]")
    ax.set_title(f"[u] {model}: microphone 3 cm from the lips")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, f"radiation_reflection_{model}.png"), dpi=120)

with open(os.path.join(out, "radiation_reflection.csv"), "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["model", "boundary", "reflection", "wall_s"])
    for r in results:
        w.writerow([r[0], r[1], f"{r[2]:.5f}", f"{r[3]:.2f}"])
