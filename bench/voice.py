#!/usr/bin/python3
"""The voice scene (fsai_demo, 2 MPI ranks): the default voice (the converged
closing cycle's flow), and on the glottis scene's own flow speed vs accuracy over three
resolutions of flow mesh, acoustic mesh and time step, and the comparison
runs — vowels a and i and the tract replaced by a short
straight tube (default and coarse resolution), the variants of the
monopole pair and the acoustic glottis (default resolution), the sound's
Newmark step without numerical damping (trapezoidal, medium and default
resolution), and on the
coarse resolution the Lighthill source without its taper (truncated at
the flow outlet) and an absorbing layer instead of the Sommerfeld
condition; and the lossless tract (rigid walls, sound-hard
subglottal end) where the sound fails.

Errors: f0 of the sound against the fold's f0 of the same run; F1, F2 from
the sound (LPC of its periodic part; the LPC of the whole window is listed
too) against the transfer-function formants of the same tract
(1D model, closed glottis) and of the acoustic domain as modelled (1D, its
open rest glottis and subglottal end); f0 and SPL also against the finest
resolution.

usage: bench/voice.py [BUILD_DIR] [--only NAME,...] [--rerun]
writes bench/results/voice.csv, voice.png; run folders
bench/results/run_voice_<name>/ (series, spectrum, WAV, summary)
"""
import argparse
import csv
import json
import os
import subprocess

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--only", default="")
ap.add_argument("--rerun", action="store_true")
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_demo")
out = os.path.join(here, "results")
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")

# The default voice's flow is the converged closing cycle's (0.35/0.035 mm
# mesh, the preset's fold, quadrature degree 2, porous ramp: run
# "u_converged"). The study below was made on the glottis scene's own
# flow: its fold and porous switch (old_fold), at three resolutions
# (coarse, medium, and "default" = the scene's 0.5/0.05 mm mesh)
old_fold = ["--vf.f2", "160", "--vf.zeta1", "0.05", "--vf.zeta2", "0.05",
            "--fluid.quadrature_degree", "4", "--closure.porous_ramp", "0"]
coarse = ["--fe.h_far", "1e-3", "--fe.h_gap", "0.1e-3", "--voice.h", "0.008", "--dt", "4e-5"] + old_fold
medium = ["--fe.h_far", "0.7e-3", "--fe.h_gap", "0.07e-3", "--voice.h", "0.006", "--dt", "3e-5"] + old_fold
scene = ["--fe.h_far", "0.5e-3", "--fe.h_gap", "0.05e-3"] + old_fold
rigid = ["--voice.yielding_walls=false", "--voice.subglottal", "hard"]
# The sound's Newmark step without numerical damping (γ = ½, the default
#): the high-frequency ringing it keeps
trapezoidal = ["--wave.newmark_gamma", "0.5", "--wave.newmark_beta", "0.25"]
runs = {
    "u_converged": [],
    "u_coarse": coarse,
    "u_medium": medium,
    "u_default": scene,
    "u_medium_trapezoidal": medium + trapezoidal,
    "u_default_trapezoidal": scene + trapezoidal,
    "a_default": scene + ["--vowel", "a"],
    "i_default": scene + ["--vowel", "i"],
    "tube_default": scene + ["--tract", "tube"],
    # The acoustic glottis and the monopole pair (both on by default): each
    # alone, and neither (Lighthill's source and the rest slit: the default
    #)
    "u_default_lighthill_only": scene + ["--voice.monopole=false", "--voice.glottal_slit=false"],
    "u_default_slit_only": scene + ["--voice.monopole=false"],
    "u_default_monopole_only": scene + ["--voice.glottal_slit=false"],
    "a_coarse": coarse + ["--vowel", "a"],
    "i_coarse": coarse + ["--vowel", "i"],
    "tube_coarse": coarse + ["--tract", "tube"],
    "notaper_coarse": coarse + ["--voice.taper=false"],
    "pml_coarse": coarse + ["--radiation", "pml"],
    # Where it fails: the lossless tract (rigid walls, sound-hard
    # subglottal end) at all three resolutions, and the hard end alone
    "u_coarse_rigid": coarse + rigid,
    "u_medium_rigid": medium + rigid,
    "u_default_rigid": scene + rigid,
    "u_hardend_coarse": coarse + ["--voice.subglottal", "hard"],
}
only = [s for s in args.only.split(",") if s]
rows = []
for name, extra in runs.items():
    if only and name not in only:
        continue
    run = os.path.join(out, f"run_voice_{name}")
    if args.rerun or not os.path.exists(os.path.join(run, "summary.json")):
        # The tract of this study: the flow domain's channel replaces the
        # vowel's first 40 mm (the voice before the tract followed the vowel
        # from the glottis: docs/voice.md, "Every vowel sounds like itself")
        cmd = ["mpirun", "-n", "2", exe, "--write_every", "0", "--voice.tract_start", "outlet",
               "--report=false", "--output", run] + extra
        print(" ".join(cmd), flush=True)
        subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(run, "summary.json")) as f:
        s = json.load(f)
    F, Ft = s["formants_from_sound_hz"], s["tract_formants_hz"]
    Fw = s.get("formants_lpc_window_hz", F) + [float("nan")] * 2
    Fd = s.get("domain_formants_hz", [float("nan")] * 2)  # not in stop-15 runs
    Fd = Fd + [float("nan")] * (2 - len(Fd))
    err = [100 * (F[k] - Ft[k]) / Ft[k] if k < len(F) else float("nan") for k in range(2)]
    derr = [100 * (F[k] - Fd[k]) / Fd[k] if k < len(F) else float("nan") for k in range(2)]
    # The share of the microphone signal's energy above 5 kHz (t >= 50 ms):
    # what the sound step's high-frequency ringing holds (the vowel's
    # harmonics that matter lie below 4 kHz)
    ser = np.genfromtxt(os.path.join(run, "series.csv"), delimiter=",", names=True)
    win = ser["t_s"] >= 0.05
    pm = ser["p_mic_pa"][win] - ser["p_mic_pa"][win].mean()
    P = np.abs(np.fft.rfft(pm)) ** 2
    fP = np.fft.rfftfreq(len(pm), ser["t_s"][1] - ser["t_s"][0])
    hf = P[fP > 5000].sum() / P.sum() if P.sum() > 0 else float("nan")
    rows.append(dict(name=name, vowel=s["vowel"], wall_s=s["loop_wall_s"],
                     flow_dofs=s["flow_dofs"], acoustic_dofs=s["acoustic_dofs"],
                     f0_fold=s["f0_fold_hz"], f0_sound=s["f0_hz"],
                     f0_err=100 * (s["f0_hz"] - s["f0_fold_hz"]) / s["f0_fold_hz"],
                     F1=F[0] if F else float("nan"), F2=F[1] if len(F) > 1 else float("nan"),
                     F1_tract=Ft[0], F2_tract=Ft[1], F1_err=err[0], F2_err=err[1],
                     F1_window=Fw[0], F2_window=Fw[1],
                     periodic_fraction=s.get("periodic_fraction", float("nan")),
                     F1_domain=Fd[0], F2_domain=Fd[1], F1_domain_err=derr[0],
                     F2_domain_err=derr[1],
                     spl_db=s["spl_db"], hf_share=hf, cycles=s["cycles"],
                     closes=s["closes_every_cycle"]))
    r = rows[-1]
    print(f"{name:15s} wall {r['wall_s']:7.1f} s  f0 fold {r['f0_fold']:7.2f} sound "
          f"{r['f0_sound']:7.2f} ({r['f0_err']:+.2f} %)  F1 {r['F1']:6.0f}/{r['F1_tract']:6.0f} "
          f"({r['F1_err']:+.1f} %)  F2 {r['F2']:6.0f}/{r['F2_tract']:6.0f} ({r['F2_err']:+.1f} %)"
          f"  as modelled {r['F1_domain']:6.0f}/{r['F2_domain']:6.0f} "
          f"({r['F1_domain_err']:+.1f} / {r['F2_domain_err']:+.1f} %)"
          f"  SPL {r['spl_db']:.1f} dB  above 5 kHz {100 * r['hf_share']:.1f} %", flush=True)

if rows:
    path = os.path.join(out, "voice.csv" if not only else "voice_partial.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
res = [r for r in rows if r["name"] in ("u_coarse", "u_medium", "u_default")]
if len(res) == 3:
    fine = res[-1]
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for key, lab in (("f0_sound", "f0 vs finest"), ("F1", "F1 vs finest"),
                     ("F2", "F2 vs finest")):
        ax.loglog([r["wall_s"] for r in res[:-1]],
                  [max(abs(r[key] - fine[key]) / fine[key] * 100, 1e-3) for r in res[:-1]],
                  "o-", label=lab)
    ax.loglog([r["wall_s"] for r in res[:-1]],
              [max(abs(r["spl_db"] - fine["spl_db"]), 1e-3) for r in res[:-1]],
              "s--", label="SPL vs finest [dB]")
    ax.loglog([r["wall_s"] for r in res], [max(abs(r["F1_err"]), 1e-3) for r in res],
              "^:", label="F1 vs tract (1D) [%]")
    ax.loglog([r["wall_s"] for r in res], [max(abs(r["F2_err"]), 1e-3) for r in res],
              "v:", label="F2 vs tract (1D) [%]")
    for r in res:
        ax.annotate(r["name"].split("_")[1], (r["wall_s"], max(abs(r["F1_err"]), 1e-3)),
                    fontsize=7)
    ax.set_xlabel("wall time of 0.1 s simulated [s] (2 ranks)")
    ax.set_ylabel("error [%] (SPL: dB)")
    ax.set_title("fsai_demo --vowel u: accuracy vs cost")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "voice.png"), dpi=120)

# Where it fails: the microphone signal of a variant minus the reference's
# (same resolution, same flow: the flow is computed identically, only the
# acoustics differ), over the analysis window t >= 50 ms


def mic(name):
    path = os.path.join(out, f"run_voice_{name}", "series.csv")
    if not os.path.exists(path):
        return None, None
    d = np.genfromtxt(path, delimiter=",", names=True)
    return d["t_s"], d["p_mic_pa"]


pairs = [("notaper_coarse", "u_coarse", "source not tapered"),
         ("pml_coarse", "u_coarse", "absorbing layer instead of Sommerfeld"),
         ("u_hardend_coarse", "u_coarse", "sound-hard subglottal end")]
diff_rows = []
for a, b, what in pairs:
    ta, pa = mic(a)
    tb, pb = mic(b)
    if ta is None or tb is None or len(ta) != len(tb):
        continue
    w = ta >= 0.05
    d = pa[w] - pb[w]
    rms_d = np.sqrt(np.mean((d - d.mean()) ** 2))
    rms_b = np.sqrt(np.mean((pb[w] - pb[w].mean()) ** 2))
    dt = ta[1] - ta[0]
    D = np.abs(np.fft.rfft((d - d.mean()) * np.hanning(len(d)), 8 * len(d)))
    f = np.fft.rfftfreq(8 * len(d), dt)
    band = f > 50
    f_peak = f[band][np.argmax(D[band])]
    diff_rows.append(dict(variant=a, reference=b, what=what, rms_diff_pa=rms_d,
                          rms_ref_pa=rms_b,
                          level_db_re_20upa=20 * np.log10(rms_d / 20e-6),
                          level_db_re_signal=20 * np.log10(rms_d / rms_b),
                          diff_peak_hz=f_peak))
    r = diff_rows[-1]
    print(f"{a} - {b} ({what}): rms difference {rms_d:.3g} Pa of {rms_b:.3g} Pa "
          f"= {r['level_db_re_20upa']:.1f} dB re 20 uPa, {r['level_db_re_signal']:+.1f} dB "
          f"re signal; difference spectrum peaks at {f_peak:.0f} Hz")
if diff_rows:
    with open(os.path.join(out, "voice_differences.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(diff_rows[0]))
        w.writeheader()
        w.writerows(diff_rows)
