#!/usr/bin/env bash
# ParaView, headless: render the XDMF of an fsai_demo --quick run (2 ranks,
# 0.01 s, written every 50 steps) with scripts/render_paraview.py and check
# that both pictures exist, are PNGs, and are not blank (pixel spread and
# colour count). Skipped (exit 77) when pvbatch or xvfb-run is not installed
# or ParaView cannot start at all (the optional packages of setup.sh).
# usage: paraview_render.sh FSAI_DEMO MPIEXEC RENDER_SCRIPT PYTHON
demo=$1
mpiexec=$2
script=$3
python=$4
source "$(dirname "$0")/common.sh"
paraview_or_skip
$mpiexec -n 2 "$demo" --quick --duration 0.01 --write_every 50 \
  --output "$work/run" >"$work/demo.log" 2>&1 || { echo "FAIL: fsai_demo"; tail -5 "$work/demo.log"; exit 1; }
pvbatch_headless "$script" "$work/run" 2>"$work/render.err" | tee "$work/render.log"
grep -q "flow.png: velocity .*mesh moved by mesh_displacement" "$work/render.log" ||
  { echo "FAIL: flow.png not rendered with the moved mesh"; tail -20 "$work/render.err"; exit 1; }
grep -q "acoustic.png: p_acoustic" "$work/render.log" ||
  { echo "FAIL: acoustic.png not rendered"; tail -20 "$work/render.err"; exit 1; }
pngs_not_blank "$python" "$work/run/flow.png" "$work/run/acoustic.png"
