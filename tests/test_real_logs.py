"""Logs as users have them (issue 33): the real-style writer of ``benchmarks/real_logs.py``
read back through ``stripcoef.ingest``, the column map of the public BlueROV2 Heavy tank logs
(``reference_tables/real_logs/bluerov2_dynamics_map.yaml``) on a file of that layout, and the
stored held-out run shown in docs/validation.md."""

import csv
import warnings

import numpy as np
import pytest

from benchmarks.real_logs import (CLOCK_OFFSET, PWM_PER_UNIT, STORED, TABLES, read_back,
                                  write_ros_chunks)
from stripcoef.ingest import read_mapped_log
from stripcoef.ingest.attitude import euler_from_matrices, euler_matrices
from stripcoef.logfile import Log

STATES = ("x", "y", "z", "phi", "theta", "psi", "u", "v", "w", "p", "q", "r")


def _truth(duration, rate, names, seed=3):
    """A log in stripcoef's conventions (NED, FRD, zyx Euler angles) with smooth states and
    stepped commands; the states need not obey any dynamics for a format round trip."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, duration + 1e-9, 1.0 / rate)
    cols = {"t": t}
    for k, c in enumerate(STATES):
        a = 0.3 if c in ("phi", "theta") else 1.0
        cols[c] = a * np.sin(0.05 * (k + 1) * t + k) + (0.02 * t if c == "psi" else 0.0)
    cols["z"] = 2.0 + np.sin(0.21 * t) + 0.3 * np.sin(0.83 * t)    # depth varies (the echo)
    for n in names:
        steps = rng.uniform(-1.0, 1.0, int(duration // 5) + 2)
        cols["n_" + n] = steps[(t // 5).astype(int)]
    cols["tether_length"] = 2.0 + 0.05 * t
    return Log(cols)


def test_real_style_chunks_read_back_to_the_log(tmp_path):
    """Two streams in ROS conventions, one-minute chunks, a second clock 0.35 s ahead, PWM in
    whole microseconds: the ingest gives the states back to the 9 digits written, the commands
    to half a microsecond of PWM, and the clock offset to within the echo's staleness (the
    controller's depth is the latest navigation sample: 0..0.1 s old at 10 Hz)."""
    names = ("port", "starboard", "vertical")
    truth = _truth(130.0, 10.0, names)
    log, notes = read_back(tmp_path, write_ros_chunks(truth, tmp_path))
    assert len(list((tmp_path / "nav").iterdir())) == 3
    assert len(list((tmp_path / "cmd").iterdir())) == 3
    offset = log.meta["streams"]["cmd"]["clock_offset"]["offset_s"]
    assert -CLOCK_OFFSET - 0.1 <= offset <= -CLOCK_OFFSET + 0.005
    assert any("clock offset" in n for n in notes)
    np.testing.assert_allclose(log["t"], truth["t"][:len(log)], atol=1e-6)
    for c in STATES:
        np.testing.assert_allclose(log[c], truth[c][:len(log)], rtol=1e-7, atol=1e-7,
                                   err_msg=c)
    # the commands at the samples whose command did not change within the offset error
    for n in names:
        cmd = truth["n_" + n][:len(log)]
        steady = np.r_[True, np.diff(cmd) == 0] & np.r_[np.diff(cmd) == 0, True]
        np.testing.assert_allclose(log["n_" + n][steady], cmd[steady],
                                   atol=0.5 / PWM_PER_UNIT, err_msg=n)
    np.testing.assert_allclose(log["tether_length"], truth["tether_length"][:len(log)],
                               atol=0.01)


def test_the_tank_map_reads_the_public_layout(tmp_path):
    """A file in the layout of ViktorNfa/bluerov2_dynamics' koopman_dataset_50Hz.csv (the
    motion capture's z-down world and forward-right-down body, as an independent check of
    those recordings found them: the map's header; zyx Euler angles in [-pi, pi], body
    velocities and rates, PX4 motor commands u1..u8) read through the stored map is the log
    in stripcoef's conventions; motors 5 and 8 push up where t5 and t8 of
    geometry/bluerov2_heavy.yaml push down."""
    truth = _truth(20.0, 50.0, [f"t{i}" for i in range(1, 9)])
    t = truth["t"]
    e = euler_from_matrices(euler_matrices(truth["phi"], truth["theta"], truth["psi"]))
    pos = np.column_stack([truth["x"], truth["y"], truth["z"]])
    vel = np.column_stack([truth["u"], truth["v"], truth["w"]])
    rat = np.column_stack([truth["p"], truth["q"], truth["r"]])
    motors = np.column_stack([truth[f"n_t{i}"] * (-1.0 if i in (5, 8) else 1.0)
                              for i in range(1, 9)])
    path = tmp_path / "koopman_dataset_50Hz.csv"
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["t", "x", "y", "z", "phi", "theta", "psi", "u", "v", "w", "p", "q", "r",
                    *(f"u{i}" for i in range(1, 9))])
        for row in np.column_stack([t, pos, e, vel, rat, motors]):
            w.writerow([repr(float(v)) for v in row])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        log = read_mapped_log(path, TABLES / "bluerov2_dynamics_map.yaml")
    assert len(log) == t.size
    for c in STATES:
        want = np.unwrap(truth[c]) if c in ("phi", "psi") else truth[c]
        got = log[c] - (log[c][0] - want[0]) if c in ("phi", "psi") else log[c]
        np.testing.assert_allclose(got, want, atol=1e-9, err_msg=c)
    for i in range(1, 9):
        np.testing.assert_allclose(log[f"n_t{i}"], truth[f"n_t{i}"], atol=1e-12)


@pytest.mark.skipif(not STORED.exists(), reason="no stored run")
def test_the_stored_run_has_both_splits_and_every_predictor():
    from validation import read_stored_run
    from validation.real_logs import section, summary

    command, rows = read_stored_run(STORED)
    assert command.startswith("python -m benchmarks.real_logs")
    by_log = {}
    for r in rows:
        by_log.setdefault(r["log"], set()).add(r["split"])
        for k in ("prior", "hold_last_velocity", "zero_velocity"):
            assert float(r[k]) >= 0.0
        calibrated = r["calibrated"]
        beats = calibrated not in ("", "None") and float(calibrated) < min(
            float(r["prior"]), float(r["hold_last_velocity"]), float(r["zero_velocity"]))
        assert (r["beats_all"] == "1") == beats
    assert by_log and all(s == {"forward", "reverse"} for s in by_log.values())
    s = summary(rows)
    assert f"**{s['beats']} of {s['rows']}**" in section()


@pytest.mark.slow
def test_a_piloted_rov_log_written_by_simulate_replays_to_its_printed_precision(tmp_path,
                                                                                capsys):
    """Issue 33: ``simulate --from-log`` of a log that ``simulate`` wrote (three thrusters
    commanded, turns both ways, a dive) gives every state back to the last digit the CSV
    prints (the thrust is applied once: the heading change is the simulated one)."""
    from stripcoef import cli
    from stripcoef.errors import ModelWarning
    from stripcoef.logfile import read_log
    from stripcoef.samples import path as sample

    vehicle = str(sample("videoray_pro3.yaml"))
    t = np.array([0.0, 3.0, 7.0, 12.0, 20.0])
    Log({"t": t, "n_port": [180.0, 200.0, -120.0, 150.0, 150.0],
         "n_starboard": [180.0, 120.0, 150.0, -100.0, 150.0],
         "n_vertical": [0.0, 100.0, 100.0, -80.0, 0.0]}).write_csv(tmp_path / "in.csv")

    def run(*args):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ModelWarning)
            rc = cli.main(["simulate", vehicle, *args])
        out = capsys.readouterr()
        assert rc == 0, out.err
        return out

    run("--inputs", str(tmp_path / "in.csv"), "--out", str(tmp_path / "log.csv"))
    log = read_log(tmp_path / "log.csv")
    assert np.ptp(np.unwrap(log["psi"])) > 0.5                 # it turned
    run("--from-log", str(tmp_path / "log.csv"), "--out", str(tmp_path / "replay.csv"))
    rep = read_log(tmp_path / "replay.csv")
    assert len(rep) == len(log)
    for c in STATES + ("n_port", "n_starboard", "n_vertical"):
        np.testing.assert_allclose(rep[c], log[c], rtol=0, atol=1e-12, err_msg=c)


def test_the_mirror_reads_pulled_tank_logs_and_names_lfs_pointers(tmp_path, capsys):
    from benchmarks.real_logs import mirror_files

    pointer = tmp_path / "rosbags" / "a" / "run1" / "koopman_dataset_50Hz.csv"
    data = tmp_path / "rosbags" / "b" / "run2" / "koopman_dataset_50Hz.csv"
    for p in (pointer, data):
        p.parent.mkdir(parents=True)
    pointer.write_text("version https://git-lfs.github.com/spec/v1\noid sha256:00\nsize 1\n")
    data.write_text("t,x\n0.0,1.0\n")
    assert mirror_files(tmp_path) == [data]
    assert "Git LFS pointer" in capsys.readouterr().out


@pytest.mark.slow
def test_the_truth_model_replays_the_independent_simulator(monkeypatch):
    """The oracle of the held-out table (:func:`benchmarks.real_logs.truth_model`) is the
    independent simulator's vehicle: on a noise-free log of that simulator (no undeclared
    effect) stripcoef's free simulation from the logged state reproduces the velocities to
    1e-3 m/s or rad/s, while the unperturbed prior does not."""
    import validation.independent as ind
    from benchmarks.real_logs import truth_model
    from stripcoef.diagnose.heldout import compare
    from validation.synthetic import rov_model

    monkeypatch.setattr(ind, "NOISE", {k: 0.0 for k in ind.NOISE})
    prior = rov_model()
    log, truth = ind.generate(prior.to_dict(), None, 5, duration=30.0, rate=20.0)
    err = compare(log, {"truth": truth_model(prior.to_dict(), truth), "prior": prior},
                  [0, 1, 2, 5], horizon=10.0)
    assert max(e["truth"] for e in err.values()) < 1e-3
    assert max(e["prior"] for e in err.values()) > 10 * max(e["truth"] for e in err.values())


def test_the_oracle_run_is_joined_to_a_held_out_run_without_it(tmp_path, monkeypatch):
    """validation/real_logs.py shows the truth's coefficients of a separate ``--oracle-only``
    run beside a held-out run made without them, joined by log, split and DOF, and counts
    the rows where even the truth loses to a trivial predictor."""
    import validation.real_logs as vr

    oracle = tmp_path / "oracle.csv"
    oracle.write_text("# python -m benchmarks.real_logs --oracle-only\n"
                      "log,truth,split,dof,truth_coefficients,hold_last_velocity,"
                      "zero_velocity,truth_beats_trivial\n"
                      "a,x,forward,roll,0.5,0.1,0.05,0\n"
                      "a,x,forward,surge,0.01,0.1,0.4,1\n")
    monkeypatch.setattr(vr, "ORACLE", oracle)
    rows = [{"log": "a", "split": "forward", "dof": d, "beats_all": b}
            for d, b in (("roll", "0"), ("surge", "1"))]
    joined, command = vr.with_oracle(rows)
    assert command.endswith("--oracle-only")
    assert [r["truth_coefficients"] for r in joined] == ["0.5", "0.01"]
    s = vr.summary([{**r, "kind": "real-style", "prior": "1", "calibrated": "0.5",
                     "prior_beats_trivial": "0"} for r in joined])
    assert (s["known"], s["unpredictable"], s["predictable"], s["beats_predictable"]) == \
        (2, 1, 1, 1)


def test_the_count_is_made_on_the_excited_and_predictable_rows():
    """validation/real_logs.py counts the calibrated model's wins on the rows the rule of
    heldout.predictable keeps (the prior's noise growth below both trivial predictors' errors),
    per row and per (log, split) pair, and says how often each model's noise-growth verdict is
    the truth's."""
    from validation.real_logs import summary

    def row(split, dof, beats, ok, growth, truth_ok):
        return {"log": "a", "kind": "real-style", "split": split, "dof": dof,
                "beats_all": beats, "predictable": ok, "prior": "1", "calibrated": "0.5",
                "prior_beats_trivial": "0", "hold_last_velocity": "0.2",
                "zero_velocity": "0.1", "truth_beats_trivial": truth_ok,
                "noise_growth_calibrated": growth, "noise_growth_prior": growth,
                "noise_growth_truth": "0.5"}

    rows = [row("forward", "surge", "1", "1", "0.05", "1"),
            row("forward", "yaw", "0", "0", "0.3", "0"),
            row("reverse", "surge", "0", "1", "0.05", "1"),
            row("reverse", "yaw", "1", "1", "0.01", "0")]
    s = summary(rows)
    assert (s["rows"], s["beats"], s["pairs_all"]) == (4, 2, 0)
    assert (s["judged"], s["beats_judged"]) == (3, 2)
    assert (s["pairs_judged"], s["pairs_judged_all"]) == (2, 1)
    assert (s["growth_known"], s["growth_agrees_prior"], s["growth_agrees_truth"]) == \
        (4, 3, 2)
    old = summary([{k: v for k, v in r.items() if not k.startswith("noise_growth")}
                   for r in rows])
    assert old["judged"] == 4                     # a run without the column judges every row


def test_a_wrong_prior_alone_does_not_exempt_a_row():
    """A row is left out of the excited and predictable ones only where both the prior's and
    the calibrated model's noise growth reach the trivial predictors' errors
    (heldout.predictable with both spreads); a row with the prior's growth alone (an older
    run) is judged by it."""
    from validation.real_logs import predictable

    base = {"hold_last_velocity": "0.26", "zero_velocity": "0.19"}
    assert predictable({**base, "noise_growth_prior": "0.54", "noise_growth_calibrated": "0.045"})
    assert predictable({**base, "noise_growth_prior": "0.05", "noise_growth_calibrated": "0.6"})
    assert not predictable({**base, "noise_growth_prior": "0.54",
                            "noise_growth_calibrated": "0.3"})
    assert not predictable({**base, "noise_growth_prior": "0.54"})
    assert predictable(base)


def test_the_why_table_reads_its_stored_rows(tmp_path, monkeypatch):
    """validation/real_logs.py shows a ``--why`` run: one row per DOF and the linearised
    stability per speed."""
    import validation.real_logs as vr

    why = tmp_path / "why.csv"
    cols = list(vr.WHY_COLUMNS)
    why.write_text("# python -m benchmarks.real_logs --duration 100 --seed 7 --why 1\n"
                   "log,truth,kind,dof," + ",".join(cols) + ",speed_m_s,largest_real_part,"
                   "leading_dof\n"
                   "a,x,dof,yaw," + ",".join(["0.5"] * len(cols)) + ",,,\n"
                   "a,x,speed,,," + "," * (len(cols) - 1) + "0.4,1.334,yaw\n")
    monkeypatch.setattr(vr, "WHY", why)
    text = "\n".join(vr.why_section())
    assert "--why 1" in text and "| yaw | 0.5000 |" in text
    assert "0.4 m/s: +1.334 1/s (yaw)" in text


def test_the_paired_verdicts_are_counted_per_record():
    """validation/real_logs.py counts the paired tests' verdicts of each record a stored run
    has (10-s rolling, 2-s), over all rows and the excited and predictable ones, with the
    truth's; a run without them gives no paragraph."""
    from validation.real_logs import paired_section

    def row(v10, t10, v2, t2, growth):
        return {"roll_verdict": v10, "roll_truth_verdict": t10, "h2_verdict": v2,
                "h2_truth_verdict": t2, "hold_last_velocity": "0.2", "zero_velocity": "0.1",
                "noise_growth_prior": growth, "noise_growth_calibrated": growth}

    rows = [row("win", "win", "win", "win", "0.01"),
            row("loss", "not distinguishable", "not distinguishable", "win", "0.3"),
            row("not distinguishable", "win", "win", "win", "0.01")]
    text = paired_section(rows)[0]
    assert "restarted every 2 s: 1 wins, 1 losses, 1 not distinguishable of 3 " \
           "(1 / 0 / 1 of the excited and predictable); the truth beats both trivial " \
           "predictors in 2 of 3" in text
    assert "2-s simulations: 2 wins, 0 losses, 1 not distinguishable of 3 (2 / 0 / 0" in text
    assert paired_section([{k: v for k, v in r.items() if "verdict" not in k}
                           for r in rows]) == []
