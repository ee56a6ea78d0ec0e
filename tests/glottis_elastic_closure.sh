#!/usr/bin/env bash
# The elastic fold in the FE flow through one closure (issue: the elastic
# fold in the closing glottis): 800 Pa, the 0.1 mm mesh, the porous ramp at
# half the mesh size, the elastic FE fold's other defaults (clamped ends,
# generalised-α, step cuts, τ_m held, local lift, remeshing, IQN-ILS). The glottis must close (the fold
# crosses the axis) and open again within the run, with every coupling step
# converged, and 2 ranks must give the serial series.csv within 1e-6.
# At Δt 2e-5, not the preset's 1e-5: at 1e-5 the coupling of the step at
# 4.47 ms ends at its tolerance, in 3 iterations serially and 4 on 2 ranks,
# and from there the two series agree to 1e-4 (the coupling tolerance's
# reach), not 1e-6; at 2e-5 every step takes the same iterations on both.
# usage: glottis_elastic_closure.sh MPIEXEC FSAI_GLOTTIS
mpiexec=$1
demo=$2
source "$(dirname "$0")/common.sh"
args=(--flow fe --fold elastic --elastic.clamped_ends --p-sub 800 --dt 2e-5
      --duration 0.0096 --fe.ramp 1e-3 --fe.h_far 1e-3 --fe.h_gap 0.1e-3
      --closure.porous_ramp 5e-5)
"$demo" "${args[@]}" --output "$work/serial" >"$work/serial.log" 2>&1 || { echo "FAIL serial run"; tail -5 "$work/serial.log"; exit 1; }
"$mpiexec" -n 2 "$demo" "${args[@]}" --output "$work/mpi2" >"$work/mpi2.log" 2>&1 || { echo "FAIL 2-rank run"; tail -5 "$work/mpi2.log"; exit 1; }
/usr/bin/python3 - "$work/serial" "$work/mpi2" <<'PY'
import json, sys
import numpy as np
names = open(f"{sys.argv[1]}/series.csv").readline().strip().split(",")
a, b = (np.loadtxt(f"{d}/series.csv", delimiter=",", skiprows=1) for d in sys.argv[1:3])
s = json.load(open(f"{sys.argv[1]}/summary.json"))
gap, Q = a[:, names.index("gap_m")], a[:, names.index("Q_m3s")]
closed = np.flatnonzero(gap <= 0)
ok = True
def check(cond, what):
    global ok
    print(("ok   " if cond else "FAIL ") + what)
    ok = ok and cond
check(len(closed) > 0, f"the glottis closes ({len(closed)} steps with the fold across the axis, "
      f"max penetration {1e6 * s['max_penetration_m']:.2f} µm)")
check(len(closed) > 0 and gap[-1] > 5e-6 and Q[-1] > 0,
      f"and opens again (last half-gap {1e6 * gap[-1]:.1f} µm, "
      f"Q {Q[-1]:.3e} m3/s, peak {Q.max():.3e})")
check(s["coupling_unconverged_steps"] == 0,
      f"every coupling step converged ({s['coupling_unconverged_steps']} not, "
      f"at most {s['coupling_iterations_max']} iterations)")
scale = np.maximum(np.abs(a).max(axis=0), 1e-300)
rel = (np.abs(b - a).max(axis=0) / scale).max() if a.shape == b.shape else np.inf
check(rel <= 1e-6, f"2 ranks = serial: series within {rel:.1e}")
sys.exit(0 if ok else 1)
PY
