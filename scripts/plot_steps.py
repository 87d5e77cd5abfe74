#!/usr/bin/python3
"""Plots columns of a run's steps.csv against each other (iga run, "output": "plots").

usage: plot_steps.py steps.csv X Y out.png [title]
X: a term, Y: one or more terms separated by ';' (one curve each); a term is a column name,
optionally scaled: "2*plate_on_ring_Fy", "-centre_uz". Empty cells (non-finite values) are
skipped. A file with no rows writes no plot.
"""
import csv
import sys

from plot_common import save


def term(text):
    """(factor, column) of "[factor*]column" or "-column"."""
    text = text.strip()
    factor = 1.0
    if "*" in text:
        f, text = text.split("*", 1)
        factor = float(f)
    elif text.startswith("-"):
        factor, text = -1.0, text[1:]
    return factor, text.strip()


def values(rows, spec):
    factor, column = term(spec)
    return [factor * float(r[column]) if r[column] != "" else None for r in rows]


def main(src, x, ys, dst, title=""):
    rows = list(csv.DictReader(open(src)))
    if not rows:
        return
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    xs = values(rows, x)
    for y in ys.split(";"):
        pts = [(a, b) for a, b in zip(xs, values(rows, y)) if a is not None and b is not None]
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", ms=3, lw=1, label=y.strip())
    ax.set_xlabel(x)
    ax.set_ylabel(ys if ";" not in ys else "")
    if ";" in ys:
        ax.legend(fontsize=8)
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    save(fig, dst)


if __name__ == "__main__":
    if len(sys.argv) not in (5, 6):
        sys.exit(__doc__)
    main(*sys.argv[1:])
