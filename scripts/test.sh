#!/usr/bin/env bash
# Quick start, command 2: install packages, build, run the default test
# suite (everything except the label "long"). Idempotent and incremental.
# Extra arguments go to ctest (e.g. -L long for the validation runs).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
build=${FSAI_BUILD:-build}
cd "$build"
if [ $# -eq 0 ]; then
  set -- -LE long
fi
status=0
ctest --output-on-failure "$@" || status=$?
# Measured figures that tests print (convergence rates, ...), for the record
grep -hE "^(Poisson MMS|Acoustics)" Testing/Temporary/LastTest.log 2>/dev/null | sort -u || true
exit $status
