#!/usr/bin/python3
"""Plots of the saddle app's results (apps/saddle_main.cpp), in the spirit of [KS15] Figs. 7-8.

usage: plot_saddle.py DIR
Reads DIR/saddle.csv, DIR/saddle_summary.json and DIR/contact_<run>.csv; writes
  DIR/saddle_load_deflection.png  load q against the centre deflection, and the number of
                                  contact / sticking points against q, for every run;
  DIR/saddle_contact_<run>.png    the active contact points at each snapshot time, sticking
                                  and sliding in two colours, with the circle of radius mu/a
                                  (79)-(81) and the fitted radius of the sticking zone;
  DIR/saddle_sticking_circle.png  from DIR/saddle_blocks.csv: the contact force ratio T/N of the
                                  small block at radius r against min(a r, mu), the mass point's
                                  friction (79)-(81), with the state (stick, partial slip, slide).
"""
import csv
import json
import math
import os

from plot_common import cli, save

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load_deflection(rows, dst):
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.5))
    for run in sorted({r["run"] for r in rows}, key=lambda n: (float(next(r["mu"] for r in rows if r["run"] == n)), n)):
        sel = [r for r in rows if r["run"] == run]
        mu = float(sel[0]["mu"])
        q = [float(r["load"]) for r in sel]
        ax1.plot([float(r["centre_deflection"]) for r in sel], q, "o-", ms=3, label=run)
        ax2.plot(q, [int(r["contact_points"]) for r in sel], "-", label=f"contact, {run}")
        if mu > 0:
            ax2.plot(q, [int(r["sticking_points"]) for r in sel], "--", label=f"sticking, {run}")
    ax1.set_xlabel("centre deflection")
    ax1.set_ylabel("load q (force / area)")
    ax1.set_title("Load against centre deflection")
    ax2.set_xlabel("load q (force / area)")
    ax2.set_ylabel("contact quadrature points")
    ax2.set_title("Contact and sticking points")
    for ax in (ax1, ax2):
        ax.grid(True, alpha=0.3)
        ax.legend()
    fig.suptitle("Covering a saddle: Kirchhoff-Love plate on the rigid hyperboloid z = a x y")
    save(fig, dst)
    plt.close(fig)


def contact_zones(points, run, a, half, dst):
    times = sorted({float(p["t"]) for p in points})
    if not times:
        return
    cols = min(len(times), 2)
    nrows = math.ceil(len(times) / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(5.2 * cols, 5 * nrows), squeeze=False)
    mu = run["mu"]
    snaps = {round(s["t"], 9): s for s in run.get("snapshots", [])}
    for ax, t in zip(axes.flat, times):
        sel = [p for p in points if float(p["t"]) == t]
        for stick, colour, label in ((0, "darkred", "sliding"), (1, "tab:blue", "sticking")):
            pts = [p for p in sel if int(p["stick"]) == stick]
            ax.scatter([float(p["x"]) for p in pts], [float(p["y"]) for p in pts], s=2, c=colour,
                       label=f"{label} ({len(pts)})")
        ang = [2 * math.pi * k / 200 for k in range(201)]
        if mu > 0:
            R = mu / a
            ax.plot([R * math.cos(s) for s in ang], [R * math.sin(s) for s in ang], "k--", lw=1,
                    label=rf"$\mu/a$ = {R:g}")
            s = snaps.get(round(t, 9))
            if s and s["sticking_radius_fit"] > 0:
                r = s["sticking_radius_fit"]
                ax.plot([r * math.cos(x) for x in ang], [r * math.sin(x) for x in ang], "k:", lw=1,
                        label=f"fitted {r:.2f}")
        ax.set_xlim(-half, half)
        ax.set_ylim(-half, half)
        ax.set_aspect("equal")
        ax.set_title(f"t = {t:g}")
        ax.legend(loc="upper right", fontsize=7, markerscale=4)
    for ax in list(axes.flat)[len(times):]:
        ax.axis("off")
    fig.suptitle(rf"Contact zone, $\mu$ = {mu:g}, $\varepsilon_T$ = {run['eps_T']:g} (x, y of the active contact points)")
    save(fig, dst)
    plt.close(fig)


def sticking_circle(rows, a, dst):
    fig, ax = plt.subplots(figsize=(7, 4.8))
    r_max = max(float(r["r"]) for r in rows) * 1.1
    marks = {"stick": ("o", "sticks"), "partial slip": ("D", "holds, partial slip"), "slide": ("x", "slides")}
    for k, mu in enumerate(sorted({float(r["mu"]) for r in rows})):
        colour = f"C{k}"
        xs = [r_max * i / 200 for i in range(201)]
        ax.plot(xs, [min(a * x, mu) for x in xs], "-", c=colour, lw=1,
                label=rf"min($a r$, $\mu$), $\mu$ = {mu:g}")
        ax.axvline(mu / a, c=colour, ls=":", lw=1)
        for state, (m, text) in marks.items():
            sel = [r for r in rows if float(r["mu"]) == mu and r["state"] == state]
            if sel:
                ax.plot([float(r["r"]) for r in sel], [float(r["T_over_N"]) for r in sel], m, c=colour,
                        ms=7, mfc="none" if state == "slide" else colour, label=rf"block {text}, $\mu$ = {mu:g}")
    ax.set_xlabel("distance r of the block from the saddle point")
    ax.set_ylabel("contact force ratio T / N")
    ax.set_title(r"Sticking circle $r = \mu / a$ (79)-(81): a small block on z = a x y")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    save(fig, dst)
    plt.close(fig)


def main(d):
    summary = json.load(open(os.path.join(d, "saddle_summary.json")))
    blocks = os.path.join(d, "saddle_blocks.csv")
    if os.path.exists(blocks):
        rows = [r for r in csv.DictReader(open(blocks)) if r["state"] != "no contact"]
        if rows:
            sticking_circle(rows, summary["a"], os.path.join(d, "saddle_sticking_circle.png"))
    rows = list(csv.DictReader(open(os.path.join(d, "saddle.csv"))))
    if not rows:
        return  # --blocks-only
    load_deflection(rows, os.path.join(d, "saddle_load_deflection.png"))
    for run in summary["runs"]:
        path = os.path.join(d, f"contact_{run['name']}.csv")
        if not os.path.exists(path):
            continue
        points = list(csv.DictReader(open(path)))
        half = max([abs(float(p[k])) for p in points for k in ("x", "y")] + [1.0]) * 1.05
        contact_zones(points, run, summary["a"], half, os.path.join(d, f"saddle_contact_{run['name']}.png"))


if __name__ == "__main__":
    cli(main, __doc__, nargs=1)
