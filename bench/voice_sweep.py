#!/usr/bin/python3
"""A parameter sweep of the voice (docs/voice.md, "Sweeps"): fsai_demo at one
fidelity for each value of one option, and f0, SPL, OQ, MFDR and H1–H2
charted against it.

For the subglottal pressure (the default, --param p-sub) the chart adds the
onset pressure (linear stability of the fold's rest position under the
Bernoulli flow, fsai_glottis --onset_sweep, with the voice's fold) and the
measured human trends it should follow:
  - SPL: 80.0 dB at 0.3 m for p_sub 10 cmH2O (981 Pa) and +9.3 dB per
    doubling of p_sub, 15 untrained male voices, syllable [pae]
    (Björklund & Sundberg 2016, J. Voice 30(1):15-20); the microphone is
    put at 0.3 m to compare (--mic_distance, 1D acoustics only);
  - f0: half an octave per 6.5 cmH2O (638 Pa) of p_sub when the pitch is
    not controlled, one male speaker, vowel [a] (Ladefoged & McKinney
    1963, J. Acoust. Soc. Am. 35(4):454-460).

usage: bench/voice_sweep.py [BUILD_DIR] [--fidelity reduced|mixed|full]
         [--param p-sub] [--values 400,600,...] [--vowel a]
         [--duration 0.3] [--extra "--vf.f1 110"] [--name NAME]
writes bench/results/voice_sweep_<name>.csv and .png; run folders
bench/results/run_sweep_<name>_<value>/
"""
import argparse
import csv
import json
import os
import shlex
import subprocess
import time

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--fidelity", default="reduced", choices=["reduced", "mixed", "full"])
ap.add_argument("--param", default="p-sub")
ap.add_argument("--values", default="300,400,500,600,800,1000,1200,1400,1600")
ap.add_argument("--vowel", default="a")
ap.add_argument("--duration", type=float, default=0.3)
ap.add_argument("--extra", default="")
ap.add_argument("--name", default="")
ap.add_argument("--rerun", action="store_true")
args = ap.parse_args()
name = args.name or f"{args.fidelity}_{args.param.replace('.', '_')}_{args.vowel}"
demo = os.path.join(args.build, "demos", "fsai_demo")
glottis = os.path.join(args.build, "demos", "fsai_glottis")
out = os.path.join(here, "results")
os.makedirs(out, exist_ok=True)
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
fidelity = {"reduced": ["--flow", "bernoulli", "--acoustics", "1d", "--mic_distance", "0.3"],
            "mixed": ["--flow", "bernoulli", "--acoustics", "fe"],
            "full": ["--flow", "fe", "--acoustics", "fe"]}[args.fidelity]
ranks = 2 if args.fidelity == "full" else 1
values = [float(v) for v in args.values.split(",")]

rows = []
for val in values:
    d = os.path.join(out, f"run_sweep_{name}_{val:g}")
    summary = os.path.join(d, "summary.json")
    if args.rerun or not os.path.exists(summary):
        cmd = [demo] + fidelity + ["--vowel", args.vowel, "--duration", str(args.duration),
                                   f"--{args.param}", f"{val:g}", "--report=false",
                                   "--output", d] + shlex.split(args.extra)
        if ranks > 1:
            cmd = ["mpirun", "-n", str(ranks)] + cmd
        t0 = time.time()
        r = subprocess.run(cmd, env=env, capture_output=True, text=True)
        if r.returncode != 0:
            print(f"{args.param} = {val:g}: failed: {r.stderr.strip()[-300:]}")
            continue
        with open(os.path.join(d, "process_wall_s"), "w") as f:
            f.write(f"{time.time() - t0}\n")
    with open(summary) as f:
        s = json.load(f)
    with open(os.path.join(d, "process_wall_s")) as f:
        wall = float(f.read())
    v = s["voice"]
    # A voice is a self-sustained oscillation that reaches the statistics
    # window: at least 3 cycles there
    voiced = (v.get("cycles") or 0) >= 3
    nan = float("nan")
    g = lambda k: (v.get(k) if v.get(k) is not None else nan) if voiced else nan
    rows.append(dict(value=val, wall_s=wall, cycles=v.get("cycles") or 0,
                     f0_hz=g("f0_hz"), spl_db=g("spl_db"), oq=g("open_quotient"),
                     mfdr_ls2=g("mfdr_ls2"), h1_h2_db=g("h1_h2_db"),
                     q_peak_ls=g("q_peak_ls"), jitter_pct=g("jitter_pct"),
                     mic_distance_m=v.get("mic_distance_m")))
    r = rows[-1]
    print(f"{args.param} = {val:7g}: {r['cycles']:3d} cycles, f0 {r['f0_hz']:6.1f} Hz, "
          f"SPL {r['spl_db']:5.1f} dB, OQ {r['oq']:.3f}, MFDR {r['mfdr_ls2']:6.0f} l/s², "
          f"H1-H2 {r['h1_h2_db']:5.1f} dB (wall {wall:.2f} s)", flush=True)

# Onset: linear stability of the reduced model with the voice's fold
onset = None
if args.param == "p-sub":
    sweep = ",".join(f"{p:g}" for p in np.arange(50, 2001, 25))
    od = os.path.join(out, f"run_sweep_{name}_onset")
    fold = ["--vf.f2", "155", "--vf.zeta1", "0.02", "--vf.zeta2", "0.02"]
    subprocess.run([glottis, "--flow", "bernoulli", "--onset_sweep", sweep,
                    "--output", od] + fold + shlex.split(args.extra),
                   env=env, capture_output=True, text=True)
    path = os.path.join(od, "onset.csv")
    if os.path.exists(path):
        with open(path) as f:
            for r in csv.DictReader(f):
                if float(r["growth_rate_1_per_s"]) > 0:
                    onset = float(r["p_sub_Pa"])
                    break
    print(f"onset (linear stability, reduced model): {onset} Pa")

with open(os.path.join(out, f"voice_sweep_{name}.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
    w.writeheader()
    for r in rows:
        w.writerow({k: (f"{x:.5g}" if isinstance(x, float) else x) for k, x in r.items()})

x = np.array([r["value"] for r in rows])
fig, ax = plt.subplots(2, 3, figsize=(13, 7))
ax = ax.ravel()
panels = [("f0_hz", "f0 [Hz]"), ("spl_db", f"SPL [dB] at {rows[0]['mic_distance_m']} m"),
          ("oq", "open quotient"), ("mfdr_ls2", "MFDR [l/s²]"),
          ("h1_h2_db", "H1–H2 [dB]"), ("q_peak_ls", "peak flow [l/s]")]
for a, (k, label) in zip(ax, panels):
    a.plot(x, [r[k] for r in rows], "o-", label=f"fsai ({args.fidelity})")
    a.set(xlabel=args.param, ylabel=label)
    if onset is not None:
        a.axvline(onset, color="0.5", ls=":", label=f"onset {onset:g} Pa")
if args.param == "p-sub":
    p = np.linspace(max(200, x.min()), x.max(), 50)
    ax[1].plot(p, 80.0 + 9.3 * np.log2(p / 981.0), "k--", lw=1,
               label="human, 0.3 m (Björklund & Sundberg 2016)")
    f0 = [r["f0_hz"] for r in rows]
    ref = next((i for i, v in enumerate(f0) if np.isfinite(v)), None)
    if ref is not None:
        ax[0].plot(p, f0[ref] * 2 ** (0.5 * (p - x[ref]) / 638.0), "k--", lw=1,
                   label="human slope (Ladefoged & McKinney 1963)")
for a in ax:
    a.legend(fontsize=7)
fig.suptitle(f"fsai_demo sweep of --{args.param}, vowel [{args.vowel}], {args.fidelity} fidelity")
fig.tight_layout()
fig.savefig(os.path.join(out, f"voice_sweep_{name}.png"), dpi=100)
print("wrote", os.path.join(out, f"voice_sweep_{name}.csv"))
