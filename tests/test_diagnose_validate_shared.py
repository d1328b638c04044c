"""The validation's per-DOF veto and its backward elimination run in turn (issue 33).

A shared change (the one current of several DOFs) kept beside calibrations that the per-DOF
veto removes is judged again without them: the seed-7 current log of benchmarks/real_logs.py
(forward split) wrote a current that, once the DOFs' calibrations were vetoed, simulated five
of six DOFs worse than the prior on the validation part. Here the scoring is a table of
errors per set of kept changes (the free simulations and the model surgery replaced), so the
test checks the rule alone.
"""

import numpy as np

from stripcoef.diagnose import heldout, validate

CAL_S, CAL_W = ("calibration", "surge"), ("calibration", "sway")
CUR_S, CUR_W = ("effect", "surge", "current"), ("effect", "sway", "current")
CHANGES = [CAL_S, CUR_S, CAL_W, CUR_W]
PRIOR = "prior"

#: Validation errors (surge, sway) relative to the prior's, by the changes kept (the current
#: is one change of both DOFs).
TABLE = {
    frozenset(): (1.0, 1.0),
    frozenset({"cal_s", "cal_w", "cur"}): (0.8, 1.2),    # sway worse: vetoed
    frozenset({"cal_w", "cur"}): (1.3, 1.1),
    frozenset({"cal_s", "cur"}): (1.25, 1.05),           # surge worse: vetoed
    frozenset({"cal_s", "cal_w"}): (1.1, 1.3),
    frozenset({"cur"}): (1.3, 1.3),                      # the current alone: worse in both
}


def _kept(excluded):
    tags = {CAL_S: "cal_s", CAL_W: "cal_w", CUR_S: "cur", CUR_W: "cur"}
    return frozenset(tags[c] for c in CHANGES if c not in excluded)


def _sse(val_log, model, dofs, **_):
    e = TABLE[frozenset()] if model == PRIOR else TABLE.get(_kept(model[1]), (1.1, 1.1))
    rows = np.array([[e[0] ** 2, e[1] ** 2]]) * (1.0 + 0.01 * np.arange(4))[:, None]
    return rows, np.ones(4)


def test_a_shared_change_left_by_the_veto_is_validated_again(monkeypatch):
    monkeypatch.setattr(validate, "_changes", lambda per: list(CHANGES))
    monkeypatch.setattr(validate, "calibrated_model",
                        lambda prior, per, fits, key: ("model", frozenset(key)))
    monkeypatch.setattr(heldout, "segment_squared_errors", _sse)
    excl, record = validate.validate_changes({"t": np.array([0.0, 10.0])}, PRIOR, {}, {},
                                             [0, 1])
    assert record["removed_for_own_dof"] == ["sway", "surge"]
    # the current, judged without the vetoed calibrations, is removed too: the written model
    # is the prior, not one that simulates both DOFs 30 % worse
    assert excl == set(CHANGES)
    assert record["kept_changes"] == record["prior"]
