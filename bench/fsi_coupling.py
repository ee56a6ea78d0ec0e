#!/usr/bin/python3
"""Where partitioned FSI fails: explicit coupling vs constant relaxation vs
Aitken vs IQN-ILS on Turek-Hron FSI2 (rho_s/rho_f = 10) and FSI3
(rho_s/rho_f = 1, strong added mass), from rest over the first T seconds
of the inflow ramp, coarse mesh (h = 0.04, h_i = 0.004), serial.

Per run: whether it diverged (and how), coupling iterations per step
(mean, max), wall time. Writes bench/results/fsi_coupling.csv and prints a
markdown table.

usage: bench/fsi_coupling.py [BUILD_DIR] [--t_end 0.3] [--dt 0.005]
"""
import argparse
import csv
import os
import subprocess
import time

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--t_end", type=float, default=0.3)
ap.add_argument("--dt", type=float, default=0.005)
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_turek_hron")
out = os.path.join(here, "results")
methods = {
    "explicit": ["--coupling.method", "constant", "--coupling.omega", "1",
                 "--coupling.max_iterations", "1"],
    "constant 0.5": ["--coupling.method", "constant", "--coupling.omega", "0.5",
                     "--coupling.max_iterations", "100"],
    "constant 0.1": ["--coupling.method", "constant", "--coupling.omega", "0.1",
                     "--coupling.max_iterations", "100"],
    "aitken": ["--coupling.method", "aitken", "--coupling.max_iterations", "100"],
    "iqn-ils": ["--coupling.method", "iqn-ils", "--coupling.max_iterations", "100"],
}
rows = []
for case in ("FSI2", "FSI3"):
    for name, flags in methods.items():
        run = os.path.join(out, f"run_fsi_{case}_{name.replace(' ', '_')}")
        cmd = [exe, "--case", case, "--t_end", str(args.t_end), "--dt", str(args.dt),
               "--write_every", "0", "--output", run] + flags
        t0 = time.time()
        p = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.time() - t0
        its = []
        with open(os.path.join(run, "coupling.csv")) as f:
            for r in csv.DictReader(f):
                its.append(int(float(r["iterations"])))
        status = "ok" if p.returncode == 0 else p.stderr.strip().splitlines()[-1]
        if p.returncode != 0:
            status = status.replace("fsai_turek_hron: error: ", "")
        rows.append(dict(case=case, method=name, steps_done=len(its),
                         steps=round(args.t_end / args.dt),
                         mean_its=sum(its) / max(len(its), 1), max_its=max(its or [0]),
                         wall_s=wall, outcome=status))
        r = rows[-1]
        print(f"{case} {name}: {r['steps_done']}/{r['steps']} steps, iterations mean "
              f"{r['mean_its']:.2f} max {r['max_its']}, {wall:.1f} s: {status}", flush=True)
with open(os.path.join(out, "fsi_coupling.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
    w.writeheader()
    w.writerows(rows)
print("\n| case | method | steps done | iterations mean / max | wall s | outcome |")
print("|---|---|---|---|---|---|")
for r in rows:
    print(f"| {r['case']} | {r['method']} | {r['steps_done']}/{r['steps']} | "
          f"{r['mean_its']:.2f} / {r['max_its']} | {r['wall_s']:.1f} | {r['outcome']} |")
