"""Every JSON output passes a strict parser (RFC 8259: no Infinity, no NaN).

A thruster without a thrust limit is the case that used to write ``Infinity``; it is written
``null`` and read back as an unlimited thruster (docs/conventions.md, "Non-finite values").
"""

import json
import math

import numpy as np
import pytest
import yaml

from stripcoef.cli import main
from stripcoef.files import json_text, strict_json
from stripcoef.model import HydroModel
from stripcoef.modelfile import load_model


def _reject(name):
    raise ValueError(f"non-standard JSON constant {name}")


def strict_loads(text):
    """json.loads that refuses Infinity, -Infinity and NaN (what JSON.parse does)."""
    return json.loads(text, parse_constant=_reject)


@pytest.fixture
def unlimited(tmp_path, geometry_dir):
    """VideoRay with its port thruster's limits removed (no max_forward / max_backward)."""
    data = yaml.safe_load((geometry_dir / "videoray_pro3.yaml").read_text())
    for key in ("max_forward", "max_backward"):
        data["thrusters"][0].pop(key)
    path = tmp_path / "unlimited.yaml"
    path.write_text(yaml.safe_dump(data))
    return path


def test_strict_parser_rejects_infinity():
    with pytest.raises(ValueError):
        strict_loads('{"a": Infinity}')
    with pytest.raises(ValueError):
        strict_loads('[NaN]')


def test_json_text_encodes_non_finite_as_null():
    text = json_text({"a": float("inf"), "b": [float("nan"), -np.inf, 1.5],
                      "c": np.float64(2.0), "d": np.array([np.inf, 3.0])})
    assert strict_loads(text) == {"a": None, "b": [None, None, 1.5], "c": 2.0, "d": [None, 3.0]}
    assert strict_json((1.0, math.inf)) == [1.0, None]


def _all_outputs(tmp_path, capsys, vehicle):
    """Every JSON a fast command writes for ``vehicle``: {label: text}."""
    out = {}
    assert main(["coefficients", str(vehicle), "--json"]) == 0
    out["coefficients --json"] = capsys.readouterr().out
    f = tmp_path / "coefficients.json"
    assert main(["coefficients", str(vehicle), "--json", "-o", str(f)]) == 0
    out["coefficients --json -o"] = f.read_text()
    f = tmp_path / "export.json"
    assert main(["export", str(vehicle), "--to", "json", "-o", str(f)]) == 0
    out["export --to json"] = f.read_text()
    f = tmp_path / "export.npz"
    assert main(["export", str(vehicle), "--to", "npz", "-o", str(f)]) == 0
    out["export --to npz: model_json"] = str(np.load(f)["model_json"])
    capsys.readouterr()
    return out


@pytest.mark.slow
def test_every_json_output_is_strict_with_an_unlimited_thruster(tmp_path, capsys, unlimited):
    outputs = _all_outputs(tmp_path, capsys, unlimited)
    assert "Infinity" in json.dumps(float("inf"))          # what the old code wrote
    for label, text in outputs.items():
        data = strict_loads(text)                          # raises on Infinity/NaN
        assert isinstance(data, dict), label
    model = strict_loads(outputs["export --to json"])
    port = model["thrusters"][0]
    assert port["name"] == "port"
    assert port["max_forward"] is None and port["max_backward"] is None
    assert model["thrusters"][1]["max_forward"] == pytest.approx(12.554)


@pytest.mark.parametrize("vehicle", ["videoray_pro3.yaml", "mares.yaml"])
def test_limits_json_is_strict(capsys, geometry_dir, vehicle):
    # limits needs finite thrust limits; its result has radii no turn reaches
    assert main(["limits", str(geometry_dir / vehicle), "--json"]) == 0
    assert isinstance(strict_loads(capsys.readouterr().out), dict)


def test_null_limit_reads_back_as_unlimited(tmp_path, capsys, unlimited):
    f = tmp_path / "model.json"
    assert main(["export", str(unlimited), "--to", "json", "-o", str(f)]) == 0
    model = load_model(f)
    assert math.isinf(model.thrusters[0].max_forward)
    assert math.isinf(model.thrusters[0].max_backward)
    assert model.thrusters[1].max_forward == pytest.approx(12.554)
    # YAML model files carry the same null
    y = tmp_path / "model.yaml"
    assert main(["export", str(unlimited), "--to", "yaml", "-o", str(y)]) == 0
    assert "max_forward: null" in y.read_text()
    assert math.isinf(load_model(y).thrusters[0].max_forward)
    # and an older file's Infinity still reads
    old = json.loads(f.read_text())
    old["thrusters"][0]["max_forward"] = float("inf")
    assert math.isinf(HydroModel.from_dict(json.loads(json.dumps(old))).thrusters[0].max_forward)


def test_identify_and_scale_json_are_strict(tmp_path, capsys):
    from validation.experiments import ROV2_BUOYANCY, ROV2_LENGTH, ROV2_MASS, rov2_pendulum_log

    log = tmp_path / "pend.csv"
    rov2_pendulum_log(0).write_csv(log)
    res = tmp_path / "pend.json"
    assert main(["identify", str(log), "--method", "pendulum", "--mass", str(ROV2_MASS),
                 "--buoyancy", str(ROV2_BUOYANCY), "--length", str(ROV2_LENGTH),
                 "--json", "-o", str(res)]) == 0
    strict_loads(res.read_text())
    assert main(["scale", str(res), "--ratio", "2", "--json"]) == 0
    strict_loads(capsys.readouterr().out)
