"""The whole-log validation with each DOF simulated alone keeps a DOF's own changes only
where the DOF's simulation has skill (issue 33, each33c, benchmarks/data/each33c_trace.md).

A DOF the pilot holds by feedback is replayed open loop: its simulated error is the missing
loop's, larger than predicting its velocity held or zero, and a change that shrinks it (a
thrust scale below 1) is not a better model. With ``logged=EACH`` in a whole-log diagnosis the
veto's reference is the best of the prior and the trivial predictors (Murphy 1988, 1992); the
scoring here is a table of errors per set of kept changes (the free simulations and the
model surgery replaced), so the test checks the rule alone.
"""

import numpy as np
import pytest

from _validation_table import PRIOR, install

from stripcoef.diagnose import validate
from stripcoef.diagnose.heldout import EACH

CAL_U, CAL_P = ("calibration", "surge"), ("calibration", "roll")
SCALE_P = ("effect", "roll", "thrust_effectiveness")
CHANGES = [CAL_U, CAL_P, SCALE_P]
#: RMS errors [m/s, rad/s] of (surge, roll) on the validation part by the changes kept:
#: every change lowers its DOF's error, but roll's stays above the trivial predictors'.
TABLE = {
    frozenset(): (0.10, 0.70),
    frozenset({CAL_U, CAL_P, SCALE_P}): (0.05, 0.55),
    frozenset({CAL_U, CAL_P}): (0.05, 0.65),
    frozenset({CAL_U}): (0.05, 0.70),
    frozenset({CAL_P, SCALE_P}): (0.10, 0.55),
    frozenset({CAL_P}): (0.10, 0.65),
}
#: hold-last-velocity and zero-velocity errors (surge, roll): roll's held at 0.3 rad/s
TRIVIAL = {"hold": [0.40, 0.31], "zero": [0.38, 0.28]}


@pytest.fixture
def table(monkeypatch):
    install(monkeypatch, CHANGES, TABLE, missing=(0.2, 1.0), trivial=TRIVIAL)


def _validate(logged, dofs=(0, 3), **kw):
    return validate.validate_changes({"t": np.array([0.0, 10.0])}, PRIOR, {}, {},
                                     list(dofs), logged=logged, **kw)


def test_a_dof_without_skill_keeps_no_change_of_its_own(table):
    excl, record = _validate(EACH)
    # roll's best model (0.55 rad/s) is worse than predicting zero roll rate (0.28): its
    # calibration and scale go, surge's calibration (0.05 against 0.38) stays
    assert excl == {CAL_P, SCALE_P}
    assert record["removed_for_own_dof"] == ["roll"]
    assert record["trivial_predictor"] == pytest.approx({"surge": 0.38, "roll": 0.28})
    assert record["kept_changes"] == pytest.approx({"surge": 0.05, "roll": 0.70})


def test_without_the_skill_rule_the_prior_is_the_only_reference(table):
    excl, record = _validate(EACH, skill=False)
    assert excl == set() and record["removed_for_own_dof"] == []
    assert "trivial_predictor" not in record


def test_the_skill_rule_is_the_each_validations_only(table):
    # the joint simulation (a whole-log diagnosis's default) keeps the prior as the
    # reference: the rule is not applied there
    excl, record = _validate([])
    assert excl == set() and "trivial_predictor" not in record
