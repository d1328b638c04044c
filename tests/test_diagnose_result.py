"""The per-DOF results of a diagnosis are typed, frozen records (diagnose/result.py) whose
JSON form is the ``per_dof.<dof>`` contract of ``diagnose --json`` (docs/diagnose.md).

Properties that can fail: the records cannot be changed (fields, their mappings); their JSON
has the contract's keys in its order, an optional field left out until a later stage sets
it; the JSON reads back to an equal record; the validation's marks return new records and
leave the old ones as they were; a Diagnosis's JSON holds its records' JSON.
"""

import json
from dataclasses import FrozenInstanceError, replace

import pytest

from stripcoef.diagnose.result import Calibration, Diagnosis, DofResult, Step
from stripcoef.diagnose.validate import with_kept

#: the keys of ``per_dof.<dof>`` (``stopped_by_shape`` only when a shape stopped the selection)
DOF_KEYS = ["dof", "metric", "units", "baseline_error", "baseline_held_out_error",
            "calibration", "calibrated_error", "calibrated_held_out_error",
            "structure_before", "stopped_by_shape", "steps", "candidates", "final_error",
            "final_held_out_error", "structure_after", "unexplained", "unexplained_evidence",
            "unexplained_signature"]
CAL_KEYS = ["parameters", "std", "prior", "band_relative", "band_source", "band_z",
            "kept_at_prior", "information_ratio", "final_parameters", "kept", "written"]
STEP_KEYS = ["effect", "applicable", "parameters", "std", "released", "units", "signature",
             "mimics", "band_excess", "error_after", "held_out_error_after", "held_out_gain",
             "delta_bic", "z", "significant", "rejected_because", "magnitude", "source",
             "error_before", "held_out_error_before", "alternatives", "dof",
             "final_parameters", "kept", "selected_parameters"]


def _selection(stopped=False) -> dict:
    """A per-DOF working dictionary as :func:`diagnose_dof` builds it (made-up numbers)."""
    step = {"effect": "tether_drag", "applicable": True, "parameters": {"c_t": 0.12},
            "std": {"c_t": 0.004}, "released": {}, "units": {"c_t": "N s^2/m^3"},
            "signature": "dependence on tether_length", "mimics": None, "band_excess": None,
            "error_after": 0.05, "held_out_error_after": 0.054, "held_out_gain": 0.64,
            "delta_bic": -196.0, "z": 28.6, "significant": True, "rejected_because": [],
            "magnitude": 0.12, "source": "Fossen 2011", "error_before": 0.146,
            "held_out_error_before": 0.149, "alternatives": [], "dof": "surge",
            "final_parameters": {"c_t": 0.118}}
    out = {"dof": "surge", "metric": "rms_window_force_residual", "units": "N",
           "baseline_error": 0.22, "baseline_held_out_error": 0.22,
           "calibration": {"parameters": {"M": 1.5}, "std": {"M": 0.4}, "prior": {"M": 10.0},
                           "band_relative": {"M": 0.3}, "band_source": {"M": "BANDS"},
                           "band_z": {"M": 0.5}, "kept_at_prior": {"D_L": "too little"},
                           "information_ratio": {"M": 2.0, "D_L": 0.1},
                           "final_parameters": {"M": 1.4}},
           "calibrated_error": 0.146, "calibrated_held_out_error": 0.149,
           "structure_before": {"bias": 0.01}, "steps": [step],
           "candidates": [dict(step), {"effect": "deadband", "applicable": False,
                                       "reason": "no commands"}],
           "final_error": 0.05, "final_held_out_error": 0.054,
           "structure_after": {"bias": 0.0}, "unexplained": False,
           "unexplained_evidence": {"held_out_gain": 0.01}, "unexplained_signature": ""}
    if stopped:
        out["stopped_by_shape"] = {"shape": "sign(v)", "gain": 0.3}
    return out


def test_a_result_cannot_be_changed():
    r = DofResult.from_dict(_selection())
    assert isinstance(r.calibration, Calibration) and isinstance(r.steps[0], Step)
    with pytest.raises(FrozenInstanceError):
        r.final_error = 0.0
    with pytest.raises(FrozenInstanceError):
        r.steps[0].kept = False
    with pytest.raises(TypeError):
        r.calibration.parameters["M"] = 0.0
    with pytest.raises(TypeError):
        r.candidates[1]["reason"] = "x"
    assert isinstance(r.steps, tuple) and isinstance(r.steps[0].rejected_because, tuple)


@pytest.mark.parametrize("stopped", [False, True])
def test_json_has_the_contracts_keys_in_order_and_reads_back(stopped):
    r = DofResult.from_dict(_selection(stopped))
    d = r.to_dict()
    keys = [k for k in DOF_KEYS if stopped or k != "stopped_by_shape"]
    assert list(d) == keys
    # kept and written (calibration), kept and selected_parameters (step): not yet set
    assert list(d["calibration"]) == CAL_KEYS[:-2]
    assert list(d["steps"][0]) == STEP_KEYS[:-2]
    assert json.loads(json.dumps(d)) == d            # plain JSON types
    assert DofResult.from_dict(d) == r
    full = replace(r, calibration=replace(r.calibration, kept=True, written={"M": 11.4}),
                   steps=(replace(r.steps[0], kept=True, selected_parameters={"c_t": 0.12}),))
    d = full.to_dict()
    assert list(d["calibration"]) == CAL_KEYS and list(d["steps"][0]) == STEP_KEYS
    assert d["calibration"]["written"] == {"M": 11.4} and d["steps"][0]["kept"] is True
    assert DofResult.from_dict(d) == full


def test_validation_marks_return_new_records():
    per = {"surge": DofResult.from_dict(_selection())}
    out = with_kept(per, {("effect", "surge", "tether_drag")})
    assert out["surge"].calibration.kept is True and out["surge"].steps[0].kept is False
    assert per["surge"].calibration.kept is None and per["surge"].steps[0].kept is None
    out = with_kept(per, {("calibration", "surge")})
    assert out["surge"].calibration.kept is False and out["surge"].steps[0].kept is True


def test_diagnosis_json_holds_the_records_json():
    r = DofResult.from_dict(_selection())
    res = Diagnosis(metric="m", metric_description="", window_s=4.0, log="x.csv",
                    vehicle="v", dof="surge", units="N", baseline_error=0.22,
                    calibrated_error=0.146, steps=list(r.steps), final_error=0.05,
                    unexplained=False, per_dof={"surge": r}, model=None)
    d = res.to_dict()
    assert d["per_dof"] == {"surge": r.to_dict()}
    assert d["steps"] == [r.steps[0].to_dict()]
    assert res.steps == r.steps and res.per_dof["surge"] is r
