"""Helpers shared by the bench scripts."""
import csv


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
