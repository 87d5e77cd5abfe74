#!/usr/bin/env python3
"""A point cloud projected on a STEP part: the certified closest points of points scattered
around the part (every face, trimmed or not), with their distances, feet and normals as numpy
arrays, on all threads. Checks each foot p of a point X by the closest point's own geometry:
the midpoint of X and p has the same foot, at half the distance. Writes the feet with their
distances (CSV) and a histogram of the distances.

    python3 point_cloud.py [PART.step] [--points N] [--quick] [--out DIR]
"""
import argparse
import os
import pathlib
import time

import numpy as np

import rigid_contact_iga as rci

SOURCE = pathlib.Path(os.environ.get("IGA_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("part", nargs="?", default=str(SOURCE / "data/cad/sheave_v30.step"))
    parser.add_argument("--points", type=int, default=100000)
    parser.add_argument("--quick", action="store_true", help="2000 points")
    parser.add_argument("--out", default="out/python_point_cloud")
    args = parser.parse_args()
    n = 2000 if args.quick else args.points
    part = rci.RigidSurface.from_cad(args.part)
    lo, hi = (b[0] for b in part.box)
    print(f"{args.part}: {part.num_pieces} faces, box {lo} .. {hi}")
    rng = np.random.default_rng(1)
    X = lo + (hi - lo) * rng.uniform(-0.1, 1.1, size=(n, 3))
    start = time.perf_counter()
    r = part.closest_points(X)
    seconds = time.perf_counter() - start
    ok = np.isin(r["status"], ["interior", "edge", "vertex"])
    print(f"{n} points in {seconds:.3f} s ({n / seconds:,.0f} per second); "
          f"{ok.sum()} feet, {r['certified'].sum()} certified")
    mid = r["point"][ok] + 0.5 * (X[ok] - r["point"][ok])
    again = part.closest_points(mid)
    size = np.linalg.norm(hi - lo)
    err = max(np.max(np.abs(np.abs(again["distance"]) - 0.5 * np.abs(r["distance"][ok]))),
              np.max(np.linalg.norm(again["point"] - r["point"][ok], axis=1)))
    print(f"midpoint check: largest deviation {err / size:.1e} of the part's size")
    os.makedirs(args.out, exist_ok=True)
    table = np.column_stack([X[ok], r["point"][ok], r["normal"][ok], r["distance"][ok],
                             r["patch"][ok]])
    np.savetxt(os.path.join(args.out, "feet.csv"), table, delimiter=",",
               header="x,y,z,px,py,pz,nx,ny,nz,distance,face", comments="")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.hist(np.abs(r["distance"][ok]), bins=60)
    ax.set_xlabel("distance to the part")
    ax.set_ylabel("points")
    ax.set_title(os.path.basename(args.part))
    fig.tight_layout()
    png = os.path.join(args.out, "distances.png")
    fig.savefig(png, dpi=120)
    print("plot:", png)
    return 0 if ok.mean() > 0.99 and err < 1e-7 * size else 1


if __name__ == "__main__":
    raise SystemExit(main())
