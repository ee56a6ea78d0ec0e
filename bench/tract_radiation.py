#!/usr/bin/python3
"""Does the FE tract sound as its area function does? (docs/voice.md,
"The tract's lip end"). F1–F3 of the vowels [u], [a], [i] by the
transfer-function method (fsai_formants, yielding walls), planar and
axisymmetric, with a radiation region (Sommerfeld) or with the tract ending
at the lips under the flanged piston's load (--radiation piston, A11),
against the 1D chain-matrix model of the same walls and lip end.

usage: bench/tract_radiation.py [BUILD_DIR] [--rerun]
writes bench/results/tract_radiation.csv; run folders
bench/results/run_tract_<vowel>_<model>_<radiation>/
"""
import argparse
import os

from benchlib import print_markdown_table, results_dir, timed_run, write_rows

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(here, "..", "build"))
ap.add_argument("--rerun", action="store_true")
args = ap.parse_args()
exe = os.path.join(args.build, "demos", "fsai_formants")
out = results_dir()
rows = []
for vowel in ["u", "a", "i"]:
    for model in ["planar", "axisym"]:
        for radiation in ["sommerfeld", "piston"]:
            d = os.path.join(out, f"run_tract_{vowel}_{model}_{radiation}")
            s = timed_run([exe, "--vowel", vowel, "--model", model,
                           "--radiation", radiation, "--yielding_walls",
                           "--snapshots", "0", "--output", d], d, args.rerun)
            wall = s["process_wall_s"]
            fe, ref = s["formants_hz"], s["formants_1d_hz"]
            row = dict(vowel=vowel, model=model, radiation=radiation, wall_s=wall)
            for k in range(3):
                f = fe[k] if k < len(fe) else float("nan")
                row[f"f{k + 1}_hz"] = f
                row[f"f{k + 1}_1d_hz"] = ref[k]
                row[f"f{k + 1}_dev_pct"] = 100 * (f / ref[k] - 1)
            rows.append(row)
write_rows(os.path.join(out, "tract_radiation.csv"),
           [{k: (f"{x:.5g}" if isinstance(x, float) else x) for k, x in r.items()}
            for r in rows])


def cell(r, k):
    return f"{r[f'f{k}_hz']:.0f} ({r[f'f{k}_dev_pct']:+.1f} %)"


print_markdown_table(
    [("vowel", lambda r: f"[{r['vowel']}]"), ("model", lambda r: r["model"]),
     ("lip end", lambda r: r["radiation"]),
     ("1D F1 / F2 / F3 [Hz]",
      lambda r: " / ".join(f"{r[f'f{k}_1d_hz']:.0f}" for k in (1, 2, 3))),
     ("FE F1", lambda r: cell(r, 1)), ("FE F2", lambda r: cell(r, 2)),
     ("FE F3", lambda r: cell(r, 3)), ("wall", lambda r: f"{r['wall_s']:.1f} s")],
    rows)
