"""The one-DOF thruster gains (diagnose's option ``dof_gains``) traced on logs of the
independent simulator (issue 33, ``gains33c``).

For each log (vehicle, category, seed of ``benchmarks.diagnose_independent``) the one-DOF
diagnosis of the effect's DOF is run with ``dof_gains`` off and on, and the row prints: the
truth's per-thruster factors (its :math:`C_t` over the prior's, forward branch) and their
contrasts within each group of thrusters (each factor over its group's mean, less 1: what
the contrasts of ``stripcoef.diagnose.gains`` estimate); the gains the one-DOF fit wrote
(and its record: test, validation, reason); the effect named first and the error cut (the
prior's RMS window residual in the DOF over the final one, as the benchmark's) in each mode.

Usage:
    python -m benchmarks.gains33c_trace --rows VEHICLE:CATEGORY:SEED[,...] [--duration 300]
        [--modes off,on]
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


def trace(vehicle: str, category: str, seed: int, duration: float, modes) -> dict:
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
    ap.add_argument("--modes", default="off,on", help="dof_gains off and/or on")
    args = ap.parse_args(argv)
    modes = tuple(args.modes.split(","))
    for row in args.rows.split(","):
        vehicle, category, seed = row.split(":")
        rec = trace(vehicle, category, int(seed), args.duration, modes)
        print("trace " + json.dumps(rec), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
