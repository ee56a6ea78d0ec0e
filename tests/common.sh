# Sourced by the test scripts (after they read their arguments): strict
# unset variables, a scratch directory $work removed on exit, MPI allowed as
# root and oversubscribed, fail=0, and xdmf_times FILE (each time of an
# XDMF file with how often it occurs).
set -u
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
fail=0

xdmf_times() { grep -o 'Time Value="[^"]*"' "$1" | sort | uniq -c | awk '{print $1, $3}' | sort -u; }

# series_close DIR_A DIR_B LABEL: DIR_B/series.csv within 1e-6 of
# DIR_A/series.csv (each column relative to its largest magnitude); prints
# one ok/FAIL line, non-zero status if not
series_close() {
  /usr/bin/python3 - "$1" "$2" "$3" <<'PY'
import sys
import numpy as np
a, b = (np.loadtxt(f"{d}/series.csv", delimiter=",", skiprows=1) for d in sys.argv[1:3])
scale = np.maximum(np.abs(a).max(axis=0), 1e-300)
rel = (np.abs(b - a).max(axis=0) / scale).max() if a.shape == b.shape else np.inf
print(f"{'ok  ' if rel < 1e-6 else 'FAIL'} {sys.argv[3]}: series within {rel:.1e} of the serial run")
sys.exit(0 if rel < 1e-6 else 1)
PY
}
