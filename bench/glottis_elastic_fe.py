#!/usr/bin/python3
"""The elastic fold in the FE flow through closure: the preset
demos/glottis/elastic_fe.toml (Δt 1e-5, h_gap 0.025 mm, clamped ends,
porous ramp, generalised-α fold step, step cuts, τ_m's step held, local
lift, remeshing, attachment wedges, IQN-ILS) for 0.2 s from rest at p_sub
400, 800 and 1200 Pa, and the same at the former preset's Δt 2e-5 on its
gap cells (h_gap 0.05 mm); with --check, the mesh/Δt check at 800 Pa:
the 0.2 s run on the gap cells h_gap 0.018, 0.035 and 0.05 mm against the
preset's 0.025 mm, at Δt 5e-6 on the preset's cells and on 0.05 mm (there
also 2e-5) against Δt 1e-5 on the same cells, and
the preset at quadrature degree 2 (the voice's) against its degree 4;
the settled cycles from 0.1 to 0.2 s of each (mean cycle peak with its
standard error: the cycles alternate large/small).

The runs go on 2 ranks, one at a time (35-60 min per 0.2 s at Δt 1e-5);
a run whose summary.json exists is not repeated. Writes
bench/results/glottis_elastic_fe.csv (and glottis_elastic_fe_check.csv)
and prints Markdown tables. The --scheme, --cuts, --deeper and --history
runs were made on the former gap cells and give them (former_mesh).

With --scheme, is the fold's step what the Δt check sees? The same fold
(clamped ends) under the Bernoulli flow at 800 Pa, 0.2 s, serially, at
Δt 2e-5 and 1e-5 with Newmark γ 0.5 (the trapezoidal rule), γ 0.6 and
generalised-α ρ∞ 0.8 (E18a): how much each step's f0 and peak flow move
when Δt is halved. Writes glottis_elastic_scheme.csv.

With --cuts, the runs that chose the preset's fold step and τ_m (800 Pa,
0.1 s, 2 ranks, step cuts): Newmark γ 0.6 (the former preset) and
generalised-α ρ∞ 0.8 at Δt 2e-5, 1e-5 (γ 0.6 also 5e-6) with τ_m
following Δt, and at Δt 1e-5 with τ_m's step held at 2e-5
(--fluid.tau_step); the porous floor held at the other Δt's value
(--closure.porous_floor_dt). Each run's cycles from 50 ms to 0.1 s
against its partner's: the same settings at the next larger Δt, or for
τ_m held, the same Δt with τ_m following it
(glottis_elastic_fe_cuts.csv, glottis_elastic_fe_cuts_check.csv).

With --subharmonics, do the cycles alternate for good? The subharmonic
ratio of the glottal flow (docs/model.md A10) over the cycles in 50 ms
windows of the 400, 800 and 1200 Pa runs, and of the same fold under the
Bernoulli flow at 800 Pa (0.2 s, serially; started if missing), there
also with p_sub ramped up over 30 ms instead of 5 ms, and with the fold's
damping ratio 0.01 or 0.02 at 66.9 and 100 Hz (Rayleigh) instead of 0.01
at 100 Hz (stiffness-proportional: 0.0067 at 66.9 Hz): the fold's lowest
in-vacuo mode (66.9 Hz, clamped ends) lies at half the pulse rate
(glottis_elastic_fe_subharmonics.csv).

With --deeper, the 1200 Pa run with step cuts down to Δt/16
(--fe.step_cuts 4) instead of Δt/4: does cutting further avoid the
unconverged steps at reopening? (It stops at 176.8 ms: docs/glottis.md.)

With --history, the 1200, 800 and 400 Pa runs and the 800 Pa check at
Δt 2e-5 with --fe.cut_history keep (the former default): the halves of a discarded attempt reuse the secant
columns of that attempt and the 8 steps before it instead of starting
IQN-ILS afresh (E13b). Against the default runs: is that what left steps
unconverged at reopening?

usage: bench/glottis_elastic_fe.py [--check] [--scheme] [--cuts] [--subharmonics] [--deeper]
                                   [--history] [--cached] [BUILD_DIR]
(--cached: tables from the runs already in bench/results, none started)
"""
import json
import os
import sys

import numpy as np

from benchlib import (MPI_ENV, glottal_cycles, pair_sem, print_markdown_table, read_float_rows,
                      results_dir, subharmonic_ratio, timed_run, upward_crossings, write_rows)

args = [a for a in sys.argv[1:] if not a.startswith("--")]
here = os.path.dirname(os.path.abspath(__file__))
build = args[0] if args else os.path.join(here, "..", "build")
exe = os.path.join(build, "demos", "fsai_glottis")
out = results_dir()
common = ["--config", os.path.join(here, "..", "demos", "glottis", "elastic_fe.toml"),
          "--duration", "0.2"]
cases = [(f"p{p}", 2, ["--p-sub", str(p)]) for p in (800, 1200, 400)]
# The former preset's step and gap cells: what Δt 2e-5 and h_gap 0.05 mm
# cost the cycle, and save (the runs below that give former_mesh were made
# on it, as the preset then was)
former_dt = ["--dt", "2e-5"]
former_mesh = ["--fe.h_gap", "0.05e-3"]
cases += [(f"p{p}_dt2e-5_h0.05", 2, ["--p-sub", str(p)] + former_dt + former_mesh)
          for p in (800, 1200, 400)]
# The runs made before the halves of a cut step started IQN-ILS afresh
# (E13b) reuse its columns, as they did then
keep = ["--fe.cut_history", "keep"]
check = [("p800_h0.018", 2, ["--p-sub", "800", "--fe.h_gap", "0.018e-3"]),
         ("p800_h0.035", 2, ["--p-sub", "800", "--fe.h_gap", "0.035e-3"]),
         ("p800_h0.05", 2, ["--p-sub", "800"] + former_mesh),
         ("p800_dt5e-6", 2, ["--p-sub", "800", "--dt", "5e-6"]),
         ("p800_dt5e-6_h0.05", 2, ["--p-sub", "800", "--dt", "5e-6"] + former_mesh),
         ("p800_dt2e-5_h0.05", 2, ["--p-sub", "800"] + former_dt + former_mesh),
         ("p800_q2", 2, ["--p-sub", "800", "--fluid.quadrature_degree", "2"])]
# The runs that led to the preset's fold step and τ_m (0.1 s at 800 Pa,
# step cuts as in the preset): Newmark γ 0.6 (the former preset) or
# generalised-α ρ∞ 0.8 (the preset's), τ_m following Δt or held at 2e-5
newmark = ["--elastic.rho_inf", "-1", "--elastic.newmark_gamma", "0.6"]
follow, held = ["--fluid.tau_step", "0"], ["--fluid.tau_step", "2e-5"]
cuts = []
for name, opts, steps in [("cuts2", newmark + follow, ("2e-5", "1e-5", "5e-6")),
                          ("alpha0.8_cuts2", follow, ("2e-5", "1e-5")),
                          ("cuts2", newmark + held, ("1e-5-tau",)),
                          ("alpha0.8_cuts2", held, ("1e-5-tau",))]:
    for step in steps:
        dt = step.split("-tau")[0]
        label = f"p800_{name}" + (f"_dt{dt}" if dt != "2e-5" else "") + \
            ("_tau2e-5" if step.endswith("-tau") else "")
        cuts.append((label, 2, ["--p-sub", "800", "--duration", "0.1", "--dt", dt] + opts + keep
                     + former_mesh))
# The porous ramp's floor χ_0 = 0.01 ρ/(σ_P Δt) changes with Δt (G4): Δt 2e-5
# with the floor of Δt 1e-5, against the Δt 1e-5 run
# (it fails), and Δt 1e-5 with the floor of Δt 2e-5, against the Δt 2e-5 run
for label, dt, floor in [("p800_cuts2_floor1e-5", "2e-5", "1e-5"),
                         ("p800_cuts2_dt1e-5_floor2e-5", "1e-5", "2e-5")]:
    cuts.append((label, 2, ["--p-sub", "800", "--duration", "0.1", "--dt", dt,
                            "--closure.porous_floor_dt", floor] + newmark + follow + keep
                     + former_mesh))
cuts_mode = "--cuts" in sys.argv
history_mode = "--history" in sys.argv
suffix = ("_cuts" if cuts_mode else "_deeper" if "--deeper" in sys.argv
          else "_history" if history_mode else "")
if history_mode:
    check = [("p800_dt1e-5_keep", 2, ["--p-sub", "800", "--dt", "1e-5"] + keep + former_mesh),
             ("p800_h0.035_keep", 2, ["--p-sub", "800", "--fe.h_gap", "0.035e-3"]
              + former_dt + keep)]
# Each run's reference in the check table: with --check the 0.2 s run at
# 800 Pa, with --cuts its Δt partner (a run without one is its own)
partners = {c[0]: "p800" + ("_keep" if history_mode else "") for c in check} if not cuts_mode else {"p800_cuts2_dt1e-5": "p800_cuts2",
            "p800_cuts2_dt5e-6": "p800_cuts2_dt1e-5",
            "p800_cuts2_dt1e-5_tau2e-5": "p800_cuts2_dt1e-5",
            "p800_alpha0.8_cuts2_dt1e-5_tau2e-5": "p800_alpha0.8_cuts2_dt1e-5",
            "p800_alpha0.8_cuts2_dt1e-5": "p800_alpha0.8_cuts2",
            "p800_cuts2_floor1e-5": "p800_cuts2_dt1e-5",
            "p800_cuts2_dt1e-5_floor2e-5": "p800_cuts2"}
# the three gap meshes at Δt 1e-5: each against the next coarser
# the Δt check ran on the former gap cells: against the preset's step there
partners.update({"p800_dt5e-6_h0.05": "p800_h0.05", "p800_dt2e-5_h0.05": "p800_h0.05"})
if "--check" in sys.argv:
    cases = check + [c for c in cases if c[0] not in {x[0] for x in check}]
if "--deeper" in sys.argv:
    cases = [("p1200_cuts4", 2, ["--p-sub", "1200", "--fe.step_cuts", "4"] + former_dt + keep
              + former_mesh)]
if history_mode:
    cases = check + [(f"p{p}_keep", 2, ["--p-sub", str(p)] + former_dt + keep + former_mesh)
                     for p in (1200, 800, 400)]
if cuts_mode:
    cases = cuts

if "--scheme" in sys.argv:
    schemes = [("gamma0.5", ["--elastic.newmark_gamma", "0.5"]),
               ("gamma0.6", ["--elastic.newmark_gamma", "0.6"]),
               ("alpha0.8", ["--elastic.rho_inf", "0.8"])]
    srows = []
    for name, opts in schemes:
        runs = {}
        for dt in ("2e-5", "1e-5"):
            folder = os.path.join(out, f"run_glottis_elastic_scheme_{name}_dt{dt}")
            if "--cached" in sys.argv and not os.path.exists(os.path.join(folder, "summary.json")):
                continue
            runs[dt] = timed_run([exe, "--flow", "bernoulli", "--fold", "elastic",
                                  "--elastic.clamped_ends", "--p-sub", "800", "--duration", "0.2",
                                  "--dt", dt, "--output", folder] + opts, folder)
        if runs.get("2e-5") and runs.get("1e-5"):
            a, b = runs["2e-5"], runs["1e-5"]
            srows.append({"scheme": name, "f0_hz": a["f0_hz"], "q_peak_m3s": a["q_peak_m3s"],
                          "f0_change": b["f0_hz"] / a["f0_hz"] - 1,
                          "q_peak_change": b["q_peak_m3s"] / a["q_peak_m3s"] - 1})
    write_rows(os.path.join(out, "glottis_elastic_scheme.csv"), srows)
    print_markdown_table([
        ("fold step", lambda r: r["scheme"]),
        ("f0 at Δt 2e-5 [Hz]", lambda r: f"{r['f0_hz']:.2f}"),
        ("peak at Δt 2e-5 [l/s]", lambda r: f"{1e3 * r['q_peak_m3s']:.3f}"),
        ("f0 change at Δt 1e-5", lambda r: f"{100 * r['f0_change']:+.2f} %"),
        ("peak change at Δt 1e-5", lambda r: f"{100 * r['q_peak_change']:+.2f} %")], srows)
    sys.exit(0)


if "--subharmonics" in sys.argv:
    windows = [(0.05, 0.1), (0.1, 0.15), (0.15, 0.2), (0.2, 0.25), (0.25, 0.3)]
    runs = [(f"FE flow, {p} Pa", f"run_glottis_elastic_fe_p{p}") for p in (400, 800, 1200)]
    runs += [(f"FE flow, {p} Pa, Δt 2e-5, h_gap 0.05 mm", f"run_glottis_elastic_fe_p{p}_dt2e-5_h0.05")
             for p in (400, 800, 1200)]
    # a numerical artefact would move under refinement: the --check runs;
    # the unconverged steps' part: the --history runs
    runs += [("FE flow, 800 Pa, h_gap 0.018 mm", "run_glottis_elastic_fe_p800_h0.018"),
             ("FE flow, 800 Pa, h_gap 0.035 mm", "run_glottis_elastic_fe_p800_h0.035"),
             ("FE flow, 800 Pa, h_gap 0.05 mm", "run_glottis_elastic_fe_p800_h0.05"),
             ("FE flow, 800 Pa, Δt 5e-6", "run_glottis_elastic_fe_p800_dt5e-6"),
             ("FE flow, 800 Pa, Δt 5e-6, h_gap 0.05 mm", "run_glottis_elastic_fe_p800_dt5e-6_h0.05")]
    runs += [(f"FE flow, {p} Pa, Δt 2e-5, cut_history keep", f"run_glottis_elastic_fe_p{p}_keep")
             for p in (400, 800, 1200)]
    runs += [("FE flow, 800 Pa, Δt 1e-5, cut_history keep",
              "run_glottis_elastic_fe_p800_dt1e-5_keep"),
             ("FE flow, 800 Pa, Δt 2e-5, h_gap 0.035 mm, cut_history keep",
              "run_glottis_elastic_fe_p800_h0.035_keep")]
    # the elastic voice's 0.3 s run (bench/voice_folds.py --flow fe --folds elastic
    # --duration 0.3 --elastic_dt 2e-5 --elastic_h_gap 0.05 --keep_cut_history)
    runs.append(("FE flow in the voice, 800 Pa, 0.3 s, cut_history keep",
                 "run_folds_elastic_800_fe_flowfe_0.3s_dt2e-5_h0.05_keep"))
    for name, tag, opts in [
            ("ramp 5 ms", "", []), ("ramp 30 ms", "_ramp0.03", ["--ramp", "0.03"]),
            ("ζ 0.01 at 66.9 Hz", "_zeta0.01", ["--elastic.zeta", "0.01",
                                                "--elastic.f_zeta_low", "66.9"]),
            ("ζ 0.02 at 66.9 Hz", "_zeta0.02", ["--elastic.zeta", "0.02",
                                                "--elastic.f_zeta_low", "66.9"])]:
        folder = "run_glottis_elastic_bernoulli_p800" + tag
        if "--cached" not in sys.argv:
            timed_run([exe, "--flow", "bernoulli", "--fold", "elastic", "--elastic.clamped_ends",
                       "--p-sub", "800", "--duration", "0.2", "--output",
                       os.path.join(out, folder)] + opts, os.path.join(out, folder))
        runs.append((f"Bernoulli flow, 800 Pa, {name}", folder))
    hrows = []
    for name, folder in runs:
        path = os.path.join(out, folder, "series.csv")
        if not os.path.exists(os.path.join(out, folder, "summary.json")):
            continue
        r = read_float_rows(path)
        t, q, g = (np.array([x[k] for x in r]) for k in ("t_s", "Q_m3s", "gap_m"))
        with open(os.path.join(out, folder, "summary.json")) as f:
            s = json.load(f)
        # the gap's swing over the later half: does the fold oscillate?
        row = {"run": name, "closes_every_cycle": int(s["closes_every_cycle"]),
               "gap_swing_um": 1e6 * float(np.ptp(g[t >= 0.1]))}
        for a, b in windows:
            key = f"shr_{1e3 * a:.0f}_{1e3 * b:.0f}ms"
            w = (t >= a) & (t < b)
            if t[-1] + 0.5 * (t[1] - t[0]) < b:  # the run ends before the window does
                row[key] = float("nan")
                continue
            # cycles from the upward crossings of the middle of the half-gap's
            # 1-99 % range (a one-step excursion leaves it in place)
            lo, hi = np.percentile(g[w], [1, 99])
            starts = [t[i] for i in upward_crossings(g, (lo + hi) / 2) if a <= t[i] <= b]
            row[key] = subharmonic_ratio(t, q, starts)
        hrows.append(row)
    write_rows(os.path.join(out, "glottis_elastic_fe_subharmonics.csv"), hrows)
    print_markdown_table([("run", lambda r: r["run"]),
                          ("gap swing after 0.1 s [µm]", lambda r: f"{r['gap_swing_um']:.0f}"),
                          ("closes", lambda r: "every cycle" if r["closes_every_cycle"] else "no")] + [
        (f"SHR {1e3 * a:.0f}-{1e3 * b:.0f} ms",
         lambda r, k=f"shr_{1e3 * a:.0f}_{1e3 * b:.0f}ms": "–" if np.isnan(r[k]) else f"{r[k]:.3f}")
        for a, b in windows], hrows)
    sys.exit(0)


def settled_cycles(folder):
    """f0, mean cycle peak [l/s] and OQ over the whole cycles from 50 ms
    (the start-up left out), their count, and the closings within them"""
    cyc = glottal_cycles(os.path.join(folder, "series.csv"), None, 0.05)
    return {"cycles": len(cyc), "f0_cycles_hz": len(cyc) / sum(1 / x["f0_hz"] for x in cyc),
            "q_peak_cycles_ls": float(np.mean([x["q_peak_ls"] for x in cyc])),
            "oq_cycles": float(np.mean([x["open_quotient"] for x in cyc])),
            "closings": sum(x["closings"] for x in cyc)}


rows = []
for label, ranks, extra in cases:
    folder = os.path.join(out, f"run_glottis_elastic_fe_{label}")
    if "--cached" in sys.argv and not os.path.exists(os.path.join(folder, "summary.json")):
        continue
    s = timed_run(["mpirun", "-n", str(ranks), exe] + common + extra + ["--output", folder],
                  folder, env=MPI_ENV)
    if s is None:
        continue
    rows.append({"case": label, "p_sub_Pa": s["parameters"]["p-sub"],
                 "f0_hz": s["f0_hz"], "open_quotient": s["open_quotient"],
                 "q_peak_m3s": s["q_peak_m3s"],
                 "closes_every_cycle": int(s["closes_every_cycle"]),
                 "closed_leakage": s["closed_leakage"],
                 "max_penetration_m": s["max_penetration_m"],
                 "mesh_quality_min": s["mesh_quality_min"],
                 "remeshes": s["remeshes"], "step_cuts": s.get("step_cuts", 0),
                 "coupling_iterations_mean": s["coupling_iterations_mean"],
                 "coupling_unconverged_steps": s["coupling_unconverged_steps"],
                 "flow_dofs": s["flow_dofs"], "wall_s": s["process_wall_s"]}
                | settled_cycles(folder))
if not rows:
    sys.exit("no run finished (a failed run leaves its log and last good state in its folder)")
write_rows(os.path.join(out, f"glottis_elastic_fe{suffix}.csv"), rows)
print_markdown_table([
    ("case", lambda r: r["case"]),
    ("f0 from 50 ms [Hz]", lambda r: f"{r['f0_cycles_hz']:.2f}"),
    ("mean cycle peak [l/s]", lambda r: f"{r['q_peak_cycles_ls']:.3f}"),
    ("OQ", lambda r: f"{r['oq_cycles']:.3f}"),
    ("closures / cycles", lambda r: f"{r['closings']} / {r['cycles']}"),
    ("leakage", lambda r: f"{100 * r['closed_leakage']:.2f} %"),
    ("max δ [µm]", lambda r: f"{1e6 * r['max_penetration_m']:.1f}"),
    ("min quality", lambda r: f"{r['mesh_quality_min']:.3f}"),
    ("remeshes", lambda r: f"{r['remeshes']}"),
    ("step cuts", lambda r: f"{r['step_cuts']}"),
    ("its/step", lambda r: f"{r['coupling_iterations_mean']:.2f}"),
    ("unconverged", lambda r: f"{r['coupling_unconverged_steps']}"),
    ("wall [s]", lambda r: f"{r['wall_s']:.0f}")], rows)

if "--check" in sys.argv or cuts_mode or history_mode:
    # The same window of each run: under --cuts the cycles that start after
    # 50 ms and end by 0.1 s; under --check, the settled cycles from 0.1 to
    # 0.2 s (the cycles alternate large/small, so the window needs many)
    t_from, t_to = (0.05, 0.1) if cuts_mode else (0.1, 0.2)
    check_rows = []
    labels = ([c[0] for c in cuts] if cuts_mode
              else ["p800" + ("_keep" if history_mode else "")] + [c[0] for c in check])
    for label in labels:
        if not os.path.exists(os.path.join(out, f"run_glottis_elastic_fe_{label}", "summary.json")):
            continue  # failed or not run
        cyc = [c for c in glottal_cycles(os.path.join(out, f"run_glottis_elastic_fe_{label}",
                                                      "series.csv"), None, t_from)
               if c["t0_s"] + 1 / c["f0_hz"] <= t_to]
        if not cyc:
            continue
        check_rows.append({"case": label, "cycles": len(cyc),
                           "f0_hz": len(cyc) / sum(1 / c["f0_hz"] for c in cyc),
                           "q_peak_ls": float(np.mean([c["q_peak_ls"] for c in cyc])),
                           "q_peak_sem_ls": pair_sem([c["q_peak_ls"] for c in cyc]),
                           # the window's later half alone: are the cycles still growing?
                           "q_peak_late_ls": float(np.mean([c["q_peak_ls"]
                                                            for c in cyc[len(cyc) // 2:]])),
                           "q_mean_ls": float(np.mean([c["q_mean_ls"] for c in cyc])),
                           "open_quotient": float(np.mean([c["open_quotient"] for c in cyc]))})
    by_case = {r["case"]: r for r in check_rows}
    for r in check_rows:
        b = by_case.get(partners.get(r["case"], r["case"]))
        r["f0_change"] = r["f0_hz"] / b["f0_hz"] - 1 if b else float("nan")
        for k in ("q_peak", "q_peak_late", "q_mean"):
            r[f"{k}_change"] = r[f"{k}_ls"] / b[f"{k}_ls"] - 1 if b else float("nan")
    write_rows(os.path.join(out, f"glottis_elastic_fe{suffix}_check.csv"), check_rows)
    print_markdown_table([
        ("case", lambda r: r["case"]),
        (f"cycles in {1e3 * t_from:.0f}-{1e3 * t_to:.0f} ms", lambda r: f"{r['cycles']}"),
        ("f0 [Hz]", lambda r: f"{r['f0_hz']:.2f} ({100 * r['f0_change']:+.2f} %)"),
        ("mean peak [l/s]", lambda r: f"{r['q_peak_ls']:.3f} ({100 * r['q_peak_change']:+.2f} %)"),
        ("its standard error", lambda r: f"{100 * r['q_peak_sem_ls'] / r['q_peak_ls']:.1f} %"),
        ("later half's mean peak", lambda r: f"{r['q_peak_late_ls']:.3f} "
                                             f"({100 * r['q_peak_late_change']:+.2f} %)"),
        ("mean flow [l/s]", lambda r: f"{r['q_mean_ls']:.4f} ({100 * r['q_mean_change']:+.2f} %)"),
        ("OQ", lambda r: f"{r['open_quotient']:.3f}")], check_rows)
