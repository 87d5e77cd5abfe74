"""rigid_contact_iga: isogeometric contact of rods and shells with rigid NURBS and analytic
surfaces (Konyukhov & Schweizerhof, STAS and CTRS), from Python.

Geometry:   NurbsCurve, NurbsSurface, Plane, Sphere, Cylinder, Torus, Cone, Hyperboloid, with
            evaluate / derivatives / normals vectorised over numpy parameter arrays.
Contact:    RigidSurface (from surfaces, a model's geometry or a STEP/IGES file) with
            closest_points(X) and rays(X, D) over (N, 3) arrays, on all threads.
Models:     Model (load, from_dict, step by step, set, save, check, run) and Result (the steps
            table, displacements, contact points and sampled bodies as numpy arrays).
Errors:     ModelError (a ValueError with .file, .pointer, .message), CadError, RestartError.

docs/python.md has the guide.
"""

from ._core import (Cone, Cylinder, Hyperboloid, NurbsCurve, NurbsSurface, Plane, RigidSurface,
                    Sphere, Surface, Torus, CadError, ModelError, RestartError)
from .model import Model, Result

__all__ = ["Cone", "Cylinder", "Hyperboloid", "NurbsCurve", "NurbsSurface", "Plane",
           "RigidSurface", "Sphere", "Surface", "Torus", "CadError", "ModelError",
           "RestartError", "Model", "Result", "rigid_surface"]


def rigid_surface(model, name):
    """The rigid surface `name` (a surface or patch group of the geometry section) of a Model
    or of a model file."""
    if not isinstance(model, Model):
        model = Model.load(model)
    return RigidSurface._from_model_json(model._text(), model.file, name)
