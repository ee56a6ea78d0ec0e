#!/usr/bin/python3
"""Convergence of the FE glottis model (fsai_glottis --flow fe, p_sub =
1200 Pa): f0, peak glottal flow and the gap's range for the default run
(Delta t = 2e-5 s, h_gap = 0.05 mm, h_far = 0.5 mm), Delta t halved, and
the mesh refined by 1/0.7 (h_gap = 0.035 mm, h_far = 0.35 mm), in two
windows: t in [0.025, 0.05] s (still growing: the runs, 0.05 s
long) and t in [0.05, 0.1] s (the limit cycle: 0.1 s runs). f0 from the
upward crossings of the mean gap, as fsai_glottis computes it. The runs
(2 ranks) are made by

  mpirun -n 2 fsai_glottis --flow fe --duration 0.1  --output bench/results/run_glottis_fe_default
  mpirun -n 2 fsai_glottis --flow fe --duration 0.05 --dt 1e-5 --output .../run_glottis_conv_dt1e-5
  mpirun -n 2 fsai_glottis --flow fe --duration 0.05 --fe.h_gap 0.035e-3 --fe.h_far 0.35e-3 \\
      --output .../run_glottis_conv_fine
  (the same with --duration 0.1 --write_every 0: run_glottis_conv_dt1e-5_01,
   run_glottis_conv_fine_01; these four with --coupling.predictor displacement,
   the default)

The study on the 0.035 mm mesh (the coarsest whose forces are converged at
a held glottis, bench/glottis_static_flow.py), 0.1 s at 2 ranks with
--write_every 0, the window [0.05, 0.1] s:
  --fe.h_gap 0.035e-3 --fe.h_far 0.35e-3                run_glottis_conv_fine_01_load
  the same with --dt 1e-5                                run_glottis_h035_dt1e-5
  --fe.h_gap 0.025e-3 --fe.h_far 0.25e-3                run_glottis_h025 (not run yet)
and run_glottis_conv_fine_01 (the displacement predictor) as the check that
the load predictor's run is the same coupled solution. The closing cycle on
that mesh (ζ1 = ζ2 = 0.02, Δt 1e-5 for 0.1 s and 5e-6 for 0.06 s;
h_gap 0.025 mm / h_far 0.25 mm at Δt 1e-5 for 0.06 s) is compared
in [0.03, 0.06] s (runs of bench/glottis_closure_converged.py), with
the single changes of that mesh (one size refined, the subglottal
channel coarser, the jet region finer) and the refinement of h and Δt
together at the same CFL (h_gap 0.025 mm, h_far 0.25 mm, Δt 0.7e-5).

The study adds the third level of that series, h_gap 0.0175 mm / h_far
0.175 mm at Δt 0.7e-5 (case h0175_dt07_z02_c75), and the observed order of
convergence with the grid convergence index of the three levels 0.035,
0.025, 0.0175 mm (Celik et al. 2008, J. Fluids Eng. 130:078001, eqs. 1-8;
the Δt of the levels, 1e-5 / 0.7e-5 / 0.7e-5, is treated as converged:
the 0.025 mm mesh's cycle at Δt 1e-5 and 0.7e-5 agree within 0.1-0.3 %).

The study adds the window t in [0.13, 0.2] s ("late": the fold's motion has
settled, the flow still drifts slowly) for the reference and the 0.025 mm
level run to 0.2 s (bench/glottis_cycle_peaks.py shows why [0.05, 0.1] s
is not settled). The study adds the reference's Δt/2 (5e-6) run to 0.2 s to
that window (case dt05_z02_c75_02s of glottis_closure_converged.py).
The study adds the finest level run to 0.2 s (case h0175_dt07_z02_c75_02s)
to that window, and the three levels' observed order in it. That run ended
at t = 0.155 s (its checkpoint was lost with the machine), so
The study adds the window t in [0.13, 0.155] s, the part of the late window
that every level reaches (3-4 cycles; bench/glottis_cycle_peaks.py pairs
its cycles one by one). The study adds the finest level run again from rest
at Δt 0.5e-5 (case h0175_dt05_z02_c75_02s: the jet CFL of the other two
levels) to the late window, as a third level of its own; it reached 0.2 s
in four legs ( from its checkpoints, logs run_restart_a-d.log).

The preset's fold has its upper mode at 155 Hz instead of 160 Hz
(demos/glottis/closing_cycle.toml, the male-range f0). Its mesh/Δt check,
the preset (degree 2, 2 ranks) from rest to 0.2 s, compared in the late
window [0.13, 0.2] s as above:
  mpirun -n 2 fsai_glottis --config demos/glottis/closing_cycle.toml
      --duration 0.2 --stats_from 0.5 --write_every 0 --checkpoint-every 4000
      [--dt 5e-6 | --fe.h_gap 0.025e-3 --fe.h_far 0.25e-3 --dt 0.7e-5]
      --output bench/results/run_glottis_f2_155_{dt05,h025_dt07}_02s
against run_glottis_preset_f2_155_02s (the same command with
--vf.f2 155 before it was the preset's).

usage: bench/glottis_fe_convergence.py   (writes bench/results/glottis_fe_convergence.csv
                                          and glottis_fe_three_levels.csv)
"""
import math
import os

from benchlib import read_float_rows, write_rows

here = os.path.dirname(os.path.abspath(__file__))
res = os.path.join(here, "results")
WINDOWS = {"growing": (0.025, 0.05), "limit cycle": (0.05, 0.1),
           "h 0.035 mm": (0.05, 0.1), "closing, h 0.035 mm": (0.03, 0.06),
           "closing, h 0.035 mm, settled": (0.05, 0.1),
           "closing, h 0.035 mm, late": (0.13, 0.2),
           "closing, h 0.035 mm, late to 0.155 s": (0.13, 0.155)}
RUNS = {"growing": (("default", "run_glottis_fe_default"),
                    ("dt/2", "run_glottis_conv_dt1e-5"),
                    ("h/1.43", "run_glottis_conv_fine")),
        "limit cycle": (("default", "run_glottis_fe_default"),
                        ("dt/2", "run_glottis_conv_dt1e-5_01"),
                        ("h/1.43", "run_glottis_conv_fine_01")),
        "h 0.035 mm": (("h 0.035 mm (load predictor)", "run_glottis_conv_fine_01_load"),
                       ("displacement predictor", "run_glottis_conv_fine_01"),
                       ("dt/2", "run_glottis_h035_dt1e-5"),
                       ("h 0.025 mm", "run_glottis_h025")),
        # the closing cycle on that mesh (bench/glottis_closure_converged.py,
        # cases dt1_z02_c75 and dt05_z02_c75: Δt 1e-5 and 5e-6, ζ 0.02)
        # ("repeat": the same configuration run again with the
        # faster solvers, which change only round-off: 2-rank runs are not
        # bitwise reproducible, and this measures what that does)
        "closing, h 0.035 mm": (("dt 1e-5", "run_glottis_h035_dt1_z02_c75"),
                                ("dt 5e-6", "run_glottis_h035_dt05_z02_c75"),
                                ("h 0.025 mm", "run_glottis_h025_dt1_z02_c75"),
                                ("dt 1e-5, repeat", "run_glottis_h035_dt1_z02_c75_s26"),
                                # one of the two sizes refined at a time
                                ("h_gap 0.025 mm only", "run_glottis_h035_hgap025_dt1_z02_c75"),
                                ("h_far 0.25 mm only", "run_glottis_h035_hfar025_dt1_z02_c75"),
                                # the subglottal channel coarser (0.7 mm)
                                ("h_inlet 0.7 mm", "run_glottis_h035_dt1_z02_c75_in07"),
                                ("h_jet 0.25 mm", "run_glottis_h035_dt1_z02_c75_jet025"),
                                # h and Δt refined together at the
                                # same CFL (h × 0.714, Δt × 0.7)
                                ("h 0.025 mm, dt 0.7e-5", "run_glottis_h025_dt07_z02_c75")),
        "closing, h 0.035 mm, settled": (("dt 1e-5", "run_glottis_h035_dt1_z02_c75"),
                                         ("dt 1e-5, repeat", "run_glottis_h035_dt1_z02_c75_s26"),
                                         # continued from 0.06 to 0.1 s
                                         ("h 0.025 mm", "run_glottis_h025_dt1_z02_c75"),
                                         # --fe.h_inlet 0.7e-3 and
                                         # --fluid.quadrature_degree 2
                                         ("h_inlet 0.7 mm, degree 2",
                                          "run_glottis_h035_dt1_z02_c75_in07_q2"),
                                         # continued from 0.056 to 0.1 s
                                         ("h 0.025 mm, dt 0.7e-5",
                                          "run_glottis_h025_dt07_z02_c75"),
                                         # the third level
                                         ("h 0.0175 mm, dt 0.7e-5",
                                          "run_glottis_h0175_dt07_z02_c75"))}
# [0.05, 0.1] s is not settled (bench/glottis_cycle_peaks.py); the
# fold's motion is from 0.13 s on, though the flow still drifts. The
# reference and the 0.025 mm level continued to 0.2 s
RUNS["closing, h 0.035 mm, late"] = (("dt 1e-5", "run_glottis_h035_dt1_z02_c75_02s"),
                                     ("h 0.025 mm, dt 0.7e-5", "run_glottis_h025_dt07_z02_c75_02s"),
                                     # the reference's Δt/2 to 0.2 s
                                     ("dt 5e-6", "run_glottis_h035_dt05_z02_c75_02s"),
                                     # the finest level to 0.2 s
                                     ("h 0.0175 mm, dt 0.7e-5", "run_glottis_h0175_dt07_z02_c75_02s"),
                                     # the finest level at the others' jet CFL
                                     ("h 0.0175 mm, dt 0.5e-5", "run_glottis_h0175_dt05_z02_c75_02s"))
# the preset with f2 = 155 Hz, its Δt/2 and its 0.025 mm level
WINDOWS["f2 155 Hz (preset), late"] = (0.13, 0.2)
RUNS["f2 155 Hz (preset), late"] = (("dt 1e-5", "run_glottis_preset_f2_155_02s"),
                                    ("dt 5e-6", "run_glottis_f2_155_dt05_02s"),
                                    ("h 0.025 mm, dt 0.7e-5", "run_glottis_f2_155_h025_dt07_02s"))
# the finest level stopped at 0.155 s; the late window cut there
RUNS["closing, h 0.035 mm, late to 0.155 s"] = RUNS["closing, h 0.035 mm, late"]
RUNS["closing, h 0.035 mm"] += (("h 0.0175 mm, dt 0.7e-5", "run_glottis_h0175_dt07_z02_c75"),)
# the three levels (h_gap [mm], run) for the observed order, coarse to fine,
# and the windows they are compared in
LEVELS = ((0.035, "run_glottis_h035_dt1_z02_c75"), (0.025, "run_glottis_h025_dt07_z02_c75"),
          (0.0175, "run_glottis_h0175_dt07_z02_c75"))
# the three levels continued to 0.2 s, compared late in the run as
# well
LEVELS_02S = ((0.035, "run_glottis_h035_dt1_z02_c75_02s"), (0.025, "run_glottis_h025_dt07_z02_c75_02s"),
              (0.0175, "run_glottis_h0175_dt07_z02_c75_02s"))
# the finest level again from rest at Δt 0.5e-5, the jet CFL of the
# other two levels (12.8 / 12.5; Δt 0.7e-5 gave it 17.9), to 0.2 s
LEVELS_02S_CFL = LEVELS_02S[:2] + ((0.0175, "run_glottis_h0175_dt05_z02_c75_02s"),)
# (t0, t1, levels, what sets them apart)
LEVEL_WINDOWS = ((0.03, 0.06, LEVELS, ""), (0.05, 0.1, LEVELS, ""), (0.13, 0.2, LEVELS_02S, ""),
                 (0.13, 0.155, LEVELS_02S, ""), (0.13, 0.2, LEVELS_02S_CFL, "finest at dt 0.5e-5"))


def stats(run, t0, t1):
    r = read_float_rows(os.path.join(res, run, "series.csv"))
    # (a run's last step may fall short of t1 by less than its Δt)
    if r[-1]["t_s"] < t1 - 1e-5:
        return None
    w = [x for x in r if t0 <= x["t_s"] <= t1 + 1e-12]
    g = [x["gap_m"] for x in w]
    t = [x["t_s"] for x in w]
    mean = sum(g) / len(g)
    cross = [t[i - 1] + (t[i] - t[i - 1]) * (mean - g[i - 1]) / (g[i] - g[i - 1])
             for i in range(1, len(g)) if g[i - 1] < mean <= g[i]]
    f0 = (len(cross) - 1) / (cross[-1] - cross[0]) if len(cross) > 1 else float("nan")
    # the peak of each whole cycle (between upward crossings), averaged: the
    # closing cycle is modulated (per-cycle peaks 0.83-0.92 l/s), and the
    # largest Q in a window follows the phase of that modulation
    peaks = [max(x["Q_m3s"] for x in w if a <= x["t_s"] < b) for a, b in zip(cross, cross[1:])]
    q_cyc = sum(peaks) / len(peaks) if peaks else float("nan")
    return f0, max(x["Q_m3s"] for x in w), len(cross) - 1, min(g), max(g), q_cyc


rows = []
print("| study | window | run | f0 | peak flow | mean cycle peak | cycles | gap min / max | f0 change "
      "| peak flow change | mean cycle peak change |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for win, (t0, t1) in WINDOWS.items():
    base = None
    for name, run in RUNS[win]:
        if not os.path.exists(os.path.join(res, run, "series.csv")):
            continue
        s = stats(run, t0, t1)
        if s is None:
            continue
        f0, qp, n, gmin, gmax, qc = s
        if base is None:
            base = (f0, qp, qc)
        rows.append({"study": win, "window": f"{t0}-{t1}", "run": name, "f0_hz": f0, "q_peak_ls": 1e3 * qp,
                     "q_cycle_peak_ls": 1e3 * qc,
                     "cycles": n, "gap_min_mm": 1e3 * gmin, "gap_max_mm": 1e3 * gmax,
                     "f0_change_pct": 100 * (f0 / base[0] - 1),
                     "q_peak_change_pct": 100 * (qp / base[1] - 1),
                     "q_cycle_peak_change_pct": 100 * (qc / base[2] - 1)})
        print(f"| {win} | [{t0}, {t1}] s | {name} | {f0:.2f} Hz | {1e3 * qp:.4f} l/s | {1e3 * qc:.4f} l/s | {n} | "
              f"{1e3 * gmin:+.3f} / {1e3 * gmax:.3f} mm | "
              f"{rows[-1]['f0_change_pct']:+.2f} % | {rows[-1]['q_peak_change_pct']:+.2f} % | "
              f"{rows[-1]['q_cycle_peak_change_pct']:+.2f} % |")
write_rows(os.path.join(res, "glottis_fe_convergence.csv"), rows)


def observed_order(h, phi):
    """Celik et al. (2008), eqs. 3-7, for three levels h[0] > h[1] > h[2]:
    the observed order p (fixed-point iteration of eq. 3, for refinement
    ratios that differ), the extrapolated value phi_ext (eq. 5) and the fine
    level's grid convergence index GCI_fine = 1.25 e21 / (r21^p - 1) (eq. 7),
    with r21 = h[1]/h[2] and e21 = |phi[2] - phi[1]| / |phi[2]|. No order
    (returns the reason as a string) for oscillatory convergence (the two
    changes of opposite sign), for a change that grows with refinement
    (|e21| >= |e32|: not in the asymptotic range; eq. 3's absolute value
    would turn it into a positive order) or for no change at all."""
    r21, r32 = h[1] / h[2], h[0] / h[1]
    e21, e32 = phi[2] - phi[1], phi[1] - phi[0]
    if abs(e21) < 1e-12 * abs(phi[2]):
        return "no change"
    if e21 * e32 <= 0:
        return "none (changes of opposite sign)"
    if abs(e21) >= abs(e32):
        return "none (the change grows with refinement)"
    p = 1.0
    for _ in range(100):
        q = math.log((r21 ** p - 1) / (r32 ** p - 1))
        p_new = abs(math.log(abs(e32 / e21)) + q) / math.log(r21)
        if abs(p_new - p) < 1e-10:
            break
        p = p_new
    ext = (r21 ** p * phi[2] - phi[1]) / (r21 ** p - 1)
    gci = 1.25 * abs(e21 / phi[2]) / (r21 ** p - 1)
    return p, ext, gci


print("\nThree levels (h_gap 0.035 / 0.025 / 0.0175 mm), observed order (Celik et al. 2008):")
print("| window | quantity | 0.035 mm | 0.025 mm | 0.0175 mm | change 0.035→0.025 | change 0.025→0.0175 "
      "| observed order p | extrapolated | GCI of 0.0175 mm | 0.025 mm from extrapolated |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
level_rows = []
for t0, t1, levels, note in LEVEL_WINDOWS:
    label = f"[{t0}, {t1}] s" + (f", {note}" if note else "")
    st = []
    for h, run in levels:
        if not os.path.exists(os.path.join(res, run, "series.csv")):
            break
        s = stats(run, t0, t1)
        if s is None:
            break
        st.append(s)
    if len(st) < 3:
        print(f"| {label} | (a level does not reach {t1} s yet) |")
        continue
    hs = [h for h, _ in levels]
    for name, k, scale, unit in (("f0", 0, 1.0, "Hz"), ("peak flow", 1, 1e3, "l/s"),
                                 ("mean cycle peak", 5, 1e3, "l/s")):
        phi = [scale * x[k] for x in st]
        o = observed_order(hs, phi)
        why, o = (o, None) if isinstance(o, str) else ("", o)
        c1, c2 = 100 * (phi[1] / phi[0] - 1), 100 * (phi[2] / phi[1] - 1)
        row = {"window": f"{t0}-{t1}" + (f" ({note})" if note else ""), "quantity": name, "coarse": phi[0], "medium": phi[1], "fine": phi[2],
               "change_coarse_medium_pct": c1, "change_medium_fine_pct": c2,
               "order": o[0] if o else float("nan"), "extrapolated": o[1] if o else float("nan"),
               "gci_fine_pct": 100 * o[2] if o else float("nan"),
               "medium_from_extrapolated_pct": 100 * (phi[1] / o[1] - 1) if o else float("nan")}
        level_rows.append(row)
        tail = (f"{o[0]:.2f} | {o[1]:.4f} {unit} | {100 * o[2]:.2f} % | {row['medium_from_extrapolated_pct']:+.2f} %"
                if o else f"{why} | | |")
        print(f"| {label} | {name} | {phi[0]:.4f} | {phi[1]:.4f} | {phi[2]:.4f} | {c1:+.2f} % | {c2:+.2f} % "
              f"| {tail} |")
if level_rows:
    write_rows(os.path.join(res, "glottis_fe_three_levels.csv"), level_rows)
