#!/usr/bin/python3
"""The reduced glottis model (fsai_glottis --flow bernoulli): phonation
onset and limit cycle vs subglottal pressure, and the time-step convergence
of the default run.

1. Linear stability of the static equilibrium (--onset_sweep): the lowest
   p_sub with a growing mode is the onset (flutter) pressure.
2. Time runs (0.3 s, statistics over the second half) for each p_sub: f0,
   open quotient, peak flow, closure in every cycle, wall time.
3. Default p_sub (1000 Pa) at dt = 4e-5, 2e-5 (default), 1e-5.
Writes bench/results/glottis_bernoulli.csv and glottis_bernoulli.png.

usage: bench/glottis_bernoulli.py [BUILD_DIR]
"""
import json
import os
import subprocess
import sys

from benchlib import print_markdown_table, read_float_rows, write_rows

here = os.path.dirname(os.path.abspath(__file__))
build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "build")
exe = os.path.join(build, "demos", "fsai_glottis")
out = os.path.join(here, "results")
tmp = os.path.join(out, "run_glottis_bernoulli")

pressures = [400, 500, 600, 700, 800, 900, 1000, 1200, 1600, 2000, 2500]
subprocess.run([exe, "--flow", "bernoulli", "--onset_sweep",
                ",".join(str(p) for p in range(100, 2001, 10)), "--output", tmp],
               check=True, stdout=subprocess.DEVNULL)
lin = read_float_rows(os.path.join(tmp, "onset.csv"))
onset = next((r for r in lin if r["growth_rate_1_per_s"] > 0), None)
print(f"linear onset: p_sub = {onset['p_sub_Pa']:.0f} Pa at {onset['frequency_hz']:.1f} Hz"
      if onset else "no onset below 2000 Pa")

rows = []
for dt, ps in [(2e-5, p) for p in pressures] + [(4e-5, 1000), (1e-5, 1000)]:
    subprocess.run([exe, "--flow", "bernoulli", "--p-sub", str(ps), "--dt", str(dt),
                    "--duration", "0.3", "--output", tmp], check=True,
                   stdout=subprocess.DEVNULL)
    with open(os.path.join(tmp, "summary.json")) as f:
        s = json.load(f)
    rows.append({"p_sub_Pa": ps, "dt_s": dt, "f0_hz": s["f0_hz"],
                 "open_quotient": s["open_quotient"], "q_peak_m3s": s["q_peak_m3s"],
                 "closes_every_cycle": int(s["closes_every_cycle"]),
                 "gap_amplitude_m": s["gap_amplitude_m"],
                 "max_penetration_m": s["max_penetration_m"],
                 "wall_per_sim_s": s["wall_per_sim_s"]})
write_rows(os.path.join(out, "glottis_bernoulli.csv"), rows)
print_markdown_table([
    ("p_sub [Pa]", lambda r: f"{r['p_sub_Pa']}"), ("dt [s]", lambda r: f"{r['dt_s']:g}"),
    ("f0 [Hz]", lambda r: f"{r['f0_hz']:.2f}"),
    ("OQ", lambda r: f"{r['open_quotient']:.3f}"),
    ("Q_peak [l/s]", lambda r: f"{1e3 * r['q_peak_m3s']:.3f}"),
    ("closes", lambda r: "yes" if r["closes_every_cycle"] else "no"),
    ("gap amp [mm]", lambda r: f"{1e3 * r['gap_amplitude_m']:.3f}"),
    ("max δ [mm]", lambda r: f"{1e3 * r['max_penetration_m']:.3f}"),
    ("wall s / sim s", lambda r: f"{r['wall_per_sim_s']:.2f}")], rows)
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(13, 3.8))
    ax[0].plot([r["p_sub_Pa"] for r in lin], [r["growth_rate_1_per_s"] for r in lin])
    ax[0].axhline(0, color="k", lw=0.5)
    ax[0].set(xlabel="p_sub [Pa]", ylabel="growth rate [1/s]",
              title="linear stability of the rest state")
    rr = [r for r in rows if r["dt_s"] == 2e-5]
    ax[1].plot([r["p_sub_Pa"] for r in rr], [r["f0_hz"] for r in rr], "o-")
    ax[1].set(xlabel="p_sub [Pa]", ylabel="f0 [Hz]", title="limit cycle f0")
    ax[2].plot([r["p_sub_Pa"] for r in rr], [1e3 * r["q_peak_m3s"] for r in rr], "o-",
               label="peak flow [l/s]")
    ax[2].plot([r["p_sub_Pa"] for r in rr], [r["open_quotient"] for r in rr], "s-",
               label="open quotient")
    ax[2].set(xlabel="p_sub [Pa]", title="flow")
    ax[2].legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "glottis_bernoulli.png"), dpi=110)
except ImportError:
    print("matplotlib missing: no chart")
