"""Issue 33 (named33f): when a thrust scale or a released coefficient "raises the held-out
error" (``diagnose.heldoutrise``): beyond TIE (2 %, the default) or, with the option
``heldout_rise="diebold_mariano"``, only when the one-sided Diebold-Mariano test of the
cross-validated window losses (Diebold & Mariano 1995; Harvey, Leybourne & Newbold 1997)
rejects at ALPHA. Measured in benchmarks/data/named33f_trace.md."""

from __future__ import annotations

import numpy as np
import pytest

from stripcoef.diagnose.compare import ALPHA
from stripcoef.diagnose.heldoutrise import RULES, rise_reasons, rise_test
from stripcoef.diagnose.scalechoice import _RELEASE_GATES, _SCALE_GATES, contender
from stripcoef.diagnose.settings import TIE, DiagnoseSettings

DM = DiagnoseSettings(heldout_rise="diebold_mariano")


def _ev(resid):
    return {"held_out_resid": np.asarray(resid, float)}


def test_the_default_is_the_tie_rule():
    assert DiagnoseSettings().heldout_rise == "tie"
    assert RULES == ("tie", "diebold_mariano")
    ref = _ev(np.ones(40))
    assert rise_reasons(-TIE * 1.5, ref, ref, "the scale") != []
    assert rise_reasons(-TIE * 0.5, ref, ref, "the scale") == []
    assert rise_reasons(0.05, ref, ref, "the scale", DM) == []       # no rise at all


def test_a_rise_within_the_window_losses_spread_refuses_nothing():
    # 40 windows whose squared held-out residuals differ by chance: the candidate's RMS is
    # 3 % higher (beyond TIE), the differences are noise, the test does not reject
    rng = np.random.default_rng(7)
    ref = rng.normal(size=40)
    cand = ref * 1.03 + 0.3 * rng.normal(size=40)
    gain = 1 - np.sqrt(np.mean(cand ** 2)) / np.sqrt(np.mean(ref ** 2))
    assert gain < -TIE
    test = rise_test(_ev(cand), _ev(ref))
    assert test["p_value"] > ALPHA and test["segments"] == 40
    assert rise_reasons(gain, _ev(cand), _ev(ref), "the scale") != []     # tie refuses
    assert rise_reasons(gain, _ev(cand), _ev(ref), "the scale", DM) == []


def test_a_rise_beyond_chance_is_refused_with_the_prefix_the_scale_choice_weighs():
    rng = np.random.default_rng(3)
    ref = rng.normal(size=60)
    cand = ref * 1.5                        # every window's loss 2.25 x the reference's
    gain = 1 - 1.5
    test = rise_test(_ev(cand), _ev(ref))
    assert test["p_value"] < 1e-3
    (reason,) = rise_reasons(gain, _ev(cand), _ev(ref), "the scale", DM)
    assert reason.startswith("held-out error rises") and "Diebold-Mariano" in reason
    assert reason.startswith(_SCALE_GATES)
    assert not reason.startswith(_RELEASE_GATES)
    trial = {"effect": "thrust_effectiveness", "significant": False,
             "rejected_because": [reason]}
    assert contender(trial)


def test_too_few_windows_refuse_nothing_and_a_bad_rule_is_an_error():
    assert rise_reasons(-0.5, _ev([2.0]), _ev([1.0]), "the scale", DM) == []
    with pytest.raises(ValueError, match="heldout_rise"):
        rise_reasons(-0.5, _ev([2.0, 1.0]), _ev([1.0, 1.0]), "the scale",
                     DiagnoseSettings(heldout_rise="bonferroni"))
