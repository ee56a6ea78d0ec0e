#!/usr/bin/python3
"""Wall time of 0.1 s of the FE glottis closing cycle, per solver (the
speed target: < 10 min on 2 cores).

The configuration is the preset demos/glottis/closing_cycle.toml (h_gap
0.035 mm, Δt 1e-5, ζ 0.02, p_sub 1200 Pa), run for 0.1 s with the flow's
cell integrals at quadrature degree 2 (the preset's: the same
cycle to 0.03 %, docs/glottis.md) and 4 (the solver's default,
at which the mesh/Δt ladder of docs/glottis.md was run). The machines here drift in speed by 15-40 %
between runs, so the two are run in interleaved pairs (4, 2, 4, 2, ...) and
compared as ratios within a pair; the order alternates from pair to pair
(4, 2, then 2, 4), as the first run of a pair tends to be the slower. The runs had the fold's upper mode at
160 Hz, the preset's value (now 155 Hz: the same mesh, Δt
and solvers; f0 2 % lower). Each run:

  mpirun -n 2 fsai_glottis --config demos/glottis/closing_cycle.toml
      --duration 0.1 --write_every 0 --fluid.quadrature_degree Q --output DIR

Its log's timer table (max over ranks) gives the breakdown; the wall time
is the whole command's (mesh generation and setup included).

usage: bench/glottis_speed.py [BUILD_DIR] [--pairs N] [--keep DIR]
       bench/glottis_speed.py --logs LOG [LOG ...]   (tabulate earlier runs)
writes bench/results/glottis_speed.csv
"""
import argparse
import os
import re
import subprocess
import tempfile
import time

from benchlib import print_markdown_table, write_rows

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..")
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(root, "build"))
ap.add_argument("--pairs", type=int, default=1)
ap.add_argument("--keep", help="keep each run's run.log and summary.json in DIR/q<Q>_<pair>")
ap.add_argument("--logs", nargs="+", help="tabulate these run logs instead of running")
args = ap.parse_args()
TARGET = 600.0  # [s] wall for 0.1 s
TIMERS = ("glottis: time loop", "fluid: solve", "fluid: assemble", "ale: move", "fluid: force")
WALL = "wall [s]"  # the log's own, or the command's when this script ran it


def parse(log):
    """{timer name: total [s]} from the log's table, the quadrature degree,
    the wall time (/usr/bin/time -v's line, if the log has one), f0 and peak
    flow of the log's summary line"""
    text = open(log).read()
    out = {name: float(m.group(1)) for name in TIMERS
           for m in [re.search(re.escape(name) + r"\s+\d+\s+([0-9.]+)", text)] if m}
    m = re.search(r"fluid\.quadrature_degree\s*=\s*(\d)", text)  # the log's parameter list
    out["degree"] = int(m.group(1))
    m = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (?:(\d+):)?(\d+):([0-9.]+)", text)
    if m:
        out[WALL] = 3600 * int(m.group(1) or 0) + 60 * int(m.group(2)) + float(m.group(3))
    m = re.search(r"f0 = ([0-9.]+) Hz.*peak flow ([0-9.e+-]+) m", text)
    if m:
        out["f0_hz"], out["q_peak_ls"] = float(m.group(1)), 1e3 * float(m.group(2))
    return out


def run(degree, keep):
    exe = os.path.join(args.build, "demos", "fsai_glottis")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    with tempfile.TemporaryDirectory() as tmp:
        out = keep or tmp
        os.makedirs(out, exist_ok=True)
        cmd = ["mpirun", "-n", "2", exe, "--config", os.path.join(root, "demos", "glottis", "closing_cycle.toml"),
               "--duration", "0.1", "--write_every", "0", "--fluid.quadrature_degree", str(degree),
               "--output", out]
        print(" ".join(cmd), flush=True)
        log = os.path.join(out, "run.log")
        t = time.monotonic()
        with open(log, "w") as f:
            subprocess.run(cmd, env=env, stdout=f, stderr=subprocess.STDOUT, check=True)
        wall = time.monotonic() - t
        r = parse(log)
    r[WALL] = wall
    return r


if args.logs:
    results = [(os.path.relpath(os.path.dirname(os.path.abspath(log)), os.path.join(here, "results")), parse(log))
               for log in args.logs]
else:
    results = []
    for k in range(args.pairs):
        for q in ((4, 2) if k % 2 == 0 else (2, 4)):
            keep = os.path.join(args.keep, f"q{q}_{k + 1}") if args.keep else None
            results.append((f"pair {k + 1}", run(q, keep)))

rows = []
for name, r in results:
    loop = r.get("glottis: time loop", float("nan"))
    row = {"run": name, "quadrature_degree": r["degree"], "wall_s": r.get(WALL, float("nan")),
           "wall_min": r.get(WALL, float("nan")) / 60, "time_loop_s": loop}
    for t in TIMERS[1:]:
        key = t.split(": ")[1].replace(" ", "_")
        row[f"{key}_s"] = r.get(t, float("nan"))
        row[f"{key}_share"] = r.get(t, float("nan")) / loop
    row["f0_hz"], row["q_peak_ls"] = r.get("f0_hz", float("nan")), r.get("q_peak_ls", float("nan"))
    row["under_target"] = row["wall_s"] < TARGET
    rows.append(row)
print_markdown_table([("run", lambda r: r["run"]), ("degree", lambda r: str(r["quadrature_degree"])),
                      ("wall", lambda r: f"{r['wall_s']:.0f} s = {r['wall_min']:.2f} min"),
                      ("time loop", lambda r: f"{r['time_loop_s']:.0f} s"),
                      ("flow solve", lambda r: f"{r['solve_s']:.0f} s ({100 * r['solve_share']:.0f} %)"),
                      ("assembly", lambda r: f"{r['assemble_s']:.0f} s ({100 * r['assemble_share']:.0f} %)"),
                      ("mesh motion", lambda r: f"{r['move_s']:.1f} s ({100 * r['move_share']:.1f} %)"),
                      ("fold forces", lambda r: f"{r['force_s']:.1f} s ({100 * r['force_share']:.1f} %)"),
                      ("f0", lambda r: f"{r['f0_hz']:.2f} Hz"), ("peak flow", lambda r: f"{r['q_peak_ls']:.4f} l/s"),
                      ("< 10 min", lambda r: "yes" if r["under_target"] else "no")], rows)
# ratios degree 2 / degree 4 within each pair (consecutive runs, either order)
for a, b in zip(rows[::2], rows[1::2]):
    if {a["quadrature_degree"], b["quadrature_degree"]} == {2, 4}:
        q4, q2 = (a, b) if a["quadrature_degree"] == 4 else (b, a)
        print(f"{a['run']} and {b['run']}: degree 2 / degree 4: wall {q2['wall_s'] / q4['wall_s']:.3f}, "
              f"time loop {q2['time_loop_s'] / q4['time_loop_s']:.3f}, "
              f"assembly {q2['assemble_s'] / q4['assemble_s']:.3f}, solve {q2['solve_s'] / q4['solve_s']:.3f}")
write_rows(os.path.join(here, "results", "glottis_speed.csv"), rows)
