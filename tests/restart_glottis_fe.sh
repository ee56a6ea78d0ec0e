#!/usr/bin/env bash
# Checkpoint/restart of fsai_glottis with the FE flow: a run killed with
# SIGKILL between checkpoints and restarted from its last checkpoint must
# reproduce the uninterrupted run. Compared: the final checkpoint's state
# files (every field of every rank: velocity, pressure, BDF history, mesh
# motion, fold, IQN-ILS columns), series.csv and coupling.csv (no gap, no
# duplicate row) byte for byte serially and within 1e-9 on 2 ranks, and
# flow.xdmf's list of times (the steps written after the checkpoint are
# replaced, not repeated). A checkpoint of 2 ranks continues on 1. A
# diverging run writes its last good state.
# usage: restart_glottis_fe.sh FSAI_GLOTTIS MPIEXEC
demo=$1
mpiexec=${2:-mpirun}
source "$(dirname "$0")/common.sh"
# 80 steps of 2e-5 s, coarse mesh; checkpoints at 20, 40, 60, 80; XDMF
# every 15 steps (so steps 45 written before the kill at 50 are redone)
args=(--flow fe --duration 0.0016 --fe.h_far 1e-3 --fe.h_gap 0.1e-3
      --checkpoint-every 20 --write_every 15)

for launcher in "" "$mpiexec -n 2"; do
  tag=${launcher:+mpi2}
  tag=${tag:-serial}
  $launcher "$demo" "${args[@]}" --output "$work/full_$tag" >/dev/null 2>&1 || { echo "FAIL $tag: full run"; fail=1; }
  $launcher "$demo" "${args[@]}" --debug.kill_at_step 50 --output "$work/cut_$tag" >/dev/null 2>&1
  status=$?
  rows=$(($(wc -l <"$work/cut_$tag/series.csv") - 1))
  echo "$tag: killed run exit status $status, $rows rows, checkpoint $(grep -o '"step": [0-9]*' "$work/cut_$tag/checkpoint.json"), files: $(cd "$work/cut_$tag" && ls checkpoint_* | tr '\n' ' ')"
  [ "$status" -ne 0 ] && [ "$rows" -eq 50 ] || { echo "FAIL $tag: the run was not killed at step 50"; fail=1; }
  $launcher "$demo" "${args[@]}" --restart "$work/cut_$tag" >/dev/null 2>&1 || { echo "FAIL $tag: restart"; fail=1; }
  if [ -z "$launcher" ]; then
    for f in series.csv coupling.csv checkpoint_80.r0.bin; do
      if cmp -s "$work/full_$tag/$f" "$work/cut_$tag/$f"; then
        echo "ok   $tag: $f identical ($(wc -c <"$work/full_$tag/$f") bytes)"
      else
        echo "FAIL $tag: $f differs or is missing"; fail=1
      fi
    done
  else
    # Two uninterrupted 2-rank runs already differ in the last digits (the
    # parallel direct solver's reductions): compare within 1e-9 of each
    # quantity's largest value
    /usr/bin/python3 - "$work/full_$tag" "$work/cut_$tag" <<'PY' || fail=1
import struct, sys
import numpy as np
a, b = sys.argv[1:3]
def state(path):
    out = {}
    with open(path, "rb") as f:
        assert f.read(13) == b"fsai-state 1\n"
        (n,) = struct.unpack("<Q", f.read(8))
        for _ in range(n):
            (ln,) = struct.unpack("<Q", f.read(8)); name = f.read(ln).decode()
            (sz,) = struct.unpack("<Q", f.read(8))
            out[name] = np.frombuffer(f.read(8 * sz), dtype="<f8")
    return out
worst = 0.0
for csv in ["series.csv", "coupling.csv"]:
    x = np.loadtxt(f"{a}/{csv}", delimiter=",", skiprows=1)
    y = np.loadtxt(f"{b}/{csv}", delimiter=",", skiprows=1)
    assert x.shape == y.shape, (csv, x.shape, y.shape)
    if csv == "coupling.csv":   # residuals of converged iterations are noise
        x, y = x[:, :2], y[:, :2]
    worst = max(worst, (np.abs(x - y).max(axis=0) / np.maximum(np.abs(x).max(axis=0), 1e-300)).max())
# The final states by mesh node / cell (the two runs' partitions differ)
def by_key(run):
    ranks = [state(f"{run}/checkpoint_80.r{r}.bin") for r in (0, 1)]
    out = {}
    for name in ranks[0]:
        if name.endswith("#keys") or name.startswith("coupling."):
            continue
        if name + "#keys" not in ranks[0]:
            out[name] = ranks[0][name]
            continue
        pairs = {}
        for s in ranks:
            v, k = s[name], s[name + "#keys"]
            for j, key in enumerate(k):
                pairs[int(key)] = v[j * (v.size // k.size):(j + 1) * (v.size // k.size)]
        out[name] = np.concatenate([pairs[key] for key in sorted(pairs)])
    return out
sa, sb = by_key(a), by_key(b)
assert sa.keys() == sb.keys()
for k in sa:
    if sa[k].size:
        worst = max(worst, np.abs(sa[k] - sb[k]).max() / max(np.abs(sa[k]).max(), 1e-300))
print(f"     mpi2: series, coupling log and final state within {worst:.1e} of each quantity's largest value")
sys.exit(0 if worst < 1e-9 else 1)
PY
  fi
  a=$(xdmf_times "$work/full_$tag/flow.xdmf"); b=$(xdmf_times "$work/cut_$tag/flow.xdmf")
  if [ "$a" = "$b" ] && ! echo "$b" | grep -qv '^4 '; then
    echo "ok   $tag: flow.xdmf has the same $(echo "$b" | wc -l) times, each once per field"
  else
    echo "FAIL $tag: flow.xdmf times differ: full [$a] restarted [$b]"; fail=1
  fi
  ls "$work/cut_$tag"/checkpoint_40.* >/dev/null 2>&1 && { echo "FAIL $tag: old checkpoint fields not removed"; fail=1; }
done

# Another number of ranks: the 2-rank run killed at step 50 continued
# serially from its checkpoint (fields by mesh node, not by rank) ends
# within the 2-rank-vs-serial difference of the uninterrupted serial run
$mpiexec -n 2 "$demo" "${args[@]}" --debug.kill_at_step 50 --output "$work/cross" >/dev/null 2>&1
"$demo" "${args[@]}" --restart "$work/cross" >/dev/null 2>&1 || { echo "FAIL restart of a 2-rank checkpoint on 1 rank"; fail=1; }
/usr/bin/python3 - "$work/full_serial" "$work/cross" "$work/full_mpi2" <<'PY' || fail=1
import sys
import numpy as np
a, b, c = (np.loadtxt(f"{d}/series.csv", delimiter=",", skiprows=1) for d in sys.argv[1:4])
scale = np.maximum(np.abs(a).max(axis=0), 1e-300)
rel = lambda x: (np.abs(x - a).max(axis=0) / scale).max()
print(f"ok   2 ranks to step 40, then 1 rank: series within {rel(b):.1e} of the serial run "
      f"(uninterrupted 2-rank run: {rel(c):.1e})")
sys.exit(0 if b.shape == a.shape and rel(b) < 1e-6 else 1)
PY

# A checkpoint of another mesh is refused with one clear line
out=$("$demo" "${args[@]}" --fe.h_gap 0.08e-3 --restart "$work/cross" 2>&1 >/dev/null)
status=$?
if [ "$status" -eq 2 ] && echo "$out" | grep -q "h_gap.*differs"; then
  echo "ok   another mesh refused: $out"
else
  echo "FAIL restart with another mesh: status $status, '$out'"; fail=1
fi

# A diverging run (the coupling may not converge in 2 iterations): one
# error line naming the step, its time and residual, and the last good
# state written for inspection
err=$("$demo" --flow fe --duration 0.004 --fe.h_far 1e-3 --fe.h_gap 0.1e-3 \
  --coupling.max_iterations 2 --coupling.on_failure error --output "$work/diverged" 2>&1 >/dev/null)
status=$?
if [ "$status" -ne 0 ] && [ "$(echo "$err" | grep -c .)" -eq 1 ] \
   && echo "$err" | grep -q "residual.*step 1 failed.*last good state" \
   && [ "$(grep -c 'Time Value' "$work/diverged/last_good.xdmf")" -eq 4 ]; then
  echo "ok   diverging coupling: $err"
else
  echo "FAIL diverging coupling: status $status, '$err'"; fail=1
fi
exit $fail
