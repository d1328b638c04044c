"""The one-DOF thruster gains (diagnose's option ``dof_gains``) traced on logs of the
independent simulator (issue 33, ``gains33c``).

For each log (vehicle, category, seed of ``benchmarks.diagnose_independent``) the one-DOF
diagnosis of the effect's DOF is run with ``dof_gains`` off and on, and the row prints: the
truth's per-thruster factors (its :math:`C_t` over the prior's, forward branch) and their
contrasts within each group of thrusters (each factor over its group's mean, less 1: what
the contrasts of ``stripcoef.diagnose.gains`` estimate); the gains the one-DOF fit wrote
(and its record: test, validation, reason); the effect named first and the error cut (the
prior's RMS window residual in the DOF over the final one, as the benchmark's) in each mode;
with ``--columns``, what the contrasts are fitted on (:func:`column_record`).

Usage:
    python -m benchmarks.gains33c_trace --rows VEHICLE:CATEGORY:SEED[,...] [--duration 300]
        [--modes off,on] [--columns]
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


def truth_contrasts(truth, prior: dict, groups) -> dict:
    """Per thruster, the truth's forward :math:`C_t` over the prior's (the factor) and that
    factor over its group's mean, less 1 (the contrast the gains estimate) [-]."""
    f = np.array([t["ct_forward"] / (float(p.get("ct_forward", 1.0))
                                     * float(p.get("eta_forward", 1.0)))
                  for t, p in zip(truth.thrusters, prior["thrusters"])])
    rel = np.zeros_like(f)
    for g in groups:
        rel[g] = f[g] / f[g].mean() - 1.0
    names = [p.get("name", str(k)) for k, p in enumerate(prior["thrusters"])]
    return {"factor": dict(zip(names, map(float, f))),
            "contrast": dict(zip(names, map(float, rel)))}


def column_record(log, prior, truth, dof: str) -> dict:
    """What the one-DOF contrasts are fitted on, on the fitting part of ``log``: the
    correlation of each contrast column (the window mean of :math:`sum_k B_ik T_k P_kj`)
    with the DOF's own thrust (the column of a thrust scale) and with the window residual
    of the prior and of the prior with the truth's thrust maps (the gains' background
    removed: what is left is the effect and the other coefficients' errors); and the
    one-DOF gain fit on the latter, whose truth is every gain 1 (a contrast fitted there
    took a force that is not the gains')."""
    from benchmarks.diagnose_independent import with_truth_maps
    from stripcoef.conventions import parse_dof
    from stripcoef.diagnose.gains import (contrast_basis, fit_thruster_gains,
                                          thruster_groups)
    from stripcoef.diagnose.heldout import split
    from stripcoef.diagnose.select import select_dofs
    from stripcoef.diagnose.settings import DEFAULT_WINDOW, VALIDATION_FRACTION
    from stripcoef.effects.laws import model_window_data

    i = parse_dof(dof)
    train, _ = split(log, VALIDATION_FRACTION, key="validation")
    out = {}
    for name, model in (("prior", prior), ("truth_maps", with_truth_maps(prior, truth))):
        data = model_window_data(train, model, window=DEFAULT_WINDOW)
        g = data.mean_held(data.thruster_force(i))
        p = contrast_basis(thruster_groups(data.alloc), g.shape[1])
        c = g @ p
        e = data.e0[:, i]
        out[name] = {
            "corr_contrast_thrust": [float(np.corrcoef(c[:, j], g.sum(1))[0, 1])
                                     for j in range(c.shape[1])],
            "corr_contrast_residual": [float(np.corrcoef(c[:, j], e)[0, 1])
                                       for j in range(c.shape[1])]}
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            fit = fit_thruster_gains(data, [i], excited=select_dofs(data)[0])
        if fit is not None:
            out[name]["gains"] = dict(zip(fit.names, fit.gains))
            out[name]["p_value"] = fit.test["p_value"]
            out[name]["reason"] = fit.reason
    return out


def trace(vehicle: str, category: str, seed: int, duration: float, modes,
          columns: bool = False) -> dict:
    """The record of one log (module docstring)."""
    from benchmarks.diagnose_independent import _prior, _prior_error
    from stripcoef.diagnose.gains import thruster_groups
    from stripcoef.diagnose.pipeline import diagnose
    from validation.independent import OUTSIDE, STRENGTHS, generate

    prior = _prior(vehicle)
    dof = ({**STRENGTHS, **OUTSIDE}.get(category) or ("surge",))[0]
    log, truth = generate(prior.to_dict(), category, seed, duration=duration)
    groups = thruster_groups(prior.allocation())
    rec = {"vehicle": vehicle, "category": category, "seed": seed, "dof": dof,
           "truth": float(truth.strength) if truth.strength is not None else None,
           "truth_thrusters": truth_contrasts(truth, prior.to_dict(), groups)}
    if columns:
        rec["columns"] = column_record(log, prior, truth, dof)
    for mode in modes:
        t0 = time.process_time()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = diagnose(log, prior, dof=dof, time_limit=float("inf"),
                           dof_gains=(mode == "on")).to_dict()
        cpu = time.process_time() - t0
        tg = res.get("thruster_gains") or {}
        prior_error = _prior_error(log, prior, dof, res["window_s"])
        rec[mode] = {
            "first": res["steps"][0]["effect"] if res["steps"] else None,
            "steps": [(s["effect"], bool(s.get("kept", True)),
                       bool(s.get("not_determined"))) for s in res["steps"]],
            "cut": prior_error / res["final_error"] if res["final_error"] else None,
            "gains": tg.get("gains"), "gains_std": tg.get("std"),
            "gains_prior_sd": tg.get("prior_sd"), "gains_applied": tg.get("applied"),
            "gains_reason": tg.get("reason"), "gains_validation": tg.get("validation"),
            "cpu": cpu}
    return rec


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", required=True, help="VEHICLE:CATEGORY:SEED[,...]")
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--modes", default="off,on",
                    help="dof_gains off and/or on (comma-separated; empty: neither)")
    ap.add_argument("--columns", action="store_true",
                    help="the contrasts' columns and their fit on the truth's maps "
                         "(column_record)")
    args = ap.parse_args(argv)
    modes = tuple(m for m in args.modes.split(",") if m)
    for row in args.rows.split(","):
        vehicle, category, seed = row.split(":")
        rec = trace(vehicle, category, int(seed), args.duration, modes, args.columns)
        print("trace " + json.dumps(rec), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
