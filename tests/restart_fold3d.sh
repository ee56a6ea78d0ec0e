#!/usr/bin/env bash
# Checkpoint/restart of fsai_fold3d: a quick run killed with SIGKILL
# between checkpoints and restarted from its last checkpoint must
# reproduce the uninterrupted run (IQN-ILS forgets its earlier steps at
# every checkpoint, in both runs): series.csv and coupling.csv byte for
# byte, serially. A 2-rank checkpoint (the interface's history by mesh
# node, not by rank: the partitioner does not repeat its partition)
# continued on 1 rank within 1e-6 of the serial run.
# usage: restart_fold3d.sh FSAI_FOLD3D MPIEXEC
demo=$1
mpiexec=${2:-mpirun}
source "$(dirname "$0")/common.sh"
args=(--quick --duration 4e-4 --write_every 0 --checkpoint-every 3)
"$demo" "${args[@]}" --output "$work/full" >"$work/full.log" 2>&1 || { echo "FAIL full run"; tail -3 "$work/full.log"; exit 1; }
# killed after step 5 of 8; the last checkpoint is step 3
"$demo" "${args[@]}" --debug.kill_at_step 5 --output "$work/cut" >/dev/null 2>&1
status=$?
rows=$(($(wc -l <"$work/cut/series.csv") - 1))
echo "killed run: exit status $status, $rows rows, checkpoint $(grep -o '"step": [0-9]*' "$work/cut/checkpoint.json")"
[ "$status" -ne 0 ] && [ "$rows" -eq 5 ] || { echo "FAIL the run was not killed at step 5"; exit 1; }
"$demo" "${args[@]}" --restart "$work/cut" >"$work/restart.log" 2>&1 || { echo "FAIL restart"; tail -3 "$work/restart.log"; exit 1; }
fail=0
for f in series.csv coupling.csv; do
  if cmp -s "$work/full/$f" "$work/cut/$f"; then
    echo "ok   $f identical ($(($(wc -l <"$work/full/$f") - 1)) rows)"
  else
    echo "FAIL $f differs"; diff "$work/full/$f" "$work/cut/$f" | head -6; fail=1
  fi
done

$mpiexec -n 2 "$demo" "${args[@]}" --debug.kill_at_step 5 --output "$work/cross" >/dev/null 2>&1
"$demo" "${args[@]}" --restart "$work/cross" >"$work/cross.log" 2>&1 || { echo "FAIL restart of a 2-rank checkpoint on 1 rank"; tail -3 "$work/cross.log"; exit 1; }
series_close "$work/full" "$work/cross" "2 ranks to step 3, then 1 rank" || fail=1
exit $fail
