#!/usr/bin/python3
"""Does the closing cycle reach a limit cycle, and how fast?

At 0.2 s the closing cycle (ζ1 = ζ2 = 0.02, the preset
demos/glottis/closing_cycle.toml) still drifts: its cycle-mean flow falls
about 0.4 % per 25 ms because the fold's mean opening shrinks
(bench/glottis_drift_fields.py). This script follows the fold's motion
cycle by cycle, long enough to see where it goes:

- per cycle (one upward crossing of the half-gap g = 0.05 mm to the next):
  f0 = 1/period, the largest and the mean flow, the open quotient (the
  share of steps not flagged closed), the largest half-gap, and the first
  harmonic of the translation h and of the rotation φ over the cycle
  (amplitude, and the phase of φ against h): the two modes' share of the
  motion;
- per run, for each of these, the fit y(t) = y∞ + A exp(−t/τ) to the
  cycles after T_FIT (at least MIN_FIT of them): the time constant of the
  approach and the value it tends to, and the mean of the last 25 ms
  against that limit;
- the 25 ms window means, and the first window after which every later
  window mean stays within 0.5 % of the last one (the settled time).

Runs: the reference (h_gap 0.035 mm, Δt 1e-5, quadrature degree 4)
continued to 0.5 s from its 0.2 s checkpoint (--restart, log
run_restart_05s.log), the preset demos/glottis/closing_cycle.toml as
committed (the same mesh and Δt at quadrature degree 2, the
fold's upper mode at 160 Hz: the preset's is 155 Hz) from
rest to 0.5 s (
  mpirun -n 2 fsai_glottis --config demos/glottis/closing_cycle.toml --vf.f2 160
      --duration 0.5 --stats_from 0.5 --write_every 0
      --checkpoint-every 10000 --output bench/results/run_glottis_preset_q2_05s
), the Δt/2 and
0.025 mm levels to 0.2 s, the 0.0175 mm level to 0.1 s at Δt 0.7e-5 and
to 0.25 s at Δt 0.5e-5, and the
reduced model (--flow bernoulli, the same fold and Δt; it runs 0.8 s in
seconds, in a temporary folder) at the same damping ζ = 0.02 and at half
and twice that: its settling time against ζ says whether the approach is
the structural modes' free decay (time constant 1/(ζ ω), 80 ms for the
100 Hz mode at ζ = 0.02). A fitted τ at the scan's lower end (5 ms) means
no exponential trend after T_FIT (an already settled or ringing sequence).

usage: bench/glottis_limit_cycle.py [BUILD_DIR]
writes bench/results/glottis_limit_cycle.csv (every cycle of every run),
glottis_limit_cycle_fit.csv (the fits) and glottis_limit_cycle.png
"""
import argparse
import json
import os
import subprocess
import tempfile

import numpy as np
from benchlib import glottal_cycles, write_rows, print_markdown_table

here = os.path.dirname(os.path.abspath(__file__))
res = os.path.join(here, "results")
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
args = ap.parse_args()
G_CROSS = 0.05e-3   # [m]: cycle starts (as glottis_cycle_peaks.py)
T_START = 0.03      # [s]: the start-up overshoot is over
T_FIT = 0.09        # [s]: the fits start here (the ±5 % start-up swing is over)
WINDOW = 0.025      # [s]
SETTLED = 0.005     # window means within 0.5 % of the last window's
MIN_FIT = 8         # cycles: fewer are not fitted
T_SHORT = 0.2       # [s]: the runs of every level reach this
TAUS = np.geomspace(0.005, 2.0, 400)  # [s]: the time constants the fit scans
RUNS = (("h 0.035 mm, dt 1e-5, to 0.5 s", "run_glottis_h035_dt1_z02_c75_05s"),
        ("h 0.035 mm, dt 5e-6, to 0.2 s", "run_glottis_h035_dt05_z02_c75_02s"),
        ("h 0.025 mm, dt 0.7e-5, to 0.2 s", "run_glottis_h025_dt07_z02_c75_02s"),
        # (its continuation, run_glottis_h0175_dt07_z02_c75_02s, stopped at
        # 0.155 s when its checkpoint was lost, short of T_SHORT: this is
        # the 0.1 s run)
        ("h 0.0175 mm, dt 0.7e-5, to 0.1 s", "run_glottis_h0175_dt07_z02_c75"),
        # the finest level at the others' jet CFL, to 0.2 s
        # (continued to 0.25 s from its step-40000 checkpoint,
        # run_restart_e.log; the first 0.2 s are the 0.2 s run's)
        ("h 0.0175 mm, dt 0.5e-5, to 0.25 s", "run_glottis_h0175_dt05_z02_c75_025s"),
        # the preset as committed (quadrature degree 2), from rest
        ("preset (degree 2), to 0.5 s", "run_glottis_preset_q2_05s"))
# the runs to 0.5 s: their own summaries (t >= 0.25 s) side by side
LONG_RUNS = ("run_glottis_h035_dt1_z02_c75_05s", "run_glottis_preset_q2_05s")
BERNOULLI = ["--flow", "bernoulli", "--dt", "1e-5", "--duration", "0.8"]
ZETAS = (0.02, 0.01, 0.04)  # the reduced model's modal damping: the closing cycle's and ×½, ×2
QUANTITIES = (("f0_hz", "f0 [Hz]"), ("q_peak_ls", "peak flow [l/s]"), ("q_mean_ls", "mean flow [l/s]"),
              ("open_quotient", "open quotient"), ("h_amp_mm", "h amplitude [mm]"),
              ("phi_amp_mrad", "φ amplitude [mrad]"), ("max_gap_mm", "largest half-gap [mm]"))


def fit_exponential(t, y):
    """y∞, A, τ of y = y∞ + A exp(−(t − t[0])/τ) by least squares; τ is
    scanned (the problem is linear in y∞ and A for a given τ). τ = inf when
    the best fit is a straight line (no approach seen)"""
    best = None
    for tau in TAUS:
        m = np.column_stack([np.ones_like(t), np.exp(-(t - t[0]) / tau)])
        c, *_ = np.linalg.lstsq(m, y, rcond=None)
        err = np.sum((m @ c - y) ** 2)
        if best is None or err < best[0]:
            best = (err, c[0], c[1], tau)
    _, y_inf, a, tau = best
    if tau == TAUS[-1]:
        return float("nan"), a, float("inf")
    return y_inf, a, tau


def fit(cyc, key):
    """fit_exponential over the cycles cyc (nan if fewer than MIN_FIT)"""
    if len(cyc) < MIN_FIT:
        return float("nan"), float("nan"), float("nan")
    return fit_exponential(np.array([x["t0_s"] for x in cyc]), np.array([x[key] for x in cyc]))


def windows(c, key):
    out, t0 = [], T_START
    while t0 < c[-1]["t0_s"]:
        w = [x[key] for x in c if t0 <= x["t0_s"] < t0 + WINDOW]
        if w:
            out.append((t0, sum(w) / len(w)))
        t0 += WINDOW
    return out


runs = [(name, glottal_cycles(os.path.join(res, run, "series.csv"), G_CROSS, T_START))
        for name, run in RUNS]
exe = os.path.join(args.build, "demos", "fsai_glottis")
if os.path.exists(exe):
    for zeta in ZETAS:
        with tempfile.TemporaryDirectory() as tmp:
            subprocess.run([exe] + BERNOULLI + ["--vf.zeta1", str(zeta), "--vf.zeta2", str(zeta),
                                                "--output", tmp], check=True, stdout=subprocess.DEVNULL)
            runs.append((f"bernoulli, ζ {zeta}",
                         glottal_cycles(os.path.join(tmp, "series.csv"), G_CROSS, T_START)))
runs = [(n, c) for n, c in runs if c]
fe_runs = [n for n, _ in runs if not n.startswith("bernoulli")]

rows, fits = [], []
for name, c in runs:
    rows += [dict(run=name, **x) for x in c]
    late = [x for x in c if x["t0_s"] >= T_FIT]
    # the same fit to the cycles that end by T_SHORT: every level ran that
    # far, and the long run shows how well it predicts
    short = [x for x in late if x["t0_s"] + 1 / x["f0_hz"] <= T_SHORT + 1e-9]
    for key, label in QUANTITIES:
        y_inf, a, tau = fit(late, key)
        y_short, _, tau_short = fit(short, key)
        last = [x[key] for x in c if x["t0_s"] >= c[-1]["t0_s"] - WINDOW]
        w = windows(c, key)
        settled = next((t0 for k, (t0, _) in enumerate(w)
                        if all(abs(m / w[-1][1] - 1) < SETTLED for _, m in w[k:-1])), None)
        fits.append({"run": name, "quantity": key, "cycles_fitted": len(late),
                     "fit_from_s": T_FIT, "until_s": c[-1]["t0_s"], "tau_s": tau, "limit": y_inf,
                     "tau_to_02s_s": tau_short, "limit_to_02s": y_short,
                     "last_window_mean": sum(last) / len(last),
                     "last_window_from_limit_pct": 100 * (sum(last) / len(last) / y_inf - 1),
                     "settled_from_s": settled if settled is not None and settled < w[-1][0]
                     else float("nan")})

print(f"Approach to the limit cycle: fit y∞ + A exp(−t/τ) to the cycles after {T_FIT} s; "
      f"'settled' = the first {1e3 * WINDOW:g} ms window after which every window mean stays within "
      f"{100 * SETTLED:g} % of the last window's (— if only the last one does)")
print_markdown_table((("run", lambda f: f["run"]), ("quantity", lambda f: f["quantity"]),
                      ("cycles", lambda f: f"{f['cycles_fitted']} to {1e3 * f['until_s']:.0f} ms"),
                      ("τ", lambda f: f"{1e3 * f['tau_s']:.0f} ms"),
                      ("limit y∞", lambda f: f"{f['limit']:.4g}"),
                      ("last 25 ms", lambda f: f"{f['last_window_mean']:.4g} "
                       f"({f['last_window_from_limit_pct']:+.2f} % from y∞)"),
                      ("settled from", lambda f: "—" if np.isnan(f["settled_from_s"])
                       else f"{1e3 * f['settled_from_s']:.0f} ms")), fits)

print(f"\nThe limits fitted to the cycles that end by {T_SHORT} s, against the first run's "
      f"(and its limit from all its cycles):")
ref = {f["quantity"]: f for f in fits if f["run"] == runs[0][0]}
print_markdown_table((("run", lambda f: f["run"]), ("quantity", lambda f: f["quantity"]),
                      ("τ", lambda f: f"{1e3 * f['tau_to_02s_s']:.0f} ms"),
                      ("limit", lambda f: f"{f['limit_to_02s']:.4g}"),
                      ("against the first run", lambda f: f"{100 * (f['limit_to_02s'] / ref[f['quantity']]['limit_to_02s'] - 1):+.2f} %"),
                      ("the first run's limit from all its cycles", lambda f: f"{ref[f['quantity']]['limit']:.4g}")),
                     [f for f in fits if f["quantity"] in ("f0_hz", "q_peak_ls", "q_mean_ls", "open_quotient")
                      and f["run"] in fe_runs and not np.isnan(f["limit_to_02s"])])

print(f"\n{1e3 * WINDOW:g} ms window means (first harmonics of h and φ, φ's phase lead over h):")
print_markdown_table((("run", lambda r: r[0]), ("window [ms]", lambda r: f"{1e3 * r[1]:.0f}"),
                      ("cycles", lambda r: str(len(r[2]))),
                      ) + tuple((label, (lambda k: lambda r: f"{np.mean([x[k] for x in r[2]]):.4g}")(key))
                                for key, label in QUANTITIES + (("phi_lead_deg", "φ lead [°]"),)),
                     [(name, t0, [x for x in c if t0 <= x["t0_s"] < t0 + WINDOW])
                      for name, c in runs for t0, _ in windows(c, "f0_hz")])

long_runs = []
for run in LONG_RUNS:
    path = os.path.join(res, run, "summary.json")
    if os.path.exists(path):
        with open(path) as f:
            sm = json.load(f)
        if sm.get("sim_time_s", 0) >= 0.5 - 1e-9:
            long_runs.append((run, sm))
if long_runs:
    ref_sm = long_runs[0][1]
    print("\nThe runs to 0.5 s, their own summaries over t >= 0.25 s (change against the first):")
    summary_keys = (("f0_hz", "f0 [Hz]", 1), ("open_quotient", "OQ", 1), ("q_peak_m3s", "peak flow [l/s]", 1e3),
                    ("q_peak_cycle_mean_m3s", "mean cycle peak [l/s]", 1e3),
                    ("closed_leakage", "leakage [% of peak]", 100), ("period_cv", "period CV [%]", 100))

    def summary_cell(sm, key, scale):
        """the value, and for the later runs its change against the first"""
        text = f"{scale * sm[key]:.4g}"
        if sm is not ref_sm:
            text += f" ({100 * (sm[key] / ref_sm[key] - 1):+.2f} %)"
        return text

    print_markdown_table((("run", lambda r: r[0]), ("cycles", lambda r: str(r[1]["cycles"])),
                          ("quadrature degree", lambda r: str(r[1]["parameters"]["fluid"]["quadrature_degree"])))
                         + tuple((label, lambda r, k=key, sc=scale: summary_cell(r[1], k, sc))
                                 for key, label, scale in summary_keys)
                         + (("wall [s]", lambda r: f"{r[1]['wall_s']:.0f} for "
                             f"{r[1]['sim_time_s'] - r[1].get('restarted_from_step', 0) * r[1]['parameters']['dt']:.2g} s"),),
                         long_runs)
write_rows(os.path.join(res, "glottis_limit_cycle.csv"), rows)
write_rows(os.path.join(res, "glottis_limit_cycle_fit.csv"), fits)

import matplotlib  # noqa: E402 (only for the picture)
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

keys = (("f0_hz", "f0 [Hz]"), ("q_peak_ls", "peak flow [l/s]"), ("q_mean_ls", "mean flow [l/s]"),
        ("h_amp_mm", "h amplitude [mm]"), ("phi_amp_mrad", "φ amplitude [mrad]"),
        ("phi_lead_deg", "φ lead over h [°]"))
fig, axs = plt.subplots(3, 2, figsize=(11, 9), sharex=True)
for ax, (key, label) in zip(axs.flat, keys):
    for name, c in runs:
        ax.plot([1e3 * x["t0_s"] for x in c], [x[key] for x in c], ".-", ms=3, lw=0.8, label=name)
    ax.set_ylabel(label)
    ax.grid(alpha=0.3)
for ax in axs[-1]:
    ax.set_xlabel("cycle start [ms]")
axs[0, 0].legend(fontsize=7)
fig.suptitle("Closing cycle (ζ = 0.02, 1200 Pa), cycle by cycle")
fig.tight_layout()
fig.savefig(os.path.join(res, "glottis_limit_cycle.png"), dpi=110)
