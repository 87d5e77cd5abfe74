"""Models from Python: a run gives the same steps.csv as `iga run`, the steps table as numpy
equals the CSV, the per-step callback sees and stops the run, a model built step by step equals
the file, set() has --set's semantics, and bad input raises ModelError with its JSON path."""
import csv
import json
import math
import subprocess

import numpy as np
import pytest

import rigid_contact_iga as rci


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    return header, np.array([[float(v) if v else math.nan for v in r] for r in body])


def test_run_gives_the_steps_csv_of_iga_run(source, build, tmp_path):
    model = source / "data/capstan.json"
    cli = tmp_path / "cli"
    subprocess.run([str(build / "apps/iga"), "run", str(model), "--out", str(cli), "--quiet"],
                   check=True, capture_output=True)
    result = rci.Model.load(model).run(out=tmp_path / "py")
    assert result.converged, result.message
    h1, a1 = read_csv(cli / "steps.csv")
    h2, a2 = read_csv(tmp_path / "py" / "steps.csv")
    assert h1 == h2 and a1.shape == a2.shape and a1.shape[0] > 5
    np.testing.assert_allclose(a2, a1, rtol=1e-12, atol=0)
    # the table as numpy: the CSV prints 12 significant digits
    table = result.steps
    assert list(table) == h2 == result.columns
    for k, name in enumerate(h2):
        np.testing.assert_allclose(table[name], a2[:, k], rtol=1e-11, atol=1e-300)
    assert result.steps_array().shape == a2.shape


def test_results_as_arrays(source):
    result = rci.Model.load(source / "data/capstan.json").set("/solver/t_end", 1.0).run()
    assert result.status == "converged" and result.t == pytest.approx(1.0)
    assert result.body_types == ["rod"]
    d = result.displacements("rope")
    assert d.ndim == 2 and d.shape[1] == 3 and np.isfinite(d).all()
    np.testing.assert_allclose(d[:, 2], 0, atol=1e-14)  # planar: z fixed
    c = result.contact_points(0)
    n = c["points"].shape[0]
    assert n > 10 and all(len(v) == n for v in c["fields"].values())
    # the rope lies on the cylinder of radius 1 with its centre line at 1.02
    np.testing.assert_allclose(np.hypot(c["points"][:, 0], c["points"][:, 1]), 1.02, atol=1e-3)
    s = result.sample("rope", 4)
    assert s["points"].shape[0] == s["params"].shape[0] > 0
    assert all(len(v) == s["points"].shape[0] for v in s["fields"].values())


def test_write_output_in_the_models_field_format(source, tmp_path):
    model = rci.Model.load(source / "data/balloon.json").set("/solver/t_end", 0.4)
    model.set("/solver/hit_times", [0.2])
    files = model.run().write_output(tmp_path / "xml", "final")
    assert "final_membrane.vts" in files
    head = (tmp_path / "xml" / "final_membrane.vts").read_bytes()[:200]
    assert head.startswith(b"<?xml") and b'type="StructuredGrid"' in head
    files = model.set("/output/field_format", "vtk").run().write_output(tmp_path / "legacy")
    assert files == ["state_membrane.vtk"]
    assert (tmp_path / "legacy" / "state_membrane.vtk").read_text().startswith("# vtk DataFile")


def test_on_step_sees_each_step_and_can_stop(source, tmp_path):
    seen = []

    def on_step(row):
        seen.append(row)
        return len(seen) < 4

    result = rci.Model.load(source / "data/capstan.json").run(out=tmp_path, on_step=on_step)
    assert result.status == "stopped" and result.num_steps == 4 and len(seen) == 4
    assert [r["step"] for r in seen] == [1, 2, 3, 4]
    np.testing.assert_allclose(result.steps["t"], [r["t"] for r in seen], rtol=0)
    _, rows = read_csv(tmp_path / "steps.csv")
    assert rows.shape[0] == 4  # the rows so far are kept

    def boom(row):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        rci.Model.load(source / "data/capstan.json").run(on_step=boom)


def test_model_built_step_by_step_equals_the_file(source, tmp_path):
    loaded = rci.Model.load(source / "data/two_ropes.json")
    d = loaded.to_dict()
    m = rci.Model(d["name"], d["description"], file=str(source / "data/two_ropes.json"))
    for name, g in d["geometry"].items():
        m.add_geometry(name, g)
    for name, v in d.get("materials", {}).items():
        m.add_material(name, **v)
    for name, v in d.get("bodies", {}).items():
        m.add_body(name, **v)
    for name, v in d.get("load_curves", {}).items():
        m.add_load_curve(name, **v)
    for name, v in d.get("rigid_motions", {}).items():
        m.add_rigid_motion(name, **v)
    for v in d.get("boundary_conditions", []):
        m.add_boundary_condition(**v)
    for v in d.get("loads", []):
        m.add_load(**v)
    for v in d.get("contact", []):
        m.add_contact(**v)
    m.solver(**d.get("solver", {}))
    if "output" in d:
        m.output(**d["output"])
    assert list(m.doc) == list(loaded.doc)  # the sections in the file's order
    assert m == loaded
    assert m.check() == loaded.check()
    m.save(tmp_path / "m.json")
    assert rci.Model.load(tmp_path / "m.json") == loaded


def test_geometry_objects_in_a_model(source):
    m = rci.Model("g")
    arc = rci.NurbsCurve(2, [0, 0, 0, 1, 1, 1], [[1, 0, 0], [1, 1, 0], [0, 1, 0]],
                         [1, math.sqrt(0.5), 1])
    m.add_geometry("arc", arc).add_geometry("ball", rci.Sphere(2.0, center=[0, 0, 1]))
    assert m.doc["geometry"]["arc"]["type"] == "nurbs_curve"
    rs = rci.rigid_surface(m, "ball")
    assert abs(rs.closest_points([[0, 0, 4]])["distance"][0] - 1.0) < 1e-14
    with pytest.raises(TypeError, match="entity"):
        m.add_geometry("x", 42)
    with pytest.raises(ValueError, match="already defined"):
        m.add_geometry("arc", arc)


def test_set_has_the_semantics_of_set(source):
    m = rci.Model.load(source / "data/capstan.json")
    m.set("/contact/0/mu", 0.5)
    assert m.get("/contact/0/mu") == 0.5
    m.set("/solver/t_end", 1.5).set("/geometry/rope/arc_elements", 12)
    assert m.doc["solver"]["t_end"] == 1.5
    with pytest.raises(rci.ModelError) as e:
        m.set("/nothing/here", 1)  # the parent is missing
    assert "/nothing/here" in str(e.value)
    with pytest.raises(rci.ModelError):
        m.set("no_slash", 1)
    with pytest.raises(TypeError):
        m.set("/solver/t_end", object())


def test_bad_input_raises_model_error_with_the_json_path(source, tmp_path):
    m = rci.Model.load(source / "data/capstan.json")
    m.set("/solver/t_ned", 1.0)  # a misspelt key: refused when built, with the allowed keys
    with pytest.raises(rci.ModelError) as e:
        m.run()
    assert e.value.pointer == "/solver/t_ned" and "t_end" in e.value.message
    assert e.value.file.endswith("capstan.json")
    assert isinstance(e.value, ValueError)
    m = rci.Model.load(source / "data/capstan.json").set("/contact/0/mu", -1)
    with pytest.raises(rci.ModelError) as e:
        m.check()
    assert e.value.pointer == "/contact/0/mu"
    with pytest.raises(rci.ModelError, match="no_such.json"):
        rci.Model.load(tmp_path / "no_such.json")
    bad = tmp_path / "bad.json"
    bad.write_text("{ \"format\": ")
    with pytest.raises(rci.ModelError, match="bad.json"):
        rci.Model.load(bad)
    with pytest.raises(TypeError):
        rci.Model.from_dict({"x": math.nan + 1j})
    with pytest.raises(TypeError, match="on_step"):
        rci.Model.load(source / "data/capstan.json").run(on_step=3)
    with pytest.raises(KeyError):
        rci.Model.load(source / "data/capstan.json").run().displacements("nobody")


def test_linear_analysis(source):
    # The Scordelis-Lo roof's linear analysis: one assembly, one solve, the linear value.
    model = rci.Model.load(source / "data/scordelis_lo.json")
    linear = model.run()
    assert linear.converged and linear.linear_steps == 1 and linear.assemblies == 1
    w = -linear.steps["free_edge_mid_uz"][-1]
    assert w == pytest.approx(0.300584, rel=1e-5)
    # Newton on the same model at 1e-5 of the load, where it is linear to 2e-6.
    newton = model.set("/solver/analysis", "nonlinear").set(
        "/load_curves/load_factor/scale", 1e-5).run()
    assert newton.converged and newton.linear_steps == 0 and newton.newton_iterations >= 2
    assert -1e5 * newton.steps["free_edge_mid_uz"][-1] == pytest.approx(w, rel=1e-5)
