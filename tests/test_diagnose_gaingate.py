"""The thrusters' gains validated on rolling 10-s segments by the changes' score
(``gains_validation="rolling"``, stripcoef.diagnose.gaingate; issue 33, real33f).

The log: a seeded noisy 60-s log of the VideoRay-like ROV (validation.synthetic.rov_model)
whose vertical thruster delivers 1.3 of its map, simulated by stripcoef's own simulate, so
the right gains are known exactly. The commands (up to 162 of the map's units) keep the
vehicle's motion deterministic: a 1e-9 m/s change of the starting surge moves the log by
2.6e-9 (``test_the_log_is_not_chaotic``). With commands of 600-900 the Munk moment of the
light ROV (Z_wdot - X_udot) u w outgrew its restoring moment and it tumbled at 28-37 rad/s:
the same change then moved the log by 53 m/s, and one CPU's round-off flipped the
validation's verdicts."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from stripcoef.diagnose.gaingate import CONSECUTIVE, ROLLING, score, validate_gains, validated
from stripcoef.diagnose.gains import ThrusterGains
from stripcoef.diagnose.gains import validated as consecutive
from stripcoef.diagnose.settings import DiagnoseSettings
from stripcoef.errors import InputError, ModelWarning
from stripcoef.simulate import simulate
from validation.synthetic import add_noise, rov_model

DOFS = [0, 2, 5]        # surge, heave, yaw


def _gains(prior, values):
    return ThrusterGains(names=tuple(th.name for th in prior.thrusters), gains=tuple(values),
                         std=(0.01,) * len(values), prior_sd=0.05, combinations=(),
                         test={"p_value": 0.0}, noise={}, dofs=("surge", "heave", "yaw"),
                         applied=True, reason="test")


def _commands(t):
    """Surge sines with a square-wave turn and a square-wave heave [the map's command units]."""
    turn = 54.0 * np.sign(np.sin(2 * np.pi * t / 5.3))
    return {"port": 108.0 * np.sin(2 * np.pi * t / 9.0) + turn,
            "starboard": 108.0 * np.sin(2 * np.pi * t / 9.0) - turn,
            "vertical": 126.0 * np.sign(np.sin(2 * np.pi * t / 7.1)), "lateral": 0.0 * t}


def _truth_log(nu0=None):
    """The noise-free 60-s log of the truth (the vertical thruster at 1.3 of its map) and the
    prior, started at rest or at ``nu0``."""
    prior = rov_model()
    truth = _gains(prior, [1.0, 1.0, 1.3, 1.0]).model(prior)
    t = np.arange(0.0, 60.0, 0.1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        return prior, simulate(truth, t, commands=_commands(t), nu0=nu0)


@pytest.fixture(scope="module")
def case():
    prior, clean = _truth_log()
    return prior, add_noise(clean, np.random.default_rng(3))


def test_the_log_is_not_chaotic():
    """The verdicts below hold on any CPU only if round-off cannot move the log: a 1e-9 m/s
    change of the starting surge stays below 1e-7 everywhere."""
    _, a = _truth_log()
    _, b = _truth_log(np.array([1e-9, 0, 0, 0, 0, 0]))
    assert max(np.max(np.abs(np.asarray(a[c]) - np.asarray(b[c]))) for c in "uvwpqr") < 1e-7


def test_the_score_counts_the_dofs_made_worse_first():
    assert score([1.0, 1.0, 1.0], [0.5, 0.5, 1.01])[0] == 1
    assert score([1.0, 1.0], [0.9, 1.0]) == (0, pytest.approx(1.81))
    # one DOF worse outweighs any gain in the others (validate.validate_changes' order)
    assert score([1.0, 1.0, 1.0], [0.1, 0.1, 1.01]) > (0, 3.0)


def test_the_right_gains_are_kept_and_a_wrong_contrast_removed_though_the_sum_falls(case):
    prior, log = case
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        right = validated(_gains(prior, [1.0, 1.0, 1.3, 1.0]), log, prior, DOFS)
        # the right vertical gain with a wrong port/starboard contrast: heave and surge
        # better, yaw worse
        wrong = [1.02, 0.98, 1.3, 1.0]
        old = consecutive(_gains(prior, wrong), log, prior, DOFS)
        new = validated(_gains(prior, wrong), log, prior, DOFS)
    assert right.applied and right.validation["dofs_worse"] == 0
    assert right.validation["segments_n"] > 20          # restarted every 2 s over 60 s
    # the consecutive rule keeps it on the sum of squared ratios, yaw simulated worse
    v = old.validation
    assert old.applied and v["sum_squared_ratio"] < len(DOFS)
    assert v["with_gains"]["yaw"] > v["prior"]["yaw"]
    # the rolling rule removes it: yaw worse
    w = new.validation
    assert not new.applied and w["dofs_worse"] >= 1
    assert w["with_gains"]["yaw"] > w["prior"]["yaw"]
    assert w["sum_squared_ratio"] < len(DOFS)           # removed by the count, not the sum
    assert "removed by the validation" in new.reason


def test_the_setting_chooses_the_rule(case):
    prior, log = case
    g = _gains(prior, [1.02, 0.98, 1.3, 1.0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        a = validate_gains(g, log, prior, DOFS, DiagnoseSettings(gains_validation=CONSECUTIVE))
        b = validate_gains(g, log, prior, DOFS, DiagnoseSettings(gains_validation=ROLLING))
    assert a.applied and not b.applied
    assert validated(g, None, prior, DOFS) is g                 # no validation log


def test_diagnose_refuses_an_unknown_rule(case):
    from stripcoef.diagnose import diagnose
    prior, log = case
    with pytest.raises(InputError, match="gains_validation"):
        diagnose(log, prior, dof="all", gains_validation="sometimes")


def test_rolling_test_keeps_gains_only_beyond_the_segments_noise(case):
    """Option ``"rolling_test"``: the pooled loss's one-sided Diebold-Mariano test. Gains that
    change nothing (every gain 1) tie with the prior: kept by the consecutive rule (sum of
    squared ratios exactly n), removed by the test (p 0.5); the right gains pass it."""
    prior, log = case
    settings = DiagnoseSettings(gains_validation="rolling_test")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        none = _gains(prior, [1.0, 1.0, 1.0, 1.0])
        old = consecutive(none, log, prior, DOFS)
        new = validate_gains(none, log, prior, DOFS, settings)
        right = validate_gains(_gains(prior, [1.0, 1.0, 1.3, 1.0]), log, prior, DOFS, settings)
    assert old.applied and old.validation["sum_squared_ratio"] == pytest.approx(3.0)
    assert not new.applied and new.validation["pooled_test"]["p_value"] == pytest.approx(0.5)
    assert right.applied and right.validation["pooled_test"]["p_value"] <= 0.05
