#!/usr/bin/python3
"""Do two or three shapes carry the elastic fold's motion?

The 2-DOF fold rests on the observation that a phonating fold moves in
2-3 dominant shapes. This script tests it on the elastic fold's limit
cycle (fsai_glottis --fold elastic, --surface_every: fold_surface.csv, the
displacement of the fold's surface points, and modes_surface.csv, the
first six in-vacuo modes at the same points):

  fsai_glottis --flow bernoulli|fe --fold elastic [--elastic.*]
      --p-sub P --duration D --surface_every 5 --output DIR

Over the second half of each run (the settled cycles), with the mean
(static) deflection removed and the points weighted by their share of the
arc length (the surface's L2 inner product):
- POD: the energy share of the first 1-5 proper orthogonal modes;
- DMD (exact DMD of the fluctuation, rank to 99.99 % of the energy, at
  most 20; amplitudes fitted to the whole window): the frequencies and
  growth rates of the modes with the largest RMS over the window, and the
  frequencies of the neutral modes (|growth| < 5 % of the angular
  frequency: the limit cycle's own);
- the leading POD shapes against the in-vacuo modes: MAC with the best
  matching mode and the share of the shape in the span of the six modes.

usage: bench/glottis_pod.py [BUILD_DIR] [--rerun] [--fe] [--fe-cover] [--cached]
  --fe adds the FE flow on the elastic fold's FE preset
  (demos/glottis/elastic_fe.toml: clamped ends) at 800 Pa for 0.2 s, on 2
  ranks (about 45 min)
  --fe-cover the same with the body-cover fold (hours: its closed phases
  take many coupling iterations, docs/glottis.md)
  --cached: the table from the runs already in bench/results, none started
writes bench/results/glottis_pod.csv and glottis_pod.png
"""
import argparse
import concurrent.futures
import json
import os
import sys

import numpy as np

from benchlib import (MPI_ENV, print_markdown_table, read_float_rows, results_dir, timed_run,
                      write_rows)

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--rerun", action="store_true")
ap.add_argument("--fe", action="store_true")
ap.add_argument("--fe-cover", action="store_true")
ap.add_argument("--cached", action="store_true")
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_glottis")
out = results_dir()

BC = ["--elastic.layers", "2"]
CL = ["--elastic.clamped_ends"]
# (label, flow, p_sub, duration, extra options)
cases = [("plane800", "bernoulli", 800, 0.25, []),
         ("clamped800", "bernoulli", 800, 0.25, CL),
         ("clamped1200", "bernoulli", 1200, 0.25, CL),
         ("cover800", "bernoulli", 800, 0.25, BC),
         ("cover_clamped800", "bernoulli", 800, 0.25, BC + CL),
         ("cover_clamped1200", "bernoulli", 1200, 0.25, BC + CL)]
# The FE flow: the preset's settings (its clamped ends included), as in
# bench/glottis_elastic_fe.py
FE = ["--config", os.path.join(here, "..", "demos", "glottis", "elastic_fe.toml")]
if args.fe:
    cases.append(("fe_preset800", "fe", 800, 0.2, FE))
if args.fe_cover:
    cases.append(("fe_cover800", "fe", 800, 0.2, FE + BC))


def folder(label):
    return os.path.join(out, f"pod_{label}")


def run(case):
    label, flow, p_sub, duration, extra = case
    if args.cached:
        return
    d = folder(label)
    mpi = ["mpirun", "-n", "2"] if flow == "fe" else []
    # timed_run skips a run whose summary.json exists unless --rerun
    timed_run(mpi + [exe, "--flow", flow, "--fold", "elastic", "--p-sub", str(p_sub),
                     "--duration", str(duration), "--surface_every", "5", "--output", d] + extra,
              d, rerun=args.rerun, env=MPI_ENV)


def mac(a, b, w):
    """Modal assurance criterion of two shapes under the weights w"""
    return (a @ (w * b)) ** 2 / ((a @ (w * a)) * (b @ (w * b)))


def analyse(label):
    d = folder(label)
    with open(os.path.join(d, "summary.json")) as f:
        s = json.load(f)
    pts = read_float_rows(os.path.join(d, "modes_surface.csv"))
    mode_cols = [k for k in pts[0] if k.endswith("_ux")]
    freqs = [float(k[1:-5]) for k in mode_cols]
    arc = np.array([p["s_m"] for p in pts])
    # Trapezoidal weights of the points along the arc, for x and y
    ds = np.diff(arc)
    w1 = np.concatenate([[ds[0] / 2], (ds[:-1] + ds[1:]) / 2, [ds[-1] / 2]])
    w = np.repeat(w1, 2)
    modes = np.array([[v for p in pts for v in (p[k], p[k[:-3] + "_uy"])]
                      for k in mode_cols]).T  # (2n, m)
    data = np.loadtxt(os.path.join(d, "fold_surface.csv"), delimiter=",", skiprows=1)
    t = data[:, 0]
    keep = t >= 0.5 * t[-1]
    t, U = t[keep], data[keep, 1:].T  # (2n, snapshots)
    dt = t[1] - t[0]
    U = U - U.mean(axis=1, keepdims=True)
    sw = np.sqrt(w)[:, None]
    Uw = sw * U
    # POD
    phi, sig, _ = np.linalg.svd(Uw, full_matrices=False)
    energy = sig**2 / np.sum(sig**2)
    pod = phi / sw  # shapes back in displacement
    # DMD of the weighted fluctuation
    X1, X2 = Uw[:, :-1], Uw[:, 1:]
    u, sv, vh = np.linalg.svd(X1, full_matrices=False)
    r = int(np.searchsorted(np.cumsum(sv**2) / np.sum(sv**2), 0.9999) + 1)
    r = min(r, 20)
    ur, sr, vr = u[:, :r], sv[:r], vh[:r].conj().T
    Atil = ur.conj().T @ X2 @ vr / sr
    lam, W = np.linalg.eig(Atil)
    Phi = X2 @ vr / sr @ W
    # Amplitudes that fit the whole window best (Jovanović, Schmid &
    # Nichols 2014), not the first snapshot alone
    V = np.vander(lam, X1.shape[1], increasing=True)
    P = (Phi.conj().T @ Phi) * (V @ V.conj().T).conj()
    q = np.diag(V @ X1.conj().T @ Phi).conj()
    b = np.linalg.solve(P, q)
    omega = np.log(lam) / dt
    # Each mode's RMS over the window (a fast-decaying mode's fitted
    # amplitude at the start can be large)
    amp = np.abs(b) * np.linalg.norm(Phi, axis=0) * np.sqrt(np.mean(np.abs(V) ** 2, axis=1))
    neutral = sorted(o.imag / (2 * np.pi) for o in omega
                     if o.imag >= 0 and abs(o.real) < 0.05 * abs(o.imag))
    dmd = sorted([(a, o.imag / (2 * np.pi), o.real) for a, o in zip(amp, omega)
                  if o.imag >= 0], reverse=True)
    amax = dmd[0][0]
    # Leading POD shapes against the in-vacuo modes
    Mw = sw * modes
    Q, _ = np.linalg.qr(Mw)
    row = {"case": label, "flow": s["parameters"]["flow"],
           "p_sub_Pa": s["parameters"]["p-sub"], "f0_hz": s["f0_hz"],
           "open_quotient": s["open_quotient"],
           "closes_every_cycle": int(s["closes_every_cycle"]),
           "invacuo_hz": " ".join(f"{f:.1f}" for f in freqs[:3])}
    for k in range(5):
        row[f"pod{k + 1}_pct"] = 100 * energy[k]
    row["pod123_pct"] = 100 * energy[:3].sum()
    best = []
    for k in range(3):
        m = [mac(pod[:, k], modes[:, j], w) for j in range(modes.shape[1])]
        j = int(np.argmax(m))
        best.append(j)
        row[f"pod{k + 1}_mode_hz"] = freqs[j]
        row[f"pod{k + 1}_mac"] = m[j]
        row[f"pod{k + 1}_in_span_pct"] = 100 * np.sum((Q.T @ phi[:, k]) ** 2)
    for k, (a, f, g) in enumerate(dmd[:4]):
        row[f"dmd{k + 1}_hz"] = f
        row[f"dmd{k + 1}_growth_1s"] = g
        row[f"dmd{k + 1}_amp"] = a / amax
    row["dmd_rank"] = r
    row["dmd_neutral_hz"] = " ".join(f"{f:.1f}" for f in neutral)
    return row, arc, pod[:, :3], modes, freqs, best


# The serial Bernoulli runs two at a time, then the FE runs (2 ranks, one at a time)
with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
    list(pool.map(run, [c for c in cases if c[1] != "fe"]))
for c in cases:
    if c[1] == "fe":
        run(c)
cases = [c for c in cases if os.path.exists(os.path.join(folder(c[0]), "summary.json"))]
if not cases:
    sys.exit("no run finished")
results = [analyse(c[0]) for c in cases]
rows = [r[0] for r in results]
write_rows(os.path.join(out, "glottis_pod.csv"), rows)
print_markdown_table([
    ("case", lambda r: r["case"]), ("p_sub", lambda r: f"{r['p_sub_Pa']:.0f}"),
    ("f0 [Hz]", lambda r: f"{r['f0_hz']:.1f}"),
    ("closes", lambda r: "yes" if r["closes_every_cycle"] else "no"),
    ("in-vacuo [Hz]", lambda r: r["invacuo_hz"]),
    ("POD 1/2/3/4/5 [%]", lambda r: " / ".join(f"{r[f'pod{k}_pct']:.1f}" for k in range(1, 6))),
    ("POD 1-3 [%]", lambda r: f"{r['pod123_pct']:.2f}"),
    ("POD k ~ mode (MAC)", lambda r: ", ".join(
        f"{r[f'pod{k}_mode_hz']:.0f} Hz ({r[f'pod{k}_mac']:.2f})" for k in range(1, 4))),
    ("in span of 6 modes [%]", lambda r: " / ".join(
        f"{r[f'pod{k}_in_span_pct']:.0f}" for k in range(1, 4))),
    ("DMD f [Hz] (growth 1/s, amp)", lambda r: ", ".join(
        f"{r[f'dmd{k}_hz']:.1f} ({r[f'dmd{k}_growth_1s']:+.1f}, {r[f'dmd{k}_amp']:.2f})"
        for k in range(1, 5) if f"dmd{k}_hz" in r)),
    ("DMD neutral [Hz]", lambda r: r["dmd_neutral_hz"])], rows)

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(14, 4))
    ax = axes[0]
    for i, r in enumerate(rows):
        ax.bar(np.arange(1, 6) + 0.8 * (i / len(rows) - 0.4),
               [r[f"pod{k}_pct"] for k in range(1, 6)], width=0.8 / len(rows),
               label=r["case"])
    ax.set_yscale("log")
    ax.set_xlabel("POD mode")
    ax.set_ylabel("energy share [%]")
    ax.legend(fontsize=7)
    labels = [c[0] for c in cases]
    for ax, name in zip(axes[1:], ["clamped800", "cover_clamped800"]):
        if name not in labels:
            continue
        k = labels.index(name)
        _, arc, pod, modes, freqs, best = results[k]
        for j in range(2):
            shape = pod[:, j] / np.abs(pod[:, j]).max()
            mode = modes[:, best[j]] / np.abs(modes[:, best[j]]).max()
            mode *= np.sign(shape @ mode)
            line, = ax.plot(1e3 * arc, shape[1::2], label=f"POD {j + 1} (u_y)")
            ax.plot(1e3 * arc, mode[1::2], "--", color=line.get_color(),
                    label=f"in-vacuo {freqs[best[j]]:.0f} Hz (u_y)")
        ax.set_title(name)
        ax.set_xlabel("arc length from the inferior attachment [mm]")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "glottis_pod.png"), dpi=110)
except ImportError:
    pass
