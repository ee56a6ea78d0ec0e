#!/usr/bin/env bash
# A demo on 2 MPI ranks must give the serial results: every number in
# summary.json outside "parameters" (and other than wall times, rank counts,
# memory, timers and Krylov iteration counts, which depend on the partition
# through BoomerAMG's parallel coarsening while the solution is the same to
# the solver's tolerance) within a relative 1e-6 (absolute 1e-12 near 0).
# usage: mpi_matches_serial.sh MPIEXEC DEMO ARGS...
mpiexec=$1
demo=$2
shift 2
source "$(dirname "$0")/common.sh"
"$demo" "$@" --output "$work/serial" >"$work/serial.log" 2>&1 || { echo "FAIL serial run"; tail -5 "$work/serial.log"; exit 1; }
"$mpiexec" -n 2 "$demo" "$@" --output "$work/mpi2" >"$work/mpi2.log" 2>&1 || { echo "FAIL 2-rank run"; tail -5 "$work/mpi2.log"; exit 1; }
/usr/bin/python3 - "$work/serial/summary.json" "$work/mpi2/summary.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
skip = ("parameters", "mpi_size", "timers", "timings", "krylov_iterations_mean", "peak_memory_mib_per_rank")
def leaves(x, path=""):
    if isinstance(x, dict):
        for k, v in x.items():
            if k in skip or "wall" in k:
                continue
            yield from leaves(v, f"{path}/{k}")
    elif isinstance(x, list):
        for i, v in enumerate(x):
            yield from leaves(v, f"{path}[{i}]")
    elif isinstance(x, (int, float)) and not isinstance(x, bool):
        yield path, float(x)
la, lb = dict(leaves(a)), dict(leaves(b))
worst, bad = 0.0, []
for k, va in la.items():
    if k not in lb:
        bad.append(f"{k} missing on 2 ranks"); continue
    d = abs(va - lb[k]) / max(abs(va), 1e-12 / 1e-6)
    worst = max(worst, d)
    if d > 1e-6:
        bad.append(f"{k}: serial {va!r}, 2 ranks {lb[k]!r}")
print(f"{len(la)} numbers compared, largest relative difference {worst:.2e}")
for m in bad:
    print("FAIL", m)
sys.exit(1 if bad or not la else 0)
PY
