#!/usr/bin/env python3
"""A parameter study of the driven drum (data/driven_drum.json): a belt over a drum that turns
once the dead load T0 is applied. For each friction coefficient mu the belt slides over the
whole arc and the anchored end carries T_B = T0 exp(mu pi) (Euler-Eytelwein), and the drum
feels the torque (T_B - T0) R about its axis (R the radius of the belt's centre line).
Prints both against the formulas and draws T_B / T0 over the turn for every mu.

    python3 drum_study.py [--quick] [--out DIR]
"""
import argparse
import math
import os
import pathlib

import numpy as np

import rigid_contact_iga as rci

SOURCE = pathlib.Path(os.environ.get("IGA_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="two values of mu")
    parser.add_argument("--out", default="out/python_drum", help="folder of the plot and CSV")
    args = parser.parse_args()
    base = rci.Model.load(SOURCE / "data/driven_drum.json")
    t0 = base.get("/loads/0/magnitude")
    radius = base.get("/geometry/rope/radius")
    mus = [0.1, 0.3] if args.quick else [0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4]
    rows, curves, worst = [], {}, 0.0
    for mu in mus:
        m = rci.Model.from_dict(base.to_dict(), file=base.file).set("/contact/0/mu", mu)
        result = m.run()
        if not result.converged:
            raise RuntimeError(f"mu = {mu}: {result.message}")
        steps = result.steps
        tb = next(c for c in result.columns if c.startswith("R") and c.endswith("_norm"))
        ratio = steps[tb][-1] / t0
        torque = abs(steps[result.pair_names[0] + "_Mz"][-1])
        exact = math.exp(mu * math.pi)
        exact_torque = (exact - 1.0) * t0 * radius
        worst = max(worst, abs(ratio - exact) / exact, abs(torque - exact_torque) / exact_torque)
        rows.append((mu, ratio, exact, torque, exact_torque))
        curves[mu] = (steps["t"], steps[tb] / t0)
    print("   mu   T_B/T0  exp(mu pi)   torque  (e^(mu pi)-1) T0 R")
    for mu, r, e, q, eq in rows:
        print(f"{mu:5.2f} {r:8.4f} {e:10.4f} {q:9.4f} {eq:12.4f}")
    print(f"largest relative error {worst:.2e}")
    os.makedirs(args.out, exist_ok=True)
    np.savetxt(os.path.join(args.out, "drum_study.csv"), np.array(rows), delimiter=",",
               header="mu,TB_over_T0,exp_mu_pi,torque,torque_formula", comments="")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 3.5))
    for mu, (t, r) in curves.items():
        ax.plot(t, r, label=rf"$\mu$ = {mu}")
        ax.axhline(math.exp(mu * math.pi), color="gray", lw=0.5, ls="--")
    ax.set_xlabel("t (drum turned from t = 1)")
    ax.set_ylabel(r"$T_B/T_0$")
    ax.legend(fontsize=8)
    fig.tight_layout()
    png = os.path.join(args.out, "drum_study.png")
    fig.savefig(png, dpi=120)
    print("plot:", png)
    # T_B within 1e-3 of the formula as the capstan (bending stiffness, discretization)
    return 0 if worst < 1e-3 else 1


if __name__ == "__main__":
    raise SystemExit(main())
