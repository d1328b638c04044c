"""Capytaine BEM cross-check (optional extra): exact sphere, transforms, CLI, errors."""

import builtins
import json
from importlib.util import find_spec

import numpy as np
import pytest
import trimesh

from stripcoef.cli import main
from stripcoef.conventions import transform_matrix
from stripcoef.errors import InputError
from stripcoef.geometry.mesh import mesh_body, revolved_mesh

# found, not imported (stripcoef.bem imports it when it solves): importing capytaine costs
# each test worker about 1.1 s of CPU while collecting
if find_spec("capytaine") is None:
    pytest.skip("capytaine not installed", allow_module_level=True)
from stripcoef.bem import bem_added_mass  # noqa: E402

RHO = 1000.0


@pytest.fixture(scope="module")
def sphere_result():
    m = trimesh.creation.icosphere(subdivisions=3, radius=0.5)     # 1280 faces
    body = mesh_body(m)
    return body, bem_added_mass(body, rho=RHO)


def test_sphere_exact(sphere_result):
    """Sphere: m11 = m22 = m33 = rho V / 2 (Newman 1977, sec. 4.13), no rotation terms."""
    body, a = sphere_result
    half = 0.5 * RHO * body.volume        # of the faceted sphere itself
    np.testing.assert_allclose(np.diag(a)[:3], half, rtol=1e-2)
    assert np.abs(a[3:, 3:]).max() < 1e-3 * half * 0.25
    np.testing.assert_allclose(a, a.T, atol=1e-12)


def test_reference_point_matches_conventions(sphere_result):
    body, a = sphere_result
    p = (0.3, -0.1, 0.2)
    a2 = bem_added_mass(body, rho=RHO, reference_point=p)
    shifted = transform_matrix(a, from_point=(0, 0, 0), to_point=p)
    np.testing.assert_allclose(a2, shifted, atol=1e-6 * np.abs(a).max())


def test_too_many_faces_refused(sphere_result):
    body, _ = sphere_result
    with pytest.raises(InputError, match="too many"):
        bem_added_mass(body, rho=RHO, max_faces=100)


def test_missing_capytaine_is_an_input_error(monkeypatch):
    real_import = builtins.__import__

    def fake_import(name, *args, **kwargs):
        if name == "capytaine":
            raise ImportError("no capytaine")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", fake_import)
    with pytest.raises(InputError, match=r"stripcoef\[bem\]"):
        bem_added_mass(trimesh.creation.icosphere(), rho=RHO)


@pytest.fixture(scope="module")
def spheroid_file(tmp_path_factory):
    t = np.linspace(0.0, np.pi, 31)[::-1]
    path = tmp_path_factory.mktemp("bem") / "spheroid.stl"
    revolved_mesh(0.6 * np.cos(t), 0.1 * np.sin(t), sections=24).export(path)   # 1440 faces
    return path


def test_compare_cli_json(spheroid_file, capsys):
    assert main(["compare", str(spheroid_file), "--rho", "1000", "--strips", "60", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert set(data["seconds"]) == {"load", "strip_theory", "bem"}
    assert data["added_mass_method"] == "strip theory"       # a spheroid: auto keeps the strips
    terms = {t["term"]: t for t in data["terms"]}
    # a spheroid: strip theory with the spheroid end correction is Lamb's solution; the
    # coarse BEM mesh is within a few per cent of it
    for name in ("Y_vdot", "Z_wdot", "M_qdot", "N_rdot"):
        assert abs(terms[name]["diff_percent"]) < 3.0
    assert "K_pdot" not in terms          # zero in both


def test_coefficients_method_bem(spheroid_file, capsys):
    assert main(["coefficients", str(spheroid_file), "--method", "bem", "--rho", "1000",
                 "--strips", "40", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    from stripcoef.assembly.methods import ADDED_MASS_METHODS   # the registry's BEM entry ran

    assert data["provenance"]["method"] == ADDED_MASS_METHODS["bem"].provenance
    assert data["provenance"]["bem_faces"] > 0 and data["provenance"]["bem_seconds"] >= 0
    assert data["added_mass"][1][1] == pytest.approx(np.pi * 4 / 3 * 0.6 * 0.01 * 1000 * 0.93,
                                                     rel=0.05)


def test_compare_bad_file_exit_2(tmp_path, capsys):
    p = tmp_path / "x.stl"
    p.write_text("garbage")
    assert main(["compare", str(p)]) == 2
    err = capsys.readouterr().err
    assert "x.stl" in err and len(err.strip().splitlines()) == 1


def test_compare_cli_table(spheroid_file, capsys):
    assert main(["compare", str(spheroid_file), "--rho", "1000", "--strips", "40"]) == 0
    out = capsys.readouterr().out
    assert "strip theory" in out and "BEM" in out and "Y_vdot" in out and "diff %" in out


def test_coefficients_method_bem_honours_the_output_format(spheroid_file, capsys):
    import yaml
    assert main(["coefficients", str(spheroid_file), "--method", "bem", "--rho", "1000",
                 "--strips", "40", "--yaml"]) == 0
    data = yaml.safe_load(capsys.readouterr().out)
    assert "bem" in data["provenance"]["method"]
    assert main(["coefficients", str(spheroid_file), "--method", "bem", "--rho", "1000",
                 "--strips", "40"]) == 0
    out = capsys.readouterr().out
    assert out.splitlines()[0].startswith("spheroid: bem (Capytaine") and "Added mass M_A" in out
