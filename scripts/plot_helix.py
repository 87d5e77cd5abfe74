#!/usr/bin/python3
"""Plots helix.csv (columns
case,sweep,mu,phi,pitch,T_ratio,exact,rel_error,pull,plateau_mean,plateau_spread,status) in the
style of the paper's Fig. 14: computed T/T0 against the pitch H with the 3-D Euler formula (83)
exp(mu phi R / sqrt(R^2 + (H/2pi)^2)) and the 2-D formula (82) exp(mu phi).

usage: plot_helix.py helix.csv out.png
R (the centre line radius) is recovered from the exact column of each row.
"""
import csv
import math
import sys

from plot_common import cli, save

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(src, dst):
    rows = list(csv.DictReader(open(src)))
    # Cases without full slip have an empty T_ratio (status other than full_slip).
    rows = [r for r in rows if r["T_ratio"] != ""]
    if not rows:
        sys.exit(f"{src}: no rows with a result")
    mu, phi = float(rows[0]["mu"]), float(rows[0]["phi"])
    H = [float(r["pitch"]) for r in rows]
    # R from a row with H != 0: exact = exp(mu phi R / sqrt(R^2 + c^2)) -> R = c q / sqrt(1 - q^2)
    R = 1.0
    for r in rows:
        c, e = float(r["pitch"]) / (2 * math.pi), float(r["exact"])
        q = math.log(e) / (float(r["mu"]) * float(r["phi"])) if float(r["mu"]) > 0 else 1.0
        if c != 0 and 0 < q < 1:
            R = c * q / math.sqrt(1 - q * q)
            break
    hi = max(H) if max(H) > 0 else 1.0
    grid = [hi * k / 200 for k in range(201)]
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    ax.plot(grid, [math.exp(mu * phi * R / math.sqrt(R * R + (h / (2 * math.pi)) ** 2)) for h in grid],
            "k-", label=r"3-D formula (83): $e^{\mu\varphi R/\sqrt{R^2+(H/2\pi)^2}}$")
    ax.plot(grid, [math.exp(mu * phi)] * len(grid), "k--", label=r"2-D formula (82): $e^{\mu\varphi}$")
    ax.plot(H, [float(r["T_ratio"]) for r in rows], "o", color="tab:red", label="computed")
    ax.set_xlabel("pitch H")
    ax.set_ylabel(r"$T/T_0$")
    ax.set_title(rf"Rope as a helix: $\mu$ = {mu:g}, $\varphi$ = {math.degrees(phi):.0f}$^\circ$, R = {R:.4g}")
    ax.grid(True, alpha=0.3)
    ax.legend()
    save(fig, dst)


if __name__ == "__main__":
    cli(main, __doc__)
