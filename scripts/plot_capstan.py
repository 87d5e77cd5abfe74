#!/usr/bin/python3
"""Plots capstan.csv (columns case,mu,phi,T_ratio,exact,rel_error) in the style of the
paper's Figs. 11-12: computed T/T0 against the Euler-Eytelwein formula exp(mu phi).

usage: plot_capstan.py capstan.csv out.png
Rows with case 'a' are the sweep over mu at fixed phi, case 'b' the sweep over phi at fixed mu.
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(src, dst):
    rows = list(csv.DictReader(open(src)))
    if not rows:
        sys.exit(f"{src}: no rows")
    cases = sorted({r["case"] for r in rows})
    fig, axes = plt.subplots(1, len(cases), figsize=(6 * len(cases), 4.5), squeeze=False)
    for ax, case in zip(axes[0], cases):
        sel = [r for r in rows if r["case"] == case]
        mus = {float(r["mu"]) for r in sel}
        phis = {float(r["phi"]) for r in sel}
        if len(mus) >= len(phis):  # sweep over mu at one phi (Fig. 11)
            phi = float(sel[0]["phi"])
            xs = [float(r["mu"]) for r in sel]
            lo, hi = min(xs), max(xs)
            grid = [lo + (hi - lo) * k / 200 for k in range(201)]
            ax.plot(grid, [math.exp(m * phi) for m in grid], "k-", label=r"$e^{\mu\varphi}$ (82)")
            ax.set_xlabel(r"friction coefficient $\mu$")
            ax.set_title(rf"$\varphi$ = {math.degrees(phi):.0f}$^\circ$")
        else:  # sweep over phi at one mu (Fig. 12)
            mu = float(sel[0]["mu"])
            xs = [math.degrees(float(r["phi"])) for r in sel]
            lo, hi = 0.0, max(xs)
            grid = [lo + (hi - lo) * k / 200 for k in range(201)]
            ax.plot(grid, [math.exp(mu * math.radians(p)) for p in grid], "k-",
                    label=r"$e^{\mu\varphi}$ (82)")
            ax.set_xlabel(r"wrap angle $\varphi$ [deg]")
            ax.set_title(rf"$\mu$ = {mu:g}")
        ax.plot(xs, [float(r["T_ratio"]) for r in sel], "o", color="tab:red", label="computed")
        ax.set_ylabel(r"$T/T_0$")
        ax.grid(True, alpha=0.3)
        ax.legend()
    fig.suptitle("Capstan (Euler-Eytelwein): Kirchhoff rod on a rigid NURBS cylinder")
    fig.tight_layout()
    fig.savefig(dst, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
