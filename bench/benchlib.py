"""Helpers shared by the bench scripts."""
import csv
import json
import os
import subprocess
import time

import numpy as np

# Where the bench scripts write their runs, tables and charts (not in git)
RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")
# mpirun as root (the machines here run as root)
MPI_ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def results_dir():
    """RESULTS, created if missing"""
    os.makedirs(RESULTS, exist_ok=True)
    return RESULTS


def timed_run(cmd, folder, rerun=False, env=None):
    """Run cmd (which writes folder/summary.json) unless that file exists
    (or rerun), timing the process into folder/process_wall_s; return the
    summary with "process_wall_s" added, or None if the run failed (its
    stderr's tail printed)."""
    summary = os.path.join(folder, "summary.json")
    timing = os.path.join(folder, "process_wall_s")
    if rerun or not os.path.exists(summary):
        t0 = time.time()
        r = subprocess.run(cmd, env=env, capture_output=True, text=True)
        if r.returncode != 0:
            print(f"{os.path.basename(folder)}: failed\n{r.stderr[-2000:]}")
            return None
        with open(timing, "w") as f:
            f.write(f"{time.time() - t0}\n")
    with open(summary) as f:
        s = json.load(f)
    with open(timing) as f:
        s["process_wall_s"] = float(f.read())
    return s


def read_float_rows(path):
    """A CSV file of numbers (a series.csv, a summary table) as a list of
    dicts column -> float."""
    with open(path) as f:
        return [{k: float(v) for k, v in x.items()} for x in csv.DictReader(f)]


def upward_crossings(values, level):
    """Indices i where values rises through level: values[i - 1] < level <=
    values[i] (the starts of a waveform's cycles)."""
    return [i for i in range(1, len(values)) if values[i - 1] < level <= values[i]]


def write_rows(path, rows):
    """Write a list of dicts (same keys, in order) as a CSV file."""
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def print_markdown_table(columns, rows):
    """Print rows as a Markdown table; columns: (header, row -> text)."""
    print("| " + " | ".join(h for h, _ in columns) + " |")
    print("|" + "---|" * len(columns))
    for r in rows:
        print("| " + " | ".join(fmt(r) for _, fmt in columns) + " |")


def first_harmonic(t, y, period):
    """Complex amplitude of y's first harmonic over one period (trapezoidal)"""
    e = np.exp(-2j * np.pi * (t - t[0]) / period)
    return 2 / period * np.trapz(y * e, t)


def subharmonic_ratio(t, x, starts, f_max=1000.0):
    """The subharmonic-to-harmonic ratio of docs/model.md A10 (as
    fsai::voice::subharmonic_ratio): x sampled at the uniform times t, over
    the largest even number 2M of whole cycles starting at `starts` (M >= 2,
    else nan); the Hann-weighted window's components at the half-integer
    multiples of the pulse rate, summed, over those at its multiples up to
    f_max."""
    n = len(starts)
    M = (n - 1) // 2 if n > 0 else 0
    if M < 2:
        return float("nan")
    t0, L = starts[0], starts[2 * M] - starts[0]
    s = (t - t0) / L
    w = (s >= 0) & (s <= 1)
    xw = x[w] * (0.5 - 0.5 * np.cos(2 * np.pi * s[w]))

    def component(bins):
        return abs(np.sum(xw * np.exp(-2j * np.pi * bins * s[w])))
    K = max(1, int(f_max * L / (2 * M)))
    return (sum(component(2 * M * k - M) for k in range(1, K + 1))
            / sum(component(2 * M * k) for k in range(1, K + 1)))


def interleaved(cases, rounds):
    """(round, case) for timing runs in interleaved rounds, rounds counted
    from 1: the machines here drift in speed between runs, so the order
    reverses from round to round and runs are compared within a round."""
    return [(k + 1, case) for k in range(rounds)
            for case in (cases if k % 2 == 0 else cases[::-1])]


def pair_sem(peaks):
    """The standard error of the mean of the cycle peaks. The elastic
    fold's cycles alternate large/small, so the spread is taken over the
    means of consecutive pairs of cycles (nan with fewer than two pairs)."""
    pairs = np.reshape(peaks[:len(peaks) // 2 * 2], (-1, 2)).mean(axis=1)
    return float(np.std(pairs, ddof=1) / np.sqrt(len(pairs))) if len(pairs) > 1 else float("nan")


def glottal_cycles(path, g_cross, t_start):
    """One dict per whole cycle of a glottis run's series.csv (none if the
    file is missing). A cycle runs from one upward crossing of the half-gap
    g = g_cross [m] to the next (g_cross None: the middle of g's range after
    t_start, for a fold that does not come near the axis); cycles that start
    before t_start [s] (the start-up) are left out. Per cycle: its start,
    f0 = 1/period, the largest and the mean flow, the open quotient (the
    share of steps not flagged closed), the closings (steps flagged closed
    after one that was not), the first harmonic of h and φ (amplitudes,
    and φ's phase lead on h), and the largest half-gap."""
    if not os.path.exists(path):
        return []
    r = read_float_rows(path)
    col = {k: np.array([x[k] for x in r]) for k in r[0]}
    t = col["t_s"]
    if g_cross is None:
        g = col["gap_m"][t > t_start]
        g_cross = (g.min() + g.max()) / 2
    up = [i for i in upward_crossings(col["gap_m"], g_cross) if t[i - 1] > t_start]
    closed = col["closed"] > 0.5
    out = []
    for a, b in zip(up, up[1:]):
        s = slice(a, b + 1)  # both ends: the trapezoids cover the whole period
        T = t[b] - t[a]
        ts = t[s]
        h1 = first_harmonic(ts, col["h_m"][s], T)
        p1 = first_harmonic(ts, col["phi_rad"][s], T)
        out.append({"t0_s": t[a], "f0_hz": 1 / T, "q_peak_ls": 1e3 * col["Q_m3s"][a:b].max(),
                    "q_mean_ls": 1e3 * np.trapz(col["Q_m3s"][s], ts) / T,
                    "open_quotient": 1 - col["closed"][a:b].mean(),
                    "closings": int((closed[a + 1:b] & ~closed[a:b - 1]).sum()),
                    "h_amp_mm": 1e3 * abs(h1), "phi_amp_mrad": 1e3 * abs(p1),
                    # in [−90°, 270°): neither model's lead (≈ 20° FE,
                    # ≈ 165° Bernoulli) wraps around there
                    "phi_lead_deg": (np.degrees(np.angle(p1 / h1)) + 90) % 360 - 90,
                    "max_gap_mm": 1e3 * col["gap_m"][a:b].max()})
    return out
