"""`stripcoef simulate` end to end: model file in, inputs CSV in, log CSV out; bad input."""

import json
from pathlib import Path

import numpy as np
import pytest

from stripcoef import cli  # noqa: E402
from stripcoef.logfile import Log, read_log  # noqa: E402
from stripcoef.modelfile import load_model
from stripcoef.export import write_export  # noqa: E402
from stripcoef.thrusters import Thruster  # noqa: E402
from test_simulate_dynamics import make_model  # noqa: E402


def save_model(model, path):
    write_export(model, "json" if str(path).endswith(".json") else "yaml", path)




def videoray_like(tmp_path, suffix=".yaml"):
    thr = [Thruster("port", np.array([-0.1, -0.1, 0.0]), np.array([1.0, 0, 0]),
                    ct_forward=2.5939e-4, ct_backward=1.0086e-4),
           Thruster("starboard", np.array([-0.1, 0.1, 0.0]), np.array([1.0, 0, 0]),
                    ct_forward=2.5939e-4, ct_backward=1.0086e-4),
           Thruster("vertical", np.array([0.0, 0.0, 0.0]), np.array([0, 0, 1.0]),
                    ct_forward=1.1901e-4, ct_backward=0.7534e-4)]
    model = make_model(thrusters=thr)
    path = tmp_path / f"model{suffix}"
    save_model(model, path)
    return model, path


def write_inputs(path, cols):
    Log(cols).write_csv(path)


@pytest.mark.parametrize("suffix", [".yaml", ".json"])
def test_cli_writes_a_log_matching_the_api(tmp_path, suffix, capsys):
    from stripcoef.simulate import simulate

    model, mpath = videoray_like(tmp_path, suffix)
    t = np.linspace(0.0, 10.0, 101)
    n = np.where(t < 5.0, 60.0, 0.0)
    write_inputs(tmp_path / "in.csv", {"t": t, "n_port": n, "n_starboard": n,
                                      "n_vertical": 0 * t})
    rc = cli.main(["simulate", str(mpath), "--inputs", str(tmp_path / "in.csv"),
                   "--out", str(tmp_path / "out.csv")])
    assert rc == 0
    assert "wrote" in capsys.readouterr().out
    log = read_log(tmp_path / "out.csv")
    for col in ("t", "x", "y", "z", "phi", "theta", "psi", "u", "v", "w", "p", "q", "r",
                "X", "Y", "Z", "K", "M", "N", "n_port", "n_starboard"):
        assert col in log
    ref = simulate(load_model(mpath), t, commands={"port": n, "starboard": n})
    np.testing.assert_allclose(log["u"], ref["u"], rtol=1e-12, atol=1e-15)
    assert log["u"].max() > 0.3
    assert model.mass == load_model(mpath).mass


def test_cli_forces_current_and_dt(tmp_path):
    _, mpath = videoray_like(tmp_path)
    t = np.array([0.0, 30.0])
    write_inputs(tmp_path / "in.csv", {"t": t, "X": [0.0, 0.0]})
    rc = cli.main(["simulate", str(mpath), "--inputs", str(tmp_path / "in.csv"),
                   "--out", str(tmp_path / "out.csv"), "--current", "0.2,0,0", "--dt", "0.5"])
    assert rc == 0
    log = read_log(tmp_path / "out.csv")
    assert len(log) == 61
    assert log["u"][-1] == pytest.approx(0.2, abs=1e-3)  # drifts with the current


@pytest.mark.parametrize("cols, extra, needle", [
    ({"t": [0.0, 1.0, 1.0], "X": [1.0, 1.0, 1.0]}, [], "duplicated timestamp"),
    ({"t": [0.0, 2.0, 1.0], "X": [1.0, 1.0, 1.0]}, [], "time goes backwards"),
    ({"X": [1.0, 1.0]}, [], "'t'"),
    ({"t": [0.0, 1.0], "n_nope": [1.0, 1.0]}, [], "n_nope"),
    ({"t": [0.0, 1.0], "depth": [1.0, 1.0]}, [], "no inputs"),
    ({"t": [0.0, 1.0], "X": [1.0, 1.0]}, ["--current", "0.2,x"], "--current"),
    ({"t": [0.0, 1.0], "X": [1.0, 1.0]}, ["--dt", "-1"], "--dt"),
])
def test_cli_bad_inputs_one_line_exit_2_no_output(tmp_path, capsys, cols, extra, needle):
    _, mpath = videoray_like(tmp_path)
    write_inputs(tmp_path / "in.csv", cols)
    out = tmp_path / "out.csv"
    rc = cli.main(["simulate", str(mpath), "--inputs", str(tmp_path / "in.csv"),
                   "--out", str(out), *extra])
    err = capsys.readouterr().err
    assert rc == 2
    assert needle in err and len(err.strip().splitlines()) == 1
    assert not out.exists()


def test_cli_nan_cell_names_column_and_row(tmp_path, capsys):
    _, mpath = videoray_like(tmp_path)
    (tmp_path / "in.csv").write_text("t,X\n0,1\n1,nan\n")
    rc = cli.main(["simulate", str(mpath), "--inputs", str(tmp_path / "in.csv"),
                   "--out", str(tmp_path / "out.csv")])
    err = capsys.readouterr().err
    assert rc == 2 and "X" in err and "row 3" in err


def test_cli_bad_model_file_and_existing_output_kept(tmp_path, capsys):
    _, mpath = videoray_like(tmp_path)
    write_inputs(tmp_path / "in.csv", {"t": [0.0, 1.0], "X": [1.0, 1.0]})
    out = tmp_path / "out.csv"
    out.write_text("previous\n")
    bad = tmp_path / "bad.json"
    data = json.loads(json.dumps(load_model(mpath).to_dict()))
    data["added_mass"] = [[1.0, 2.0]]
    bad.write_text(json.dumps(data))
    rc = cli.main(["simulate", str(bad), "--inputs", str(tmp_path / "in.csv"), "--out", str(out)])
    err = capsys.readouterr().err
    assert rc == 2 and "added_mass" in err
    assert out.read_text() == "previous\n"
    rc = cli.main(["simulate", str(tmp_path / "missing.yaml"), "--inputs",
                   str(tmp_path / "in.csv"), "--out", str(out)])
    assert rc == 2 and "file not found" in capsys.readouterr().err


def test_cli_passes_other_columns_through_to_effects_and_log(tmp_path):
    # a calibrated model with a tether drag effect reads tether_length from the inputs
    model, _ = videoray_like(tmp_path)
    model = model.with_effects({"name": "buoyancy_offset", "dof": "surge", "parameters": {"b": 0.5}})
    mpath = tmp_path / "cal.yaml"
    save_model(model, mpath)
    write_inputs(tmp_path / "in.csv", {"t": [0.0, 40.0], "X": [0.0, 0.0],
                                      "tether_length": [3.0, 3.0]})
    rc = cli.main(["simulate", str(mpath), "--inputs", str(tmp_path / "in.csv"),
                   "--out", str(tmp_path / "out.csv"), "--dt", "1"])
    assert rc == 0
    log = read_log(tmp_path / "out.csv")
    np.testing.assert_allclose(log["tether_length"], 3.0)
    assert log["u"][-1] > 0.05  # the constant 0.5 N offset pushes it forward


def test_cli_vehicle_file_is_estimated_by_strip_theory(tmp_path):
    vehicle = Path(__file__).resolve().parents[1] / "geometry" / "videoray_pro3.yaml"
    write_inputs(tmp_path / "in.csv", {"t": [0.0, 10.0], "n_port": [60.0, 60.0],
                                      "n_starboard": [60.0, 60.0], "n_vertical": [0.0, 0.0]})
    rc = cli.main(["simulate", str(vehicle), "--inputs", str(tmp_path / "in.csv"),
                   "--out", str(tmp_path / "out.csv"), "--dt", "0.1"])
    assert rc == 0
    log = read_log(tmp_path / "out.csv")
    assert len(log) == 101 and log["u"][-1] > 0.01 and log["X"][-1] > 0
