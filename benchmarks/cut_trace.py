"""Why a diagnosis's error cut falls short of the truth's own (issue 33): the remaining window
residual of the calibrated model traced to its causes, on logs of the independent simulator.

For one log of ``benchmarks.diagnose_independent`` (vehicle, category, seed, mode) the
diagnosis is run once and the RMS window force residual in the effect's DOF (the metric of
``stripcoef.diagnose.pipeline``: the diagnosis's ``baseline_error`` and ``final_error``, the
model's own effects subtracted, :func:`stripcoef.diagnose.written.window_errors`) is computed on
the fitting part of the log for

- ``prior``: the prior (the baseline; whole-log: the prior with the fitted thruster gains,
  ``gains``, is the diagnosis's baseline);
- ``fitted``: every change the selection made, none removed (the fits as selected,
  :func:`stripcoef.diagnose.calibrate.calibrated_model` without exclusions);
- ``written``: the model the diagnosis writes (after the validation's removals), its final
  error;
- ``truth``: the truth's own model (``validation.detectability.truth_model`` with its force
  effect, the truth's cut's denominator).

Then the written model's residual is decomposed by groups of coefficients (:data:`GROUPS`):
each group of the written model replaced by the truth's (``written <- truth``: how much of the
written model's residual that group's error costs), and each group of the truth's model
replaced by the written model's (``truth <- written``: the residual that group's error alone
adds to the truth's). The groups: the DOF's own added mass, its own drags, the other DOFs'
added masses (they act through C_A(nu) nu, Fossen 2011 eq. 6.43), the other drags, the
buoyancy, the thrust map (the thrusters' coefficients, branches and dead band, with a thrust
scale), and the force effects (tether, momentum drag, current, lag, delay).

Usage:
    python -m benchmarks.cut_trace --rows VEHICLE:CATEGORY:SEED:MODE[,...] [--duration 300]
        [--dof-gains]
"""

from __future__ import annotations

import argparse
import copy
import json
import os
import time
import warnings

import numpy as np

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

#: The coefficient groups the written model's residual is decomposed by (module docstring)
GROUPS = ("own_added_mass", "own_drag", "other_added_mass", "other_drag", "buoyancy",
          "thrust_map", "force_effects")
#: The effects written as part of the thrust map (a thrust scale is a model effect entry)
THRUST_ENTRIES = ("thrust_effectiveness",)


def _swap(into: dict, source: dict, group: str, i: int) -> dict:
    """The model dictionary ``into`` with ``group`` (:data:`GROUPS`) taken from ``source``
    (DOF index ``i`` the effect's)."""
    out = copy.deepcopy(into)
    if group in ("own_added_mass", "other_added_mass", "own_drag", "other_drag"):
        keys = (("added_mass",) if "added_mass" in group
                else ("linear_damping", "quadratic_damping"))
        for k in keys:
            a, b = np.array(out[k], float), np.asarray(source[k], float)
            mask = np.zeros((6, 6), bool)
            mask[i, i] = True
            if group.startswith("other"):
                mask = ~mask
            a[mask] = b[mask]
            out[k] = a.tolist()
    elif group == "buoyancy":
        out["volume"] = source["volume"]
    elif group == "thrust_map":
        out["thrusters"] = copy.deepcopy(source["thrusters"])
        out["effects"] = ([e for e in out.get("effects", []) if e["name"] not in THRUST_ENTRIES]
                          + [e for e in source.get("effects", [])
                             if e["name"] in THRUST_ENTRIES])
    elif group == "force_effects":
        out["effects"] = ([e for e in out.get("effects", []) if e["name"] in THRUST_ENTRIES]
                          + [e for e in source.get("effects", [])
                             if e["name"] not in THRUST_ENTRIES])
    return out


def truth_dict(prior, truth) -> dict:
    """The truth's model (``validation.detectability.truth_model``) as a dictionary, its
    force effect as a model effect entry at the truth's parameters (``true_parameters``; the
    library law, as the truth's cut takes it)."""
    from validation.detectability import FORCE_EFFECTS, true_parameters, truth_model
    from validation.independent import STRENGTHS
    d = truth_model(prior, truth).to_dict()
    d["effects"] = []
    if truth.effect in FORCE_EFFECTS:
        dof = STRENGTHS[truth.effect][0]
        d["effects"] = [{"name": truth.effect,
                         "dof": "all" if truth.effect in ("thruster_lag", "actuation_delay",
                                                          "current") else dof,
                         "parameters": true_parameters(truth)}]
    return d


def trace(vehicle: str, category: str, seed: int, mode: str, duration: float = 300.0,
          dof_gains: bool = True) -> dict:
    """The record of one log (module docstring; ``dof_gains``: diagnose's option)."""
    from stripcoef.conventions import parse_dof
    from stripcoef.diagnose.calibrate import calibrated_model
    from stripcoef.diagnose.heldout import split
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.diagnose.settings import DEFAULT_WINDOW, VALIDATION_FRACTION
    from stripcoef.diagnose.written import window_errors
    from stripcoef.effects import get_effect
    from stripcoef.model import HydroModel
    from validation.independent import STRENGTHS, generate

    from benchmarks.diagnose_independent import _prior

    prior = _prior(vehicle)
    dof_name = STRENGTHS[category][0]
    i = parse_dof(dof_name)
    log, truth = generate(prior.to_dict(), category, seed, duration=duration)
    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof=dof_name if mode == "dof" else "all",
                       time_limit=float("inf"), dof_gains=dof_gains)
    t_diag = time.process_time() - t0
    train, _ = split(log, VALIDATION_FRACTION, key="validation")

    def err(model) -> float:
        if isinstance(model, dict):
            model = HydroModel.from_dict(model)
        return float(window_errors(train, model, [i], window=DEFAULT_WINDOW)[dof_name])

    base = prior
    gains = res.thruster_gains or {}
    if gains.get("applied"):
        base = get_effect("thruster_gain").apply(
            prior, None, {f"gain_{k}": float(g) for k, g in gains["gains"].items()})
    per = res.per_dof
    fitted = calibrated_model(base, per, res.fits, frozenset())
    written = res.model
    wd, td = written.to_dict(), truth_dict(prior, truth)
    r = per[dof_name]
    out = {"vehicle": vehicle, "category": category, "seed": seed, "mode": mode,
           "dof": dof_name, "t_diagnose": t_diag, "dof_gains": dof_gains,
           "prior": err(prior), "baseline": float(r.baseline_error), "fitted": err(fitted),
           "written": err(written), "final": float(r.final_error), "truth": err(td),
           "steps": [(s.effect, bool(s.kept)) for s in r.steps],
           "calibration_kept": bool(r.calibration.kept),
           "calibration": {n: [float(r.calibration.prior[n]),
                               float(r.calibration.written.get(n, np.nan))
                               if r.calibration.written else None,
                               float(r.calibration.band_z.get(n, np.nan))]
                           for n in r.calibration.parameters},
           "kept_at_prior": dict(r.calibration.kept_at_prior),
           "bounds_hit": res.bounds_hit.get(dof_name) if res.bounds_hit else None,
           "removed": (res.validation or {}).get("removed"),
           "validation": {k: (res.validation or {}).get(k) for k in
                          ("prior", "all_changes", "kept_changes", "removed_for_own_dof")},
           "written_effects": [e for e in wd.get("effects", [])],
           "truth_effects": td["effects"]}
    out["written_from_truth"] = {g: err(_swap(wd, td, g, i)) for g in GROUPS}
    out["truth_from_written"] = {g: err(_swap(td, wd, g, i)) for g in GROUPS}
    # the coefficients of the effect's DOF: prior, written, truth
    out["coefficients"] = {k: [float(np.asarray(prior.to_dict()[k], float)[i, i]),
                               float(np.asarray(wd[k], float)[i, i]),
                               float(np.asarray(td[k], float)[i, i])]
                           for k in ("added_mass", "linear_damping", "quadratic_damping")}
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", required=True,
                    help="comma-separated VEHICLE:CATEGORY:SEED:MODE (mode dof or all)")
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--dof-gains", dest="dof_gains", action="store_true", default=True,
                    help="diagnose's dof_gains (its default)")
    ap.add_argument("--no-dof-gains", dest="dof_gains", action="store_false",
                    help="diagnose with dof_gains=False")
    args = ap.parse_args(argv)
    for spec in args.rows.split(","):
        vehicle, category, seed, mode = spec.split(":")
        rec = trace(vehicle, category, int(seed), mode, args.duration, args.dof_gains)
        print("trace " + json.dumps(rec, default=float), flush=True)
        print(_text(rec), flush=True)
    return 0


def _text(rec: dict) -> str:
    """One trace in words: the errors and the cut each group's error costs."""
    e = rec["written"]
    lines = [f"{rec['vehicle']} {rec['category']} {rec['seed']} {rec['mode']} ({rec['dof']}): "
             f"baseline {rec['baseline']:.4g} (prior {rec['prior']:.4g}), fitted "
             f"{rec['fitted']:.4g}, written {e:.4g} (final {rec['final']:.4g}), truth "
             f"{rec['truth']:.4g}; cut {rec['baseline'] / e:.2f}, fitted's "
             f"{rec['baseline'] / rec['fitted']:.2f}, truth's {rec['prior'] / rec['truth']:.2f}; "
             f"steps {rec['steps']}, calibration kept {rec['calibration_kept']}, removed "
             f"{rec['removed']}"]
    for g in GROUPS:
        a, b = rec["written_from_truth"][g], rec["truth_from_written"][g]
        lines.append(f"  {g:17s} written<-truth {a:.4g} (cut {rec['baseline'] / a:.2f})  "
                     f"truth<-written {b:.4g} (cut {rec['prior'] / b:.2f})")
    lines.append(f"  coefficients (prior, written, truth): {rec['coefficients']}; "
                 f"calibration (prior, written, band z): {rec['calibration']}; kept at prior "
                 f"{rec['kept_at_prior']}; bounds hit {rec['bounds_hit']}")
    lines.append(f"  effects written {rec['written_effects']}; truth's {rec['truth_effects']}")
    lines.append(f"  validation (free-simulation errors): {rec.get('validation')}")
    return "\n".join(lines)


if __name__ == "__main__":
    raise SystemExit(main())
