#!/usr/bin/python3
"""The voice at three fidelities (docs/voice.md, "Three fidelities"): cost
against the distance from the full model.

  reduced  --flow bernoulli --acoustics 1d   (serial)
  mixed    --flow bernoulli --acoustics fe   (serial)
  full     --flow fe --acoustics fe          (2 ranks; the default voice)

for the vowels u, a, i at p_sub 800 and 1200 Pa, 0.1 s each (statistics
over [0.05, 0.1] s, the default). Each run's wall time (process start to
exit, no report.png) and its voice measures (summary.json "voice", by the
current build's analysis: fsai_demo --reanalyse); the
distance of each level from the full run of the same vowel and pressure
on f0, OQ, peak flow, SPL and the sound's F1/F2, and each level's F1/F2
against the tract's own (1D, closed glottis).

usage: bench/voice_fidelity.py [BUILD_DIR] [--levels reduced,mixed,full]
                               [--vowels u,a,i] [--p_sub 800,1200]
                               [--radiation piston|sommerfeld] [--rerun]
                               [--cached]
writes bench/results/voice_fidelity.csv and voice_fidelity.png; run folders
bench/results/run_fidelity_<level>_<vowel>_<p_sub>/
"""
import argparse
import csv
import json
import os
import subprocess

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

from benchlib import timed_run

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--levels", default="reduced,mixed,full")
ap.add_argument("--vowels", default="u,a,i")
ap.add_argument("--p_sub", default="800,1200")
ap.add_argument("--radiation", default="piston",
                help="the FE levels' lip end (fsai_demo --radiation); other than "
                     "the default, its runs and table get the suffix _RADIATION")
ap.add_argument("--rerun", action="store_true")
ap.add_argument("--cached", action="store_true",
                help="only the runs already made (no new run)")
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_demo")
out = os.path.join(here, "results")
os.makedirs(out, exist_ok=True)
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
levels = {
    "reduced": (["--flow", "bernoulli", "--acoustics", "1d"], 1),
    "mixed": (["--flow", "bernoulli", "--acoustics", "fe"], 1),
    "full": (["--flow", "fe", "--acoustics", "fe"], 2),
}


suffix = "" if args.radiation == "piston" else f"_{args.radiation}"


def run(level, vowel, p_sub):
    opts, ranks = levels[level]
    if level != "reduced":
        opts = opts + ["--radiation", args.radiation]
    d = os.path.join(out, f"run_fidelity_{level}_{vowel}_{p_sub}" +
                     (suffix if level != "reduced" else ""))
    cmd = [exe] + opts + ["--vowel", vowel, "--p-sub", str(p_sub),
                          "--report=false", "--output", d]
    if ranks > 1:
        cmd = ["mpirun", "-n", str(ranks)] + cmd
    if args.cached and not os.path.exists(os.path.join(d, "summary.json")):
        return None
    s = timed_run(cmd, d, args.rerun, env)
    if s is None:
        return None
    # The measures by this build's analysis (--reanalyse reads the run's
    # series.csv again; the run itself is not repeated)
    subprocess.run([exe] + opts + ["--vowel", vowel, "--p-sub", str(p_sub), "--reanalyse",
                                   "--report=false", "--output", d],
                   env=env, capture_output=True, check=True)
    with open(os.path.join(d, "reanalysis.json")) as f:
        s["voice"] = json.load(f)["voice"]
    return s


rows = []
for p in [int(x) for x in args.p_sub.split(",")]:
    for v in args.vowels.split(","):
        for lev in args.levels.split(","):
            s = run(lev, v, p)
            if s is None:
                continue
            m = s["voice"]
            F = (m.get("formants_hz") or []) + [float("nan")] * 2
            T = s["tract_formants_hz"]
            rows.append(dict(level=lev, vowel=v, p_sub=p,
                             wall_s=s["process_wall_s"], loop_s=s["loop_wall_s"],
                             f0_hz=m["f0_hz"], oq=m["open_quotient"],
                             q_peak_ls=m["q_peak_ls"], spl_db=m["spl_db"],
                             mfdr_ls2=m["mfdr_ls2"], h1_h2_db=m["h1_h2_db"],
                             f1_hz=F[0], f2_hz=F[1], tract_f1_hz=T[0],
                             tract_f2_hz=T[1],
                             f1_vs_tract_pct=100 * (F[0] - T[0]) / T[0],
                             f2_vs_tract_pct=100 * (F[1] - T[1]) / T[1],
                             method=m.get("formant_method", "")))
            r = rows[-1]
            print(f"{lev:8s} [{v}] {p:5d} Pa: wall {r['wall_s']:7.1f} s, f0 {r['f0_hz']:.1f} Hz, "
                  f"OQ {r['oq']:.3f}, Q {r['q_peak_ls']:.3f} l/s, SPL {r['spl_db']:.1f} dB, "
                  f"F1/F2 {r['f1_hz']:.0f}/{r['f2_hz']:.0f} Hz "
                  f"({r['f1_vs_tract_pct']:+.1f} / {r['f2_vs_tract_pct']:+.1f} % vs tract "
                  f"{r['tract_f1_hz']:.0f}/{r['tract_f2_hz']:.0f})", flush=True)

# Distance from the full run of the same vowel and pressure
keys = [("f0_hz", "f0"), ("oq", "OQ"), ("q_peak_ls", "peak flow"),
        ("f1_hz", "F1"), ("f2_hz", "F2")]
for r in rows:
    full = [q for q in rows if q["level"] == "full" and q["vowel"] == r["vowel"]
            and q["p_sub"] == r["p_sub"]]
    for k, _ in keys:
        r[f"{k}_vs_full_pct"] = (100 * (r[k] - full[0][k]) / full[0][k]
                                 if full else float("nan"))
    r["spl_vs_full_db"] = r["spl_db"] - full[0]["spl_db"] if full else float("nan")
with open(os.path.join(out, f"voice_fidelity{suffix}.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
    w.writeheader()
    for r in rows:
        w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in r.items()})

fig, ax = plt.subplots(1, 2, figsize=(12, 4.8))
marker = {"reduced": "o", "mixed": "s", "full": "^"}
has_full = any(r["level"] == "full" for r in rows)
for lev in levels:
    sel = [r for r in rows if r["level"] == lev]
    if not sel or lev == "full" or not has_full:
        continue
    for i, (k, name) in enumerate(keys):
        x = [r["wall_s"] for r in sel]
        y = [abs(r[f"{k}_vs_full_pct"]) for r in sel]
        ax[0].scatter(x, y, marker=marker[lev], color=f"C{i}",
                      label=f"{name}" if lev == "reduced" else None)
if has_full:
    ax[0].set(xscale="log", yscale="log", xlabel="wall time of 0.1 s of voice [s]",
              ylabel="|distance from the full model| [%]",
              title="cost vs distance from the full model (o reduced, □ mixed)")
    ax[0].legend(fontsize=8)
for lev in levels:
    sel = [r for r in rows if r["level"] == lev]
    if not sel:
        continue
    ax[1].scatter([r["wall_s"] for r in sel], [abs(r["f1_vs_tract_pct"]) for r in sel],
                  marker=marker[lev], color="C0", label=f"F1 {lev}")
    ax[1].scatter([r["wall_s"] for r in sel], [abs(r["f2_vs_tract_pct"]) for r in sel],
                  marker=marker[lev], color="C1", label=f"F2 {lev}")
ax[1].axhline(10, color="k", lw=0.6, ls="--")
ax[1].set(xscale="log", xlabel="wall time of 0.1 s of voice [s]",
          ylabel="|sound F − tract F| [%]", title="the sound's F1/F2 against the tract's")
ax[1].legend(fontsize=7, ncol=3)
fig.tight_layout()
fig.savefig(os.path.join(out, f"voice_fidelity{suffix}.png"), dpi=110)
print("wrote", os.path.join(out, f"voice_fidelity{suffix}.csv"))
