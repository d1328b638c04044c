r"""Trace of a one-DOF diagnosis of an independent-simulator log (issue 33): why the effect of
the log is or is not named first.

For each log seed: the truth's background on the log (its buoyancy change [N] and, in the
effect's DOF, its thrusters' forward and backward factors against the prior's map on the
log's commands, ``benchmarks.diagnose_independent.truth_factors``), the effect's size in
the thrust's units (``magnitude_truth``), the shares of the DOF's forward and backward
thrust and how far its backward part is a constant (the cosine of F^- with a constant
column: a one-signed column carries a mean, the buoyancy change's column), then every
first-step candidate (held-out gain, z, delta BIC, parameters, why rejected), the step's
pair tests (``diagnose.select._competing``: each member's p against the model holding both)
and the steps named with their final parameters. Nothing is changed in the diagnosis.

Run: ``python -m benchmarks.momentum_trace --seeds 29112028,29212028`` (VideoRay, momentum
drag, 300 s; the logs of ``python -m benchmarks.diagnose_independent --seed 29112026
--repeats 2 --categories momentum_drag --vehicles videoray_pro3``). Output in
``benchmarks/data/momentum33_trace.md``.
"""
from __future__ import annotations

import argparse
import json
import time
import warnings

import numpy as np


def trace(seed: int, vehicle: str, category: str, duration: float) -> dict:
    """One log's trace (module docstring) as a dict."""
    from benchmarks.diagnose_independent import (_background, _prior, magnitude_truth,
                                                 truth_factors)
    from stripcoef.conventions import parse_dof
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.effects.windows import window_data
    from validation.independent import STRENGTHS, generate

    prior = _prior(vehicle)
    dof = STRENGTHS[category][0]
    i = parse_dof(dof)
    log, truth = generate(prior.to_dict(), category, seed, duration=duration)
    data = window_data(log, prior)
    fk = data.thruster_force(i)
    pos = np.where(data.thrust >= 0, fk, 0.0).sum(axis=1)
    neg = np.where(data.thrust < 0, fk, 0.0).sum(axis=1)
    rp, rn = float(np.sqrt(np.mean(pos ** 2))), float(np.sqrt(np.mean(neg ** 2)))
    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof=dof, time_limit=float("inf")).to_dict()
    cpu = time.process_time() - t0
    r = (res.get("per_dof") or {dof: res})[dof]
    cands = [{"effect": c["effect"], "held_out_gain": c["held_out_gain"], "z": c["z"],
              "delta_bic": c["delta_bic"], "parameters": c["parameters"],
              "significant": c["significant"], "rejected_because": c["rejected_because"]}
             for c in r["candidates"] if c.get("applicable")]
    comparison = next((s.get("comparison") for s in r["steps"] if s.get("comparison")), None)
    pairs = [{"pair": t["pair"], "held_out_error_joint": t["held_out_error_joint"],
              "p": {k: v["p_value"] for k, v in t["members"].items()}}
             for t in (comparison or {}).get("tests", [])]
    return {"seed": seed, "vehicle": vehicle, "category": category, "dof": dof,
            "truth": float(truth.strength),
            "truth_thrust_units": float(magnitude_truth(truth, prior.to_dict(), category, dof)),
            "background": _background(truth, prior.to_dict()),
            "factors": truth_factors(log, truth, prior, i),
            "forward_share": rp / (rp + rn) if rp + rn > 0 else float("nan"),
            "backward_cos_constant": float(abs(neg.sum()) / np.sqrt(neg.size * np.sum(neg ** 2)))
            if np.any(neg) else 0.0,
            "baseline_error": r["baseline_error"], "final_error": r["final_error"],
            "candidates": cands, "pairs": pairs,
            "steps": [{"effect": s["effect"], "z": s["z"], "held_out_gain": s["held_out_gain"],
                       "final_parameters": s.get("final_parameters") or s["parameters"],
                       "kept": s.get("kept")} for s in r["steps"]],
            "cpu_s": cpu}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seeds", default="29112028,29212028")
    ap.add_argument("--vehicle", default="videoray_pro3")
    ap.add_argument("--category", default="momentum_drag")
    ap.add_argument("--duration", type=float, default=300.0)
    args = ap.parse_args(argv)
    for seed in (int(s) for s in args.seeds.split(",")):
        print(json.dumps(trace(seed, args.vehicle, args.category, args.duration),
                         default=float), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
