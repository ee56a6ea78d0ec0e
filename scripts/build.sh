#!/usr/bin/env bash
# Configure (once) and build fsai incrementally in ./build (or $FSAI_BUILD).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${FSAI_BUILD:-build}
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build" -j "$(nproc)"
