"""The validation's ``judge="coupled"`` (issue 33, adopt33g): a removal judged on the DOFs of
the changes it removes and on the other DOFs whose prior simulation has skill (each DOF
simulated alone, ``logged=EACH``). A heave bias is a buoyancy change, which acts in pitch too
(Fossen 2011, eq. 4.6): the pitch simulation it moves judges it. The scoring is a table of
errors per set of kept changes (the free simulations and the model surgery replaced), with the
errors of the VideoRay-like actuation-delay log 1796039007 of seed 1795938998 of the
independent benchmark (benchmarks/data/adopt33g_trace.md), so the test checks the rule alone."""

import numpy as np
import pytest

from _validation_table import PRIOR, install

from stripcoef.diagnose import validate
from stripcoef.diagnose.heldout import EACH

CAL_W, BIAS_W = ("calibration", "heave"), ("effect", "heave", "buoyancy_offset")
CHANGES = [CAL_W, BIAS_W]
#: RMS errors [m/s, rad/s] of (heave, pitch), each simulated alone: the bias takes heave from
#: 0.0131 to 0.0117 and pitch from 0.0374 to 0.0425 (the prior's 0.0302)
TABLE = {
    frozenset(): (0.0226, 0.0302),
    frozenset({CAL_W, BIAS_W}): (0.0117, 0.0425),
    frozenset({CAL_W}): (0.0131, 0.0374),
}
#: the better trivial predictor's errors (heave, pitch): the prior has skill in both
TRIVIAL = {"hold": [0.0713, 0.1998], "zero": [0.0800, 0.2500]}


@pytest.fixture
def table(monkeypatch):
    install(monkeypatch, CHANGES, TABLE, missing=(1.0, 1.0), trivial=TRIVIAL)


def _validate(**kw):
    return validate.validate_changes({"t": np.array([0.0, 10.0])}, PRIOR, {}, {}, [2, 4],
                                     logged=EACH, **kw)


def test_judged_on_heave_alone_the_bias_stays(table):
    excl, record = _validate(judge=validate.OWN)
    assert excl == set()
    assert record["kept_changes"] == pytest.approx({"heave": 0.0117, "pitch": 0.0425})


def test_the_pitch_it_moves_judges_it_too(table):
    excl, record = _validate(judge=validate.COUPLED)
    # with heave's calibration and bias left out pitch is no worse than the prior (one DOF
    # fewer worse): the first criterion of the score
    assert excl == {CAL_W, BIAS_W}
    assert record["kept_changes"] == pytest.approx({"heave": 0.0226, "pitch": 0.0302})


def test_a_dof_without_skill_does_not_judge(monkeypatch):
    # pitch's prior no better than predicting zero rate: only heave judges, as "own"
    install(monkeypatch, CHANGES, TABLE, missing=(1.0, 1.0),
            trivial={"hold": [0.0713, 0.0290], "zero": [0.0800, 0.0300]})
    excl, _ = _validate(judge=validate.COUPLED)
    assert BIAS_W not in excl


def test_coupled_is_a_judge_diagnose_takes():
    assert validate.COUPLED in validate.JUDGES
