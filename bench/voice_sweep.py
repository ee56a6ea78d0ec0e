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
    put at 0.3 m to compare (--mic_distance; the FE acoustics end at the
    lips under the piston load, A11, and radiate to any distance);
  - f0: half an octave per 6.5 cmH2O (638 Pa) of p_sub when the pitch is
    not controlled, one male speaker, vowel [a] (Ladefoged & McKinney
    1963, J. Acoust. Soc. Am. 35(4):454-460).

--param fold-stiffness scales both modal stiffnesses of the 2-DOF fold
(its in-vacuo frequencies 100 / 155 Hz times the square root of the value),
charted against the string model's f0 ∝ √stiffness.

usage: bench/voice_sweep.py [BUILD_DIR] [--fidelity reduced|mixed|full]
         [--param p-sub|fold-stiffness|OPTION] [--values 400,600,...] [--vowel a]
         [--duration 0.3] [--extra "--vf.f1 110"] [--name NAME]
writes bench/results/voice_sweep_<name>.csv and .png; run folders
bench/results/run_sweep_<name>_<value>/
"""
import argparse
import csv
import os
import shlex
import subprocess

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from benchlib import timed_run

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
# The microphone at 0.3 m (the human data's): the 1D tract's and the FE
# tract's piston load (A11) both radiate a monopole to any distance
fidelity = {"reduced": ["--flow", "bernoulli", "--acoustics", "1d"],
            "mixed": ["--flow", "bernoulli", "--acoustics", "fe"],
            "full": ["--flow", "fe", "--acoustics", "fe"]}[args.fidelity] + \
    ["--mic_distance", "0.3"]
ranks = 2 if args.fidelity == "full" else 1
values = [float(v) for v in args.values.split(",")]


def option(val):
    """The fsai_demo options for one value of --param"""
    if args.param == "fold-stiffness":
        # Both modal stiffnesses of the 2-DOF fold times val: its in-vacuo
        # frequencies (the voice's 100 / 155 Hz) times sqrt(val)
        return ["--vf.f1", f"{100 * val ** 0.5:g}", "--vf.f2", f"{155 * val ** 0.5:g}"]
    return [f"--{args.param}", f"{val:g}"]


rows = []
for val in values:
    d = os.path.join(out, f"run_sweep_{name}_{val:g}")
    cmd = [demo] + fidelity + ["--vowel", args.vowel, "--duration", str(args.duration),
                               "--report=false", "--output", d] + option(val) + \
        shlex.split(args.extra)
    if ranks > 1:
        cmd = ["mpirun", "-n", str(ranks)] + cmd
    s = timed_run(cmd, d, args.rerun, env)
    if s is None:
        continue
    wall = s["process_wall_s"]
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
if args.param == "fold-stiffness":
    # A string's (or spring's) f0 grows as the square root of its stiffness
    # (Titze 1994, Principles of Voice Production, §8): through the value 1
    f0 = [r["f0_hz"] for r in rows]
    ref = next((i for i, v in enumerate(x) if v == 1.0 and np.isfinite(f0[i])), None)
    if ref is not None:
        k = np.linspace(x.min(), x.max(), 50)
        ax[0].plot(k, f0[ref] * np.sqrt(k / x[ref]), "k--", lw=1,
                   label="f0 ∝ √stiffness (string model, Titze 1994)")
for a in ax:
    a.legend(fontsize=7)
fig.suptitle(f"fsai_demo sweep of --{args.param}, vowel [{args.vowel}], {args.fidelity} fidelity")
fig.tight_layout()
fig.savefig(os.path.join(out, f"voice_sweep_{name}.png"), dpi=100)
print("wrote", os.path.join(out, f"voice_sweep_{name}.csv"))
