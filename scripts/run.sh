#!/usr/bin/env bash
# Quick start, command 1: install packages, build, run the main job.
# Idempotent and incremental. Extra arguments go to the demo.
# The main job is, for now, the most complete scene that exists: the
# Poisson verification study (fsai_poisson); it becomes
# `fsai_demo --vowel u` once the voice scene lands.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
build=${FSAI_BUILD:-build}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$build/demos/fsai_poisson" --output results/fsai_poisson "$@"
