"""Log replay: one rule (``simulate.log_inputs``) for ``simulate --from-log``, held-out
validation and diagnose. A log written by ``stripcoef simulate`` replayed with
``simulate --from-log`` gives its states back (issue 31: thrust was counted twice, -297 deg of
heading in 20 s instead of -0.7 deg)."""

import warnings

import numpy as np
import pytest

from stripcoef import cli
from stripcoef.conventions import POSE, VELOCITIES
from stripcoef.errors import InputError, ModelWarning
from stripcoef.logfile import Log, read_log
from stripcoef.modelfile import load_model
from stripcoef.logfile import log_inputs
from stripcoef.simulate import replay, simulate

STATES = POSE + VELOCITIES


def _run(args, capsys):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        rc = cli.main(args)
    out = capsys.readouterr()
    assert rc == 0, out.err
    return out


def test_a_simulated_remus_log_replays_to_its_printed_precision(remus_file, tmp_path, capsys):
    """Thrust, a rudder turn and an elevator: the CLI writes the log (X..N = the applied thrust,
    n_propeller, delta_*), the CLI replays it; every state equals the log's to the last digit
    the CSV prints (repr: the floats themselves)."""
    t = np.array([0.0, 4.0, 9.0, 20.0])
    Log({"t": t, "n_propeller": [1500.0, 1500.0, 1500.0, 1500.0],
         "delta_rudder": [0.0, 0.12, -0.05, -0.05],
         "delta_elevator": [0.0, 0.0, 0.08, 0.08]}).write_csv(tmp_path / "in.csv")
    _run(["simulate", str(remus_file), "--inputs", str(tmp_path / "in.csv"),
          "--out", str(tmp_path / "log.csv")], capsys)
    log = read_log(tmp_path / "log.csv")
    assert np.ptp(log["X"]) == 0 and log["X"][0] > 1.0          # the thrust is logged in X
    out = _run(["simulate", str(remus_file), "--from-log", str(tmp_path / "log.csv"),
                "--out", str(tmp_path / "replay.csv")], capsys)
    rep = read_log(tmp_path / "replay.csv")
    assert "not applied again" not in out.err
    for c in STATES + ("X", "N", "n_propeller", "delta_rudder", "delta_elevator"):
        np.testing.assert_allclose(rep[c], log[c], rtol=0, atol=1e-12, err_msg=c)
    # from the middle of the log: the state there and the inputs after it, to the integrator's
    # tolerance (rtol 1e-8; the segments start elsewhere than in the first run)
    _run(["simulate", str(remus_file), "--from-log", str(tmp_path / "log.csv"), "--start", "6",
          "--duration", "8", "--out", str(tmp_path / "mid.csv")], capsys)
    mid = read_log(tmp_path / "mid.csv")
    rows = (log["t"] >= 6.0 - 1e-9) & (log["t"] <= 14.0 + 1e-9)
    for c in STATES:
        np.testing.assert_allclose(mid[c], log[c][rows], rtol=0, atol=1e-6, err_msg=c)


def test_a_forces_log_replays_exactly_and_a_thrust_log_through_the_library(remus_file):
    model = load_model(remus_file)
    t = np.linspace(0.0, 10.0, 101)
    forces = np.tile([5.0, 0.0, -1.0, 0.0, 0.2, 0.3], (t.size, 1))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        log = simulate(model, t, forces=forces)
        again = replay(model, log)
        thrust_log = simulate(model, t, commands={"propeller": 1200.0},
                              deflections={"rudder": 0.1})
        thrust_again = replay(model, thrust_log)
    for c in STATES:
        np.testing.assert_allclose(again[c], log[c], rtol=0, atol=1e-12, err_msg=c)
        np.testing.assert_allclose(thrust_again[c], thrust_log[c], rtol=0, atol=1e-12,
                                   err_msg=c)


def test_the_rule(remus_file):
    """Commands act through the thruster map; X..N with commands are their record (not applied
    again; the mismatch with the model's thrust is reported); other columns are channels."""
    model = load_model(remus_file)
    t = np.linspace(0.0, 1.0, 5)
    thrust = float(model.thrusters[0].thrust(1000.0))
    b = model.allocation()[:, 0]
    cols = {"t": t, "n_propeller": np.full(5, 1000.0), "delta_rudder": np.zeros(5),
            "tether_length": np.full(5, 2.0)}
    cols.update({f: np.full(5, thrust * b[i]) for i, f in enumerate("XYZKMN")})
    inp = log_inputs(Log(cols), model)
    assert inp.forces is None and inp.thrust_mismatch < 1e-12
    assert set(inp.commands) == {"propeller"} and set(inp.deflections) == {"rudder"}
    assert set(inp.channels) == {"tether_length"}
    cols["Y"] = np.full(5, 3.0)                           # a side force the thrust lacks
    inp = log_inputs(Log(cols), model)
    assert inp.forces is None and inp.thrust_mismatch == pytest.approx(3.0)
    # without commands, X..N are the applied force
    del cols["n_propeller"]
    inp = log_inputs(Log(cols), model)
    assert inp.forces is not None and inp.forces[0, 1] == 3.0
    # windows and resampling keep every input
    part = inp.window(1, 4).at([0.3, 0.6], "previous")
    assert part.forces.shape == (2, 6) and part.channels["tether_length"].shape == (2,)
    with pytest.raises(InputError, match="n_nope"):
        log_inputs(Log({"t": t, "n_nope": t}), model)
    with pytest.raises(InputError, match="delta_nope"):
        log_inputs(Log({"t": t, "delta_nope": t}), model)
    with pytest.raises(InputError, match="no inputs"):
        log_inputs(Log({"t": t, "u": t}), model)


def test_the_cli_warns_when_the_logged_forces_are_more_than_the_thrust(remus_file, tmp_path,
                                                                        capsys):
    t = np.array([0.0, 2.0])
    Log({"t": t, "n_propeller": [1000.0, 1000.0], "Y": [3.0, 3.0]}).write_csv(tmp_path / "in.csv")
    assert cli.main(["simulate", str(remus_file), "--inputs", str(tmp_path / "in.csv"),
                     "--out", str(tmp_path / "o.csv")]) == 0
    err = capsys.readouterr().err
    assert "X..N differ from the thrust of its n_ commands" in err
    assert "by up to 9 N or N m" in err and "not applied again" in err


def test_held_out_replay_is_the_cli_replay(remus_file):
    """diagnose's held-out free simulation replays a log by the same rule: with its own model a
    simulated log (thrust logged in X..N, commands, a rudder) is predicted to the integrator's
    tolerance."""
    from stripcoef.diagnose.heldout import free_simulation_errors

    model = load_model(remus_file)
    t = np.linspace(0.0, 12.0, 121)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        log = simulate(model, t, commands={"propeller": 1500.0},
                       deflections={"rudder": np.where(t < 5, 0.0, 0.1)},
                       nu0=[1.0, 0, 0, 0, 0, 0])
        err = free_simulation_errors(log, model, list(range(6)), horizon=5.0)
    assert max(err) < 1e-4
