#!/usr/bin/env bash
# Checkpoint/restart of fsai_glottis (reduced model): a run killed with
# SIGKILL between checkpoints and restarted from its last checkpoint must
# reproduce the uninterrupted run — the same series.csv byte for byte (no
# gap, no duplicate row) and the same final state and limit-cycle figures —
# serially and on 2 ranks; a restart with changed physics is refused.
# usage: restart_glottis.sh FSAI_GLOTTIS MPIEXEC
demo=$1
mpiexec=${2:-mpirun}
source "$(dirname "$0")/common.sh"
args=(--duration 0.06 --p-sub 800)

for launcher in "" "$mpiexec -n 2"; do
  tag=${launcher:+mpi2}
  tag=${tag:-serial}
  $launcher "$demo" "${args[@]}" --output "$work/full_$tag" >/dev/null 2>&1 || { echo "FAIL $tag: full run"; fail=1; }
  # killed after step 2100 of 3000; the last checkpoint is step 1600
  $launcher "$demo" "${args[@]}" --checkpoint-every 800 --debug.kill_at_step 2100 \
    --output "$work/cut_$tag" >/dev/null 2>&1
  status=$?
  rows=$(($(wc -l <"$work/cut_$tag/series.csv") - 1))
  echo "$tag: killed run exit status $status, $rows rows written, checkpoint $(grep -o '"step": [0-9]*' "$work/cut_$tag/checkpoint.json")"
  [ "$status" -ne 0 ] && [ "$rows" -eq 2100 ] || { echo "FAIL $tag: the run was not killed at step 2100"; fail=1; }
  $launcher "$demo" "${args[@]}" --checkpoint-every 800 --restart "$work/cut_$tag" >/dev/null 2>&1 || { echo "FAIL $tag: restart"; fail=1; }
  if cmp -s "$work/full_$tag/series.csv" "$work/cut_$tag/series.csv"; then
    echo "ok   $tag: series.csv identical ($(($(wc -l <"$work/full_$tag/series.csv") - 1)) rows)"
  else
    echo "FAIL $tag: series.csv differs"; fail=1
  fi
  /usr/bin/python3 - "$work/full_$tag" "$work/cut_$tag" <<'PY' || fail=1
import json, sys
a, b = (json.load(open(d + "/summary.json")) for d in sys.argv[1:3])
keys = ["f0_hz", "open_quotient", "q_peak_m3s", "closed_leakage", "max_penetration_m", "cycles"]
bad = [k for k in keys if abs(a[k] - b[k]) > 1e-10 * abs(a[k])]
print("     summary", {k: b[k] for k in keys}, "restarted_from_step", b.get("restarted_from_step"))
if bad or b.get("restarted_from_step") != 1600:
    print("FAIL summary differs:", bad); sys.exit(1)
PY
done

# Changed physics: refused with one clear line
out=$("$demo" --duration 0.06 --p-sub 900 --restart "$work/cut_serial" 2>&1 >/dev/null)
status=$?
if [ "$status" -eq 2 ] && echo "$out" | grep -q "p-sub.*differs"; then
  echo "ok   changed --p-sub refused: $out"
else
  echo "FAIL changed --p-sub: status $status, '$out'"; fail=1
fi
exit $fail
