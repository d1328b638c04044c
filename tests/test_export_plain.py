"""Plain-data exports (json, yaml, csv, npz, python): round trips, points and axes, registry."""

from __future__ import annotations

import io
import json
import warnings

import numpy as np
import pytest
import yaml
from _export_models import torpedo

from stripcoef.conventions import transform_matrix
from stripcoef.errors import InputError
from stripcoef.export import FORMATS, export_model, write_export
from stripcoef.export.csvtable import read as read_csv
from stripcoef.model import HydroModel
from conftest import load_module

MATRICES = ("rigid_body_mass", "added_mass", "linear_damping", "quadratic_damping")
SHORT = {"rigid_body_mass": "M_RB", "added_mass": "M_A", "linear_damping": "D_L",
         "quadratic_damping": "D_Q"}
T = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])


def assert_same_model(a: HydroModel, b: HydroModel, rtol=1e-12):
    for key in MATRICES + ("reference_point", "center_of_gravity", "center_of_buoyancy"):
        np.testing.assert_allclose(getattr(a, key), getattr(b, key), rtol=rtol, atol=1e-12,
                                   err_msg=key)
    for key in ("mass", "volume", "density", "gravity", "kinematic_viscosity", "name"):
        assert getattr(a, key) == getattr(b, key), key
    assert [t.to_dict() for t in a.thrusters] == [t.to_dict() for t in b.thrusters]
    assert a.conditions == b.conditions and a.provenance == b.provenance


@pytest.mark.parametrize("fmt", ["json", "yaml"])
def test_json_yaml_round_trip(fmt):
    model = torpedo()
    text = export_model(model, fmt)
    data = json.loads(text) if fmt == "json" else yaml.safe_load(text)
    assert data == json.loads(json.dumps(model.to_dict()))
    assert_same_model(HydroModel.from_dict(data), model, rtol=0)


@pytest.mark.parametrize("fmt", ["json", "yaml"])
def test_about_cg_and_back_gives_the_original(fmt):
    model = torpedo()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")        # D_Q rotation columns: approximate but invertible
        text = export_model(model, fmt, point="CG")
        data = json.loads(text) if fmt == "json" else yaml.safe_load(text)
        at_cg = HydroModel.from_dict(data)
        back = at_cg.about(model.reference_point)
    np.testing.assert_allclose(at_cg.reference_point, model.center_of_gravity)
    np.testing.assert_allclose(at_cg.r_g, 0.0, atol=1e-15)
    assert not np.allclose(at_cg.added_mass, model.added_mass)   # really moved
    assert_same_model(back, model, rtol=1e-12)


def test_csv_round_trip_in_flu_about_a_point():
    model = torpedo()
    point = (0.4, -0.01, 0.02)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        data = read_csv(export_model(model, "csv", point="0.4,-0.01,0.02", axes="FLU"))
        moved = model.about(point)
    assert data["name"] == model.name and data["axes"] == "FLU"
    np.testing.assert_allclose(data["reference_point"], point)
    for key in MATRICES:
        # FLU -> FRD is the same involution; back at the model's own point
        frd = transform_matrix(data[key], axes="FLU")
        np.testing.assert_allclose(frd, getattr(moved, key), rtol=1e-14, atol=1e-15)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            back = transform_matrix(frd, from_point=point, to_point=model.reference_point)
        np.testing.assert_allclose(back, getattr(model, key), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(data["r_g"], T[:3] * (model.center_of_gravity - point))
    np.testing.assert_allclose(data["r_b"], T[:3] * (model.center_of_buoyancy - point))
    for key in ("mass", "volume", "density", "gravity", "kinematic_viscosity"):
        assert data[key] == getattr(model, key)
    assert data["thrusters"] == ["port", "vertical"]
    np.testing.assert_allclose(data["thruster_allocation"], T[:, None] * moved.allocation())
    assert data["thruster_params"]["vertical"]["eta_backward"] == 0.85
    assert data["thruster_params"]["vertical"]["max_forward"] == float("inf")


def test_csv_units_column():
    text = export_model(torpedo(), "csv")
    rows = {tuple(r.split(",")[:3]): r.split(",")[4] for r in text.splitlines()[1:]}
    assert rows[("added_mass", "surge", "surge")] == "kg"
    assert rows[("added_mass", "sway", "yaw")] == "kg m"
    assert rows[("linear_damping", "yaw", "yaw")] == "kg m^2/s"
    assert rows[("quadratic_damping", "sway", "sway")] == "kg/m"
    assert rows[("quadratic_damping", "yaw", "sway")] == "kg"


def test_csv_reader_rejects_other_files():
    with pytest.raises(InputError, match="header"):
        read_csv("a,b\n1,2\n", file="x.csv")
    with pytest.raises(InputError, match="line 2"):
        read_csv("quantity,row,col,value,unit\nadded_mass,surge,bogus,1,kg\n", file="x.csv")


def test_npz_round_trip(tmp_path):
    model = torpedo()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        blob = export_model(model, "npz", point="CB", axes="FLU")
        moved = model.about(model.center_of_buoyancy)
    assert isinstance(blob, bytes)
    with np.load(io.BytesIO(blob), allow_pickle=False) as npz:
        for key, short in SHORT.items():
            np.testing.assert_allclose(npz[short], transform_matrix(getattr(moved, key),
                                                                    axes="FLU"), rtol=1e-14)
        assert str(npz["axes"]) == "FLU" and str(npz["point"]) == "CB"
        np.testing.assert_allclose(npz["r_b"], 0.0, atol=1e-15)
        np.testing.assert_allclose(npz["B_thrusters"], T[:, None] * moved.allocation())
        assert list(npz["thrusters"]) == ["port", "vertical"]
        restored = HydroModel.from_dict(json.loads(str(npz["model_json"])))
    assert_same_model(restored, moved, rtol=0)
    # through a file too
    path = write_export(model, "npz", tmp_path / "m.npz")
    with np.load(path, allow_pickle=False) as npz:
        np.testing.assert_array_equal(npz["M_A"], model.added_mass)


def test_python_module_imports_with_the_matrices(tmp_path):
    model = torpedo()
    path = write_export(model, "python", tmp_path / "torpedo_model.py", axes="FLU")
    mod = load_module(path, "torpedo_model")
    for key, short in SHORT.items():
        np.testing.assert_array_equal(getattr(mod, short),
                                      transform_matrix(getattr(model, key), axes="FLU"))
    np.testing.assert_array_equal(mod.M, mod.M_RB + mod.M_A)
    assert mod.AXES == "FLU" and mod.MASS == model.mass and mod.VOLUME == model.volume
    np.testing.assert_array_equal(mod.R_G, T[:3] * model.r_g)
    assert mod.THRUSTERS == ("port", "vertical")
    np.testing.assert_allclose(mod.B_THRUSTERS, T[:, None] * model.allocation())
    # SNAME names in FLU: Y_r keeps its sign (y and r both flip), Y_pdot changes sign
    assert mod.COEFFICIENTS["X_udot"] == -model.added_mass[0, 0]
    assert mod.COEFFICIENTS["Y_r"] == -model.linear_damping[1, 5]
    assert mod.COEFFICIENTS["Y_pdot"] == model.added_mass[1, 3] != 0


def test_registry_lists_formats_and_rejects_unknown():
    assert set(FORMATS) == {"gazebo", "uuv", "mss", "python", "json", "yaml", "csv", "npz"}
    with pytest.raises(InputError) as err:
        export_model(torpedo(), "urdf")
    message = str(err.value)
    assert "urdf" in message and all(name in message for name in FORMATS)


@pytest.mark.parametrize("point", ["CX", "1,2", "a,b,c", (1.0, 2.0), "nan,0,0", (0, 0, np.inf),
                                   None.__class__])
def test_a_point_that_is_not_a_point(point):
    with pytest.raises(InputError, match="point"):
        export_model(torpedo(), "json", point=point)


def test_options_that_do_not_apply_are_errors():
    with pytest.raises(InputError, match="legacy_added_mass"):   # the CLI names --legacy-added-mass (test_export_cli)
        export_model(torpedo(), "uuv", legacy_added_mass=True)
    with pytest.raises(InputError, match="link_name"):
        export_model(torpedo(), "json", link_name="base")
    with pytest.raises(InputError, match="FRD"):
        export_model(torpedo(), "json", axes="FLU")
    with pytest.raises(InputError, match="FRD or FLU"):
        export_model(torpedo(), "csv", axes="NED")
    with pytest.raises(InputError, match="link"):
        export_model(torpedo(), "gazebo", link_name="bad name")


@pytest.mark.parametrize("fmt", sorted(FORMATS))
def test_effects_a_format_cannot_hold_are_a_trap(fmt):
    from stripcoef.export import SimulatorTrapWarning
    model = torpedo()
    model = model.with_effects({"effect": "tether_drag", "parameters": {"c": 1.0}})
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = export_model(model, fmt)
    traps = [str(w.message) for w in caught if w.category is SimulatorTrapWarning
             and "tether_drag" in str(w.message)]
    assert bool(traps) == (fmt not in ("json", "yaml", "npz"))
    if fmt == "json":
        assert HydroModel.from_dict(json.loads(out)).effects == model.effects


def test_write_is_atomic_and_keeps_the_old_file_on_error(tmp_path):
    target = tmp_path / "model.json"
    target.write_text("old")
    with pytest.raises(InputError):
        write_export(torpedo(), "json", target, point="nowhere")
    assert target.read_text() == "old"
    write_export(torpedo(), "json", target)
    assert json.loads(target.read_text())["name"] == "torpedo"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["model.json"]
    with pytest.raises(InputError, match="folder"):
        write_export(torpedo(), "json", tmp_path / "missing" / "m.json")
    with pytest.raises(InputError, match="folder"):
        write_export(torpedo(), "json", tmp_path)


def test_written_files_are_readable_by_others(tmp_path):
    import os
    import stat
    mask = os.umask(0o022)
    try:
        path = write_export(torpedo(), "json", tmp_path / "m.json")
    finally:
        os.umask(mask)
    assert stat.S_IMODE(path.stat().st_mode) == 0o644


@pytest.mark.parametrize("name, attr", [("cg", "center_of_gravity"),
                                        ("center_of_buoyancy", "center_of_buoyancy"),
                                        ("reference_point", "reference_point"),
                                        ("origin", None)])
def test_named_points(name, attr):
    model = torpedo()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        data = json.loads(export_model(model, "json", point=name))
    want = np.zeros(3) if attr is None else getattr(model, attr)
    np.testing.assert_array_equal(data["reference_point"], want)
