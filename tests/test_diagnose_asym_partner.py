"""The validation removes a translation's thrust asymmetry with the buoyancy offset it was
admitted beside (diagnose/validate.py, ``partners``; issue 33, asym33s).

A thrust asymmetry selected after its DOF's buoyancy offset was not tested for
identification apart from a buoyancy change (diagnose/thrusterparts.py: the DOF held the
offset); refitted without the offset it takes the bias. The seeded log is generated from a
known truth (the independent simulator; no asymmetry in the truth's thrusters).
"""

from __future__ import annotations

import warnings

import pytest

from conftest import shipped_model
from stripcoef.diagnose.validate import partners

CHANGES = [("calibration", "heave"), ("effect", "heave", "buoyancy_offset"),
           ("effect", "heave", "thrust_asymmetry"), ("effect", "pitch", "thrust_asymmetry")]


def test_the_asymmetry_goes_with_the_offset_it_was_admitted_beside():
    got = partners({("effect", "heave", "buoyancy_offset")}, CHANGES)
    assert got == {("effect", "heave", "buoyancy_offset"), ("effect", "heave", "thrust_asymmetry")}


def test_an_asymmetry_tested_before_the_offset_or_in_a_rotation_stays():
    # selected before the offset: its identification test ran without it
    first = [("effect", "heave", "thrust_asymmetry"), ("effect", "heave", "buoyancy_offset")]
    assert partners({("effect", "heave", "buoyancy_offset")}, first) == {
        ("effect", "heave", "buoyancy_offset")}
    # a rotation's asymmetry is never tested beside a buoyancy change (thrusterparts)
    pitch = [("effect", "pitch", "buoyancy_offset"), ("effect", "pitch", "thrust_asymmetry")]
    assert partners({("effect", "pitch", "buoyancy_offset")}, pitch) == {
        ("effect", "pitch", "buoyancy_offset")}
    # removing the asymmetry alone does not take the offset
    assert partners({("effect", "heave", "thrust_asymmetry")}, CHANGES) == {
        ("effect", "heave", "thrust_asymmetry")}


@pytest.mark.slow
def test_no_asymmetry_written_without_its_offset_on_a_seeded_log():
    """VideoRay-like log 1795929178 (seed 1795929171 of the independent benchmark; the truth
    0.53 N more buoyant than the prior, no asymmetry): the whole-log run selects the heave
    buoyancy offset, then a heave asymmetry beside it (eta_b / eta_f - 1 = -0.32). Before, the
    validation removed the offset alone and the asymmetry, refitted without it, was written
    at +2.06; now a written asymmetry is never without its offset."""
    from stripcoef.diagnose.pipeline import diagnose
    from validation.independent import generate

    prior = shipped_model("videoray_pro3.yaml")
    log, _ = generate(prior.to_dict(), "added_mass_error", 1795929178, duration=300.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof="all", time_limit=float("inf")).to_dict()
    steps = {s["effect"]: s for s in res["per_dof"]["heave"]["steps"]}
    assert list(steps)[:2] == ["buoyancy_offset", "thrust_asymmetry"]
    asym = steps["thrust_asymmetry"]
    if asym["kept"]:
        assert steps["buoyancy_offset"]["kept"]
        p = asym["final_parameters"]
        # the written value is the one the selection admitted, beside the offset
        assert p["eta_backward"] / p["eta_forward"] - 1.0 == pytest.approx(
            asym["selected_parameters"]["eta_backward"]
            / asym["selected_parameters"]["eta_forward"] - 1.0, abs=0.05)
    removed = res["validation"]["removed"]
    assert "buoyancy_offset heave" not in removed or any(
        r.startswith("thrust_asymmetry heave (with the heave buoyancy_offset") for r in removed)
