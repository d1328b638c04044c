"""The validation's ``judge="own"`` (issue 33, closed33d): each removal judged on the DOFs of
the changes it removes (the equation decoupling of output-error identification), so that a
DOF a change does not address does not veto it; the summed score (``"all"``) lets it. The
scoring is a table of errors per set of kept changes (the free simulations and the model
surgery replaced), so the test checks the rule alone."""

import numpy as np
import pytest

from _validation_table import PRIOR, install

from stripcoef.diagnose import validate

CAL_W, DRAG_W = ("calibration", "heave"), ("effect", "heave", "momentum_drag")
CAL_P = ("calibration", "roll")
CHANGES = [CAL_W, DRAG_W, CAL_P]
#: RMS errors [m/s, rad/s] of (heave, roll) by the changes kept: the heave drag takes heave
#: from 0.03 to 0.01 and moves the roll simulation (no change of roll's) from 0.06 to 0.125,
#: a hair above the prior's 0.12
TABLE = {
    frozenset(): (0.09, 0.12),
    frozenset({CAL_W, DRAG_W, CAL_P}): (0.01, 0.125),
    frozenset({CAL_W, CAL_P}): (0.03, 0.06),
    frozenset({CAL_W, DRAG_W}): (0.01, 0.13),
    frozenset({CAL_P}): (0.09, 0.06),
    frozenset({CAL_W}): (0.03, 0.12),
}


@pytest.fixture
def table(monkeypatch):
    install(monkeypatch, CHANGES, TABLE)


def _validate(**kw):
    return validate.validate_changes({"t": np.array([0.0, 10.0])}, PRIOR, {}, {}, [2, 3],
                                     logged=[], **kw)


def test_the_summed_score_lets_another_dof_remove_a_change(table):
    excl, record = _validate()
    # removing the drag takes roll from 0.125 to 0.06 (r 1.04 -> 0.5), heave 0.01 -> 0.03
    assert excl == {DRAG_W}
    assert record["kept_changes"] == pytest.approx({"heave": 0.03, "roll": 0.06})


def test_judged_on_its_own_dof_the_change_stays(table):
    excl, record = _validate(judge=validate.OWN)
    # the heave changes judged on heave stay; roll's calibration judged on roll makes it no
    # better than the prior (0.125 against 0.12): the per-DOF veto removes it
    assert excl == {CAL_P}
    assert record["removed_for_own_dof"] == ["roll"]
    assert record["kept_changes"] == pytest.approx({"heave": 0.01, "roll": 0.13})


def test_a_bad_judge_is_refused():
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.errors import InputError
    from stripcoef.logfile import Log

    with pytest.raises(InputError, match="validation_judge"):
        diagnose(Log({"t": np.arange(5.0)}), None, validation_judge="some")
