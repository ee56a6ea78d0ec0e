#!/usr/bin/env bash
# Checkpoint/restart of fsai_demo (the voice, --quick on 2 ranks): killed
# with SIGKILL between checkpoints and restarted from the last one, the run
# must reproduce the uninterrupted run's series (flow, fold, p' at the lips
# and the microphone) and summary (f0, formants, SPL) within 1e-9 of each
# quantity's largest value (two uninterrupted 2-rank runs differ in the
# last digits), and acoustic.xdmf must hold each output time once. The
# reduced voice (serial) restarts byte for byte.
# usage: restart_voice.sh FSAI_DEMO MPIEXEC
demo=$1
mpiexec=${2:-mpirun}
source "$(dirname "$0")/common.sh"
# --quick: 800 steps of 5e-5 s; checkpoints every 200, XDMF every 150
args=(--quick --checkpoint-every 200 --write_every 150)
$mpiexec -n 2 "$demo" "${args[@]}" --output "$work/full" >/dev/null 2>&1 || { echo "FAIL full run"; fail=1; }
$mpiexec -n 2 "$demo" "${args[@]}" --debug.kill_at_step 500 --output "$work/cut" >/dev/null 2>&1
status=$?
rows=$(($(wc -l <"$work/cut/series.csv") - 1))
echo "killed run: exit status $status, $rows rows, checkpoint $(grep -o '"step": [0-9]*' "$work/cut/checkpoint.json")"
[ "$status" -ne 0 ] && [ "$rows" -eq 500 ] || { echo "FAIL the run was not killed at step 500"; fail=1; }
$mpiexec -n 2 "$demo" "${args[@]}" --restart "$work/cut" >/dev/null 2>&1 || { echo "FAIL restart"; fail=1; }
/usr/bin/python3 - "$work/full" "$work/cut" <<'PY' || fail=1
import json, sys
import numpy as np
a, b = sys.argv[1:3]
x = np.loadtxt(f"{a}/series.csv", delimiter=",", skiprows=1)
y = np.loadtxt(f"{b}/series.csv", delimiter=",", skiprows=1)
if x.shape != y.shape:
    print("FAIL series shapes", x.shape, y.shape); sys.exit(1)
worst = (np.abs(x - y).max(axis=0) / np.maximum(np.abs(x).max(axis=0), 1e-300)).max()
sa, sb = (json.load(open(f"{d}/summary.json")) for d in (a, b))
keys = ["f0_hz", "f0_fold_hz", "spl_db", "formants_from_sound_hz", "coupling_iterations_mean"]
for k in keys:
    va, vb = np.atleast_1d(sa.get(k, np.nan)).astype(float), np.atleast_1d(sb.get(k, np.nan)).astype(float)
    if va.shape == vb.shape and va.size:
        worst = max(worst, np.nanmax(np.abs(va - vb) / np.maximum(np.abs(va), 1e-300)))
    else:
        print("FAIL summary key", k, va, vb); sys.exit(1)
print(f"ok   series ({x.shape[0]} rows) and summary {', '.join(keys)} within {worst:.1e}; "
      f"restarted_from_step {sb.get('restarted_from_step')}")
sys.exit(0 if worst < 1e-9 and sb.get("restarted_from_step") == 400 else 1)
PY
for f in flow acoustic; do
  [ -s "$work/full/$f.xdmf" ] && [ -s "$work/cut/$f.xdmf" ] || { echo "FAIL $f.xdmf missing"; fail=1; continue; }
  a=$(grep -o 'Time Value="[^"]*"' "$work/full/$f.xdmf" | sort | uniq -c)
  b=$(grep -o 'Time Value="[^"]*"' "$work/cut/$f.xdmf" | sort | uniq -c)
  if [ "$a" = "$b" ]; then
    echo "ok   $f.xdmf: the same $(echo "$b" | wc -l) output times"
  else
    echo "FAIL $f.xdmf times differ: [$a] vs [$b]"; fail=1
  fi
done
# The reduced voice (Bernoulli flow, 1D tract: its state in
# checkpoint.json), serially: the restarted series byte for byte
args=(--flow bernoulli --acoustics 1d --duration 0.1 --report=false --checkpoint-every 1000)
"$demo" "${args[@]}" --output "$work/rfull" >/dev/null 2>&1 || { echo "FAIL reduced full run"; fail=1; }
"$demo" "${args[@]}" --debug.kill_at_step 2500 --output "$work/rcut" >/dev/null 2>&1
"$demo" "${args[@]}" --restart "$work/rcut" >/dev/null 2>&1 || { echo "FAIL reduced restart"; fail=1; }
if cmp -s "$work/rfull/series.csv" "$work/rcut/series.csv"; then
  echo "ok   reduced voice: restarted series.csv byte-identical ($(wc -l <"$work/rcut/series.csv") lines)"
else
  echo "FAIL reduced voice: restarted series.csv differs"; fail=1
fi
exit $fail
