"""CLI: stripcoef identify / scale on CSV logs; JSON contract; bad input -> one line, exit 2."""

import json

import numpy as np
import pytest

from stripcoef.cli import main
from validation.experiments import (ROV2_BUOYANCY, ROV2_LENGTH, ROV2_MASS,
                                            romeo_experiment, rov2_pendulum_log,
                                            rov2_torsion_log, videoray_yaw_log)
from stripcoef.logfile import Log

CONTRACT = ("method", "model", "dof", "parameters", "std", "relative_error_percent", "cost",
            "degrees_of_freedom", "rms_error")


@pytest.fixture
def logs(tmp_path):
    pts, _ = romeo_experiment(2, seed=2)
    out = {}
    out["steady"] = tmp_path / "heave.csv"
    Log({"w": pts.velocity, "Z": pts.force, "n_h": pts.n_h}).write_csv(out["steady"])
    out["yaw"] = tmp_path / "yaw.csv"
    videoray_yaw_log(0).write_csv(out["yaw"])
    out["pend"] = tmp_path / "pend.csv"
    rov2_pendulum_log(0).write_csv(out["pend"])
    out["tors"] = tmp_path / "tors.csv"
    rov2_torsion_log(0).write_csv(out["tors"])
    return out


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("model", ["standard", "eta", "eta-md", "LQB", "LNB"])
def test_steady_json_contract(logs, capsys, model):
    d = _json(capsys, ["identify", str(logs["steady"]), "--method", "steady", "--dof", "heave",
                       "--model", model, "--json"])
    assert all(k in d for k in CONTRACT)
    assert d["method"] == "steady" and d["dof"] == "heave"
    if model.startswith("eta"):
        assert 0.4 < d["parameters"]["eta"] < 0.75


def test_one_step_table_and_json(logs, capsys):
    assert main(["identify", str(logs["yaw"]), "--method", "one-step", "--dof", "yaw",
                 "--inertia", "0.02532"]) == 0
    out = capsys.readouterr().out
    assert "alpha" in out and "N_rdot" in out and "J_LS" in out
    d = _json(capsys, ["identify", str(logs["yaw"]), "--method", "one-step", "--json"])
    assert set(d["parameters"]) >= {"alpha", "beta", "gamma", "delta", "N_r", "N_rr"}
    assert d["degrees_of_freedom"] == 1080 - 1 - 4        # N - 1 differences, 4 parameters


def test_pendulum_then_scale(logs, capsys, tmp_path):
    res = tmp_path / "pend.json"
    assert main(["identify", str(logs["pend"]), "--method", "pendulum", "--mass", str(ROV2_MASS),
                 "--buoyancy", str(ROV2_BUOYANCY), "--length", str(ROV2_LENGTH), "--refine",
                 "--json", "-o", str(res)]) == 0
    d = json.loads(res.read_text())
    assert {"m_a", "K_L", "K_Q"} <= set(d["parameters"]) and d["rms_error"] < 0.06
    s = _json(capsys, ["scale", str(res), "--ratio", str(1 / 0.3), "--json"])
    assert s["parameters"]["m_a"] == pytest.approx(d["parameters"]["m_a"] / 0.3 ** 3)
    assert main(["scale", str(res), "--ratio", "3.333"]) == 0
    assert "Reynolds" in capsys.readouterr().out


def test_torsion_and_compare(logs, capsys, tmp_path):
    d = _json(capsys, ["identify", str(logs["tors"]), "--method", "torsion", "--stiffness",
                       "0.05", "--inertia", "0.012", "--json"])
    assert d["dof"] == "yaw" and "I_a" in d["parameters"]
    rng = np.random.default_rng(0)
    r = np.radians(np.r_[np.linspace(2, 10, 7), -np.linspace(2, 10, 8)])
    f = tmp_path / "yawsteady.csv"
    Log({"r": r, "N": 40 * r + rng.normal(0, 0.5, r.size)}).write_csv(f)
    assert main(["identify", str(f), "--method", "steady", "--dof", "yaw", "--model",
                 "compare"]) == 0
    out = capsys.readouterr().out
    assert "recommended: LNB" in out and "LQB positive" in out
    d = _json(capsys, ["identify", str(f), "--method", "steady", "--dof", "yaw", "--model",
                       "compare", "--json"])
    assert d["recommended"].startswith("LNB") and len(d["comparison"]) == 8


def test_plot_written(logs, tmp_path):
    pytest.importorskip("matplotlib")
    for method, log, extra in (("steady", "steady", ["--model", "eta"]),
                               ("one-step", "yaw", []),
                               ("pendulum", "pend", [])):
        png = tmp_path / f"{method}.png"
        assert main(["identify", str(logs[log]), "--method", method, "--plot", str(png),
                     *extra]) == 0
        assert png.read_bytes()[:4] == b"\x89PNG"


def _bad(tmp_path, capsys, text, argv_extra=("--method", "one-step")):
    f = tmp_path / "bad.csv"
    f.write_text(text)
    code = main(["identify", str(f), *argv_extra])
    err = capsys.readouterr().err.strip()
    assert code == 2 and "\n" not in err and "Traceback" not in err
    return err


def test_bad_logs_one_line_exit_2(tmp_path, capsys):
    err = _bad(tmp_path, capsys, "t,r\n0,0.1\n0.1,0.2\n0.2,0.3\n")
    assert "'N'" in err                                          # missing column
    err = _bad(tmp_path, capsys, "t,r,N\n0,0.1,1\n0.1,abc,1\n0.2,0.3,1\n")
    assert "row 3" in err and "r" in err and "abc" in err        # non-numeric
    err = _bad(tmp_path, capsys, "t,r,N\n0,0.1,1\n0.2,0.2,1\n0.1,0.3,1\n")
    assert "t" in err and "row 4" in err                         # time goes backwards
    err = _bad(tmp_path, capsys, "t,r,N\n0,0.1,1\n0.1,0.2,1\n0.1,0.3,1\n")
    assert "duplicated timestamp" in err
    err = _bad(tmp_path, capsys, "t,r,N\n0,0.1,1\n0.1,nan,1\n0.2,0.3,1\n")
    assert "row 3" in err and "r" in err                         # NaN gap
    err = _bad(tmp_path, capsys, "t,r,N\n0,0.1,1\n0.1,,1\n0.2,0.3,1\n")
    assert "row 3" in err


def test_bad_options_one_line_exit_2(logs, tmp_path, capsys):
    assert main(["identify", str(logs["steady"]), "--method", "steady", "--model", "cubic"]) == 2
    assert "eta" in capsys.readouterr().err
    assert main(["identify", str(logs["steady"]), "--method", "steady", "--dof", "sideways"]) == 2
    assert "surge" in capsys.readouterr().err
    assert main(["identify", str(tmp_path / "none.csv"), "--method", "steady"]) == 2
    assert "not found" in capsys.readouterr().err
    assert main(["identify", str(logs["pend"]), "--method", "pendulum", "--model", "x"]) == 2
    capsys.readouterr()
    out = tmp_path / "keep.json"
    out.write_text("old")
    assert main(["identify", str(logs["yaw"]), "--method", "one-step", "--json",
                 "--plot", str(tmp_path / "nofolder" / "a.png"), "-o", str(out)]) == 2
    assert out.read_text() == "old"                              # no partial output
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    assert main(["scale", str(bad), "--ratio", "3"]) == 2
    assert "JSON" in capsys.readouterr().err


@pytest.mark.slow
def test_one_step_with_vehicle_thruster_map(tmp_path, capsys):
    """Commands n_port, n_starboard + the shipped VideoRay file: torque from the bench map
    (T = Ct n|n|, Wang & Clark 2006 Table I) and I_zz from the vehicle give the same fit as the torque."""
    from pathlib import Path

    from stripcoef.identify.inputs import vehicle_model
    vehicle = Path(__file__).resolve().parents[1] / "geometry" / "videoray_pro3.yaml"
    model = vehicle_model(vehicle)
    port = next(t for t in model.thrusters if t.name == "port")
    stb = next(t for t in model.thrusters if t.name == "starboard")
    log = videoray_yaw_log(0)
    thrust = log["N"] / (2 * port.wrench_column(model.reference_point)[5])
    f = tmp_path / "cmd.csv"
    Log({"t": log["t"], "r": log["r"], "n_port": port.command_for(thrust),
         "n_starboard": stb.command_for(-thrust)}).write_csv(f)
    d = _json(capsys, ["identify", str(f), "--method", "one-step", "--vehicle", str(vehicle),
                       "--json"])
    g = tmp_path / "torque.csv"
    log.write_csv(g)
    ref = _json(capsys, ["identify", str(g), "--method", "one-step", "--inertia", "0.02532",
                         "--json"])
    for k in ("alpha", "beta", "gamma", "delta", "N_rdot"):
        assert d["parameters"][k] == pytest.approx(ref["parameters"][k], rel=1e-6)
    f.write_text(f.read_text().replace("n_port", "n_bow"))
    assert main(["identify", str(f), "--method", "one-step", "--vehicle", str(vehicle)]) == 2
    assert "n_bow" in capsys.readouterr().err


def test_compare_with_few_points_gives_valid_json(tmp_path, capsys):
    """Per-direction fits with N - p - 1 <= 0 have infinite AICc: JSON null, not a crash."""
    f = tmp_path / "few.csv"
    f.write_text("r,N\n0.05,2\n0.1,4.1\n-0.05,-2.05\n-0.1,-4\n")
    d = _json(capsys, ["identify", str(f), "--method", "steady", "--dof", "yaw", "--model",
                       "compare", "--json"])
    assert any(c["aicc"] is None for c in d["comparison"])
    assert d["recommended"] == "LNB together"


def test_python_api_matches_cli(logs, capsys):
    from stripcoef.errors import InputError
    from stripcoef.identify.api import identify_log
    from stripcoef.logfile import read_log
    fit, cmp = identify_log(read_log(logs["steady"]), "steady", model="eta")
    d = _json(capsys, ["identify", str(logs["steady"]), "--method", "steady", "--model", "eta",
                       "--json"])
    assert cmp is None and fit.to_dict()["parameters"] == d["parameters"]
    with pytest.raises(InputError, match="one-step"):
        identify_log(read_log(logs["steady"]), "kalman")
