#!/usr/bin/env bash
# ParaView, headless: render the XDMF of an fsai_demo --quick run (2 ranks,
# 0.01 s, written every 50 steps) with scripts/render_paraview.py and check
# that both pictures exist, are PNGs, and are not blank (pixel spread and
# colour count). Skipped (exit 77) when pvbatch or xvfb-run is not installed
# or ParaView cannot start at all (the optional packages of setup.sh).
# usage: paraview_render.sh FSAI_DEMO MPIEXEC RENDER_SCRIPT PYTHON
set -u
demo=$1
mpiexec=$2
script=$3
python=$4
if ! command -v pvbatch >/dev/null || ! command -v xvfb-run >/dev/null; then
  echo "SKIP: pvbatch or xvfb-run not installed (optional packages of scripts/setup.sh)"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "from paraview.simple import *" >"$work/smoke.py"
if ! xvfb-run -a pvbatch "$work/smoke.py" >/dev/null 2>&1; then
  echo "SKIP: pvbatch does not start here"
  exit 77
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
$mpiexec -n 2 "$demo" --quick --duration 0.01 --write_every 50 \
  --output "$work/run" >"$work/demo.log" 2>&1 || { echo "FAIL: fsai_demo"; tail -5 "$work/demo.log"; exit 1; }
xvfb-run -a pvbatch "$script" "$work/run" 2>"$work/render.err" | tee "$work/render.log"
grep -q "flow.png: velocity .*mesh moved by mesh_displacement" "$work/render.log" ||
  { echo "FAIL: flow.png not rendered with the moved mesh"; tail -20 "$work/render.err"; exit 1; }
grep -q "acoustic.png: p_acoustic" "$work/render.log" ||
  { echo "FAIL: acoustic.png not rendered"; tail -20 "$work/render.err"; exit 1; }
"$python" - "$work/run/flow.png" "$work/run/acoustic.png" <<'PY'
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
