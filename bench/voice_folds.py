#!/usr/bin/python3
"""The voice with the 2-DOF and with the elastic fold, side by side
(docs/voice.md, "The elastic fold in the voice"): the Bernoulli flow with
the 1D tract (reduced) and the FE tract (mixed), the same p_sub and vowel,
clamped fold ends
for the elastic fold (its plane-strain fold does not close every cycle at
800 Pa, docs/glottis.md). f0, open quotient, peak and mean flow, MFDR, SPL,
H1–H2, the subharmonic ratio of the sound and of the flow, and the
sound's F1/F2 (summary.json "voice").

With --flow fe, the full voice (FE flow, FE sound, 2 ranks, 0.1 s): each
fold on the voice's defaults (`fsai_demo` and `fsai_demo --fold elastic`:
the elastic fold on the glottis preset's settings and flow mesh). A
duration other than the default goes into the run folders' names
(_<duration>s); --folds picks the folds (2dof,elastic). --elastic_dt runs
the elastic fold at another Δt than its preset's 1e-5 (the former 2e-5:
_dt<Δt>), --elastic_h_gap on another gap mesh than its preset's 0.025 mm
(the former 0.05: _h<h_gap in mm>), --keep_cut_history with the halves of a cut step reusing the
coupling's IQN-ILS columns (--fe.cut_history keep, docs/model.md E13b, as
the committed 0.2 and 0.3 s rows were run, at Δt 2e-5 on 0.05 mm: _keep).

usage: bench/voice_folds.py [BUILD_DIR] [--p_sub 800] [--vowel u]
                            [--duration 0.3] [--acoustics 1d,fe]
                            [--flow bernoulli|fe] [--elastic_dt DT] [--elastic_h_gap MM]
                            [--keep_cut_history]
                            [--rerun]
writes bench/results/voice_folds.csv (voice_folds_fe.csv); run folders
bench/results/run_folds_<fold>_<p_sub>[_fe][_flowfe][_<duration>s][_dt<Δt>][_h<MM>][_keep]/
"""
import argparse
import csv
import os

from benchlib import MPI_ENV, timed_run

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--p_sub", default="800")
ap.add_argument("--vowel", default="u")
ap.add_argument("--duration", default=None, help="0.3 (Bernoulli flow), 0.1 (FE flow)")
ap.add_argument("--acoustics", default="1d,fe",
                help="the sound's fidelities (fsai_demo --acoustics)")
ap.add_argument("--flow", default="bernoulli", choices=["bernoulli", "fe"])
ap.add_argument("--folds", default="2dof,elastic")
ap.add_argument("--rerun", action="store_true")
ap.add_argument("--keep_cut_history", action="store_true",
                help="the elastic fold with --fe.cut_history keep (the committed FE-flow rows)")
ap.add_argument("--elastic_dt", default=None,
                help="the elastic fold at this Δt instead of its preset's (the former 2e-5)")
ap.add_argument("--elastic_h_gap", default=None,
                help="the elastic fold's gap cells [mm] instead of its preset's (the former 0.05)")
args = ap.parse_args()
fe_flow = args.flow == "fe"
default_duration = "0.1" if fe_flow else "0.3"
args.duration = args.duration or default_duration
if fe_flow:
    args.acoustics = "fe"
exe = os.path.join(args.build, "demos", "fsai_demo")
out = os.path.join(here, "results")
os.makedirs(out, exist_ok=True)
# Clamped ends: given for the Bernoulli flow, the default in the FE flow
folds = {"2dof": [], "elastic": ["--fold", "elastic", "--elastic.clamped_ends"]
         + (["--fe.cut_history", "keep"] if args.keep_cut_history and fe_flow else [])
         + (["--dt", args.elastic_dt] if args.elastic_dt else [])
         + (["--fe.h_gap", f"{args.elastic_h_gap}e-3"] if args.elastic_h_gap else [])}
# The elastic fold's variant, in its run folders' and the table's names
variant = (f"_dt{args.elastic_dt}" if args.elastic_dt else "") \
    + (f"_h{args.elastic_h_gap}" if args.elastic_h_gap else "") \
    + ("_keep" if args.keep_cut_history else "")
rows = []


def nan_if_none(x):
    """A summary's measure (null where it could not be taken, or absent)"""
    return float("nan") if x is None else x


runs = [(p, ac, fold) for p in args.p_sub.split(",")
        for ac in args.acoustics.split(",") for fold in args.folds.split(",")]
for p, ac, fold in runs:
    opts = folds[fold]
    d = os.path.join(out, f"run_folds_{fold}_{p}" + ("" if ac == "1d" else f"_{ac}")
                     + ("_flowfe" if fe_flow else "")
                     + ("" if args.duration == default_duration else f"_{args.duration}s")
                     + (variant if fold == "elastic" else ""))
    launch = ["mpirun", "-n", "2", exe] if fe_flow else [exe]
    s = timed_run(launch + ["--flow", args.flow, "--acoustics", ac,
                   "--vowel", args.vowel, "--p-sub", p,
                   "--duration", args.duration, "--report=false",
                   "--output", d] + opts, d, args.rerun, env=MPI_ENV)
    if s is None:
        raise SystemExit(1)
    wall = s["process_wall_s"]
    v = s["voice"]
    F = (v.get("formants_hz") or []) + [float("nan")] * 2
    rows.append(dict(fold=fold, acoustics=ac, p_sub=p, f0_hz=v["f0_hz"], sound_f0_hz=s["f0_hz"],
                     oq=v["open_quotient"], q_peak_ls=v["q_peak_ls"],
                     q_mean_ls=v["q_mean_ls"], mfdr_ls2=v["mfdr_ls2"],
                     spl_db=v["spl_db"], h1_h2_db=v["h1_h2_db"],
                     shr=nan_if_none(v.get("shr")), shr_flow=nan_if_none(v.get("shr_flow")),
                     jitter_pct=v["jitter_pct"], f1_hz=F[0], f2_hz=F[1],
                     wall_s=wall))
    r = rows[-1]
    print(f"{fold:8s} {ac} {p} Pa: f0 {r['f0_hz']:.1f} Hz (sound {r['sound_f0_hz']:.1f}), "
          f"OQ {r['oq']:.3f}, Q peak {r['q_peak_ls']:.3f} mean {r['q_mean_ls']:.3f} l/s, "
          f"MFDR {r['mfdr_ls2']:.0f} l/s², SPL {r['spl_db']:.1f} dB, H1-H2 {r['h1_h2_db']:.1f} dB, "
          f"SHR {r['shr']:.3f} (flow {r['shr_flow']:.3f}), "
          f"F1/F2 {r['f1_hz']:.0f}/{r['f2_hz']:.0f} Hz, jitter {r['jitter_pct']:.2f} %, "
          f"wall {wall:.1f} s", flush=True)
table = "voice_folds" + ("_fe" if fe_flow else "") \
    + ("" if args.duration == default_duration else f"_{args.duration}s") + variant + ".csv"
with open(os.path.join(out, table), "w",
          newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
    w.writeheader()
    for r in rows:
        w.writerow({k: (f"{x:.5g}" if isinstance(x, float) else x) for k, x in r.items()})
