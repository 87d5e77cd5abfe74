#!/usr/bin/python3
"""Plots columns of a run's steps.csv against each other (iga run, "output": "plots").

usage: plot_steps.py steps.csv X Y out.png [title [reference.json]]
X: a term, Y: one or more terms separated by ';' (one curve each); a term is a column name,
optionally scaled: "2*plate_on_ring_Fy", "-centre_uz". Empty cells (non-finite values) are
skipped. A file with no rows writes no plot. reference.json: [{"label", "points": [[x, y],
...]}, ...], published points drawn as markers (in the plot's units).
"""
import csv
import json
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


def main(src, x, ys, dst, title="", reference=""):
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
    markers = "sD^vxP"
    refs = json.load(open(reference)) if reference else []
    curves = ys.split(";")
    for k, r in enumerate(refs):
        # One set per curve: the curve's colour; otherwise black.
        colour = "C%d" % k if len(refs) == len(curves) else "k"
        ax.plot([p[0] for p in r["points"]], [p[1] for p in r["points"]], markers[k % 6],
                ms=7, mfc="none", mew=1.5, color=colour, label=r["label"])
    ax.set_xlabel(x)
    ax.set_ylabel(ys if ";" not in ys else "")
    if ";" in ys or refs:
        ax.legend(fontsize=8)
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    save(fig, dst)


if __name__ == "__main__":
    if len(sys.argv) not in (5, 6, 7):
        sys.exit(__doc__)
    main(*sys.argv[1:])
