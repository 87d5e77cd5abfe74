#!/usr/bin/env python3
"""The capstan from Python: a rope over a rigid cylinder (data/capstan.json), pulled until the
whole contact arc slides, for friction coefficients mu at a wrap angle phi. At full slip the
tension ratio T/T0 is exp(mu phi) (Euler-Eytelwein; [KS15] Sect. 6.3). Draws T/T0 against the
formula and prints the relative errors.

    python3 capstan_sweep.py [--quick] [--out DIR]
"""
import argparse
import math
import os
import pathlib

import numpy as np

import rigid_contact_iga as rci

SOURCE = pathlib.Path(os.environ.get("IGA_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


def tension_ratio(model, mu, phi_deg):
    """T/T0 at full slip: the reaction at the pulled end over the dead load T0. A run that ends
    before the whole arc slides is pulled again twice as far (as the capstan app does)."""
    m = rci.Model.from_dict(model.to_dict(), file=model.file)
    m.set("/contact/0/mu", mu).set("/geometry/rope/angle_deg", phi_deg)
    pull = m.get("/boundary_conditions/1/magnitude")
    while True:
        result = m.run()
        if result.full_slip:
            break
        if not result.converged or pull * 2 > model.get("/app/max_pull"):
            raise RuntimeError(f"mu = {mu}, phi = {phi_deg} deg: no full slip ({result.message})")
        pull *= 2
        m.set("/boundary_conditions/1/magnitude", pull)
    column = next(c for c in result.columns if c.startswith("R") and c.endswith("_norm"))
    return result.steps[column][-1] / m.get("/loads/0/magnitude")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="three values of mu")
    parser.add_argument("--out", default="out/python_capstan", help="folder of the plot")
    args = parser.parse_args()
    model = rci.Model.load(SOURCE / "data/capstan.json")
    phi_deg = 180.0
    mus = [0.0, 0.3, 0.6] if args.quick else list(np.round(np.linspace(0, 1, 11), 2))
    ratios = [tension_ratio(model, mu, phi_deg) for mu in mus]
    exact = [math.exp(mu * math.radians(phi_deg)) for mu in mus]
    print("   mu    T/T0    exp(mu phi)   rel. error")
    for mu, r, e in zip(mus, ratios, exact):
        print(f"{mu:5.2f} {r:9.5f} {e:11.5f}   {abs(r - e) / e:9.2e}")
    worst = max(abs(r - e) / e for r, e in zip(ratios, exact))
    print(f"largest relative error {worst:.2e}")
    os.makedirs(args.out, exist_ok=True)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fine = np.linspace(0, max(mus), 100)
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.plot(fine, np.exp(fine * math.radians(phi_deg)), "k-", label=r"$e^{\mu\varphi}$")
    ax.plot(mus, ratios, "o", label="rigid_contact_iga")
    ax.set_xlabel(r"$\mu$")
    ax.set_ylabel(r"$T/T_0$")
    ax.set_title(r"Capstan, $\varphi$ = 180°")
    ax.legend()
    fig.tight_layout()
    png = os.path.join(args.out, "capstan_sweep.png")
    fig.savefig(png, dpi=120)
    print("plot:", png)
    # The rope's bending stiffness (EI / (T0 R^2) = 1e-4) and the discretization keep T/T0
    # within about 3e-4 of the formula (BENCHMARKS.md); 1e-3 leaves room for round-off.
    return 0 if worst < 1e-3 else 1


if __name__ == "__main__":
    raise SystemExit(main())
