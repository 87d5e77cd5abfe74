#!/usr/bin/env python3
"""Vectorised closest points from Python against the C++ benchmark (issue 35): the certified
cold projections of bench_projection's point sets (A: a band of +-5 % of the patch size around
the surface; B: a box 1.3 times the bounding box; C: far points) onto the free-form bicubic
patch and the NURBS torus, N points per set, through RigidSurface.closest_points on one thread
and on all, medians of 5 runs. Then runs bench_projection on the same surfaces and sets (its
own random points of the same distributions) and prints both rates and their ratio.

    PYTHONPATH=build/release/python python3 bench/bench_python_projection.py [N] [build dir]
"""
import os
import pathlib
import re
import subprocess
import sys
import time

import numpy as np

import rigid_contact_iga as rci

SOURCE = pathlib.Path(__file__).resolve().parents[1]


def point_sets(surface, n, rng):
    (u0, u1), (v0, v1) = surface.domain
    grid = np.stack(np.meshgrid(np.linspace(u0, u1, 60), np.linspace(v0, v1, 60)), -1)
    pts = surface.evaluate(grid.reshape(-1, 2))
    lo, hi = pts.min(0), pts.max(0)
    c, half, diag = 0.5 * (lo + hi), 0.5 * (hi - lo), np.linalg.norm(hi - lo)
    size = 2 * half.max()
    uv = np.column_stack([u0 + (0.02 + 0.96 * rng.random(n)) * (u1 - u0),
                          v0 + (0.02 + 0.96 * rng.random(n)) * (v1 - v0)])
    a = surface.evaluate(uv) + ((2 * rng.random(n) - 1) * 0.05 * size)[:, None] * surface.normals(uv)
    b = c + 1.3 * (2 * rng.random((n, 3)) - 1) * half
    d = rng.random((n, 3)) - 0.5
    far = c + ((1 + 2 * rng.random(n)) * diag)[:, None] * d / np.linalg.norm(d, axis=1)[:, None]
    return {"A": a, "B": b, "C": far}


def rate(n, run):
    times = []
    for _ in range(5):
        t = time.perf_counter()
        run()
        times.append(time.perf_counter() - t)
    return n / sorted(times)[2]


def cpp_rates(build, n, label):
    exe = pathlib.Path(build) / "bench" / "bench_projection"
    out = subprocess.run([str(exe), str(n), label], capture_output=True, text=True, check=True)
    rates = {}
    for line in out.stdout.splitlines():
        m = re.match(rf"{label}\s+([ABC])\s+certified\s+\|\s+cold\s+([0-9.]+) /s", line)
        if m:
            rates[m.group(1)] = float(m.group(2))
    return rates


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 100000
    build = sys.argv[2] if len(sys.argv) > 2 else SOURCE / "build" / "release"
    rng = np.random.default_rng(12345)
    print(f"certified cold closest points, {n} points per set, medians of 5 runs "
          f"({os.cpu_count()} cores)")
    print("surface   set | C++ 1 core /s | Python 1 thread /s  ratio | Python all threads /s")
    for label, file, name in (("freeform", "freeform_bicubic.json", "freeform"),
                              ("torus", "torus_patch.json", "torus")):
        model = rci.Model.load(SOURCE / "data" / file)
        rs = rci.rigid_surface(model, name)
        sets = point_sets(model.geometry_object(name), n, rng)
        cpp = cpp_rates(build, n, label)
        for key, X in sets.items():
            one = rate(n, lambda: rs.closest_points(X, threads=1))
            every = rate(n, lambda: rs.closest_points(X, threads=0))
            c = cpp.get(key, float("nan"))
            print(f"{label:9s} {key}   | {c:13.0f} | {one:18.0f}  {one / c:5.2f} | {every:12.0f}")


if __name__ == "__main__":
    main()
