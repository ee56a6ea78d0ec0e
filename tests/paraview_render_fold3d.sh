#!/usr/bin/env bash
# ParaView, headless: render a few steps of fsai_fold3d --quick (fold.xdmf
# and flow.xdmf) with scripts/render_fold3d.py and check that the picture
# shows the moved fold and the flow on its plane and is not blank. Skipped
# (exit 77) without pvbatch or xvfb-run, as paraview_render.sh.
# usage: paraview_render_fold3d.sh FSAI_FOLD3D RENDER_SCRIPT PYTHON
demo=$1
script=$2
python=$3
source "$(dirname "$0")/common.sh"
paraview_or_skip
"$demo" --quick --duration 5e-4 --write_every 5 --modes 0 \
  --output "$work/run" >"$work/demo.log" 2>&1 || { echo "FAIL: fsai_fold3d"; tail -5 "$work/demo.log"; exit 1; }
pvbatch_headless "$script" "$work/run" 2>"$work/render.err" | tee "$work/render.log"
grep -q "fold3d.png: t = 0.0005 s, fold |u| up to [1-9]" "$work/render.log" ||
  { echo "FAIL: fold3d.png not rendered at the last frame with a moved fold"; tail -20 "$work/render.err"; exit 1; }
pngs_not_blank "$python" "$work/run/fold3d.png"
