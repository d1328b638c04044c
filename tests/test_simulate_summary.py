"""simulate: --no-munk/--no-coriolis, '-o -' for stdout, the default output step for short
inputs, the summary of what happened and the warnings for a runaway heading or a divergence."""


import numpy as np
import pytest

from stripcoef.cli import main
from stripcoef.logfile import Log, read_log
from stripcoef.modelfile import load_model
from stripcoef.simulate import simulate, summarize_motion


@pytest.fixture
def straight(tmp_path):
    """A spheroid pushed forward with a small side force: the Munk moment turns it round."""
    f = tmp_path / "in.csv"
    f.write_text("t,X,Y\n0,20,0.05\n60,20,0.05\n")
    return f


def _log_from_text(text, tmp_path):
    f = tmp_path / "stdout.csv"
    f.write_text(text)
    return read_log(f)


def test_stdout_default_step_summary_and_runaway_warning(tmp_path, capsys, geometry_dir,
                                                         straight, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["simulate", str(geometry_dir / "spheroid.yaml"), "--inputs", str(straight),
                 "-o", "-"]) == 0
    out, err = capsys.readouterr()
    assert not (tmp_path / "-").exists()
    log = _log_from_text(out, tmp_path)
    # 2 input rows, no --dt: every 0.1 s
    assert len(log) == 601 and np.allclose(np.diff(log["t"]), 0.1)
    assert "wrote stdout: 601 samples" in err and "every 0.1 s" in err
    s = summarize_motion(log)
    assert s.heading_change < -2 * np.pi
    assert f"heading change {s.heading_change:.4g} rad" in err
    assert f"final speed {s.final_speed:.4g} m/s" in err
    assert "distance travelled" in err and "max |roll|" in err and "max |pitch|" in err
    assert "warning: the heading runs away" in err and "--no-munk" in err
    # the same without the Munk moment: straight, no warning
    assert main(["simulate", str(geometry_dir / "spheroid.yaml"), "--inputs", str(straight),
                 "--out", "-", "--no-munk"]) == 0
    out, err = capsys.readouterr()
    calm = summarize_motion(_log_from_text(out, tmp_path))
    assert abs(calm.heading_change) < 0.1 and "warning" not in err
    assert calm.distance > s.distance


def test_switches_match_the_library(tmp_path, capsys, geometry_dir):
    f = tmp_path / "in.csv"
    f.write_text("t,X,Y,N\n0,20,2,0.5\n5,20,2,0.5\n")
    model = load_model(geometry_dir / "spheroid.yaml")
    t = np.arange(0.0, 5.0 + 1e-9, 0.5)
    forces = np.tile([20, 2, 0, 0, 0, 0.5], (t.size, 1)).astype(float)
    got = {}
    for flags, kw in (([], {}), (["--no-munk"], {"munk": False}),
                      (["--no-coriolis"], {"coriolis": False})):
        out = tmp_path / f"log{len(got)}.csv"
        assert main(["simulate", str(geometry_dir / "spheroid.yaml"), "--inputs", str(f),
                     "--out", str(out), "--dt", "0.5", *flags]) == 0
        log = read_log(out)
        want = simulate(model, t, forces=forces, **kw)
        assert np.allclose(log.velocities(), want.velocities(), rtol=1e-12, atol=1e-15)
        got[tuple(flags)] = log.velocities()[-1]
    capsys.readouterr()
    assert not np.allclose(got[()], got[("--no-munk",)])
    assert not np.allclose(got[()], got[("--no-coriolis",)])


def test_long_inputs_keep_their_times(tmp_path, capsys, geometry_dir):
    t = np.linspace(0.0, 2.0, 150)
    f = tmp_path / "in.csv"
    Log({"t": t, "X": np.full(t.size, 5.0)}).write_csv(f)
    out = tmp_path / "log.csv"
    assert main(["simulate", str(geometry_dir / "sphere.yaml"), "--inputs", str(f),
                 "--out", str(out)]) == 0
    assert np.array_equal(read_log(out)["t"], t)
    assert "default for inputs" not in capsys.readouterr().out


def _synthetic(psi, n_moment, *, u=1.0, theta=None):
    t = np.linspace(0.0, 100.0, psi.size)
    cols = {"t": t, "x": u * t, "y": 0 * t, "z": 0 * t, "phi": 0 * t,
            "theta": 0 * t if theta is None else theta, "psi": psi,
            "u": np.full(t.size, u), "v": 0 * t, "w": 0 * t, "p": 0 * t, "q": 0 * t,
            "r": np.gradient(psi, t), "X": 0 * t, "Y": 0 * t, "Z": 0 * t, "K": 0 * t,
            "M": 0 * t, "N": n_moment}
    return Log(cols)


def test_summary_warnings():
    psi = np.linspace(0.0, 20.0, 1001)
    # heading turned 20 rad with no net yaw moment: runaway
    s = summarize_motion(_synthetic(psi, np.zeros(1001)))
    assert s.heading_change == pytest.approx(20.0) and s.distance == pytest.approx(100.0)
    assert len(s.warnings) == 1 and "heading runs away" in s.warnings[0]
    # a deliberate turn (a steady yaw moment): no warning
    assert summarize_motion(_synthetic(psi, np.full(1001, 0.3))).warnings == ()
    # a moment that averages out (a zig-zag) but a heading that turns: runaway
    zigzag = 0.3 * np.sign(np.sin(np.linspace(0, 20 * np.pi, 1001)))
    assert summarize_motion(_synthetic(psi, zigzag)).warnings
    # a looped pitch and a diverging speed
    s = summarize_motion(_synthetic(np.zeros(1001), np.zeros(1001),
                                    theta=np.linspace(0, 3.0, 1001)))
    assert any("capsized or looped" in w for w in s.warnings)
    s = summarize_motion(_synthetic(np.zeros(1001), np.zeros(1001), u=50.0))
    assert any("diverges" in w for w in s.warnings)
    assert summarize_motion(_synthetic(np.zeros(1001), np.zeros(1001))).warnings == ()


def test_a_rudder_turn_is_commanded_not_a_runaway(remus_file, tmp_path, capsys):
    """A held rudder turns REMUS more than once in 150 s (0.45 turns in 60 s under the default
    lift, whose turning circle is wider than Hoerner's; 150 s since each fin's Munk moment is
    counted once, in its lift, which widens it by 10 %): its yaw moment
    u|u| (B_delta delta)_N is steady,
    so the turn is commanded and the Munk warning stays silent; with --no-munk there is no Munk
    moment to blame (issue 37: it fired in both cases)."""
    f = tmp_path / "turn.csv"
    f.write_text("t,n_propeller,delta_rudder\n0,1500,0.12\n150,1500,0.12\n")
    for flags in ([], ["--no-munk"]):
        out = tmp_path / "log.csv"
        assert main(["simulate", str(remus_file), "--inputs", str(f), "--out", str(out),
                     *flags]) == 0
        err = capsys.readouterr().err
        log = read_log(out)
        assert summarize_motion(log).heading_change < -2 * np.pi     # more than a turn
        assert "heading runs away" not in err, flags
    # the check reads the surfaces' moment from the model: without it, the log alone shows
    # a spin with no applied yaw moment
    assert any("heading runs away" in w for w in summarize_motion(log).warnings)
    model = load_model(remus_file)
    assert summarize_motion(log, model=model).warnings == ()


def test_no_munk_warning_without_the_munk_moment():
    psi = np.linspace(0.0, 20.0, 1001)
    assert summarize_motion(_synthetic(psi, np.zeros(1001)), munk=False).warnings == ()


def test_the_stall_check_reads_no_angle_at_near_zero_speed(remus_file):
    """REMUS left to itself (no thrust, undeflected elevator) rises and barely moves forward:
    the angle of attack -v_f/u of a fin is not defined as u -> 0 (issue 37: 101.5 deg; here the
    old check said 4560.7 deg at u ~ 0.03 m/s); the check reads angles only where u is at least
    0.1 m/s and 10 % of the run's top speed, as flow angles (within 90 deg + |delta|)."""
    import warnings

    from stripcoef.errors import ModelWarning

    model = load_model(remus_file)
    t = np.linspace(0.0, 20.0, 201)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        log = simulate(model, t, deflections={"elevator": 0.0})
    stall = [str(w.message) for w in caught
             if issubclass(w.category, ModelWarning) and "stall" in str(w.message)]
    for text in stall:
        angle = float(text.split("angle of attack ")[1].split(" deg")[0])
        u = float(text.split("(u = ")[1].split(" m/s")[0])
        assert angle <= 90.0 and u >= max(0.1, 0.1 * np.max(np.abs(log["u"]))) - 1e-3


def test_a_pitch_loop_is_reported_although_pitch_stays_within_90_degrees():
    """Euler angles from the quaternion keep |theta| <= 90 deg; the loop is seen as the body z
    axis pointing up (cos(phi) cos(theta) < 0)."""
    from test_simulate_dynamics import _spinning_top

    t = np.linspace(0.0, 10.0, 201)
    log = simulate(_spinning_top(), t, nu0=[0, 0, 0, 0, 0.5, 0], rtol=1e-10, atol=1e-12)
    s = summarize_motion(log)
    assert s.max_pitch <= np.pi / 2 + 1e-12
    assert any("capsized or looped" in w and "tilted 180 deg" in w for w in s.warnings)
