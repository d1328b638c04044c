"""The one-DOF thrusters' gains judged inside the written model (issue 33, gains33f;
``gains_judge="written"``, :mod:`stripcoef.diagnose.gainjudge`).

The rule is the validation's own (:func:`stripcoef.diagnose.validate.validate_changes`): a
model's score is (DOFs simulated worse than the prior, sum of squared error ratios), and a
change stays only when its model scores strictly better; a tie goes to the simpler model.
The two diagnoses are stubs here: what is tested is which written model is returned and that
the record says what was compared, read from the two diagnoses' own validation records.
"""

from dataclasses import dataclass
from types import SimpleNamespace

import math
import pytest

from stripcoef.diagnose import gainjudge
from stripcoef.diagnose.settings import DiagnoseSettings


@dataclass(frozen=True)
class _Stub:
    name: str
    validation: dict
    thruster_gains: dict | None


def _runner(with_error, without_error, prior_error=0.1):
    """A stand-in for pipeline.run: the gains' pass (gains_judge 'none') and the
    prior-map pass (dof_gains False), each with its written model's validation error."""
    calls = []

    def run(log, model, *, dof, settings, budget):
        calls.append(settings)
        if not settings.dof_gains:
            return _Stub("without", {"prior": {"surge": prior_error},
                                     "kept_changes": {"surge": without_error}}, None)
        assert settings.gains_judge == gainjudge.NONE
        return _Stub("with", {"prior": {"surge": 0.09},          # the gained prior's
                              "kept_changes": {"surge": with_error}},
                     {"applied": True, "reason": "significant", "gains": {"t1": 1.1}})
    return run, calls


def _judged(run):
    return gainjudge.judged(run, None, None, "surge",
                            DiagnoseSettings(gains_judge=gainjudge.WRITTEN), None)


def test_gains_kept_when_their_written_model_simulates_the_validation_log_better():
    run, calls = _runner(with_error=0.05, without_error=0.06)
    got = _judged(run)
    assert got.name == "with" and got.thruster_gains["applied"]
    v = got.thruster_gains["validation"]
    assert v["rule"] == "written"
    # ratios to the prior's error on the prior's maps (the without-gains run's "prior")
    assert v["score_with_gains"] == [0.0, pytest.approx(0.25)]
    assert v["score_without_gains"] == [0.0, pytest.approx(0.36)]
    assert len(calls) == 2


@pytest.mark.parametrize("with_error", [0.07, 0.06, None])
def test_gains_removed_with_their_partners_when_not_better(with_error):
    # worse, a tie (the simpler model), or a diverged simulation: the DOF as selected on
    # the prior's maps is returned, the gains' record kept and marked not written
    run, _ = _runner(with_error=with_error, without_error=0.06)
    got = _judged(run)
    assert got.name == "without"
    assert got.thruster_gains["applied"] is False
    assert "removed by the validation of the written model" in got.thruster_gains["reason"]
    if with_error is None:
        assert got.thruster_gains["validation"]["score_with_gains"] == [math.inf, math.inf]


def test_score_counts_dofs_worse_than_the_prior_first():
    assert gainjudge.score({"a": 2.0, "b": 0.1}, {"a": 1.0, "b": 1.0}) == (1, pytest.approx(4.01))
    assert gainjudge.score({"a": 0.5}, {"a": 1.0}) < gainjudge.score({"a": 1.01}, {"a": 1.0})


def test_judged_only_for_one_dof_a_validation_log_and_an_applied_fit():
    s = DiagnoseSettings(gains_judge=gainjudge.WRITTEN)
    applied = SimpleNamespace(applied=True)
    assert gainjudge.after_selection(s, [0], object(), applied)
    assert not gainjudge.after_selection(s, [0, 1], object(), applied)
    assert not gainjudge.after_selection(s, [0], None, applied)
    assert not gainjudge.after_selection(s, [0], object(), SimpleNamespace(applied=False))
    assert not gainjudge.after_selection(s, [0], object(), None)
    assert not gainjudge.after_selection(DiagnoseSettings(gains_judge=gainjudge.PRIOR),
                                         [0], object(), applied)
    assert DiagnoseSettings().gains_judge == gainjudge.WRITTEN       # the default


def test_an_unknown_gains_judge_is_an_input_error():
    # the options are checked before the log or the model is read
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.errors import InputError

    with pytest.raises(InputError, match="gains_judge"):
        diagnose(None, None, dof="surge", time_limit=1.0, gains_judge="later")


def test_whole_log_gains_judged_against_the_log_diagnosed_without_them():
    # "written_all" (real33g): the whole log diagnosed with the gains applied unvalidated and
    # again with the gains not fitted ("off", not dof_gains, which a whole log ignores)
    calls = []

    def run(log, model, *, dof, settings, budget):
        calls.append(settings)
        if settings.gains_judge == gainjudge.OFF:
            return _Stub("without", {"prior": {"surge": 0.1, "yaw": 0.2},
                                     "kept_changes": {"surge": 0.09, "yaw": 0.15}}, None)
        assert settings.gains_judge == gainjudge.NONE and settings.dof_gains
        return _Stub("with", {"prior": {"surge": 0.08, "yaw": 0.1},     # the gained prior's
                              "kept_changes": {"surge": 0.08, "yaw": 0.21}},
                     {"applied": True, "reason": "significant", "gains": {"t1": 1.1}})

    got = gainjudge.judged(run, None, None, "all",
                           DiagnoseSettings(gains_judge=gainjudge.WRITTEN_ALL), None,
                           whole=True)
    # with the gains yaw is worse than the file's prior (1 DOF worse), without them none is
    assert got.name == "without" and got.thruster_gains["applied"] is False
    v = got.thruster_gains["validation"]
    assert v["score_with_gains"] == [1.0, pytest.approx(0.64 + 1.1025)]
    assert v["score_without_gains"] == [0.0, pytest.approx(0.81 + 0.5625)]
    assert [s.gains_judge for s in calls] == [gainjudge.NONE, gainjudge.OFF]


def test_written_all_judges_whole_log_fits_and_off_fits_no_gains():
    applied = SimpleNamespace(applied=True)
    s = DiagnoseSettings(gains_judge=gainjudge.WRITTEN_ALL)
    assert gainjudge.after_selection(s, [0, 1], object(), applied)
    assert gainjudge.after_selection(s, [0], object(), applied)
    assert not gainjudge.after_selection(s, [0, 1], None, applied)
    assert gainjudge.fitted(DiagnoseSettings(), [0, 1])
    assert gainjudge.fitted(DiagnoseSettings(), [0])
    assert not gainjudge.fitted(DiagnoseSettings(dof_gains=False), [0])
    assert gainjudge.fitted(DiagnoseSettings(dof_gains=False), [0, 1])
    assert not gainjudge.fitted(DiagnoseSettings(gains_judge=gainjudge.OFF), [0, 1])
