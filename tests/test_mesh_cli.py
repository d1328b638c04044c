"""`stripcoef coefficients MESH`: end to end, JSON contract, bad input exit codes."""

import json

import numpy as np
import pytest

from stripcoef.cli import main
from stripcoef.geometry.mesh import revolved_mesh
from stripcoef.hull.lamb import spheroid_added_mass

RHO = 1000.0


def spheroid_file(path, a=0.6, b=0.1, n_ax=80, n_circ=48, scale=1.0):
    t = np.linspace(0.0, np.pi, n_ax + 1)[::-1]
    m = revolved_mesh(a * np.cos(t), b * np.sin(t), sections=n_circ)
    m.apply_scale(scale)
    m.export(path)
    return path


def lamb(a, b, rho=RHO):
    """Lamb's exact diagonal (stripcoef.hull.lamb.spheroid_added_mass, tested in test_hull_lamb)."""
    return spheroid_added_mass(a, b, rho=rho)

@pytest.mark.parametrize("ext", [".stl", ".ply"])
def test_spheroid_mesh_end_to_end(tmp_path, capsys, ext):
    path = spheroid_file(tmp_path / f"s{ext}")
    assert main(["coefficients", str(path), "--rho", "1000", "--strips", "100", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    for key in ("added_mass", "linear_damping", "quadratic_damping", "rigid_body_mass",
                "coefficients", "reference_point"):
        assert key in data
    ma = np.array(data["added_mass"])
    ref = lamb(0.6, 0.1)
    # the mesh is an inscribed 48-gon: its volume is 0.29 % below the spheroid's
    np.testing.assert_allclose(np.diag(ma)[[0, 1, 2, 4, 5]], ref[[0, 1, 2, 4, 5]], rtol=1e-2)
    np.testing.assert_allclose(data["reference_point"], 0.0, atol=1e-6)


def test_mm_axis_and_origin_flags(tmp_path, capsys):
    path = tmp_path / "s_mm.obj"
    t = np.linspace(0.0, np.pi, 61)[::-1]
    m = revolved_mesh(0.6 * np.cos(t), 0.1 * np.sin(t), sections=32)
    m.vertices = np.asarray(m.vertices)[:, [1, 2, 0]] * 1000.0      # along the file's z, in mm
    m.export(path)
    assert main(["coefficients", str(path), "--length-unit", "mm", "--axis", "z", "--json",
                 "--strips", "60"]) == 0
    a = json.loads(capsys.readouterr().out)
    assert a["density"] == pytest.approx(1025.0, rel=2e-3)                # sea water default
    ma = np.array(a["added_mass"])
    assert ma[1, 1] == pytest.approx(lamb(0.6, 0.1, a["density"])[1], rel=2e-2)


def test_output_file_and_bad_inputs(tmp_path, capsys):
    out = tmp_path / "model.json"
    bad = tmp_path / "bad.stl"
    bad.write_text("solid nothing\nendsolid\n")
    assert main(["coefficients", str(bad), "--json", "-o", str(out)]) == 2
    assert not out.exists()
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "bad.stl" in err[0]
    big = spheroid_file(tmp_path / "big.stl", scale=1000.0)
    assert main(["coefficients", str(big)]) == 2
    assert "length-unit" in capsys.readouterr().err


def test_repairs_are_reported_on_stderr(tmp_path, capsys):
    t = np.linspace(0.0, np.pi, 61)[::-1]
    m = revolved_mesh(0.6 * np.cos(t), 0.1 * np.sin(t), sections=32)
    m.invert()
    path = tmp_path / "inside_out.stl"
    m.export(path)
    assert main(["coefficients", str(path), "--json", "--strips", "40"]) == 0
    captured = capsys.readouterr()
    assert "flipped inward-pointing normals" in captured.err
    assert json.loads(captured.out)["volume"] > 0
