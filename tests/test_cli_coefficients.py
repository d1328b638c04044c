"""The coefficients command and its JSON output contract."""

import json

import numpy as np
import pytest

from stripcoef.cli import main

from conftest import GEOMETRY


@pytest.fixture(scope="module")
def mares_json():
    import io
    from contextlib import redirect_stdout

    buf = io.StringIO()
    with redirect_stdout(buf):
        assert main(["coefficients", str(GEOMETRY / "mares.yaml"), "--json"]) == 0
    return json.loads(buf.getvalue())


def test_contract_keys(mares_json):
    d = mares_json
    assert d["dof"] == ["surge", "sway", "heave", "roll", "pitch", "yaw"]
    for key in ("reference_point", "added_mass", "linear_damping", "quadratic_damping",
                "rigid_body_mass", "mass", "volume", "center_of_gravity", "center_of_buoyancy",
                "coefficients", "conditions"):
        assert key in d
    for key in ("added_mass", "linear_damping", "quadratic_damping", "rigid_body_mass"):
        assert np.asarray(d[key]).shape == (6, 6)
    assert len(d["reference_point"]) == 3


def test_fossen_signs(mares_json):
    d = mares_json
    ma = np.asarray(d["added_mass"])
    assert np.all(np.diag(ma)[[0, 1, 2, 4, 5]] > 0)
    c = d["coefficients"]
    assert c["X_udot"] == pytest.approx(-ma[0, 0])
    assert c["Y_vv"] == pytest.approx(-d["quadratic_damping"][1][1])
    assert c["X_uu"] < 0 and c["N_rr"] < 0
    for key in ("N_vv", "M_ww", "Y_rr", "Z_qq"):    # strip cross terms
        assert key in c


def test_conditions_report_reynolds_and_regime(mares_json):
    cond = mares_json["conditions"]
    for key in ("reynolds_length", "regime", "cf_laminar", "cf_turbulent", "cf_used",
                "hull_reynolds_diameter", "hull_crossflow_cd_y", "density",
                "kinematic_viscosity"):
        assert key in cond


def test_table_and_yaml_and_output_file(tmp_path, capsys):
    assert main(["coefficients", str(GEOMETRY / "capsule.yaml")]) == 0
    out = capsys.readouterr().out
    assert "Added mass M_A" in out and "Quadratic damping" in out
    f = tmp_path / "m.yaml"
    assert main(["coefficients", str(GEOMETRY / "capsule.yaml"), "--yaml", "-o", str(f)]) == 0
    import yaml

    assert yaml.safe_load(f.read_text())["dof"][0] == "surge"


def test_model_round_trip(mares_json):
    from stripcoef.model import HydroModel

    m = HydroModel.from_dict(mares_json)
    assert json.loads(json.dumps(m.to_dict()))["added_mass"] == mares_json["added_mass"]
