# Sourced by the test scripts (after they read their arguments): strict
# unset variables, a scratch directory $work removed on exit, MPI allowed as
# root and oversubscribed, fail=0, xdmf_times FILE (each time of an XDMF
# file with how often it occurs), series_close, and for the ParaView tests
# paraview_or_skip and pngs_not_blank.
set -u
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
fail=0

xdmf_times() { grep -o 'Time Value="[^"]*"' "$1" | sort | uniq -c | awk '{print $1, $3}' | sort -u; }

# series_close DIR_A DIR_B LABEL: DIR_B/series.csv within 1e-6 of
# DIR_A/series.csv (each column relative to its largest magnitude; the
# modal coordinates q<k>_m together, relative to the largest of them: a
# mode the load does not excite has only round-off in its column); prints
# one ok/FAIL line, non-zero status if not
series_close() {
  /usr/bin/python3 - "$1" "$2" "$3" <<'PY'
import re
import sys
import numpy as np
a, b = (np.loadtxt(f"{d}/series.csv", delimiter=",", skiprows=1) for d in sys.argv[1:3])
with open(f"{sys.argv[1]}/series.csv") as f:
    names = f.readline().strip().split(",")
scale = np.maximum(np.abs(a).max(axis=0), 1e-300)
modal = [i for i, n in enumerate(names) if re.fullmatch(r"q\d+_m", n)]
if modal:
    scale[modal] = scale[modal].max()
rel = (np.abs(b - a).max(axis=0) / scale).max() if a.shape == b.shape else np.inf
print(f"{'ok  ' if rel < 1e-6 else 'FAIL'} {sys.argv[3]}: series within {rel:.1e} of the serial run")
sys.exit(0 if rel < 1e-6 else 1)
PY
}

# paraview_or_skip: exit 77 (skipped) unless pvbatch and xvfb-run are
# installed and ParaView starts (the optional packages of setup.sh)
paraview_or_skip() {
  if ! command -v pvbatch >/dev/null || ! command -v xvfb-run >/dev/null; then
    echo "SKIP: pvbatch or xvfb-run not installed (optional packages of scripts/setup.sh)"
    exit 77
  fi
  echo "from paraview.simple import *" >"$work/smoke.py"
  if ! xvfb-run -a pvbatch "$work/smoke.py" >/dev/null 2>&1; then
    echo "SKIP: pvbatch does not start here"
    exit 77
  fi
}

# pvbatch_headless ARGS...: pvbatch under a virtual X server, tried twice
# (xvfb-run -a can hand out a display that a server just stopping still
# holds, and ParaView then aborts creating its window)
pvbatch_headless() {
  xvfb-run -a pvbatch "$@" && return 0
  sleep 2
  xvfb-run -a pvbatch "$@"
}

# pngs_not_blank PYTHON PNG...: each PNG exists and is not blank (pixel
# spread and colour count); non-zero status if one is
pngs_not_blank() {
  local python=$1
  shift
  "$python" - "$@" <<'PY'
import sys
import matplotlib.image as mpimg
import numpy as np
bad = 0
for path in sys.argv[1:]:
    img = mpimg.imread(path)[..., :3]
    colours = len(np.unique(img.reshape(-1, 3), axis=0))
    print(f"{path}: {img.shape[1]} x {img.shape[0]} px, pixel std {img.std():.3f}, {colours} colours")
    if img.std() < 0.02 or colours < 50:
        print(f"FAIL: {path} is blank")
        bad = 1
sys.exit(bad)
PY
}
