#!/usr/bin/python3
"""What sets f0 of the closing cycle? The fold's parameters one at a time.

The design asks for a 2-DOF fold with in-vacuo modes ≈ 100 and 160 Hz and a
limit cycle in the male range 85-155 Hz. The FE scene's limit cycle is
155.29 Hz on the preset's mesh and ≈ 156-157 Hz mesh-converged (docs/glottis.md,
"f0 and the male range"). This script measures how far each of the fold's
parameters moves f0, without changing any default:

1. The reduced model (--flow bernoulli, the preset's ζ = 0.02 and
   Δt = 1e-5, 0.5 s from rest, the summary over t >= 0.25 s), one parameter
   at a time around the default: f2, f1, the elastic axis offset axis_dx,
   the modal damping ζ, p_sub. A pair (f1, f2) that no spring pair can give
   with the axis's mass coupling is refused by the demo (its InputError):
   that row says "inadmissible"; the edges of the admissible range of f2,
   f1 and axis_dx are found by bisection on that error. Runs go to a
   temporary folder; each takes about a second.
2. The FE scene (the preset demos/glottis/closing_cycle.toml) with
   f2 = 155 and 170 Hz, and with f1 = 90 Hz, from rest to 0.2 s:
     mpirun -n 2 fsai_glottis --config demos/glottis/closing_cycle.toml
         --duration 0.2 --stats_from 0.5 --write_every 0
         --checkpoint-every 5000 --vf.f2 F2 (or --vf.f1 F1 --vf.f2 160)
         --output bench/results/run_glottis_preset_f2_F2_02s (f1_F1)
   (the preset's f2 was 160 Hz; it is 155 Hz since, so
   --vf.f2 155 is now the preset itself) against the preset's earlier run
   (100 / 160 Hz, run_glottis_preset_q2_05s)
   over the same cycles: those starting in [0.13, 0.2) s (the late window
   of the convergence study (docs/glottis.md); the preset's limit cycle, t >= 0.25 s,
   is 0.5 % above it in f0). Cycles start where the half-gap rises through
   0.05 mm, or through the middle of its range for a fold that stays
   farther from the axis (f1 = 90 Hz).

3. The limit cycle: the f2 = 155 Hz run continued from its
   0.2 s checkpoint to 0.5 s,
     mpirun -n 2 fsai_glottis --config demos/glottis/closing_cycle.toml
         --vf.f2 155 --duration 0.5 --stats_from 0.5 --write_every 0
         --checkpoint-every 5000
         --restart bench/results/run_glottis_preset_f2_155_05s
   (a copy of the 0.2 s folder), against the preset's 0.5 s run: the
   demos' own summaries over t >= 0.25 s.

usage: bench/glottis_f0_fold.py [BUILD_DIR]
writes bench/results/glottis_f0_fold.csv (reduced model),
glottis_f0_fold_fe.csv (FE windows), glottis_f0_fold_limit.csv (FE limit
cycles) and glottis_f0_fold.png
"""
import argparse
import json
import os
import subprocess
import tempfile

from benchlib import glottal_cycles, print_markdown_table, read_float_rows, write_rows

here = os.path.dirname(os.path.abspath(__file__))
res = os.path.join(here, "results")
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_glottis")

# the reduced model at the preset's damping and time step
BERNOULLI = ["--flow", "bernoulli", "--dt", "1e-5", "--duration", "0.5", "--stats_from", "0.5",
             "--vf.zeta1", "0.02", "--vf.zeta2", "0.02"]
# the demo's in-vacuo frequencies: the reference point of the tables
DEFAULTS = {"vf.f1": 100.0, "vf.f2": 160.0}
SWEEPS = (("vf.f2", (151, 152, 155, 160, 165, 170, 180)),
          ("vf.f1", (85, 90, 95, 100, 105, 110)),
          ("vf.axis_dx", (-0.5e-3, -0.75e-3, -1e-3, -1.25e-3, -1.5e-3)),
          ("zeta", (0.01, 0.02, 0.05, 0.1)),
          ("p-sub", (800, 1200, 2000)))
UNITS = {"vf.f2": " [Hz]", "vf.f1": " [Hz]", "vf.axis_dx": " [mm]", "zeta": "", "p-sub": " [Pa]"}
G_CROSS = 0.05e-3  # [m]: cycle starts (as glottis_limit_cycle.py)
T_START = 0.03     # [s]
WINDOW = (0.13, 0.2)  # [s]: cycles starting here
LIMIT_RUNS = ((100, 155, "run_glottis_preset_f2_155_05s"),
              (100, 160, "run_glottis_preset_q2_05s"))
FE_RUNS = ((100, 155, "run_glottis_preset_f2_155_02s"),
           (100, 160, "run_glottis_preset_q2_05s"),
           (100, 170, "run_glottis_preset_f2_170_02s"),
           (90, 160, "run_glottis_preset_f1_90_02s"))


def run_demo(opts, tmp):
    """Run the demo with opts into the folder tmp: True if it ran, False if
    it refused the fold's frequencies (its InputError); any other failure
    raises"""
    p = subprocess.run([exe] + opts + ["--output", tmp], capture_output=True, text=True)
    if p.returncode != 0 and "cannot both be in-vacuo frequencies" not in p.stderr:
        raise RuntimeError(f"{' '.join(opts)}: {p.stderr.strip()}")
    return p.returncode == 0


def reduced(param, value):
    """One reduced-model run with param = value, the others at the demo's
    defaults (ζ: the preset's)"""
    opts = list(BERNOULLI)
    if param == "zeta":
        opts[opts.index("--vf.zeta1") + 1] = opts[opts.index("--vf.zeta2") + 1] = str(value)
    else:
        opts += [f"--{param}", str(value)]
    row = {"parameter": param, "value": value, "admissible": 1, "f0_hz": float("nan"),
           "open_quotient": float("nan"), "q_peak_ls": float("nan"), "closes_every_cycle": 0}
    with tempfile.TemporaryDirectory() as tmp:
        if not run_demo(opts, tmp):
            row["admissible"] = 0
            return row
        with open(os.path.join(tmp, "summary.json")) as f:
            s = json.load(f)
    row.update(f0_hz=s["f0_hz"], open_quotient=s["open_quotient"],
               q_peak_ls=1e3 * s["q_peak_m3s"], closes_every_cycle=int(s["closes_every_cycle"]))
    return row


def admissible(param, value):
    """Whether the demo accepts param = value (the others at its defaults)"""
    with tempfile.TemporaryDirectory() as tmp:
        return run_demo(["--flow", "bernoulli", "--duration", "1e-4", f"--{param}", str(value)], tmp)


def boundary(param, ok, refused, steps=20):
    """Bisection between an accepted and a refused value of param"""
    for _ in range(steps):
        mid = (ok + refused) / 2
        if admissible(param, mid):
            ok = mid
        else:
            refused = mid
    return ok


def cell(fmt):
    """A table column's cell function: fmt(row), or "inadmissible" for a
    refused parameter pair"""
    return lambda r: fmt(r) if r["admissible"] else "inadmissible"


rows = []
if os.path.exists(exe):
    for param, values in SWEEPS:
        rows += [reduced(param, v) for v in values]
    write_rows(os.path.join(res, "glottis_f0_fold.csv"), rows)
    base = next(r for r in rows if r["parameter"] == "vf.f2" and r["value"] == DEFAULTS["vf.f2"])
    print("Reduced model (0.5 s, ζ 0.02, Δt 1e-5, t >= 0.25 s), one parameter at a time "
          "(the others: f1 100 Hz, f2 160 Hz, axis_dx -1 mm, ζ 0.02, p_sub 1200 Pa):")
    print_markdown_table([
        ("parameter", lambda r: r["parameter"]), ("value", lambda r: f"{r['value']:g}"),
        ("f0 [Hz]", cell(lambda r: f"{r['f0_hz']:.2f}")),
        ("f0 change", cell(lambda r: f"{r['f0_hz'] / base['f0_hz'] - 1:+.2%}")),
        ("OQ", cell(lambda r: f"{r['open_quotient']:.3f}")),
        ("peak flow [l/s]", cell(lambda r: f"{r['q_peak_ls']:.3f}")),
        ("closes every cycle", cell(lambda r: "yes" if r["closes_every_cycle"] else "no"))], rows)
    # where the spring pair stops existing: f2/f1 has a lower bound set by
    # the mass coupling S of the axis offset
    print("\nAdmissible range, the others at their defaults (bisection on the demo's InputError):")
    print(f"  f2 >= {boundary('vf.f2', 160, 140):.2f} Hz, f1 <= {boundary('vf.f1', 100, 120):.2f} Hz, "
          f"axis_dx >= {1e3 * boundary('vf.axis_dx', -1e-3, -2e-3):.3f} mm")
else:
    print(f"{exe} not found: the reduced-model sweep is skipped")

fe = []
for f1, f2, run in FE_RUNS:
    path = os.path.join(res, run, "series.csv")
    c = [x for x in glottal_cycles(path, G_CROSS, T_START) if WINDOW[0] <= x["t0_s"] < WINDOW[1]]
    if not c:  # the gap stays above G_CROSS: cycles from the middle of its range
        c = [x for x in glottal_cycles(path, None, T_START) if WINDOW[0] <= x["t0_s"] < WINDOW[1]]
    if not c:
        continue
    f0 = len(c) / sum(1 / x["f0_hz"] for x in c)
    fe.append({"f1_hz": f1, "f2_hz": f2, "cycles": len(c), "f0_hz": f0,
               "q_peak_ls": max(x["q_peak_ls"] for x in c),
               "q_cycle_peak_mean_ls": sum(x["q_peak_ls"] for x in c) / len(c),
               "open_quotient": sum(x["open_quotient"] for x in c) / len(c),
               "closes_every_cycle": int(all(x["open_quotient"] < 1 for x in c)),
               "min_gap_mm": 1e3 * min(x["gap_m"] for x in read_float_rows(path)
                                       if c[0]["t0_s"] <= x["t_s"] < c[-1]["t0_s"] + 1 / c[-1]["f0_hz"])})
if fe:
    write_rows(os.path.join(res, "glottis_f0_fold_fe.csv"), fe)
    ref = next((r for r in fe if (r["f1_hz"], r["f2_hz"]) == (DEFAULTS["vf.f1"], DEFAULTS["vf.f2"])),
               fe[0])
    print(f"\nFE scene (the preset), cycles starting in [{WINDOW[0]}, {WINDOW[1]}) s, against "
          f"f1 / f2 = {ref['f1_hz']} / {ref['f2_hz']} Hz:")
    print_markdown_table([
        ("f1 [Hz]", lambda r: f"{r['f1_hz']}"), ("f2 [Hz]", lambda r: f"{r['f2_hz']}"),
        ("cycles", lambda r: f"{r['cycles']}"),
        ("f0 [Hz]", lambda r: f"{r['f0_hz']:.2f}"),
        ("f0 change", lambda r: f"{r['f0_hz'] / ref['f0_hz'] - 1:+.2%}"),
        ("largest Q [l/s]", lambda r: f"{r['q_peak_ls']:.4f}"),
        ("mean cycle peak [l/s]", lambda r: f"{r['q_cycle_peak_mean_ls']:.4f}"),
        ("OQ", lambda r: f"{r['open_quotient']:.3f}"),
        ("closes every cycle", lambda r: "yes" if r["closes_every_cycle"] else "no"),
        ("smallest half-gap [mm]", lambda r: f"{r['min_gap_mm']:.3f}")], fe)
    for k, other in (("f2_hz", "f1_hz"), ("f1_hz", "f2_hz")):
        line = sorted((r for r in fe if r[other] == ref[other]), key=lambda r: r[k])
        for a, b in zip(line, line[1:]):
            print(f"df0/d{k[:2]} = {(b['f0_hz'] - a['f0_hz']) / (b[k] - a[k]):.3f} "
                  f"({k[:2]} {a[k]} -> {b[k]} Hz)")

limit = []
for f1, f2, run in LIMIT_RUNS:
    path = os.path.join(res, run, "summary.json")
    if not os.path.exists(path):
        continue
    with open(path) as f:
        s = json.load(f)
    if s.get("sim_time_s", 0) < 0.5:
        continue  # not yet at its limit cycle
    limit.append({"f1_hz": f1, "f2_hz": f2, "cycles": s["cycles"], "f0_hz": s["f0_hz"],
                  "open_quotient": s["open_quotient"], "q_peak_ls": 1e3 * s["q_peak_m3s"],
                  "closed_leakage": s["closed_leakage"],
                  "closes_every_cycle": int(s["closes_every_cycle"]),
                  "q_peak_drift": s["q_peak_drift"], "period_drift": s["period_drift"]})
if limit:
    write_rows(os.path.join(res, "glottis_f0_fold_limit.csv"), limit)
    print("\nFE scene (the preset), limit cycle: the demo's summary over t >= 0.25 s of 0.5 s")
    print_markdown_table([
        ("f1 [Hz]", lambda r: f"{r['f1_hz']}"), ("f2 [Hz]", lambda r: f"{r['f2_hz']}"),
        ("cycles", lambda r: f"{r['cycles']}"), ("f0 [Hz]", lambda r: f"{r['f0_hz']:.2f}"),
        ("OQ", lambda r: f"{r['open_quotient']:.3f}"),
        ("peak flow [l/s]", lambda r: f"{r['q_peak_ls']:.4f}"),
        ("leakage", lambda r: f"{r['closed_leakage']:.2%}"),
        ("closes every cycle", lambda r: "yes" if r["closes_every_cycle"] else "no"),
        ("drift peak / period", lambda r: f"{r['q_peak_drift']:+.2%} / {r['period_drift']:+.2%}")],
        limit)

if rows:
    import matplotlib  # (only for the picture)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(1, len(SWEEPS), figsize=(15, 3.6), sharey=True)
    for ax, (param, _) in zip(axs, SWEEPS):
        r = [x for x in rows if x["parameter"] == param and x["admissible"]]
        scale = 1e3 if param == "vf.axis_dx" else 1
        closes = [x for x in r if x["closes_every_cycle"]]
        ax.plot([scale * x["value"] for x in r], [x["f0_hz"] for x in r], "-", color="C0", lw=0.8)
        ax.plot([scale * x["value"] for x in closes], [x["f0_hz"] for x in closes], "o", color="C0",
                label="reduced, closes every cycle")
        ax.plot([scale * x["value"] for x in r if not x["closes_every_cycle"]],
                [x["f0_hz"] for x in r if not x["closes_every_cycle"]], "o", mfc="none", color="C0",
                label="reduced, does not close")
        for k, other in (("f2_hz", "f1_hz"), ("f1_hz", "f2_hz")):
            line = sorted((x for x in fe if x[other] == DEFAULTS["vf." + other[:2]]),
                          key=lambda x: x[k])
            if param == "vf." + k[:2] and line:
                ax.plot([x[k] for x in line], [x["f0_hz"] for x in line], "-", color="C1", lw=0.8)
                for closes, mfc in ((1, "C1"), (0, "none")):
                    pts = [x for x in line if x["closes_every_cycle"] == closes]
                    ax.plot([x[k] for x in pts], [x["f0_hz"] for x in pts], "s", color="C1", mfc=mfc,
                            label=f"FE preset, [{WINDOW[0]}, {WINDOW[1]}) s"
                            + ("" if closes else ", does not close"))
        ax.axhline(155, color="k", ls="--", lw=0.8)
        ax.set_xlabel(param + UNITS[param])
        ax.grid(alpha=0.3)
    axs[0].set_ylabel("f0 [Hz] (dashed: the male range's 155 Hz)")
    axs[0].legend(fontsize=7, loc="lower right")
    fig.suptitle("f0 of the closing cycle against the fold's parameters, one at a time")
    fig.tight_layout()
    fig.savefig(os.path.join(res, "glottis_f0_fold.png"), dpi=110)
