#!/usr/bin/env python3
"""The 45-degree bend (Bathe & Bolourchi 1979; Simo & Vu-Quoc 1986) in the inextensible Kirchhoff
rod theory, by shooting: the reference for tests/iga/rod/test_twisting_rod.cpp.

A cantilever bent to a 45-degree arc of radius 100 in the x-y plane (clamped at the origin,
tangent +y, arc centre (100, 0, 0)), 1 x 1 section, E = 1e7, G = 5e6, EI = E/12, GJ = G/6, a
dead vertical force P at the tip. With no distributed load the force resultant is P e_z along
the rod and the moment is m(s) = (r(L) - r(s)) x P e_z; the frame (d1 = tangent, d2, d3) turns
at the material curvature w = K + C^-1 R^T m, C = diag(GJ, EI, EI), K = (0, 0, 1/100). The tip
r(L) is found by Newton (scipy's fsolve) on r(L) = the integrated r at s = L.
Usage: scripts/bend45_kirchhoff.py [P ...]   (default: 300 450 600)
"""
import sys

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve

E, G, RADIUS = 1e7, 5e6, 100.0
C = np.diag([G / 6.0, E / 12.0, E / 12.0])
K = np.array([0.0, 0.0, 1.0 / RADIUS])
L = RADIUS * np.pi / 4.0
# d1 = +y, d3 = -z, d2 = d3 x d1 = +x: turning about d3 bends the tangent towards +x.
FRAME0 = np.column_stack([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])


def tip_of(r_tip, force):
    def rhs(_, y):
        r, frame = y[:3], y[3:].reshape(3, 3)
        w = K + np.linalg.solve(C, frame.T @ np.cross(r_tip - r, force))
        wx = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
        return np.concatenate([frame[:, 0], (frame @ wx).ravel()])

    y0 = np.concatenate([np.zeros(3), FRAME0.ravel()])
    return solve_ivp(rhs, [0.0, L], y0, rtol=1e-12, atol=1e-12).y[:3, -1]


def main():
    loads = [float(a) for a in sys.argv[1:]] or [300.0, 450.0, 600.0]
    guess = tip_of(np.zeros(3), np.zeros(3))  # the unloaded tip (29.29, 70.71, 0)
    print(f"unloaded tip ({guess[0]:.4f}, {guess[1]:.4f}, {guess[2]:.4f})")
    for p in loads:
        force = np.array([0.0, 0.0, p])
        guess = fsolve(lambda q: tip_of(q, force) - q, guess, xtol=1e-13)
        print(f"P = {p:6.1f}: tip ({guess[0]:.4f}, {guess[1]:.4f}, {guess[2]:.4f})")


if __name__ == "__main__":
    main()
