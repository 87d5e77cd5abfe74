#!/usr/bin/python3
"""Plots capstan.csv (columns
case,sweep,mu,phi,T_ratio,exact,rel_error,pull,plateau_mean,plateau_spread,status) in the style of
the paper's Figs. 11-12: computed T/T0 against the Euler-Eytelwein formula exp(mu phi).

usage: plot_capstan.py capstan.csv out.png
One panel per sweep and fixed value: a sweep with more friction coefficients than wrap angles
gets one panel per phi (T/T0 over mu, Fig. 11), otherwise one panel per mu (T/T0 over phi,
Fig. 12); each panel holds only the rows of its fixed value. Cases that did not reach full slip
(status other than full_slip, T_ratio empty) are marked on the formula's curve with an x.
"""
import csv
import math
import sys

from plot_common import cli, save


def panels(rows):
    """[(title, over_mu, fixed value, rows)] in the order of the file."""
    out = []
    sweeps = list(dict.fromkeys(r.get("sweep", r["case"]) for r in rows))
    for sweep in sweeps:
        sel = [r for r in rows if r.get("sweep", r["case"]) == sweep]
        mus = sorted({float(r["mu"]) for r in sel})
        phis = sorted({float(r["phi"]) for r in sel})
        over_mu = len(mus) >= len(phis)
        for fixed in phis if over_mu else mus:
            key = "phi" if over_mu else "mu"
            part = [r for r in sel if math.isclose(float(r[key]), fixed, rel_tol=1e-12)]
            out.append((sweep, over_mu, fixed, part))
    return out


def main(src, dst):
    import matplotlib  # here, so that panels() can be tested without matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = list(csv.DictReader(open(src)))
    if not rows:
        sys.exit(f"{src}: no rows")
    ps = panels(rows)
    fig, axes = plt.subplots(1, len(ps), figsize=(6 * len(ps), 4.5), squeeze=False)
    for ax, (sweep, over_mu, fixed, sel) in zip(axes[0], ps):
        ok = [r for r in sel if r.get("status", "full_slip") == "full_slip" and r["T_ratio"] != ""]
        bad = [r for r in sel if r not in ok]
        if over_mu:  # sweep over mu at one phi (Fig. 11)
            phi = fixed
            xs = [float(r["mu"]) for r in sel]
            lo, hi = min(xs), max(xs)
            grid = [lo + (hi - lo) * k / 200 for k in range(201)]
            ax.plot(grid, [math.exp(m * phi) for m in grid], "k-", label=r"$e^{\mu\varphi}$ (82)")
            ax.set_xlabel(r"friction coefficient $\mu$")
            ax.set_title(rf"{sweep}: $\varphi$ = {math.degrees(phi):.0f}$^\circ$")
            x_of = lambda r: float(r["mu"])  # noqa: E731
        else:  # sweep over phi at one mu (Fig. 12)
            mu = fixed
            xs = [math.degrees(float(r["phi"])) for r in sel]
            lo, hi = 0.0, max(xs)
            grid = [lo + (hi - lo) * k / 200 for k in range(201)]
            ax.plot(grid, [math.exp(mu * math.radians(p)) for p in grid], "k-",
                    label=r"$e^{\mu\varphi}$ (82)")
            ax.set_xlabel(r"wrap angle $\varphi$ [deg]")
            ax.set_title(rf"{sweep}: $\mu$ = {mu:g}")
            x_of = lambda r: math.degrees(float(r["phi"]))  # noqa: E731
        ax.plot([x_of(r) for r in ok], [float(r["T_ratio"]) for r in ok], "o", color="tab:red",
                label="computed")
        if bad:
            ax.plot([x_of(r) for r in bad], [float(r["exact"]) for r in bad], "x", color="tab:gray",
                    label="no full slip (" + ", ".join(sorted({r.get("status", "?") for r in bad})) + ")")
        ax.set_ylabel(r"$T/T_0$")
        ax.grid(True, alpha=0.3)
        ax.legend()
    fig.suptitle("Capstan (Euler-Eytelwein): Kirchhoff rod on a rigid NURBS cylinder")
    save(fig, dst)


if __name__ == "__main__":
    cli(main, __doc__)
