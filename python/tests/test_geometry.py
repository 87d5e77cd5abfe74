"""Geometry from numpy: NURBS curves and surfaces against closed forms, derivatives against
finite differences, analytic surfaces, and bad arguments raising Python exceptions."""
import math

import numpy as np
import pytest

import rigid_contact_iga as rci

W = math.sqrt(0.5)


def quarter_circle(radius=1.0):
    """The rational quadratic quarter circle of radius R in the xy-plane."""
    return rci.NurbsCurve(2, [0, 0, 0, 1, 1, 1], [[radius, 0, 0], [radius, radius, 0],
                                                  [0, radius, 0]], [1, W, 1])


def quarter_cylinder(radius=2.0, height=3.0):
    """A quarter of the cylinder x^2 + y^2 = R^2, 0 <= z <= H: circle in u, line in v."""
    arc = np.array([[radius, 0, 0], [radius, radius, 0], [0, radius, 0]], float)
    P = np.stack([arc, arc + [0, 0, height]], axis=1)  # (3, 2, 3): i along u
    w = np.array([[1, 1], [W, W], [1, 1]])
    return rci.NurbsSurface(2, 1, [0, 0, 0, 1, 1, 1], [0, 0, 1, 1], P, w)


def test_curve_points_lie_on_the_circle():
    c = quarter_circle(1.5)
    u = np.linspace(0, 1, 101)
    x = c.evaluate(u)
    assert x.shape == (101, 3)
    np.testing.assert_allclose(np.linalg.norm(x, axis=1), 1.5, rtol=1e-14)
    C, dC, ddC = c.derivatives(u, 2)
    np.testing.assert_allclose(np.einsum("ij,ij->i", C, dC), 0, atol=1e-13)  # tangent _|_ radius
    h = 1e-6
    inner = u[1:-1]  # central differences inside the domain: error O(h^2)
    fd = (c.evaluate(inner + h) - c.evaluate(inner - h)) / (2 * h)
    np.testing.assert_allclose(dC[1:-1], fd, atol=1e-8)
    fd2 = (c.derivatives(inner + h, 1)[1] - c.derivatives(inner - h, 1)[1]) / (2 * h)
    np.testing.assert_allclose(ddC[1:-1], fd2, atol=1e-7)
    assert c.degree == 2 and c.control_points.shape == (3, 3)
    np.testing.assert_allclose(c.weights, [1, W, 1])
    assert c.domain == (0.0, 1.0)


def test_surface_points_normals_and_derivatives():
    s = quarter_cylinder()
    rng = np.random.default_rng(3)
    uv = rng.random((200, 2))
    x = s.evaluate(uv)
    np.testing.assert_allclose(np.hypot(x[:, 0], x[:, 1]), 2.0, rtol=1e-14)
    np.testing.assert_allclose(x[:, 2], 3.0 * uv[:, 1], rtol=1e-14)
    n = s.normals(uv)
    radial = x.copy()
    radial[:, 2] = 0
    radial /= np.linalg.norm(radial, axis=1)[:, None]
    # rho_u x rho_v points outward for this net (u counter-clockwise, v up)
    np.testing.assert_allclose(n, radial, atol=1e-13)
    d = s.derivatives(uv)
    h = 1e-6
    for k, name in ((0, "Su"), (1, "Sv")):
        e = np.zeros(2)
        e[k] = h
        fd = (s.evaluate(np.clip(uv + e, 0, 1)) - s.evaluate(np.clip(uv - e, 0, 1))) / (2 * h)
        np.testing.assert_allclose(d[name], fd, atol=1e-6)
    fd = (s.derivatives(np.clip(uv + [h, 0], 0, 1))["Su"] -
          s.derivatives(np.clip(uv - [h, 0], 0, 1))["Su"]) / (2 * h)
    np.testing.assert_allclose(d["Suu"], fd, atol=1e-5)
    assert s.control_points.shape == (3, 2, 3) and s.weights.shape == (3, 2)
    np.testing.assert_allclose(s.control_points[1, 1], [2, 2, 3])
    s.normal_sign = -1
    np.testing.assert_allclose(s.normals(uv[:5]), -radial[:5], atol=1e-13)


def test_analytic_surfaces():
    sp = rci.Sphere(2.0, center=[1, 0, 0])
    (u0, u1), (v0, v1) = sp.domain
    uv = np.column_stack([np.linspace(u0, u1, 50), np.linspace(v0 * 0.9, v1 * 0.9, 50)])
    x = sp.evaluate(uv)
    np.testing.assert_allclose(np.linalg.norm(x - [1, 0, 0], axis=1), 2.0, rtol=1e-14)
    np.testing.assert_allclose(sp.normals(uv), (x - [1, 0, 0]) / 2.0, atol=1e-14)
    cyl = rci.Cylinder(0.5, axis=[1, 0, 0], domain=((0, math.pi), (-1, 1)))
    y = cyl.evaluate([[0.3, 0.7]])
    assert abs(math.hypot(y[0, 1], y[0, 2]) - 0.5) < 1e-15 and abs(y[0, 0] - 0.7) < 1e-15
    t = rci.Torus(3.0, 1.0)
    assert t.type == "torus" and t.closed_u and t.closed_v


def test_bad_arguments_raise():
    s = quarter_cylinder()
    with pytest.raises(ValueError, match=r"uv: expected shape \(N, 2\), got \(4, 3\)"):
        s.evaluate(np.zeros((4, 3)))
    with pytest.raises(TypeError, match="uv: expected an array of real numbers, got dtype"):
        s.evaluate(np.array([["a", "b"]]))
    with pytest.raises(TypeError, match="real numbers"):
        s.evaluate(np.array([[1 + 2j, 0]]))
    with pytest.raises(ValueError, match="uv: row 1 holds nan"):
        s.evaluate([[0.5, 0.5], [math.nan, 0.1]])
    with pytest.raises(ValueError, match=r"uv\[:, 0\]: row 0: 1.5 is outside the domain"):
        s.evaluate([[1.5, 0.5]])
    with pytest.raises(ValueError):  # decreasing knots: the C++ GeometryError
        rci.NurbsCurve(2, [0, 0, 0, 1, 0.5, 1], [[0, 0, 0], [1, 0, 0], [2, 0, 0]])
    with pytest.raises(ValueError, match=r"control_points: expected shape \(n_u, n_v, 3\)"):
        rci.NurbsSurface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1], np.zeros((4, 3)))
    with pytest.raises(ValueError, match="weights: expected shape"):
        rci.NurbsSurface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1], np.zeros((2, 2, 3)), np.ones(4))
    with pytest.raises(ValueError, match="center: row 0 holds inf"):
        rci.Sphere(1.0, center=[math.inf, 0, 0])
    with pytest.raises(ValueError, match="order"):
        quarter_circle().derivatives([0.5], 7)


def test_every_public_name_has_a_docstring():
    for name in rci.__all__:
        obj = getattr(rci, name)
        assert obj.__doc__ and obj.__doc__.strip(), name
        for attr in dir(obj):
            if attr.startswith("_"):
                continue
            member = getattr(obj, attr)
            if callable(member) or isinstance(member, property):
                assert member.__doc__ and member.__doc__.strip(), f"{name}.{attr}"
