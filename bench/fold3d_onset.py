#!/usr/bin/python3
"""Phonation onset and limit cycle of the 3D fold (fsai_fold3d,
docs/fold3d.md), on 2 ranks.

For each subglottal pressure a run from rest (p_sub ramped over 2 ms),
and the mid-length half-gap g(t): its half peak-to-peak swing in the
first 10 ms after the start-up (t_from .. t_from + 10 ms) and in the last
10 ms. The oscillation is self-sustained when the late swing is at least
the early one (amplitude ratio >= 1); the onset pressure lies between the
highest decaying and the lowest sustained p_sub. A least-squares growth
rate of the swings is reported too (it mixes growth and saturation: the
ratio decides). The longest run is the limit cycle: f0, peak and mean
flow, and the shares of the fold's in-vacuo modes in its oscillation
(summary.json's mode_hz, mode_shares).

--mesh coarse (the default here) runs the fold at 2 mm and the gap cells
at 0.4 mm, about 4x cheaper per step than fsai_fold3d's defaults
(--mesh default); the mesh check compares the two.

usage: bench/fold3d_onset.py [BUILD_DIR] [--pressures 400,600,800]
       [--duration 0.04] [--mesh coarse|default] [--write_every N] [--rerun]
writes bench/results/fold3d_onset_<mesh>.csv
"""
import argparse
import math
import os

import numpy as np

from benchlib import MPI_ENV, print_markdown_table, read_float_rows, results_dir, timed_run, write_rows

here = os.path.dirname(os.path.abspath(__file__))
MESHES = {
    "coarse": ["--fold.h", "2e-3", "--channel.h_gap", "0.4e-3", "--channel.h_far", "2.5e-3"],
    "default": [],
}


def swings(t, g, t_from, t_to=math.inf):
    """(time, half swing) between successive extrema of g in [t_from, t_to]"""
    w = (t >= t_from) & (t <= t_to)
    t, g = t[w], g[w]
    ext = [i for i in range(1, len(g) - 1) if (g[i] - g[i - 1]) * (g[i + 1] - g[i]) < 0]
    return [(0.5 * (t[a] + t[b]), 0.5 * abs(g[b] - g[a])) for a, b in zip(ext, ext[1:])]


def growth_rate(sw):
    """Least-squares slope of log(half swing) against time [1/s]"""
    if len(sw) < 4:
        return float("nan")
    x = np.array([s[0] for s in sw])
    y = np.log([max(s[1], 1e-30) for s in sw])
    return float(np.polyfit(x, y, 1)[0])


def dominant_frequency(t, y, t_from):
    """The largest peak of y's spectrum over t >= t_from (Hann window,
    zero-padded 8x) [Hz]: the oscillation's frequency also where it decays
    (the summary's f0 needs three whole cycles of the half-gap)"""
    w = t >= t_from
    x = y[w] - y[w].mean()
    n = 8 * len(x)
    spectrum = np.abs(np.fft.rfft(x * np.hanning(len(x)), n))
    return float(np.fft.rfftfreq(n, t[1] - t[0])[np.argmax(spectrum)])


def two_mode_fit(t, y, t_from, f1, f2=160.0):
    """Least-squares fit of y over t >= t_from by c + Σ_k A_k e^(σ_k t)
    cos(2π f_k t + φ_k), k = 1, 2 (from f1, f2 and a few phases): the
    frequencies and growth rates of the two modes in the swing, finer than
    the spectrum's bins. Returns (f1, σ1, f2, σ2, rms residual / rms y)."""
    from scipy.optimize import curve_fit

    def model(t, c, a1, s1, g1, p1, a2, s2, g2, p2):
        return (c + a1 * np.exp(s1 * t) * np.cos(2 * np.pi * g1 * t + p1)
                + a2 * np.exp(s2 * t) * np.cos(2 * np.pi * g2 * t + p2))
    w = t >= t_from
    x, v = t[w] - t_from, y[w]
    best = None
    for p1 in np.linspace(0, 2 * np.pi, 6, endpoint=False):
        for p2 in np.linspace(0, 2 * np.pi, 6, endpoint=False):
            try:
                p, _ = curve_fit(model, x, v, p0=[v.mean(), v.std(), 0, f1, p1, v.std() / 3, 0, f2, p2],
                                 maxfev=20000)
            except RuntimeError:
                continue
            r = np.sqrt(np.mean((model(x, *p) - v) ** 2))
            if best is None or r < best[0]:
                best = (r, p)
    if best is None:
        return (float("nan"),) * 5
    r, p = best
    (g1, s1), (g2, s2) = sorted([(p[3], p[2]), (p[7], p[6])])
    return g1, s1, g2, s2, r / max(v.std(), 1e-300)


def fit_columns(fit):
    f1, s1, f2, s2, rest = fit
    return {"fit_f1_hz": round(f1, 2), "fit_growth1_per_s": round(s1, 1), "fit_f2_hz": round(f2, 2),
            "fit_growth2_per_s": round(s2, 1), "fit_residual": round(rest, 3)}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
    ap.add_argument("--pressures", default="400,600,800")
    ap.add_argument("--duration", type=float, default=0.04)
    ap.add_argument("--t_from", type=float, default=0.01, help="end of the start-up [s]")
    ap.add_argument("--mesh", choices=list(MESHES), default="coarse")
    ap.add_argument("--write_every", default="0", help="steps between XDMF outputs (for a picture)")
    ap.add_argument("--rerun", action="store_true")
    a = ap.parse_args()
    demo = os.path.join(a.build, "demos", "fsai_fold3d")
    out = results_dir()
    rows = []
    for p in [float(x) for x in a.pressures.split(",")]:
        folder = os.path.join(out, "fold3d_onset", f"{a.mesh}_p{p:g}_T{a.duration:g}")
        cmd = ["mpirun", "-n", "2", demo, "--p-sub", str(p), "--duration", str(a.duration),
               "--write_every", a.write_every, "--checkpoint-every", "200", *MESHES[a.mesh], "--output", folder]
        s = timed_run(cmd, folder, a.rerun, env=MPI_ENV)
        if s is None:
            continue
        series = read_float_rows(os.path.join(folder, "series.csv"))
        t = np.array([r["t_s"] for r in series])
        g = np.array([r["gap_m"] for r in series])
        early = swings(t, g, a.t_from, a.t_from + 0.01)
        late = swings(t, g, t[-1] - 0.01)
        amp = lambda sw: max((x[1] for x in sw), default=float("nan"))
        shares = s.get("mode_shares", [])
        rows.append({
            "mesh": a.mesh,
            "p_sub_pa": p,
            "duration_s": a.duration,
            "early_swing_m": amp(early),
            "late_swing_m": amp(late),
            "amplitude_ratio": round(amp(late) / amp(early), 3),
            "growth_rate_per_s": round(growth_rate(swings(t, g, a.t_from)), 1),
            "f0_hz": round(s["f0_hz"], 2),
            "f_gap_spectrum_hz": round(dominant_frequency(t, g, a.t_from), 1),
            **fit_columns(two_mode_fit(t, g, a.t_from, dominant_frequency(t, g, a.t_from))),
            "cycles": s["cycles"],
            "q_peak_m3s": s["q_peak_m3s"],
            "q_mean_m3s": s["q_mean_m3s"],
            "gap_min_m": s["gap_min_m"],
            "mode_hz": " ".join(f"{f:.1f}" for f in s.get("mode_hz", [])),
            "mode_shares": " ".join(f"{x:.3f}" for x in shares),
            "modal_rest_mean": round(s.get("modal_rest_mean", float("nan")), 4),
            "coupling_its_per_step": round(s["coupling_iterations_mean"], 2),
            "unconverged_steps": s["coupling_unconverged_steps"],
            "wall_per_sim_ms_s": round(s["wall_per_sim_s"] / 1000, 1),
            "flow_dofs": s["flow_dofs"],
            "solid_dofs": s["solid_dofs"],
        })
    if rows:
        write_rows(os.path.join(out, f"fold3d_onset_{a.mesh}.csv"), rows)
        print_markdown_table([(k, lambda r, k=k: str(r[k])) for k in rows[0]], rows)
        decaying = [r["p_sub_pa"] for r in rows if r["amplitude_ratio"] < 1]
        sustained = [r["p_sub_pa"] for r in rows if r["amplitude_ratio"] >= 1]
        if decaying and sustained and max(decaying) < min(sustained):
            print(f"onset between {max(decaying):g} and {min(sustained):g} Pa")


if __name__ == "__main__":
    main()
