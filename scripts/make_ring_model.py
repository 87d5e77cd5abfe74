#!/usr/bin/python3
"""Writes data/ring_between_plates.json: a quarter of a circular ring (R = 1) as an exact
rational curve (the quadratic quarter circle elevated to degree 4, then split into 16 elements by
knot insertion: C^3 quartic elements, free of the membrane locking that quadratic ones show at
EA R^2 / EI = 1e6), and the analysis of it crushed between two plates.

usage: make_ring_model.py [out.json]
"""
import sys
import json
import math
def insert(p, U, Pw, u):
    # Boehm knot insertion, homogeneous control points Pw (lists of 4)
    k = max(i for i in range(len(U)-1) if U[i] <= u < U[i+1])
    Q = []
    for i in range(len(Pw)+1):
        if i <= k - p: Q.append(Pw[i])
        elif i >= k + 1: Q.append(Pw[i-1])
        else:
            a = (u - U[i]) / (U[i+p] - U[i])
            Q.append([a*Pw[i][j] + (1-a)*Pw[i-1][j] for j in range(4)])
    return U[:k+1] + [u] + U[k+1:], Q
R = 1.0; w = math.sqrt(0.5)
P = [[0, R, 0], [R, R, 0], [R, 0, 0]]; W = [1, w, 1]
Pw = [[P[i][0]*W[i], P[i][1]*W[i], P[i][2]*W[i], W[i]] for i in range(3)]
from math import comb
deg = 4  # the quadratic arc elevated (exact), then split: C^3 quartic elements (no locking)
Pw = [[sum(comb(2, j) * comb(deg - 2, i - j) / comb(deg, i) * Pw[j][c]
           for j in range(max(0, i - deg + 2), min(2, i) + 1)) for c in range(4)]
      for i in range(deg + 1)]
U = [0] * (deg + 1) + [1] * (deg + 1)
n = 16
for k in range(1, n):
    U, Pw = insert(deg, U, Pw, k / n)
pts = [[q[0]/q[3], q[1]/q[3], q[2]/q[3]] for q in Pw]; wts = [q[3] for q in Pw]
m = {"format": "iga-contact-model", "version": 1, "name": "ring_between_plates",
 "description": "An elastic ring (R = 1, EI = 1, EA = 1e6) crushed between two rigid plates that move towards each other (issue 14): a quarter of the ring (from the top point, where the upper plate touches it, to the side point), symmetric about the planes x = 0 and y = 0 (the lower plate is the mirror image of the upper one). For small deflection the change of diameter is delta = (pi/4 - 2/pi) P R^3 / EI = 0.1488 P R^3 / EI (Timoshenko, Strength of Materials; Roark), P the plate force: twice the force on the quarter's plate (steps.csv plate_on_ring_Fy), delta twice the top point's descent (top_uy). Then large deflection: the upper plate travels 0.4 R (delta = 0.8 R), the contact zone grows from a point to a flat. The quarter model imposes the symmetry.",
 "geometry": {
   "ring": {"type": "nurbs_curve", "degree": deg, "knots": U, "control_points": pts, "weights": wts},
   "plate": {"type": "plane", "center": [0, R, 0], "axis": [0, -1, 0], "domain": {"u": [-0.5, 1.5], "v": [-0.5, 0.5]}}},
 "materials": {"ring": {"type": "rod", "EA": 1e6, "EI": 1.0}},
 "bodies": {"ring": {"type": "rod", "curve": "ring", "material": "ring"}},
 "load_curves": {"travel": {"type": "ramp", "description": "the upper plate's travel: 0.4 at t = 1"}},
 "boundary_conditions": [
   {"type": "symmetry", "body": "ring", "end": "start", "normal": [1, 0, 0], "description": "plane x = 0 through the top point"},
   {"type": "symmetry", "body": "ring", "end": "end", "normal": [0, 1, 0], "description": "plane y = 0 through the side point"},
   {"type": "fix", "body": "ring", "points": "all", "components": [2], "description": "planar"}],
 "contact": [{"name": "plate_on_ring", "type": "curve_to_rigid", "body": "ring", "rigid": "plate", "eps_N": 1e5, "radius": 0, "points_per_element": 6}],
 "rigid_motions": {"plate": {"translation": {"vector": [0, -0.4, 0], "curve": "travel"}}},
 "solver": {"t_end": 1, "initial_step": 0.005, "max_step": 0.05, "min_step": 1e-7, "max_iterations": 30, "hit_times": [0.005]},
 "output": {"vtk": "all", "monitors": [{"name": "top", "at": "start"}, {"name": "side", "at": "end"}],
            "plots": [{"x": "-2*top_uy", "y": "2*plate_on_ring_Fy", "file": "force_travel.png",
                       "title": "Ring between plates: plate force P against the shortening of the diameter"},
                      {"x": "-2*top_uy", "y": "2*side_ux", "file": "diameters.png",
                       "title": "Lengthening of the horizontal diameter against the shortening of the vertical one"}]}}
open(sys.argv[1] if len(sys.argv) > 1 else 'data/ring_between_plates.json', 'w').write(json.dumps(m, indent=2) + "\n")
