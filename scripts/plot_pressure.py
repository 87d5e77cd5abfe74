#!/usr/bin/python3
"""Plots <app>_pressure.csv (columns case,mu,phi,theta,pressure,exact): the line pressure along
the contact arc at full slip (per element, the mean over its contact points) against the
closed form T0 e^{mu theta} / rho, one curve per case (issue 12 item 6).

usage: plot_pressure.py pressure.csv out.png
A file with no rows (no case reached full slip, or no planar wrap path) writes no plot.
"""
import csv
import math

from plot_common import cli, save


def main(src, dst):
    rows = list(csv.DictReader(open(src)))
    if not rows:
        return
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cases = list(dict.fromkeys(r["case"] for r in rows))
    fig, ax = plt.subplots(figsize=(8, 5))
    for k, case in enumerate(cases):
        sel = [r for r in rows if r["case"] == case]
        th = [math.degrees(float(r["theta"])) for r in sel]
        color = plt.cm.viridis(k / max(1, len(cases) - 1))
        ax.plot(th, [float(r["pressure"]) for r in sel], "o", color=color, ms=4,
                label=f"{case}: mu {float(sel[0]['mu']):g}, phi {math.degrees(float(sel[0]['phi'])):.0f} deg")
        ax.plot(th, [float(r["exact"]) for r in sel], "-", color=color, lw=1)
    ax.set_xlabel(r"angle from the loaded end $\theta$ [deg]")
    ax.set_ylabel("line pressure (force per length)")
    ax.set_yscale("log")
    ax.set_title(r"Contact pressure at full slip: computed (dots) and $T_0 e^{\mu\theta}/\rho$ (lines)")
    ax.grid(True, alpha=0.3)
    if len(cases) <= 12:
        ax.legend(fontsize=7)
    save(fig, dst)


if __name__ == "__main__":
    cli(main, __doc__)
