#!/usr/bin/python3
"""Chart of a fsai_formants run: |H(f)| (FE at the lips or glottis, the
microphone, and the 1D chain-matrix model) with the formants marked.

usage: plot_transfer_function.py RUN_DIR   (writes RUN_DIR/transfer_function.png)
"""
import csv
import json
import math
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt


def main():
    run = sys.argv[1]
    with open(f"{run}/summary.json") as f:
        summary = json.load(f)
    cols = {}
    with open(f"{run}/transfer_function.csv") as f:
        reader = csv.DictReader(f)
        for row in reader:
            for k, v in row.items():
                cols.setdefault(k, []).append(float(v) if v not in ("", "nan") else math.nan)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    f = cols["f_hz"]
    model = summary.get("model", "")
    ax.plot(f, cols["h_db"], label=f"{model} (FE)" if model != "1d" else "1D model")
    if "h_mic_db" in cols and not all(math.isnan(v) for v in cols["h_mic_db"]):
        ax.plot(f, cols["h_mic_db"], lw=0.8, label="microphone (FE)")
    if model != "1d":
        ax.plot(f, cols["h_1d_db"], "k--", lw=0.8, label="1D chain-matrix model")
    for k, F in enumerate(summary.get("formants_hz", [])):
        ax.axvline(F, color="C3", lw=0.6, ls=":")
        ax.text(F, ax.get_ylim()[1], f" F{k + 1} {F:.0f}", color="C3",
                va="top", fontsize=8, rotation=90)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("|H| [dB re 1 Pa s/m³]")
    ax.set_title(f"Vowel {summary.get('vowel', '?')}: {model}, "
                 f"{summary.get('radiation', '')}")
    ax.legend(loc="lower left", fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(f"{run}/transfer_function.png", dpi=120)


if __name__ == "__main__":
    main()
