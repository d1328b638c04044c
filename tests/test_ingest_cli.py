"""Column-mapped CSVs and ROS bags straight into identify / diagnose / simulate; a free
simulation from a log's state; no missing column read as zeros."""

import json

import numpy as np
import pytest

from validation import ingest_truth as T  # noqa: E402
from stripcoef import cli  # noqa: E402
from stripcoef.export import write_export  # noqa: E402
from stripcoef.logfile import Log, read_log  # noqa: E402
from test_simulate_dynamics import make_model  # noqa: E402


@pytest.fixture(scope="module")
def case(tmp_path_factory):
    """The truth's model file, its navigation + wrench CSVs with a map, and a ROS 2 bag."""
    d = tmp_path_factory.mktemp("ingest_cli")
    model = make_model(coupled=True)
    truth = T.Truth(model, seed=4, duration=20.0)
    write_export(model, "yaml", d / "model.yaml")
    nav_t = truth.nav_times(seed=5, rate=10.0, jitter=0.2)
    T.write_nav_csv(d / "nav.csv", truth, nav_t)
    T.write_wrench_csv(d / "wrench.csv", truth)
    (d / "map.yaml").write_text(T.NAV_WRENCH_MAP % {"start": T.EPOCH_NS * 1e-9})
    (d / "bagmap.yaml").write_text(T.BAG_MAP)
    pytest.importorskip("rosbags")
    T.write_bag(d / "bag", truth, 0.3 + np.arange(190) * 0.1, ros=2)
    return d, truth


@pytest.mark.parametrize("log, m", [("nav.csv", "map.yaml"), ("bag", "bagmap.yaml")])
def test_identify_reads_a_mapped_csv_and_a_ros2_bag(case, capsys, log, m):
    d, _ = case
    rc = cli.main(["identify", str(d / log), "--map", str(d / m), "--method", "one-step",
                   "--dof", "yaw", "--inertia", "0.0253", "--json"])
    out = capsys.readouterr()
    assert rc == 0, out.err
    fit = json.loads(out.out)
    assert fit["dof"] == "yaw" and "applied force from column N" in " ".join(fit["notes"])


def test_a_bag_without_map_is_a_one_line_error(case, capsys):
    d, _ = case
    rc = cli.main(["identify", str(d / "bag"), "--method", "one-step", "--dof", "yaw"])
    err = capsys.readouterr().err
    assert rc == 2 and len(err.splitlines()) == 1
    assert "--map: a ROS bag needs a column map; got " in err


def test_bad_map_is_a_one_line_error_naming_the_key(case, capsys):
    d, _ = case
    bad = d / "bad.yaml"
    bad.write_text((d / "map.yaml").read_text().replace("order: xyzw", "order: zyxw"))
    rc = cli.main(["diagnose", str(d / "nav.csv"), "--map", str(bad), "--vehicle",
                   str(d / "model.yaml")])
    err = capsys.readouterr().err
    assert rc == 2 and len(err.splitlines()) == 1
    assert "bad.yaml: attitude.order: unknown value; got 'zyxw'" in err


def test_diagnose_a_dof_without_its_velocity_column_is_an_error(case, capsys):
    """--dof yaw on a log without r used to run on zeros; now one line naming the column."""
    d, truth = case
    t = np.arange(0.0, 20.0, 0.1)
    Log({"t": t, "u": truth("u", t), "v": truth("v", t), "N": truth.force_at(t)[:, 5]}
        ).write_csv(d / "no_r.csv")
    rc = cli.main(["diagnose", str(d / "no_r.csv"), "--vehicle", str(d / "model.yaml"),
                   "--dof", "yaw"])
    err = capsys.readouterr().err
    assert rc == 2 and len(err.splitlines()) == 1
    assert "no_r.csv: r: missing required column" in err


def test_dof_all_says_which_dofs_it_drops_and_why(case):
    from stripcoef.diagnose.pipeline import select_dofs
    from stripcoef.effects.windows import window_data
    from stripcoef.modelfile import load_model

    d, truth = case
    t = np.arange(0.0, 20.0, 0.05)
    f = truth.force_at(t)
    log = Log({"t": t, "u": truth("u", t), "v": truth("v", t), "w": 0 * t + 1e-5 * np.sin(t),
               "r": truth("r", t), "X": f[:, 0], "Y": 0 * t, "Z": f[:, 2], "N": f[:, 5]},
              source="surge.csv")
    dofs, dropped = select_dofs(window_data(log, load_model(d / "model.yaml"), window=1.0))
    assert dofs == [0, 5]
    assert dropped == {"sway": "no applied force in sway (Y is zero throughout)",
                       "heave": "not excited (std of w 7e-06 m/s <= 0.001)",
                       "roll": "no column p in the log", "pitch": "no column q in the log"}


def test_simulate_from_log_reproduces_the_log_with_its_own_model(case, tmp_path, capsys):
    """Started from the logged state (not rest at the origin) and fed the logged inputs, the
    true model predicts the log to the integrator's tolerance; from rest it does not."""
    d, truth = case
    t = np.arange(5.0, 15.0 + 1e-9, 0.02)
    cols = {k: truth(k, t) for k in ("x", "y", "z", "phi", "theta", "psi",
                                     "u", "v", "w", "p", "q", "r")}
    f = truth.force_at(t)
    cols.update({k: f[:, i] for i, k in enumerate("XYZKMN")})
    Log({"t": t, **cols}).write_csv(tmp_path / "log.csv")
    rc = cli.main(["simulate", str(d / "model.yaml"), "--from-log", str(tmp_path / "log.csv"),
                   "--start", "6", "--duration", "4", "--out", str(tmp_path / "pred.csv")])
    out = capsys.readouterr().out
    assert rc == 0
    pred = read_log(tmp_path / "pred.csv")
    assert pred["t"][0] == pytest.approx(6.0) and pred["t"][-1] == pytest.approx(10.0)
    for k in ("u", "v", "w", "p", "q", "r", "phi", "psi"):
        np.testing.assert_allclose(pred[k], truth(k, pred["t"]), atol=1e-6, err_msg=k)
    assert "free simulation from the logged state at t = 6 s (4 s)" in out
    # the RMS lines follow the header (the motion summary above it is indented too)
    after = out.split("free simulation from the logged state", 1)[1].splitlines()[1:]
    rms = {line.split(":")[0].strip(): float(line.split(":")[1].split()[0])
           for line in after if line.startswith("  ")}
    assert max(rms.values()) < 1e-6      # measured: 4e-10 .. 2e-8 (rtol 1e-8)
    rc = cli.main(["simulate", str(d / "model.yaml"), "--inputs", str(tmp_path / "log.csv"),
                   "--out", str(tmp_path / "rest.csv")])
    rest = read_log(tmp_path / "rest.csv")
    assert np.abs(rest["u"] - truth("u", rest["t"])).max() > 0.05


def test_simulate_from_a_mapped_bag_warns_about_missing_state(case, tmp_path, capsys):
    d, _ = case
    m = d / "bagmap_surge.yaml"
    m.write_text(T.BAG_MAP.split("position:")[0]
                 + "velocity: {stream: odom, columns: [twist.twist.linear.x, null, null]}\n"
                 + "wrench: {stream: wrench, columns: [wrench.force.x, wrench.force.y, "
                 "wrench.force.z, wrench.torque.x, wrench.torque.y, wrench.torque.z]}\n")
    rc = cli.main(["simulate", str(d / "model.yaml"), "--from-log", str(d / "bag"),
                   "--map", str(m), "--duration", "3", "--out", str(tmp_path / "p.csv")])
    assert rc == 0
    cap = capsys.readouterr()       # the CLI prints warnings as "warning: ..." lines
    assert "warning: " in cap.err
    assert "no column x, y, z, phi, theta, psi, v, w, p, q, r: the initial state takes 0" \
        in cap.err
    assert "  u:" in cap.out and "  v:" not in cap.out


@pytest.mark.parametrize("extra, needle", [
    ([], "--inputs: no inputs; expected --inputs INPUTS and/or --from-log LOG"),
    (["--inputs", "IN", "--start", "1"], "--start: applies to --from-log only"),
    (["--from-log", "LOG", "--start", "99"], "--start: start outside the log; got 99.0"),
    (["--from-log", "LOG", "--duration", "-1"], "--duration: not a positive duration"),
])
def test_simulate_from_log_bad_arguments(case, tmp_path, capsys, extra, needle):
    d, _ = case
    Log({"t": [0.0, 1.0, 2.0], "u": [0.1, 0.1, 0.1], "X": [1.0, 1.0, 1.0]}).write_csv(
        tmp_path / "log.csv")
    extra = [str(tmp_path / "log.csv") if a in ("IN", "LOG") else a for a in extra]
    rc = cli.main(["simulate", str(d / "model.yaml"), "--out", str(tmp_path / "o.csv"), *extra])
    err = capsys.readouterr().err
    assert rc == 2 and needle in err and len(err.splitlines()) == 1
    assert not (tmp_path / "o.csv").exists()


@pytest.mark.parametrize("log, m", [("nav.csv", "map.yaml"), ("bag", "bagmap.yaml")])
def test_diagnose_a_mapped_log_with_its_true_model_finds_nothing(case, capsys, log, m):
    """Straight into diagnose: with the model that generated the log, the yaw residual of the
    mapped log is small (under 10 % of the yaw moment's spread) and no effect is added; the
    CSV log read with the quaternion's columns in the wrong order (its rates come from the
    attitude) is far off (a control: the check sees a wrong attitude). (Reading FLU as FRD would not do as a control in yaw alone:
    it flips both r and N, and the yaw equation is symmetric under that mirror.)"""
    d, truth = case
    args = ["--vehicle", str(d / "model.yaml"), "--dof", "yaw", "--window", "1",
            "--no-resimulate", "--json"]
    rc = cli.main(["diagnose", str(d / log), "--map", str(d / m), *args])
    out = capsys.readouterr().out
    assert rc == 0
    res = json.loads(out)
    spread = np.std(truth.wrench[:, 5])
    assert res["steps"] == [] and res["unexplained"] is False
    assert res["baseline_error"] < 0.1 * spread, (res["baseline_error"], spread)
    if log != "nav.csv":
        return                      # the bag's rates come from its IMU, not the attitude
    wrong = d / f"wrong_{m}"
    wrong.write_text((d / m).read_text().replace("order: xyzw", "order: wxyz"))
    rc = cli.main(["diagnose", str(d / log), "--map", str(wrong), *args])
    res = json.loads(capsys.readouterr().out)
    assert res["baseline_error"] > 0.5 * spread, (res["baseline_error"], spread)
