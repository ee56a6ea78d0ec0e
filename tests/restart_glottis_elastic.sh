#!/usr/bin/env bash
# Checkpoint/restart of fsai_glottis with the elastic fold: a run killed
# with SIGKILL between checkpoints and restarted from its last checkpoint
# must reproduce the uninterrupted run, with the Bernoulli flow and with
# the FE flow (IQN-ILS: its history of earlier steps is forgotten at every
# checkpoint, by both runs). Serially series.csv, coupling.csv and the
# final checkpoint (fold u, v, a by mesh node and edge; flow, mesh motion,
# surface pressures) byte for byte, and the XDMF files' times (those
# written after the checkpoint replaced, not repeated). A 2-rank checkpoint
# of the FE scene continues on 1 rank within 1e-6 of the serial run. The
# Bernoulli case (a body-cover fold) also records the fold's surface
# (fold_surface.csv, cut back to the checkpoint like series.csv). The
# remeshed case meshes the channel again after every step (E13a; a wider
# rest gap keeps the glottis open enough for it): the restart meshes the
# checkpoint's boundary again and continues on it. The cut case fails
# every first attempt (a coupling tolerance out of reach in 3 iterations)
# and takes each step as two halves (E13b): one row per step, each step
# cut once, and its restart byte for byte too.
# usage: restart_glottis_elastic.sh FSAI_GLOTTIS MPIEXEC
demo=$1
mpiexec=${2:-mpirun}
source "$(dirname "$0")/common.sh"

# name | steps | kill at | options
cases=(
  "bernoulli|500|250|--flow bernoulli --fold elastic --elastic.layers 2 --duration 0.01 --checkpoint-every 100 --write_every 30 --surface_every 10"
  "fe|80|50|--flow fe --fold elastic --duration 0.0008 --fe.h_far 1e-3 --fe.h_gap 0.1e-3 --fe.ramp 1e-3 --coupling.method iqn-ils --checkpoint-every 20 --write_every 15"
  "fe_cuts|10|7|--flow fe --fold elastic --duration 0.0001 --fe.h_far 1e-3 --fe.h_gap 0.1e-3 --fe.ramp 1e-3 --coupling.method iqn-ils --coupling.tol 1e-12 --coupling.max_iterations 3 --coupling.on_failure warn --fe.step_cuts 1 --checkpoint-every 5 --write_every 4"
  "fe_remesh|10|7|--flow fe --fold elastic --duration 0.0001 --fe.h_far 1e-3 --fe.h_gap 0.1e-3 --fe.ramp 1e-3 --glottis.rest_gap 0.3e-3 --fe.remesh_quality 0.99 --checkpoint-every 5 --write_every 3"
)
for case in "${cases[@]}"; do
  IFS='|' read -r name steps kill opts <<<"$case"
  read -r -a args <<<"$opts"
  "$demo" "${args[@]}" --output "$work/full_$name" >/dev/null 2>&1 || { echo "FAIL $name: full run"; fail=1; }
  "$demo" "${args[@]}" --debug.kill_at_step "$kill" --output "$work/cut_$name" >/dev/null 2>&1
  status=$?
  rows=$(($(wc -l <"$work/cut_$name/series.csv") - 1))
  [ "$status" -ne 0 ] && [ "$rows" -eq "$kill" ] || { echo "FAIL $name: the run was not killed at step $kill ($rows rows)"; fail=1; }
  "$demo" "${args[@]}" --restart "$work/cut_$name" >/dev/null 2>&1 || { echo "FAIL $name: restart"; fail=1; }
  files=(series.csv coupling.csv "checkpoint_$steps.r0.bin")
  [ "$name" = bernoulli ] && files+=(fold_surface.csv modes_surface.csv)
  for f in "${files[@]}"; do
    if cmp -s "$work/full_$name/$f" "$work/cut_$name/$f"; then
      echo "ok   $name: $f identical ($(wc -c <"$work/full_$name/$f") bytes)"
    else
      echo "FAIL $name: $f differs or is missing"; fail=1
    fi
  done
  for x in "$work/full_$name"/*.xdmf; do
    f=$(basename "$x")
    a=$(xdmf_times "$x"); b=$(xdmf_times "$work/cut_$name/$f")
    if [ -n "$a" ] && [ "$a" = "$b" ] && ! echo "$b" | awk '{print $1}' | sort -u | sed -n 2p | grep -q .; then
      echo "ok   $name: $f has the same $(echo "$b" | wc -l) times, each once per field"
    else
      echo "FAIL $name: $f times differ: full [$a] restarted [$b]"; fail=1
    fi
  done
done

# Every step of the cut case taken as two halves, one row each
# (the summary's result, after the parameter fe.step_cuts)
cuts=$(grep -o '"step_cuts": *[0-9]*' "$work/full_fe_cuts/summary.json" | tail -1 | grep -o '[0-9]*$')
rows=$(($(wc -l <"$work/full_fe_cuts/coupling.csv") - 1))
if [ "$cuts" = 10 ] && [ "$rows" = 10 ]; then
  echo "ok   fe_cuts: 10 steps cut once each, 10 coupling rows"
else
  echo "FAIL fe_cuts: step_cuts '$cuts', coupling rows $rows (10 and 10 expected)"; fail=1
fi

# The FE scene's 2-rank checkpoint (fields by mesh node / edge, not by
# rank) continued on 1 rank
IFS='|' read -r _ _ _ opts <<<"${cases[1]}"
read -r -a args <<<"$opts"
$mpiexec -n 2 "$demo" "${args[@]}" --debug.kill_at_step 50 --output "$work/cross" >/dev/null 2>&1
"$demo" "${args[@]}" --restart "$work/cross" >/dev/null 2>&1 || { echo "FAIL restart of a 2-rank checkpoint on 1 rank"; fail=1; }
series_close "$work/full_fe" "$work/cross" "fe: 2 ranks to step 40, then 1 rank" || fail=1
exit $fail
