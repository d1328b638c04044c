"""The thrusters' shared timing (issue 33: a lag fitted per DOF where the thrusters have one)
and the validation's per-DOF test (diagnose/calibrate.py, validate.py, heldout.py)."""

from dataclasses import replace

import numpy as np
import pytest

from stripcoef.diagnose.calibrate import SHARED_TIMING
from stripcoef.diagnose.heldout import diebold_mariano
from stripcoef.diagnose.pipeline import diagnose
from stripcoef.diagnose.validate import partners
from test_diagnose_closedloop import make_log
from validation.synthetic import rov_model


def test_diebold_mariano_by_hand():
    """d = 1, 2, 3, 4: mean 2.5, autocovariances 1.25 and 0.3125, one lag (Newey-West
    1994's floor(4 (4/100)^(2/9)) = 1, Bartlett weight 1/2): long-run variance 1.5625,
    DM = 2.5 / sqrt(1.5625 / 4) * sqrt(3/4) = 2 sqrt(3)."""
    got = diebold_mariano([1.0, 2.0, 3.0, 4.0], [0.0, 0.0, 0.0, 0.0])
    assert got["lags"] == 1
    assert got["statistic"] == pytest.approx(2.0 * np.sqrt(3.0), rel=1e-12)
    assert got["p_value"] > 0.95                      # a is worse: no evidence it is better
    flipped = diebold_mariano([0.0] * 4, [1.0, 2.0, 3.0, 4.0])
    assert flipped["statistic"] == pytest.approx(-2.0 * np.sqrt(3.0), rel=1e-12)
    assert flipped["p_value"] == pytest.approx(1.0 - got["p_value"], abs=1e-12)


def test_the_shared_timing_goes_in_all_its_dofs_and_not_with_a_calibration():
    changes = [("calibration", "surge"), ("effect", "surge", "thruster_lag"),
               ("effect", "surge", "linear_drag"), ("calibration", "yaw"),
               ("effect", "yaw", "thruster_lag")]
    # the calibration takes its own effects, not the shared lag
    assert partners({("calibration", "surge")}, changes) == {
        ("calibration", "surge"), ("effect", "surge", "linear_drag")}
    # the lag removed in one DOF is removed in all
    assert partners({("effect", "yaw", "thruster_lag")}, changes) == {
        ("effect", "surge", "thruster_lag"), ("effect", "yaw", "thruster_lag")}
    assert "thruster_lag" in SHARED_TIMING


@pytest.mark.slow
def test_one_lag_for_all_thrusters_is_written_in_every_driven_dof():
    """A truth whose thrusters lag 0.4 s (simulated by stripcoef with the lag in all DOFs):
    every diagnosed DOF gets the lag with one time constant, within 3 of its joint standard
    deviations (plus 5 % for the window quadrature) of the truth."""
    prior = rov_model()
    lagged = replace(prior, effects=[{"name": "thruster_lag", "dof": "all",
                                      "parameters": {"time_constant": 0.4}}])
    log, _, _ = make_log(8, truth=lagged, duration=120.0)
    res = diagnose(log, prior, dof="all", effects=["thruster_lag"], validation=None)
    lags = {d: [s for s in r.steps if s.effect == "thruster_lag"]
            for d, r in res.per_dof.items()}
    assert len(lags) >= 2 and all(len(v) == 1 for v in lags.values()), lags
    values = {d: v[0].parameters["time_constant"] for d, v in lags.items()}
    assert len(set(values.values())) == 1, values
    # written once for all DOFs (one force law in a simulation), read back in each DOF
    written = [e for e in res.model.effects if e["name"] == "thruster_lag"]
    assert len(written) == 1 and written[0]["dof"] == "all"
    assert written[0]["parameters"]["time_constant"] == pytest.approx(
        next(iter(values.values())), rel=1e-12)
    value = next(iter(values.values()))
    sd = max(v[0].std["time_constant"] for v in lags.values())
    assert abs(value - 0.4) <= 3 * sd + 0.05 * 0.4, (value, sd)
