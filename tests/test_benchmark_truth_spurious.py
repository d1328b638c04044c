"""Issue 33: the independent benchmark calls a whole-log step spurious only when the truth has
no such effect on the log, measured from the truth's own thrusters on the log's commands
(benchmarks.diagnose_independent.truth_effects), not from one mean thrust gain per DOF."""

from __future__ import annotations

import numpy as np
import pytest

from benchmarks.diagnose_independent import _is_spurious, truth_effects, truth_has
from validation.independent import generate
from validation.synthetic import rov_model


def test_the_truth_has_an_effect_when_it_goes_the_same_way_and_the_step_resolves_it():
    # fitted +10 % at z 5: sd 2 %; the truth's +7 % is 3.5 sd from zero, +5 % only 2.5
    assert truth_has(0.10, 5.0, 0.07)
    assert not truth_has(0.10, 5.0, 0.05)
    assert not truth_has(0.10, 5.0, -0.07)       # the other way
    assert not truth_has(0.10, float("nan"), 0.07)


def test_a_step_is_spurious_by_the_truths_record_and_by_the_earlier_rule_without_one():
    row = {"category": "tether_drag", "dof": "surge", "mode": "all",
           "buoyancy_change": 0.5, "thrust_gain": {"pitch": 1.01, "heave": 1.2},
           "truth_has": {"pitch": [{"effect": "thrust_asymmetry", "has": True}]}}
    # one mean gain of 1.01 in pitch: the earlier rule calls the asymmetry spurious
    assert _is_spurious(row, "pitch", "thrust_asymmetry", 0, "mean gain")
    assert not _is_spurious(row, "pitch", "thrust_asymmetry", 0)
    # heave's scale: no record, the earlier rule (gain 1.2 > THRUST_BAND) in both
    assert not _is_spurious(row, "heave", "thrust_effectiveness", 0)
    assert _is_spurious(row, "yaw", "linear_drag", 0)
    assert not _is_spurious(row, "surge", "linear_drag", 0)   # the effect's own DOF


def test_thrusters_of_one_factor_carry_no_asymmetry_and_their_factor_as_gain():
    """Every thruster at 1.1 of the prior's map: in every DOF the truth's asymmetry on the
    log is zero and its gain 1.1 (the DOFs whose forward and backward parts this short log
    separates: surge and heave)."""
    prior = rov_model()
    log, truth = generate(prior.to_dict(), None, 11, duration=20.0)
    base = {(t["name"]): t for t in prior.to_dict()["thrusters"]}
    for t in truth.thrusters:
        p = base[t["name"]]
        t["ct_forward"] = 1.1 * float(p.get("ct_forward", 1.0)) * float(p.get("eta_forward", 1))
        t["ct_backward"] = 1.1 * float(p.get("ct_backward", 1.0)) * float(
            p.get("eta_backward", 1.0))
    row = {"category": "clean", "dof": "surge", "buoyancy_change": 0.0,
           "step_detail": {d: [{"effect": "thrust_asymmetry", "z": 10.0, "kept": True,
                                "parameters": {"eta_forward": 1.0, "eta_backward": 1.1}},
                               {"effect": "thrust_effectiveness", "z": 10.0, "kept": True,
                                "parameters": {"scale": 1.1}}]
                           for d in ("surge", "heave")}}
    got = truth_effects(log, truth, prior, row)
    for d in ("surge", "heave"):
        asym, gain = got[d]
        assert asym["truth"] == pytest.approx(0.0, abs=1e-9)
        assert not asym["has"]
        assert gain["truth"] == pytest.approx(0.1, abs=1e-9)
        assert gain["has"]
    assert np.isfinite(got["surge"][0]["fitted"])


def test_a_log_seed_names_its_vehicle_category_and_repeat():
    """The run's seeding (``log_seed``) and its inverse (``log_of``): every log of a full
    run maps back to the vehicle, category and repeat it was drawn for, and a seed no log
    of the run has is refused. The stored traces name logs by these seeds (e.g. 1795940009,
    the BlueROV2 clean log of base 1795938998's first repeat)."""
    from benchmarks.diagnose_independent import VEHICLES, log_of, log_seed, run_categories

    cats = run_categories()
    base = 1795938998
    for rep in range(2):
        for v, vehicle in enumerate(VEHICLES):
            for c, cat in enumerate(cats):
                assert log_of(base, log_seed(base, rep, v, c)) == (vehicle, cat, rep)
    assert log_of(base, 1795940009) == ("bluerov2_heavy", "clean", 0)
    for bad in (base - 1, base + 2 * 1000, base + len(cats)):
        with pytest.raises(ValueError, match="is not a log of base seed"):
            log_of(base, bad)
