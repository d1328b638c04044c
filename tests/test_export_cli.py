"""``stripcoef export``: formats from vehicle and model files, and every class of bad input."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from _export_models import torpedo

from stripcoef.cli import main
from stripcoef.model import HydroModel

ROOT = Path(__file__).resolve().parent.parent
SPHERE = ROOT / "geometry" / "sphere.yaml"


@pytest.fixture()
def model_file(tmp_path):
    path = tmp_path / "torpedo.json"
    path.write_text(json.dumps(torpedo().to_dict()))
    return path


def run(capsys, *argv):
    code = main(["export", *map(str, argv)])
    out, err = capsys.readouterr()
    return code, out, err


def one_line_error(code, err):
    assert code == 2
    lines = [ln for ln in err.splitlines() if not ln.startswith("warning:")]
    assert len(lines) == 1 and lines[0].startswith("stripcoef export: error:"), err
    assert "Traceback" not in err
    return lines[0]


def test_model_file_to_stdout(capsys, model_file):
    code, out, _ = run(capsys, model_file, "--to", "gazebo", "--link", "hull")
    assert code == 0
    root = ET.fromstring(out)
    assert root.find("./model/plugin/link_name").text == "hull"
    code, out, _ = run(capsys, model_file, "--to", "json", "--point", "CG")
    assert code == 0
    np.testing.assert_allclose(json.loads(out)["reference_point"], torpedo().center_of_gravity)


def test_model_yaml_file_is_a_model_not_a_vehicle(capsys, tmp_path, model_file):
    code, out, _ = run(capsys, model_file, "--to", "yaml")
    path = tmp_path / "torpedo_model.yaml"
    path.write_text(out)
    code, out, _ = run(capsys, path, "--to", "json")
    assert code == 0
    assert HydroModel.from_dict(json.loads(out)).name == "torpedo"


def test_vehicle_file_to_file(capsys, tmp_path):
    out_path = tmp_path / "sphere.sdf"
    code, out, err = run(capsys, SPHERE, "--to", "gazebo", "-o", out_path, "--legacy-added-mass")
    assert code == 0 and out == ""
    root = ET.parse(out_path).getroot()
    assert root.find("./model/plugin/xDotU") is not None
    assert root.find("./model/link/inertial/fluid_added_mass") is None


def test_negative_point_coordinates(capsys, model_file):
    code, out, _ = run(capsys, model_file, "--to", "json", "--point=-0.1,0,0.02")
    assert code == 0
    np.testing.assert_allclose(json.loads(out)["reference_point"], [-0.1, 0.0, 0.02])


def test_unknown_format_lists_the_valid_ones(capsys, model_file, tmp_path):
    code, _, err = run(capsys, model_file, "--to", "urdf", "-o", tmp_path / "x.urdf")
    line = one_line_error(code, err)
    assert "'urdf'" in line and "gazebo" in line and "npz" in line and "mss" in line
    assert not (tmp_path / "x.urdf").exists()


@pytest.mark.parametrize("point", ["CX", "1,2", "1,2,x", "nan,0,0"])
def test_a_point_that_is_not_a_point(capsys, model_file, tmp_path, point):
    target = tmp_path / "out.json"
    target.write_text("previous")
    code, _, err = run(capsys, model_file, "--to", "json", "-o", target, f"--point={point}")
    assert "point" in one_line_error(code, err)
    assert target.read_text() == "previous"          # replaced only by a complete file
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []


@pytest.mark.parametrize("where", ["missing/out.json", "."])
def test_unwritable_output(capsys, model_file, tmp_path, where):
    code, _, err = run(capsys, model_file, "--to", "json", "-o", tmp_path / where)
    assert "output" in one_line_error(code, err)


def test_npz_needs_an_output_file(capsys, model_file, tmp_path):
    code, out, err = run(capsys, model_file, "--to", "npz")
    assert "-o FILE" in one_line_error(code, err) and out == ""
    code, _, _ = run(capsys, model_file, "--to", "npz", "-o", tmp_path / "m.npz")
    assert code == 0
    with np.load(tmp_path / "m.npz", allow_pickle=False) as npz:
        np.testing.assert_array_equal(npz["M_A"], torpedo().added_mass)


def test_options_that_do_not_apply(capsys, model_file):
    code, _, err = run(capsys, model_file, "--to", "uuv", "--legacy-added-mass")
    assert "--legacy-added-mass" in one_line_error(code, err)
    code, _, err = run(capsys, model_file, "--to", "uuv", "--point", "CB")
    assert "CG" in one_line_error(code, err)
    code, _, err = run(capsys, model_file, "--to", "mss", "--axes", "FLU")
    assert "FRD" in one_line_error(code, err)


def test_bad_model_files(capsys, tmp_path):
    data = torpedo().to_dict()
    del data["added_mass"]
    data["rigid_body_mass"] = [[0.0] * 6] * 6
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({**data, "added_mass": [[1.0] * 5] * 6}))
    code, _, err = run(capsys, bad, "--to", "json")
    line = one_line_error(code, err)
    assert "bad.json" in line and "added_mass" in line and "(6, 6)" in line
    bad.write_text("{not json")
    code, _, err = run(capsys, bad, "--to", "json")
    assert "JSON" in one_line_error(code, err)
    code, _, err = run(capsys, tmp_path / "none.yaml", "--to", "json")
    assert "not found" in one_line_error(code, err)
    mesh = tmp_path / "hull.stl"
    mesh.write_text("solid x\nendsolid x\n")
    code, _, err = run(capsys, mesh, "--to", "json")
    assert "stripcoef coefficients MESH" in one_line_error(code, err)


def test_mss_file_name_sets_the_function_name(capsys, model_file, tmp_path):
    code, _, _ = run(capsys, model_file, "--to", "mss", "-o", tmp_path / "rov_a.m")
    assert code == 0
    assert "= rov_a(x, tau, Vc, delta)" in (tmp_path / "rov_a.m").read_text().splitlines()[0]
    code, _, err = run(capsys, model_file, "--to", "mss", "-o", tmp_path / "rov-a.m")
    assert "function name" in one_line_error(code, err)
    assert not (tmp_path / "rov-a.m").exists()
