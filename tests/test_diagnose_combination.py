"""The skill veto's reference in a DOF the open-loop replay cannot predict (issue 33, cut33f;
:mod:`stripcoef.diagnose.combination`): the least-squares combination of the prior's
simulation and the trivial predictors. Its error (an exact combination, and never above the
prior's or a trivial predictor's), the segments it is computed on (those of the validation's
losses), and the rule: applied only where the prior has no skill, with the validation's
scoring replaced by a table of errors (tests/_validation_table.py)."""

import warnings

import numpy as np
import pytest

from _rov_logs import square_wave_log
from _validation_table import PRIOR, install

from stripcoef.diagnose import combination, validate
from stripcoef.diagnose.heldout import EACH, segment_squared_errors
from stripcoef.errors import ModelWarning


def test_an_exact_combination_has_no_error():
    rng = np.random.default_rng(1)
    sim, start = rng.standard_normal(200), rng.standard_normal(200)
    assert combination.combined_rms(sim, 0.6 * sim + 0.4 * start, start) == \
        pytest.approx(0.0, abs=1e-12)


def test_the_combination_is_never_worse_than_the_prior_or_a_trivial_predictor():
    rng = np.random.default_rng(2)
    for _ in range(20):
        sim, start, obs = (rng.standard_normal(150) for _ in range(3))
        got = combination.combined_rms(sim, obs, start)

        def rms(x):
            return float(np.sqrt(np.mean(x ** 2)))

        assert got <= min(rms(obs - sim), rms(obs - start), rms(obs)) + 1e-12


def test_segment_velocities_pool_to_the_validations_losses():
    _, log, other = square_wave_log()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        got = combination.segment_velocities(log, other, [0, 5], horizon=3.0, logged=EACH)
        sse, _ = segment_squared_errors(log, other, [0, 5], horizon=3.0, logged=EACH)
    if got is None:
        pytest.skip("this model's inputs are not replayed in batch")
    for k, (sim, obs, start) in enumerate(got):
        assert np.sum((sim - obs) ** 2) == pytest.approx(sse[:, k].sum(), rel=1e-9)
        assert sim.size == obs.size == start.size == len(log)


CAL_U, CAL_P = ("calibration", "surge"), ("calibration", "pitch")
SCALE_P = ("effect", "pitch", "thrust_effectiveness")
CHANGES = [CAL_U, CAL_P, SCALE_P]
#: RMS errors [m/s, rad/s] of (surge, pitch): pitch's prior (0.23) is worse than zero
#: velocity (0.19), its scale 0.188 beats zero by 1 % (closed33d's log 1795930174)
TABLE = {
    frozenset(): (0.10, 0.23),
    frozenset({CAL_U, CAL_P, SCALE_P}): (0.05, 0.188),
    frozenset({CAL_U, CAL_P}): (0.05, 0.22),
    frozenset({CAL_U}): (0.05, 0.23),
    frozenset({CAL_P, SCALE_P}): (0.10, 0.188),
    frozenset({CAL_P}): (0.10, 0.22),
}
TRIVIAL = {"hold": [0.40, 0.25], "zero": [0.38, 0.19]}


@pytest.fixture
def table(monkeypatch):
    install(monkeypatch, CHANGES, TABLE, missing=(0.2, 1.0), trivial=TRIVIAL)
    # the combination of the prior and the trivial predictors: surge 0.04 (below the
    # model's 0.05, but surge's prior has skill), pitch 0.16
    monkeypatch.setattr(combination, "combination_errors",
                        lambda log, prior, dofs, **_: [0.04, 0.16][:len(dofs)])


def _validate(**kw):
    return validate.validate_changes({"t": np.array([0.0, 10.0])}, PRIOR, {}, {}, [0, 4],
                                     logged=EACH, **kw)


def test_a_held_dofs_scale_that_only_rescales_the_prior_goes(table):
    excl, record = _validate(reference=combination.COMBINATION)
    # pitch's changes (0.188) do not beat the prior combined with the trivial predictors
    # (0.16); surge's prior has skill (0.10 < 0.38), so its calibration is judged as before
    assert excl == {CAL_P, SCALE_P}
    assert record["removed_for_own_dof"] == ["pitch"]
    assert record["combined_reference"] == pytest.approx({"surge": 0.04, "pitch": 0.16})


def test_with_the_trivial_reference_the_scale_stays(table):
    excl, record = _validate()
    assert excl == set() and "combined_reference" not in record


def test_a_bad_reference_is_refused():
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.errors import InputError
    from stripcoef.logfile import Log

    with pytest.raises(InputError, match="validation_reference"):
        diagnose(Log({"t": np.arange(5.0)}), None, validation_reference="some")
