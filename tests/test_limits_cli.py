"""``stripcoef limits``: output contract, plots, model files, and bad input (exit 2)."""

import json

import numpy as np
import pytest
import yaml

from limits_helpers import make_model
from stripcoef import cli


@pytest.fixture
def model_json(tmp_path):
    path = tmp_path / "model.json"
    path.write_text(json.dumps(make_model(name="demo").to_dict()))
    return path


def run(argv, capsys):
    code = cli.main(argv)
    out, err = capsys.readouterr()
    return code, out, err


KEYS = {"surge_speed_max", "heave_speed_max", "yaw_rate_max", "sway_speed_max",
        "min_turning_radius", "turning"}
TURN_KEYS = {"radius", "u_max", "v", "drift_angle", "thrust", "saturated"}


def test_json_contract(model_json, capsys):
    code, out, err = run(["limits", str(model_json), "--json", "--radii", "1:9:3"], capsys)
    assert code == 0, err
    data = json.loads(out)
    assert KEYS <= set(data)
    assert data["sway_speed_max"] is None
    assert [p["radius"] for p in data["turning"]] == [1.0, 5.0, 9.0]
    for p in data["turning"]:
        assert TURN_KEYS <= set(p)
        assert set(p["thrust"]) == {"P1", "P2", "V1", "V2"}
        assert p["saturated"] in p["thrust"]
        assert all(np.isfinite(v) for v in (p["u_max"], p["v"], p["drift_angle"]))


def test_table_and_munk_switch(model_json, capsys):
    code, out, _ = run(["limits", str(model_json), "--radii", "2:4:2"], capsys)
    assert code == 0 and "surge speed max" in out and "Munk moment on" in out
    code, out2, _ = run(["limits", str(model_json), "--radii", "2:4:2", "--no-munk"], capsys)
    assert code == 0 and "Munk moment off" in out2
    code, out3, _ = run(["limits", str(model_json), "--radii", "2:4:2", "--json",
                         "--no-coriolis"], capsys)
    assert json.loads(out3)["options"] == {"munk": True, "coriolis": False}


def test_yaml_model_file_detected_by_content(tmp_path, capsys):
    path = tmp_path / "model.yaml"
    path.write_text(yaml.safe_dump(json.loads(json.dumps(make_model().to_dict()))))
    code, out, err = run(["limits", str(path), "--json", "--radii", "3:3:1"], capsys)
    assert code == 0, err
    assert json.loads(out)["surge_speed_max"] > 0.0


def test_plot_written(model_json, tmp_path, capsys):
    png = tmp_path / "limits.png"
    code, _, err = run(["limits", str(model_json), "--radii", "1:5:3", "--plot", str(png)],
                       capsys)
    assert code == 0, err
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []


def test_plot_without_matplotlib_is_a_clear_error(model_json, tmp_path, capsys, monkeypatch):
    import builtins
    real = builtins.__import__

    def fake(name, *args, **kwargs):
        if name.startswith("matplotlib"):
            raise ImportError(name)
        return real(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", fake)
    png = tmp_path / "x.png"
    code, out, err = run(["limits", str(model_json), "--radii", "1:2:2", "--plot", str(png)],
                         capsys)
    assert code == 2 and "matplotlib" in err and not png.exists()


def _bad_model(tmp_path, **changes):
    data = make_model().to_dict()
    for key, value in changes.items():
        data[key] = value
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(data))
    return path


def _one_line_error(code, out, err, *words):
    assert code == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err
    for w in words:
        assert w in lines[0], lines[0]


def test_no_thrusters(tmp_path, capsys):
    path = _bad_model(tmp_path, thrusters=[])
    _one_line_error(*run(["limits", str(path)], capsys), "no thrusters", "bad.json")


def test_thruster_with_zero_maximum(tmp_path, capsys):
    data = make_model().to_dict()
    data["thrusters"][1]["max_forward"] = 0.0
    data["thrusters"][1]["max_backward"] = 0.0
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(data))
    _one_line_error(*run(["limits", str(path)], capsys), "P2", "thrusters[1]", "> 0")


def test_thruster_without_limit(tmp_path, capsys):
    data = make_model().to_dict()
    data["thrusters"][0]["max_forward"] = float("inf")
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(data))
    _one_line_error(*run(["limits", str(path)], capsys), "thrusters[0].max_forward", "finite")


def test_negative_drag(tmp_path, capsys):
    d = np.diag([2.0, 5, -5, 0.5, 1, 1]).tolist()
    path = _bad_model(tmp_path, linear_damping=d)
    _one_line_error(*run(["limits", str(path)], capsys), "linear_damping[2][2]", "-5.0",
                    "not positive")


def test_indefinite_drag(tmp_path, capsys):
    d = np.diag([2.0, 5, 5, 0.5, 1, 1])
    d[0, 1] = d[1, 0] = 10.0                     # diagonal fine, matrix indefinite
    path = _bad_model(tmp_path, linear_damping=d.tolist())
    _one_line_error(*run(["limits", str(path)], capsys), "linear_damping", "not positive")


def test_not_a_matrix(tmp_path, capsys):
    path = _bad_model(tmp_path, quadratic_damping=[[1, 2], [3, 4]])
    _one_line_error(*run(["limits", str(path)], capsys), "quadratic_damping", "(6, 6)")


@pytest.mark.parametrize("radii,word", [("-1:5:3", "positive"), ("5:1:3", "increasing"),
                                        ("0:5:3", "positive"), ("1:5", "R1:R2:N"),
                                        ("a:b:c", "R1:R2:N"), ("1:5:0", "N >= 1")])
def test_bad_radii(model_json, capsys, radii, word):
    _one_line_error(*run(["limits", str(model_json), f"--radii={radii}"], capsys),
                    "--radii", word)


def test_missing_file(tmp_path, capsys):
    _one_line_error(*run(["limits", str(tmp_path / "nope.yaml")], capsys), "not found")


def test_failed_run_leaves_earlier_plot_untouched(tmp_path, capsys, model_json):
    png = tmp_path / "keep.png"
    png.write_bytes(b"old")
    path = _bad_model(tmp_path, thrusters=[])
    code, _, _ = run(["limits", str(path), "--plot", str(png)], capsys)
    assert code == 2 and png.read_bytes() == b"old"


def test_no_yaw_thruster_is_reported_not_nan(tmp_path, capsys):
    data = make_model().to_dict()
    data["thrusters"] = [t for t in data["thrusters"] if t["name"] in ("P1", "V1", "V2")]
    data["thrusters"][0]["position"] = [-0.6, 0.0, 0.0]
    path = tmp_path / "noyaw.json"
    path.write_text(json.dumps(data))
    code, out, err = run(["limits", str(path), "--json"], capsys)
    assert code == 0, err
    d = json.loads(out)
    assert d["yaw_rate_max"] is None and d["turning"] == [] and d["min_turning_radius"] is None
    assert d["surge_speed_max"] > 0.0
    assert any("yaw" in n for n in d["notes"])
    code, out, err = run(["limits", str(path)], capsys)
    assert code == 0 and "unreachable" in out
    # a figure of the turning circle cannot be drawn: one-line error, no file
    png = tmp_path / "t.png"
    _one_line_error(*run(["limits", str(path), "--plot", str(png)], capsys), "nothing to plot",
                    "yaw")
    assert not png.exists()


def test_turn_speed_above_top_speed(model_json, capsys):
    _one_line_error(*run(["limits", str(model_json), "--radii", "2:4:2", "--turn-speed", "5"],
                         capsys), "straight-line")


def test_vehicle_file_mares(capsys):
    from pathlib import Path
    mares = Path(__file__).resolve().parent.parent / "geometry" / "mares.yaml"
    code, out, err = run(["limits", str(mares), "--json", "--radii", "2:8:2", "--no-munk"],
                         capsys)
    assert code == 0, err
    data = json.loads(out)
    assert data["name"] == "MARES" and data["sway_speed_max"] is None
    assert [p["saturated"] for p in data["turning"]] == ["P1", "P1"]


def test_vehicle_file_without_thrusters(tmp_path, capsys):
    from pathlib import Path
    mares = Path(__file__).resolve().parent.parent / "geometry" / "mares.yaml"
    data = yaml.safe_load(mares.read_text())
    del data["thrusters"]
    path = tmp_path / "nothr.yaml"
    path.write_text(yaml.safe_dump(data))
    _one_line_error(*run(["limits", str(path)], capsys), "no thrusters", "nothr.yaml")


@pytest.mark.parametrize("fmt,suffix", [("--json", "json"), ("--yaml", "yaml")])
def test_model_file_from_coefficients_gives_the_same_limits(tmp_path, capsys, fmt, suffix):
    from pathlib import Path
    mares = str(Path(__file__).resolve().parent.parent / "geometry" / "mares.yaml")
    model = tmp_path / f"mares.{suffix}"
    code, _, err = run(["coefficients", mares, fmt, "-o", str(model)], capsys)
    assert code == 0, err
    args = ["--json", "--radii", "3:3:1", "--no-munk"]
    code, out_model, err = run(["limits", str(model)] + args, capsys)
    assert code == 0, err
    code, out_vehicle, _ = run(["limits", mares] + args, capsys)
    a, b = json.loads(out_model), json.loads(out_vehicle)
    for key in ("surge_speed_max", "heave_speed_max", "yaw_rate_max", "min_turning_radius"):
        assert a[key] == pytest.approx(b[key], rel=1e-9)
    assert a["turning"][0]["u_max"] == pytest.approx(b["turning"][0]["u_max"], rel=1e-9)
