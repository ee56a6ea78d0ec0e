#!/usr/bin/env bash
# Quick start, command 1: install packages, build, run the main job.
# Idempotent and incremental. Extra arguments go to the demo.
# The main job is the voice: `fsai_demo --vowel u` on 2 MPI ranks (0.1 s of
# phonation: flow, folds and sound; results in results/fsai_demo/, among
# them sound.wav and report.png).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
build=${FSAI_BUILD:-build}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpirun -n 2 "$build/demos/fsai_demo" --vowel u --output results/fsai_demo "$@"
