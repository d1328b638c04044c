r"""Why a named effect's value within 15 % of the truth is not what the written model holds
(issue 33, mag33g): one log of ``benchmarks.diagnose_independent`` diagnosed again, with
the validation's record and the written model read for the effect's DOF.

For each log (vehicle, category, seed, mode) the diagnosis is run as the benchmark runs it
(``benchmarks.diagnose_independent._diagnosed``'s call; ``--options`` adds diagnose's
keyword arguments, e.g. the six whole-log options) and prints, for the effect's DOF:

- every step: its value as selected (the naming step's fit, ``selected_parameters``), as
  refitted with the DOF's other steps (``final_parameters``) and whether the written model
  holds it (``kept``);
- the validation's record: the changes it removed, the DOFs whose own changes it vetoed
  (``removed_for_own_dof``), and the DOF's free-simulation errors of the prior, of every
  change, of the kept changes and of the better trivial predictor;
- the benchmark's magnitude (:func:`benchmarks.diagnose_independent.magnitude_truth`, the
  truth in the written model's units) and the effect's magnitude in the written model
  itself (:func:`benchmarks.written_units.written_magnitude`): the written model's change of the coefficient the
  effect changes (the inertia, the linear drag, the restoring force, the thrust), or the
  written effect's own parameter (its DOF's entry or the thrusters' one shared entry); 0
  when the written model holds none.

Usage:
    python -m benchmarks.mag33g_trace --rows VEHICLE:CATEGORY:SEED:MODE[,...]
        [--duration 300] [--options six]
"""

from __future__ import annotations

import argparse
import json
import os
import time
import warnings

import numpy as np

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

#: The six whole-log options of the closed loop measured together at stop 54
#: (``--validation-others each --validation-horizon correlation --validation-judge own
#: --validation-reference combination --noise-with-bias --linked-gains identified``)
SIX = {"validation_others": "each", "validation_horizon": "correlation",
       "validation_judge": "own", "validation_reference": "combination",
       "noise_with_bias": True, "linked_gains": "identified"}


#: One prior per vehicle in a run of several logs (HydroModel is frozen)
_PRIORS: dict = {}


def trace(vehicle: str, category: str, seed: int, mode: str, duration: float,
          options: dict) -> dict:
    """One log's trace (module docstring): a JSON-able record."""
    from benchmarks.diagnose_independent import (_prior, held_scales, magnitude_truth,
                                                 written_gain)
    from benchmarks.written_units import written_magnitude
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.effects import get_effect
    from validation.independent import STRENGTHS, generate

    prior = _PRIORS.get(vehicle)
    if prior is None:
        prior = _PRIORS[vehicle] = _prior(vehicle)
    dof_name = STRENGTHS[category][0]
    log, truth = generate(prior.to_dict(), category, seed, duration=duration)
    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof=dof_name if mode == "dof" else "all",
                       time_limit=float("inf"), **options)
    cpu = time.process_time() - t0
    d = res.to_dict()
    per = d.get("per_dof") or {dof_name: d}
    steps = per.get(dof_name, {}).get("steps", [])
    g_w = written_gain(d, prior.to_dict(), dof_name)
    match = [s for s in steps if s["effect"] == category]
    out = {"vehicle": vehicle, "category": category, "seed": seed, "mode": mode,
           "dof": dof_name, "cpu_s": cpu, "written_gain": g_w,
           "steps": [{"effect": s["effect"], "kept": s.get("kept"),
                      "selected": s.get("selected_parameters"),
                      "final": s.get("final_parameters") or s["parameters"]}
                     for s in steps],
           "calibration": {k: v for k, v in (per.get(dof_name, {}).get("calibration")
                                             or {}).items()
                           if k in ("written", "final_parameters", "prior")}}
    val = d.get("validation") or {}
    out["validation"] = {k: val.get(k) for k in ("removed", "removed_for_own_dof",
                                                 "refitted")}
    out["validation_errors"] = {k: (val.get(k) or {}).get(dof_name) for k in (
        "prior", "all_changes", "kept_changes", "trivial_predictor", "combined_reference")
        if isinstance(val.get(k), dict)}
    kept = bool(match[0].get("kept", True)) if match else True
    ref = magnitude_truth(truth, prior.to_dict(), category, dof_name,
                          held_scales(steps, kept), g_w)
    # the reference of the written model as it is: its kept scales (held_scales(kept=True))
    ref_written = magnitude_truth(truth, prior.to_dict(), category, dof_name,
                                  held_scales(steps, True), g_w)
    out["reference"] = float(ref)
    out["reference_written"] = float(ref_written)
    if match:
        est = get_effect(category).magnitude(match[0].get("final_parameters")
                                             or match[0]["parameters"])
        sel = get_effect(category).magnitude(match[0].get("selected_parameters")
                                             or match[0]["parameters"])
        out["estimate"] = float(est)
        out["estimate_error"] = abs(abs(est) - abs(ref)) / abs(ref)
        out["selected"] = float(sel)
        out["selected_error"] = abs(abs(sel) - abs(ref)) / abs(ref)
        out["kept"] = kept
    wm = written_magnitude(res.model, prior, category, dof_name)
    out["written_magnitude"] = wm
    out["written_error"] = abs(abs(wm) - abs(ref_written)) / abs(ref_written)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", required=True, help="VEHICLE:CATEGORY:SEED:MODE[,...]")
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--options", default="default", choices=("default", "six"),
                    help="'six': the six whole-log options (SIX)")
    args = ap.parse_args(argv)
    options = SIX if args.options == "six" else {}
    for spec in args.rows.split(","):
        vehicle, category, seed, mode = spec.split(":")
        got = trace(vehicle, category, int(seed), mode, args.duration, options)
        print("trace " + json.dumps(got, default=float), flush=True)
        print(f"  {vehicle} {category} {seed} {mode} ({args.options}): "
              f"estimate {got.get('estimate', np.nan):+.4g} (selected "
              f"{got.get('selected', np.nan):+.4g}) kept {got.get('kept')}; reference "
              f"{got['reference']:+.4g}, error {100 * got.get('estimate_error', np.nan):.1f} %; "
              f"written model {got['written_magnitude']:+.4g} against "
              f"{got['reference_written']:+.4g}: {100 * got['written_error']:.1f} %; "
              f"removed {got['validation']['removed']}, vetoed "
              f"{got['validation']['removed_for_own_dof']}; {got['cpu_s']:.1f} s CPU",
              flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
