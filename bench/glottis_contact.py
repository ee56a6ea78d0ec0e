#!/usr/bin/python3
"""The elastic fold's contact with the axis: the penalty (the default) and
the Hertz force of the model (G5: F_H = k_H delta^1.5 (1 + b_H
d(delta)/dt), k_H from contact.E, contact.nu and the osculating radius at
the lowest surface point, on the whole depth L_g, spread over the
overlapping surface; --elastic.contact hertz), with the Bernoulli flow:

  fsai_glottis --flow bernoulli --fold elastic --elastic.clamped_ends
      --elastic.contact penalty|hertz --p-sub P --duration 0.2
      --surface_every 2 --output DIR

Per run the limit cycle (summary.json over the second half) and, over the
last whole cycle, the contact force and the penetration (series.csv) and
the contact line: the reference arc lengths of the surface points below
the axis (fold_surface.csv).

usage: bench/glottis_contact.py [BUILD_DIR] [--rerun]
writes bench/results/glottis_contact.csv and glottis_contact.png
"""
import argparse
import concurrent.futures
import json
import os
import subprocess

import numpy as np

from benchlib import print_markdown_table, read_float_rows, results_dir, upward_crossings, write_rows

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--rerun", action="store_true")
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_glottis")
out = results_dir()
cases = [(f"{c}{p}", c, p) for p in (800, 1200) for c in ("penalty", "hertz")]


def folder(label):
    return os.path.join(out, f"contact_{label}")


def run(case):
    label, contact, p_sub = case
    d = folder(label)
    if os.path.exists(os.path.join(d, "summary.json")) and not args.rerun:
        return
    subprocess.run([exe, "--flow", "bernoulli", "--fold", "elastic",
                    "--elastic.clamped_ends", "--elastic.contact", contact,
                    "--p-sub", str(p_sub), "--duration", "0.2", "--surface_every", "2",
                    "--output", d], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def last_cycle(label):
    """The last whole cycle: t, contact force, penetration, contact line"""
    d = folder(label)
    r = read_float_rows(os.path.join(d, "series.csv"))
    t = np.array([x["t_s"] for x in r])
    g = np.array([x["gap_m"] for x in r])
    up = upward_crossings(g, 0.5 * (g[t > 0.1].min() + g[t > 0.1].max()))
    a, b = up[-2], up[-1]
    pts = read_float_rows(os.path.join(d, "modes_surface.csv"))
    s = np.array([p["s_m"] for p in pts])
    Y = np.array([p["Y_m"] for p in pts])
    surf = np.loadtxt(os.path.join(d, "fold_surface.csv"), delimiter=",", skiprows=1)
    ts = surf[:, 0]
    keep = (ts >= t[a]) & (ts <= t[b])
    y = Y[None, :] + surf[keep, 2::2]
    below = y < 0
    lo = np.array([s[row].min() if row.any() else np.nan for row in below])
    hi = np.array([s[row].max() if row.any() else np.nan for row in below])
    return {"t": t[a:b + 1] - t[a], "F": np.array([x["contact_force_N"] for x in r[a:b + 1]]),
            "pen": np.array([x["penetration_m"] for x in r[a:b + 1]]),
            "ts": ts[keep] - t[a], "line": (lo, hi)}


with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
    list(pool.map(run, cases))
rows, cycles = [], {}
for label, contact, p_sub in cases:
    with open(os.path.join(folder(label), "summary.json")) as f:
        s = json.load(f)
    c = last_cycle(label)
    cycles[label] = c
    width = np.nanmax(c["line"][1] - c["line"][0]) if np.any(np.isfinite(c["line"][0])) else 0
    rows.append({"case": label, "contact": contact, "p_sub_Pa": p_sub, "f0_hz": s["f0_hz"],
                 "open_quotient": s["open_quotient"], "q_peak_ls": 1e3 * s["q_peak_m3s"],
                 "closes_every_cycle": int(s["closes_every_cycle"]),
                 "max_penetration_mm": 1e3 * s["max_penetration_m"],
                 "cycle_max_force_mN": 1e3 * c["F"].max(),
                 "contact_line_max_mm": 1e3 * width,
                 "wall_per_sim_s": s["wall_per_sim_s"]})
write_rows(os.path.join(out, "glottis_contact.csv"), rows)
print_markdown_table([
    ("contact", lambda r: r["contact"]), ("p_sub [Pa]", lambda r: f"{r['p_sub_Pa']}"),
    ("f0 [Hz]", lambda r: f"{r['f0_hz']:.1f}"), ("OQ", lambda r: f"{r['open_quotient']:.3f}"),
    ("peak flow [l/s]", lambda r: f"{r['q_peak_ls']:.3f}"),
    ("closes", lambda r: "yes" if r["closes_every_cycle"] else "no"),
    ("max penetration [mm]", lambda r: f"{r['max_penetration_mm']:.3f}"),
    ("max contact force [mN]", lambda r: f"{r['cycle_max_force_mN']:.2f}"),
    ("longest contact line [mm]", lambda r: f"{r['contact_line_max_mm']:.2f}")], rows)

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(14, 4))
    for label, c in cycles.items():
        if not label.endswith("1200"):
            continue
        axes[0].plot(1e3 * c["t"], 1e3 * c["F"], label=label)
        axes[1].plot(1e3 * c["t"], 1e3 * c["pen"], label=label)
        line, = axes[2].plot(1e3 * c["ts"], 1e3 * c["line"][0], label=f"{label}: inferior end")
        axes[2].plot(1e3 * c["ts"], 1e3 * c["line"][1], "--", color=line.get_color(),
                     label=f"{label}: superior end")
    axes[0].set_ylabel("contact force [mN]")
    axes[1].set_ylabel("penetration of the axis [mm]")
    axes[1].set_yscale("log")
    axes[2].set_ylabel("contact line, arc length [mm]")
    for ax in axes:
        ax.set_xlabel("time in the last cycle [ms]")
        ax.legend(fontsize=7)
    fig.suptitle("elastic fold, clamped ends, Bernoulli flow, 1200 Pa: one cycle")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "glottis_contact.png"), dpi=110)
except ImportError:
    pass
