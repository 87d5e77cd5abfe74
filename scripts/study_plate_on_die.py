#!/usr/bin/python3
"""Mesh and penalty study of data/plate_on_die.json against the strip (cylindrical bending)
solution of a Kirchhoff plate pressed by q onto a flat support that turns into a fillet of
radius r at x_s (small slopes, D = E h^3 / (12 (1 - nu^2))):

  the plate lies on the flat up to a, where it lifts off with a line force F_a = q e; it spans
  freely to b = x_s + e on the fillet (landing line force F_b = q (s - e)), wraps the fillet
  with pressure q up to c = L - sqrt(2 D / (q r)), leaves it with a line force F_c = q (L - c)
  and hangs free to its edge L;  s = b - a = 12^(1/4) sqrt(D / (q r)),  e = s/2 - D / (q r s).

(The free span a..b is the quartic w = -q t^4 / (24 D) + C t^3 from a, where w = w' = w'' = 0;
at b it meets the fillet with its height, slope and curvature -1/r.) Along the line x = 0 of
the plate (far from the die's corners) the contact pressure of each run is integrated over the
flat part (0 < y < x_s: q a + F_a) and the fillet (y > x_s: F_b + q (c - b) + F_c) and the ends
of its contact zones are read off. The springs that hold the plate before contact (one per
control point) are softened to 1e-3 (24/n)^2 on n x n elements, the same foundation modulus on
every mesh, ~0.06 per unit area (with 0.01 they would carry ~3 % of the load at the
overhang), and the first step is 0.005 so that the free plate does not fall past the search
distance before it touches.

usage: study_plate_on_die.py [OUT_DIR]   (needs build/release/apps/iga; ~2 min on 2 cores)
writes OUT_DIR/plate_on_die_study.csv and .png (pressure along x = 0, each run, theory marked)
"""
import csv
import math
import os
import subprocess
import sys

from plot_common import save
from plot_vtk_line import read_vtk

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
IGA = os.path.join(ROOT, "build", "release", "apps", "iga")
MODEL = os.path.join(ROOT, "data", "plate_on_die.json")

E, H, NU, Q, R, L, XS = 1e5, 0.01, 0.3, 1.0, 0.5, 1.8, 1.5


def strip_theory():
    D = E * H**3 / (12 * (1 - NU**2))
    s = 12**0.25 * math.sqrt(D / (Q * R))
    e = s / 2 - D / (Q * R * s)
    b = XS + e
    a = b - s
    c = L - math.sqrt(2 * D / (Q * R))
    fb, fw, fc = Q * (s - e), Q * (c - b), Q * (L - c)
    return {"a": a, "b": b, "c": c, "flat": Q * a + Q * e, "fillet": fb + fw + fc,
            "centroid": (fb * b + fw * (b + c) / 2 + fc * c) / (fb + fw + fc)}


def along_x0(vtk):
    points, p = read_vtk(vtk, "contact_pressure")
    line = sorted((pt[1], v) for pt, v in zip(points, p) if abs(pt[0]) < 1e-3 and pt[1] >= -1e-9)
    return [y for y, _ in line], [v for _, v in line]


def integrate(y, p, lo, hi):
    total = 0.0
    for k in range(len(y) - 1):
        m = 0.5 * (y[k] + y[k + 1])
        if lo <= m < hi:
            total += 0.5 * (p[k] + p[k + 1]) * (y[k + 1] - y[k])
    return total


def centroid(y, p, lo):
    """Where the resultant of the pressure beyond lo acts."""
    num = den = 0.0
    for k in range(len(y) - 1):
        m = 0.5 * (y[k] + y[k + 1])
        if m >= lo:
            f = 0.5 * (p[k] + p[k + 1]) * (y[k + 1] - y[k])
            num, den = num + f * m, den + f
    return num / den if den > 0 else float("nan")


def zones(y, p):
    """(a, b, c): last sample in contact on the flat, first and last on the fillet."""
    flat = [yy for yy, v in zip(y, p) if v > 0 and yy < XS]
    fillet = [yy for yy, v in zip(y, p) if v > 0 and yy >= XS]
    return (max(flat) if flat else float("nan"), min(fillet) if fillet else float("nan"),
            max(fillet) if fillet else float("nan"))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "out", "plate_on_die_study")
    os.makedirs(out, exist_ok=True)
    th = strip_theory()
    print("strip theory: a = %.4f, b = %.4f, c = %.4f, flat %.4f, fillet %.4f at %.4f" %
          (th["a"], th["b"], th["c"], th["flat"], th["fillet"], th["centroid"]))
    rows, curves = [], []
    for n, eps in [(24, 1e4), (48, 1e4), (24, 1e5), (48, 1e5)]:
        run = os.path.join(out, f"n{n}_eps{eps:g}")
        done = subprocess.run([IGA, "run", MODEL, "-o", run, "-q",
                        "--set", f"/geometry/plate/refine/subdivide={n}",
                        "--set", f"/contact/0/eps_N={eps:g}",
                        "--set", f"/boundary_conditions/1/stiffness={1e-3 * (24 / n)**2:g}",
                        "--set", "/solver/initial_step=0.005",
                        # pressure samples 0.01 apart: the line forces are resolved
                        "--set", f"/output/samples_per_element={384 // n}"])
        if done.returncode != 0:  # reported by iga run; its results so far are in `run`
            print(f"{n} elements, eps_N {eps:.0e}: iga run failed (exit {done.returncode})")
            continue
        y, p = along_x0(os.path.join(run, "last_shell.vts"))
        a, b, c = zones(y, p)
        flat, fillet = integrate(y, p, 0.0, XS), integrate(y, p, XS, 10.0)
        rows.append({"elements": n, "eps_N": eps, "a": a, "b": b, "c": c, "flat": flat,
                     "fillet": fillet, "fillet_error": fillet / th["fillet"] - 1,
                     "fillet_centroid": centroid(y, p, XS),
                     "p_max": max(p)})
        curves.append((f"{n} x {n}, eps_N = {eps:g}", y, p))
        print("%2d elements, eps_N %.0e: a %.4f  b %.4f  c %.4f  flat %.4f  fillet %.4f (%+.1f %%)"
              " at %.4f  p_max %.2f" % (n, eps, a, b, c, flat, fillet,
                                        100 * rows[-1]["fillet_error"],
                                        rows[-1]["fillet_centroid"], max(p)))
    if not rows:
        sys.exit("study_plate_on_die: no run converged")
    with open(os.path.join(out, "plate_on_die_study.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for label, y, p in curves:
        ax.plot(y, p, label=label, lw=1)
    for key in ("a", "b", "c"):
        ax.axvline(th[key], color="k", ls=":", lw=0.8)
    ax.axvline(XS, color="r", ls="--", lw=0.8, label="seam flat top / fillet")
    ax.set_xlim(0.8, L)
    ax.set_xlabel("y (x = 0)")
    ax.set_ylabel("contact pressure")
    ax.set_title("plate on the filleted die: strip theory a, b, c dotted")
    ax.legend(fontsize=8)
    save(fig, os.path.join(out, "plate_on_die_study.png"))


if __name__ == "__main__":
    main()
