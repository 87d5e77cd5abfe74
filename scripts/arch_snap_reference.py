#!/usr/bin/env python3
"""Reference path of data/arch_snap.json (issue 17): a shallow pinned circular arch under a
central point load, as the extensible Kirchhoff elastica the rod element discretizes (Green
axial strain eps = (l^2 - 1)/2 with the stretch l, tangential force EA eps l; curvature per
reference length, moment EI (theta' - theta_0')), by shooting from the support to the apex
(symmetric half) and pseudo-arclength continuation in (theta_0, H, P, delta).

Unknowns at the pinned support: the end angle theta_0 (no moment there) and the horizontal
reaction H; the vertical reaction is P/2. Conditions at the apex: theta = 0 and x = 0 (the
symmetry plane) and y = rise - delta. Prints the limit points (P, delta) and the apex deflection
under P = 0.01 on the far branch; with --table, the path (delta, P) every few steps.

usage: arch_snap_reference.py [--table]
"""
import sys

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve

R, HALF_ANGLE, EI, EA = 100.0, np.radians(10.0), 1.0, 10.0
S = R * HALF_ANGLE  # reference length of the half arch
X0, Y0 = -R * np.sin(HALF_ANGLE), 0.0  # the support
RISE = R * (1.0 - np.cos(HALF_ANGLE))


def stretch(n_t):
    """l with EA (l^2 - 1)/2 l = n_t (Newton from 1)."""
    l = 1.0
    for _ in range(60):
        l -= (l**3 - l - 2.0 * n_t / EA) / (3.0 * l * l - 1.0)
    return l


def shoot(theta0, H, P):
    V = 0.5 * P

    def rhs(_, z):
        x, y, th = z
        m = (x - X0) * V - (y - Y0) * H  # moment of the support's reaction (H, V)
        l = stretch(-(H * np.cos(th) + V * np.sin(th)))  # tangential force: compression < 0
        return [l * np.cos(th), l * np.sin(th), -1.0 / R + m / EI]

    sol = solve_ivp(rhs, [0.0, S], [X0, Y0, theta0], rtol=1e-12, atol=1e-14, method="DOP853")
    return sol.y[:, -1]


SCALE = np.array([0.1, 0.05, 0.01, 1.0])  # theta_0, H, P, delta


def conditions(zs):
    theta0, H, P, delta = zs * SCALE
    x, y, th = shoot(theta0, H, P)
    return np.array([th, x, y - (RISE - delta)])


def path(ds=0.05, delta_end=2.5 * RISE):
    z = np.array([HALF_ANGLE, 0.0, 0.0, 0.0]) / SCALE
    tangent = np.array([0.0, 0.0, 0.0, 1.0])
    points = [z * SCALE]
    while points[-1][3] < delta_end:
        z_prev = z

        def eqs(w, z_prev=z_prev, tangent=tangent):
            return np.concatenate([conditions(w), [np.dot(w - z_prev, tangent) - ds]])

        z = fsolve(eqs, z_prev + ds * tangent, xtol=1e-14)
        if np.max(np.abs(eqs(z))) > 1e-10:
            raise RuntimeError("continuation failed at delta = %g" % (z[3] * SCALE[3]))
        tangent = (z - z_prev) / np.linalg.norm(z - z_prev)
        points.append(z * SCALE)
    return np.array(points)


def refine_extremum(p, k):
    """The limit point near path point k: dP/ds = 0 along the path, by bisection on the
    continuation restarted between points k-1 and k+1 (parabola through the three first)."""
    d, P = p[k - 1:k + 2, 3], p[k - 1:k + 2, 2]
    c = np.polyfit(d, P, 2)
    d_star = -c[1] / (2.0 * c[0])
    # solve the conditions at that delta for theta_0, H, P (near the limit point P is flat in
    # delta, so delta is a good parameter there)
    z0 = p[k, :3] / SCALE[:3]
    z = fsolve(lambda w: conditions(np.append(w, d_star / SCALE[3])), z0, xtol=1e-14)
    # the maximum over a fine scan in delta around d_star
    best = None
    for dd in np.linspace(d_star - 0.02, d_star + 0.02, 41):
        z = fsolve(lambda w: conditions(np.append(w, dd / SCALE[3])), z, xtol=1e-14)
        Pv = z[2] * SCALE[2]
        if best is None or (c[0] < 0 and Pv > best[1]) or (c[0] > 0 and Pv < best[1]):
            best = (dd, Pv)
    return best


def main():
    p = path()
    P = p[:, 2]
    for k in range(1, len(P) - 1):
        if (P[k] - P[k - 1]) * (P[k + 1] - P[k]) < 0.0:
            d_star, P_star = refine_extremum(p, k)
            kind = "maximum" if P[k] > P[k - 1] else "minimum"
            print("limit point (%s): P = %.6e at apex deflection %.5f" % (kind, P_star, d_star))
    # the far branch at P = 0.01
    k = int(np.argmin(np.abs(P[len(P) // 2:] - 0.01))) + len(P) // 2
    z = fsolve(lambda w: conditions(np.array([w[0], w[1], 0.01 / SCALE[2], w[2]])),
               np.array([p[k, 0] / SCALE[0], p[k, 1] / SCALE[1], p[k, 3]]), xtol=1e-14)
    print("apex deflection under P = 0.01 on the far branch: %.6f" % z[2])
    if "--table" in sys.argv:
        for row in p[::4]:
            print("%.5f %.7e" % (row[3], row[2]))


if __name__ == "__main__":
    main()
