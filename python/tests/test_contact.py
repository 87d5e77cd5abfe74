"""Rigid surfaces from Python: vectorised closest points and rays against closed forms and the
closest point's own geometry, threads, CAD files, and bad arguments."""
import math

import numpy as np
import pytest

import rigid_contact_iga as rci
from test_geometry import quarter_cylinder


def test_sphere_closest_points_match_the_closed_form():
    rs = rci.RigidSurface([rci.Sphere(2.0, center=[1, 0, 0])])
    rng = np.random.default_rng(7)
    X = rng.normal(size=(2000, 3)) * 3 + [1, 0, 0]
    r = rs.closest_points(X)
    assert set(r) >= {"uv", "point", "normal", "distance", "status", "certified"}
    assert np.all(np.isin(r["status"], ["interior", "edge", "vertex"]))
    rho = np.linalg.norm(X - [1, 0, 0], axis=1)
    np.testing.assert_allclose(r["distance"], rho - 2.0, atol=1e-12 * rho.max())
    np.testing.assert_allclose(r["point"], [1, 0, 0] + 2.0 * (X - [1, 0, 0]) / rho[:, None],
                               atol=1e-12)


def test_nurbs_patch_closest_points_are_certified_and_threads_agree():
    rs = rci.RigidSurface([quarter_cylinder(2.0, 3.0)])
    rng = np.random.default_rng(11)
    phi = rng.uniform(0.05, math.pi / 2 - 0.05, 5000)
    rad = rng.uniform(0.5, 4.0, 5000)
    z = rng.uniform(0.1, 2.9, 5000)
    X = np.column_stack([rad * np.cos(phi), rad * np.sin(phi), z])
    one = rs.closest_points(X, threads=1)
    two = rs.closest_points(X, threads=2)
    assert one["certified"].all() and (one["status"] == "interior").all()
    np.testing.assert_allclose(one["distance"], rad - 2.0, atol=1e-11)
    np.testing.assert_allclose(one["point"][:, 2], z, atol=1e-11)
    for key in ("uv", "point", "normal", "distance"):
        np.testing.assert_allclose(one[key], two[key], rtol=0, atol=1e-13)


def test_rays_hit_the_sphere_where_the_line_cuts_it():
    rs = rci.RigidSurface([rci.Sphere(1.0)])
    X = np.array([[3.0, 0, 0], [0, 0.5, 4.0], [5, 5, 5]])
    D = np.array([[-1.0, 0, 0], [0, 0, -2.0], [1, 0, 0]])
    r = rs.rays(X, D)
    np.testing.assert_allclose(r["point"][0], [1, 0, 0], atol=1e-12)
    assert abs(r["distance"][0] - 2.0) < 1e-12  # x + xi D = rho: xi = 2
    z = math.sqrt(1 - 0.25)
    np.testing.assert_allclose(r["point"][1], [0, 0.5, z], atol=1e-12)
    assert abs(r["distance"][1] - (4.0 - z)) < 1e-12  # the length along D / |D|
    assert r["status"][2] in ("miss", "tangent") and np.isnan(r["distance"][2])


def test_cad_part_point_cloud(source):
    """On a STEP part (screw.step): a point X and its foot p; every point of the segment from p
    to X has the same foot, at the same fraction of the distance."""
    rs = rci.RigidSurface.from_cad(source / "tests/data/cad/occt/screw.step")
    assert rs.num_pieces > 1
    lo, hi = rs.box
    rng = np.random.default_rng(5)
    X = lo + (hi - lo) * rng.uniform(-0.2, 1.2, size=(400, 3))
    r = rs.closest_points(X)
    ok = np.isin(r["status"], ["interior", "edge", "vertex"])
    assert ok.mean() > 0.99
    mid = r["point"][ok] + 0.5 * (X[ok] - r["point"][ok])
    h = rs.closest_points(mid)
    size = np.linalg.norm(hi - lo)
    np.testing.assert_allclose(np.abs(h["distance"]), 0.5 * np.abs(r["distance"][ok]),
                               atol=1e-9 * size)
    np.testing.assert_allclose(h["point"], r["point"][ok], atol=1e-7 * size)


def test_rigid_surface_of_a_model(source):
    rs = rci.rigid_surface(source / "data/capstan.json", "cylinder")
    r = rs.closest_points([[0.0, 3.0, 0.5]])
    assert abs(r["distance"][0] - 2.0) < 1e-10


def test_bad_arguments_raise(source):
    rs = rci.RigidSurface([rci.Sphere(1.0)])
    with pytest.raises(ValueError, match=r"X: expected shape \(N, 3\), got \(5, 2\)"):
        rs.closest_points(np.zeros((5, 2)))
    with pytest.raises(ValueError, match=r"got \(2, 3, 1\)"):
        rs.closest_points(np.zeros((2, 3, 1)))
    with pytest.raises(TypeError, match="dtype"):
        rs.closest_points(np.array([["1", "2", "3"]]))
    with pytest.raises(TypeError, match="dtype"):
        rs.closest_points(np.array([[True, False, True]]))
    with pytest.raises(TypeError):
        rs.closest_points("not points")
    with pytest.raises(ValueError, match="X: row 2 holds nan"):
        rs.closest_points([[2, 0, 0], [0, 2, 0], [math.nan, 0, 0]])
    with pytest.raises(ValueError, match="D: expected as many rows as X"):
        rs.rays(np.zeros((3, 3)) + 2, np.ones((2, 3)))
    with pytest.raises(ValueError, match="D: row 0 is the zero vector"):
        rs.rays([[2, 0, 0]], [[0, 0, 0]])
    with pytest.raises(ValueError, match="at least one surface"):
        rci.RigidSurface([])
    with pytest.raises(TypeError, match=r"surfaces\[0\]: expected a Surface"):
        rci.RigidSurface([1, 2])
    with pytest.raises(rci.CadError, match="no_such_file.step"):
        rci.RigidSurface.from_cad(source / "no_such_file.step")
    with pytest.raises(rci.ModelError, match="'nothing'"):
        rci.rigid_surface(source / "data/capstan.json", "nothing")
    # int arrays are real numbers: accepted and converted
    r = rs.closest_points(np.array([[0, 0, 3]]))
    assert abs(r["distance"][0] - 2.0) < 1e-14
