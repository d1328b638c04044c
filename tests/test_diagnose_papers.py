"""The papers' cases of issue 7 (Wang & Clark 2006 VideoRay surge, Indiveri 1998 ROMEO heave)."""

import pytest

from validation.cases import (VIDEORAY_MEASURED, romeo_case, videoray_case,
                                      videoray_tether_gap)


def test_videoray_tether_gap_numbers():
    gap = videoray_tether_gap()
    # model thrust at 0.51 m/s with Table I's experimental X_u, X_u|u|
    assert gap["thrust"] == pytest.approx(0.9460 * 0.51 + 6.0418 * 0.51 ** 2, rel=1e-12)
    # the tether must take the difference of the hull drag at 0.51 and 0.47 m/s
    assert gap["tether_force"] == pytest.approx(0.2747, abs=1e-4)
    assert gap["c_t_L"] == pytest.approx(gap["tether_force"] / VIDEORAY_MEASURED ** 2)
    # our reconstruction from Table I (C_t forward, n = 60, two thrusters)
    assert gap["table_speed"] == pytest.approx(0.483, abs=1e-3)
    assert 5.0 < gap["length_along_flow"] < 10.0 and gap["length_cross_flow"] < 0.5


@pytest.fixture(scope="module")
def videoray():
    return videoray_case(seed=0)


@pytest.mark.slow
def test_videoray_diagnosis_finds_the_tether_with_length_column(videoray):
    res = videoray["with_tether_length"]
    assert res["steps"] and res["steps"][0]["effect"] == "tether_drag"
    c_t = res["steps"][0]["parameters"]["c_t"]
    assert c_t == pytest.approx(videoray["c_t_truth"], rel=0.15)
    assert res["baseline_error"] / res["final_error"] >= 3.0


@pytest.mark.slow
def test_videoray_without_length_the_tether_is_only_a_larger_drag(videoray):
    # the paper's situation: no tether_length channel; the tether looks like X_u|u| + 20 %,
    # inside strip theory's band, so the diagnosis calibrates D_Q and names no effect
    res = videoray["without_tether_length"]
    surge = res["per_dof"]["surge"]
    assert res["steps"] == []
    assert surge["calibration"]["band_z"]["D_Q"] > 0.3
    cand = {c["effect"]: c for c in surge["candidates"]}
    assert cand["tether_drag"]["signature"] is None and cand["tether_drag"]["mimics"] == "D_Q"


@pytest.fixture(scope="module")
def romeo():
    return romeo_case(seed=0)


@pytest.mark.slow
def test_romeo_finds_the_upward_efficiency_in_all_five(romeo):
    for row in romeo:
        steps = {s["effect"]: s for s in row["diagnosis"]["steps"]}
        assert "thrust_asymmetry" in steps, row["experiment"]
        p = steps["thrust_asymmetry"]["final_parameters"]
        assert p["eta_backward"] / p["eta_forward"] == pytest.approx(0.57, rel=0.15)
        assert row["diagnosis"]["baseline_error"] / row["diagnosis"]["final_error"] >= 3.0


@pytest.mark.slow
def test_romeo_buoyancy_bias_disappears(romeo):
    z = []
    for row in romeo:
        w = row["weight_truth"]
        # standard model: biased toward heavy in every experiment (it compensates the
        # over-estimated upward thrust with weight) -- the chapter's "wrong in all five":
        # the same sign every time, each clearly (z > 1.5; experiment 1, the lightest,
        # W - B = -35.7 N, has the smallest bias, about 2 sigma) ...
        z.append((row["standard_buoyancy"] - w) / row["standard_buoyancy_std"])
        assert z[-1] > 1.5, row["experiment"]
        # with the efficiency: the bias at least four times smaller (or under 1.5 N) in
        # every experiment ...
        assert abs(row["eta_buoyancy"] - w) < max(0.25 * abs(row["standard_buoyancy"] - w),
                                                  1.5)
        # ... and the truth within 3 standard deviations (or 1.5 N), experiment 5 apart
        # (test_romeo_experiment_5_buoyancy_within_three_sigma)
        if row["experiment"] != 5:
            assert abs(row["eta_buoyancy"] - w) < max(3 * row["eta_buoyancy_std"], 1.5)
    # ... and beyond doubt over the five (pooled z of independent experiments)
    assert sum(z) / len(z) ** 0.5 > 6.0
    # the neutral experiment: no buoyancy effect added
    neutral = romeo[2]["diagnosis"]["steps"]
    assert "buoyancy_offset" not in [s["effect"] for s in neutral]


@pytest.mark.xfail(strict=True, reason=(
    "experiment 5 (the heaviest, W - B = +35.7 N, most upward thrust): the eta model's fitted "
    "scale is high (added mass +21 %, eta_forward +6 %, b = 42.0 +- 1.5 N against 35.7 N; "
    "with the earlier 500 kg body: b = 40.5 +- 2.2 N with raw window end values, and the same "
    "with 10x wider bands, so not the band priors); cause not traced. The bias still shrinks "
    "from 33.6 N to 6.3 N."))
@pytest.mark.slow
def test_romeo_experiment_5_buoyancy_within_three_sigma(romeo):
    row = romeo[4]
    assert abs(row["eta_buoyancy"] - row["weight_truth"]) < 3 * row["eta_buoyancy_std"]


@pytest.mark.slow
def test_validation_doc_diagnosis_section_is_current(videoray, romeo, monkeypatch):
    """docs/validation.md's section of these cases is what the code writes now
    (tests/test_validation_doc.py), from the diagnoses of the module fixtures above: the
    section calls ``videoray_case(seed=0)`` and ``romeo_case(seed=0)``, as they do."""
    import validation.cases

    from test_validation_doc import assert_section_is_current

    def once(value):
        def case(seed=0):
            assert seed == 0
            return value
        return case

    monkeypatch.setattr(validation.cases, "videoray_case", once(videoray))
    monkeypatch.setattr(validation.cases, "romeo_case", once(romeo))
    assert_section_is_current("diagnosis")
