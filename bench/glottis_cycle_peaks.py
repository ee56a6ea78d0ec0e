#!/usr/bin/python3
"""The closing cycle's peak glottal flow, cycle by cycle.

In t in [0.05, 0.1] s the peak flow of the closing cycle (ζ1 = ζ2 = 0.02,
bench/glottis_closure_converged.py) swings by about ±5 % from cycle to
cycle, and the three mesh levels of bench/glottis_fe_convergence.py
(h_gap 0.035 / 0.025 / 0.0175 mm) compare single maxima or 7-cycle means
of that swinging sequence. This script asks three questions of the runs:

1. Is the swing numerical noise or a property of the coupled solution?
   Each level's cycles are paired with the reference's (h_gap 0.035 mm,
   Δt 1e-5) by their number after t = 30 ms (the k-th with the k-th, as
   long as their starts lie within half a period: the finest mesh's period
   is 1 % shorter, its cycles drift) and their peak flows compared pair by
   pair. Noise would give ratios scattered as widely as the swing; a mesh
   effect gives a steady ratio.
2. Does the FE cycle settle? The reference continued to 0.2 s (case
   dt1_z02_c75_02s): the spread of the per-cycle peaks in successive 25 ms
   windows, and the mean peak of each window.
3. How long does the swing take to die out, and what does it do to the
   statistics compared? The reduced model (--flow bernoulli, the same
   fold, damping and Δt) runs 0.5 s in seconds: its per-cycle peaks in
   the same windows against its settled value (the mean of the cycles
   after 0.4 s). Its run goes to a temporary folder; its cycles are kept
   in the CSV.

Cycles run from one upward crossing of the half-gap g = 0.05 mm to the
next (the gap swings from about −0.1 to 0.52 mm); the peak of a cycle is
its largest Q.

usage: bench/glottis_cycle_peaks.py [BUILD_DIR]
writes bench/results/glottis_cycle_peaks.csv (every cycle of every run)
"""
import argparse
import math
import os
import subprocess
import tempfile

from benchlib import read_float_rows, upward_crossings, write_rows

here = os.path.dirname(os.path.abspath(__file__))
res = os.path.join(here, "results")
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
args = ap.parse_args()
G_CROSS = 0.05e-3  # [m]
T_START = 0.03     # [s]: the start-up overshoot is over (closing_converged's t_settle)
REFERENCE = ("h 0.035 mm, dt 1e-5, to 0.2 s", "run_glottis_h035_dt1_z02_c75_02s")
RUNS = (("h 0.035 mm, dt 1e-5", "run_glottis_h035_dt1_z02_c75"),
        ("h 0.035 mm, dt 5e-6", "run_glottis_h035_dt05_z02_c75"),
        ("h 0.025 mm, dt 1e-5", "run_glottis_h025_dt1_z02_c75"),
        ("h 0.025 mm, dt 0.7e-5", "run_glottis_h025_dt07_z02_c75"),
        ("h 0.0175 mm, dt 0.7e-5", "run_glottis_h0175_dt07_z02_c75"),
        ("h 0.025 mm, dt 0.7e-5, to 0.2 s", "run_glottis_h025_dt07_z02_c75_02s"),
        ("h 0.035 mm, dt 5e-6, to 0.2 s", "run_glottis_h035_dt05_z02_c75_02s"),
        ("h 0.0175 mm, dt 0.7e-5, to 0.2 s", "run_glottis_h0175_dt07_z02_c75_02s"),
        # the finest level again from rest at the others' jet CFL
        # (reached 0.2 s)
        ("h 0.0175 mm, dt 0.5e-5, to 0.2 s", "run_glottis_h0175_dt05_z02_c75_02s"))
WINDOW = 0.025  # [s]: the long run's windows
# the cycles that start in [0.1, 0.15) s, which every run to 0.2 s
# completes (the finest level's ended at 0.155 s)
LATE = (0.1, 0.15)  # [s]
# and the cycles that start in [0.1, 0.19) s, for the runs that
# reach 0.2 s (a cycle is 6.5 ms)
LATE_FULL = (0.1, 0.19)  # [s]
# the five cycles the finest level at dt 0.5e-5 had completed when
# it was paused at 0.14 s (the first rows of docs/glottis.md's table)
LATE_PARTIAL = (0.095, 0.125)  # [s]


def cycles(run):
    """(start [s], period [s], peak Q [m³/s]) of every whole cycle after T_START"""
    path = os.path.join(res, run, "series.csv")  # (run: a folder in res, or absolute)
    if not os.path.exists(path):
        return []
    r = [(x["t_s"], x["gap_m"], x["Q_m3s"]) for x in read_float_rows(path)]
    up = [i for i in upward_crossings([x[1] for x in r], G_CROSS) if r[i - 1][0] > T_START]
    return [(r[a][0], r[b][0] - r[a][0], max(x[2] for x in r[a:b])) for a, b in zip(up, up[1:])]


def window_stats(c, t0, t1):
    """(cycles, f0 = cycles / their duration, mean peak, (max − min) / mean
    of the peaks, CV of the period, first and last start) of the cycles of c
    starting in [t0, t1); None if there are none"""
    w = [x for x in c if t0 <= x[0] < t1]
    if not w:
        return None
    f0 = len(w) / sum(x[1] for x in w)
    q = [x[2] for x in w]
    qm = sum(q) / len(q)
    cv = math.sqrt(sum((x[1] - 1 / f0) ** 2 for x in w) / len(w)) * f0
    return len(w), f0, qm, (max(q) - min(q)) / qm, cv, w[0][0], w[-1][0]


ref_name, ref_run = REFERENCE
ref = cycles(ref_run)
if not ref:
    ref_name, ref_run = RUNS[0]
    ref = cycles(ref_run)
rows = []
print(f"Per-cycle peak flow against the reference ({ref_name}), cycles paired by number:")
print("| run | cycles paired | cycle starts [ms] | peak flow of each cycle [l/s] | against the reference, "
      "each cycle | mean | range |")
print("|---|---|---|---|---|---|---|")
for name, run in (REFERENCE,) + RUNS:
    c = cycles(run)
    if not c:
        continue
    pairs = []
    for k, (t, T, q) in enumerate(c):
        paired = k < len(ref) and abs(ref[k][0] - t) < 0.5 * T
        d = 100 * (q / ref[k][2] - 1) if paired else float("nan")
        rows.append({"run": name, "cycle_start_s": t, "period_s": T, "q_peak_ls": 1e3 * q,
                     "reference_cycle_start_s": ref[k][0] if paired else float("nan"),
                     "change_from_reference_pct": d})
        if paired and run != ref_run:
            pairs.append((t, q, d))
    if run == ref_run or not pairs:
        continue
    ds = [d for _, _, d in pairs]
    print(f"| {name} | {len(pairs)} | " + " ".join(f"{1e3 * t:.1f}" for t, _, _ in pairs) + " | "
          + " ".join(f"{1e3 * q:.3f}" for _, q, _ in pairs) + " | "
          + " ".join(f"{d:+.1f}" for d in ds) + f" % | {sum(ds) / len(ds):+.2f} % | "
          f"{min(ds):+.1f} … {max(ds):+.1f} % |")

for t0, t1 in (LATE_PARTIAL, LATE, LATE_FULL):
    print(f"\nThe same cycles late in the run (those starting in [{t0}, {t1}) s), against the reference:")
    print("| run | cycles | their starts [ms] | f0 = cycles / their duration | mean of the cycle peaks | f0 change "
          "| mean peak change | cycle-to-cycle: peaks (max − min) / mean | period CV |")
    print("|---|---|---|---|---|---|---|---|---|")
    late_ref = None
    for name, run in (REFERENCE,) + RUNS:
        c = cycles(run)
        # every cycle that starts before t1 is whole if the run's last whole
        # cycle ends after t1; a run that stops less than a period earlier
        # (the finest level at dt 0.7e-5, stopped at 0.155 s) misses its last
        # one, and is marked; a run still going is left out
        end = c[-1][0] + c[-1][1] if c else 0.0
        st = window_stats(c, t0, t1) if c and end >= t1 - c[-1][1] else None
        if st is None:
            continue
        n, f0, qm, spread, cv, first, last = st
        late_ref = late_ref or (f0, qm)
        short = f" (its last whole cycle ends at {1e3 * end:.1f} ms)" if end < t1 else ""
        print(f"| {name}{short} | {n} | {1e3 * first:.1f} … {1e3 * last:.1f} | {f0:.2f} Hz | "
              f"{1e3 * qm:.4f} l/s | {100 * (f0 / late_ref[0] - 1):+.2f} % | "
              f"{100 * (qm / late_ref[1] - 1):+.2f} % | {100 * spread:.2f} % | {100 * cv:.2f} % |")

print(f"\nThe start-up swing of {ref_name}, {1e3 * WINDOW:g} ms windows:")
print("| window [ms] | cycles | f0 | mean peak flow | spread of the peaks (max − min) / mean |")
print("|---|---|---|---|---|")
t0 = T_START
while ref and t0 < ref[-1][0]:
    st = window_stats(ref, t0, t0 + WINDOW)
    if st:
        n, f0, mean, spread = st[:4]
        print(f"| {1e3 * t0:.0f}–{1e3 * (t0 + WINDOW):.0f} | {n} | {f0:.2f} Hz | {1e3 * mean:.4f} l/s | "
              f"{100 * spread:.2f} % |")
    t0 += WINDOW

# 3. The reduced model of the same fold, long enough to settle
BERNOULLI = ["--flow", "bernoulli", "--dt", "1e-5", "--vf.zeta1", "0.02", "--vf.zeta2", "0.02",
             "--duration", "0.5"]
T_SETTLED = 0.4  # [s]
exe = os.path.join(args.build, "demos", "fsai_glottis")
if os.path.exists(exe):
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([exe] + BERNOULLI + ["--output", tmp], check=True, stdout=subprocess.DEVNULL)
        b = cycles(tmp)
    settled = [q for t, _, q in b if t >= T_SETTLED]
    q_inf = sum(settled) / len(settled)
    rows += [{"run": "bernoulli " + " ".join(BERNOULLI[2:]), "cycle_start_s": t, "period_s": T,
              "q_peak_ls": 1e3 * q, "reference_cycle_start_s": float("nan"),
              "change_from_reference_pct": 100 * (q / q_inf - 1)} for t, T, q in b]
    print(f"\nThe reduced model, {' '.join(BERNOULLI)}: settled peak flow {1e3 * q_inf:.4f} l/s "
          f"(mean of the {len(settled)} cycles after {T_SETTLED} s); windows against it:")
    print("| window [s] | cycles | largest peak | mean of the cycle peaks | spread (max − min) |")
    print("|---|---|---|---|---|")
    for t0, t1 in ((0.05, 0.1), (0.1, 0.15), (0.15, 0.2), (0.2, 0.25), (0.25, 0.3), (0.3, 0.4)):
        q = [x[2] for x in b if t0 <= x[0] < t1]
        print(f"| [{t0}, {t1}] | {len(q)} | {100 * (max(q) / q_inf - 1):+.2f} % | "
              f"{100 * (sum(q) / len(q) / q_inf - 1):+.2f} % | {100 * (max(q) - min(q)) / q_inf:.2f} % |")
write_rows(os.path.join(res, "glottis_cycle_peaks.csv"), rows)
