"""Trace of a whole-log spurious step (issue 33, spur33d): one log of the independent
simulator diagnosed whole-log (diagnose's defaults, ``validation_others="logged"``, as
``benchmarks.diagnose_independent``) against the prior and against the prior with parts of the
truth put in; for the traced DOF, every step and every candidate judged with its test.

``python -m benchmarks.spur33d_trace VEHICLE CATEGORY SEED DOF SWAP[,SWAP...] [--json DIR]``

SWAP: ``none`` (the vehicle file, as the benchmark), ``maps`` (the truth's thrust maps,
``benchmarks.diagnose_independent.with_truth_maps``), ``truth`` (the truth's own model, its
effect included where it is a coefficient: ``validation.detectability.truth_model``),
``without`` (the truth's model without the log's effect), or ``GROUP`` of
:data:`benchmarks.cut_trace.GROUPS` (that group of the truth's model without the effect put
into the prior; own/other relative to DOF). ``--noise-with-bias``: the oracle of a rule not
adopted, the calibration's identifiability (``diagnose.fit._identifiability``) judged with the
window residual's noise level fitted with a free constant beside the calibration's columns (a
bias is not noise; the Cramer-Rao bound holds the innovations' variance, Ljung 1999 sec. 9.2),
swapped in for this run only. A trace, not a model change: benchmarks/data/spur33d_trace.md.
"""
from __future__ import annotations

import argparse
import contextlib
import json
import os
import time
import warnings

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


@contextlib.contextmanager
def noise_with_bias():
    """``diagnose.fit._identifiability`` (and select's name for it) with its noise level
    ``fit._sigma`` fitted with a free constant column beside the calibration's (module
    docstring), inside the block only."""
    import numpy as np
    from stripcoef.diagnose import fit, select

    original, sigma = fit._identifiability, fit._sigma

    def with_bias(y, H, sd=None, *args, **kwargs):
        sd = np.full(H.shape[1], np.inf) if sd is None else np.asarray(sd, float)
        return sigma(y, np.column_stack([H, np.ones(len(y))]), np.append(sd, np.inf))

    def identifiability(*args, **kwargs):
        fit._sigma = with_bias
        try:
            return original(*args, **kwargs)
        finally:
            fit._sigma = sigma

    fit._identifiability = select._identifiability = identifiability
    try:
        yield
    finally:
        fit._identifiability = select._identifiability = original


def swapped(prior, truth, name: str, i: int):
    """The prior of swap ``name`` (module docstring); ``i`` the traced DOF's index."""
    from stripcoef.model import HydroModel
    from validation.detectability import truth_model, truth_without

    from benchmarks.cut_trace import GROUPS, _swap
    from benchmarks.diagnose_independent import with_truth_maps

    if name == "none":
        return prior
    if name == "maps":
        return with_truth_maps(prior, truth)
    if name == "truth":
        return truth_model(prior, truth)
    source = truth_model(prior, truth_without(prior, truth))
    if name == "without":
        return source
    if name in GROUPS:
        return HydroModel.from_dict(_swap(prior.to_dict(), source.to_dict(), name, i))
    raise SystemExit(f"unknown swap {name!r}")


def _step_text(s: dict) -> str:
    ev = s.get("evidence") or {}
    pars = ", ".join(f"{k} {v:.4g}" for k, v in s["parameters"].items())
    return (f"{s['effect']} ({pars}) z {s['z']:.1f}, held-out gain {100 * s['held_out_gain']:.1f} %"
            f", p {ev.get('p_adjusted', ev.get('p_value', float('nan'))):.2g}"
            + ("" if s.get("kept", True) else ", removed"))


def _candidate_text(c: dict) -> str:
    if not c.get("applicable", True):
        return f"{c['effect']}: not applicable"
    why = "; ".join(c.get("rejected_because") or ())
    return (f"{c['effect']}: z {c.get('z', float('nan')):.1f}, gain "
            f"{100 * c.get('held_out_gain', float('nan')):.1f} %"
            + (f" [{why}]" if why else " [passes]"))


def trace_one(vehicle: str, category: str, seed: int, dof: str, name: str,
              duration: float = 300.0, bias: bool = False) -> tuple[dict, float]:
    """The whole-log diagnosis (its JSON form) against swap ``name``, and its CPU time [s]
    (``bias``: under :func:`noise_with_bias`)."""
    from stripcoef.conventions import parse_dof
    from stripcoef.diagnose.pipeline import diagnose
    from validation.independent import generate

    from benchmarks.diagnose_independent import _prior

    prior = _prior(vehicle)
    log, truth = generate(prior.to_dict(), category, seed, duration=duration)
    model = swapped(prior, truth, name, parse_dof(dof))
    t0 = time.process_time()
    with warnings.catch_warnings(), (noise_with_bias() if bias else contextlib.nullcontext()):
        warnings.simplefilter("ignore")
        res = diagnose(log, model, dof="all", time_limit=float("inf"),
                       validation_others="logged").to_dict()
    return res, time.process_time() - t0


def lines(res: dict, dof: str, name: str, cpu: float) -> list[str]:
    out = [f"## {name} (CPU {cpu:.1f} s)"]
    kept = {d: list(r["calibration"]["kept_at_prior"]) for d, r in res["per_dof"].items()}
    for d, r in res["per_dof"].items():
        steps = "; ".join(_step_text(s) for s in r["steps"]) or "-"
        out.append(f"- {d}: prior {r['baseline_error']:.4g}, calibrated "
                   f"{r['calibrated_error']:.4g}, final {r['final_error']:.4g} | {steps}")
    r = res["per_dof"].get(dof)
    if r is not None:
        out.append(f"  {dof} calibration change: "
                   + ", ".join(f"{k} {v:+.4g}" for k, v in r["calibration"]["parameters"].items()))
        out.append(f"  {dof} calibration kept at the prior: {kept.get(dof)}")
        out.append(f"  {dof} candidates: " + " | ".join(_candidate_text(c)
                                                      for c in r["candidates"]))
        for w in r.get("withdrawn") or ():
            out.append(f"  {dof} withdrawn: {w}")
    out.append(f"  gains: {res.get('thruster_gains')}")
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("vehicle")
    ap.add_argument("category")
    ap.add_argument("seed", type=int)
    ap.add_argument("dof")
    ap.add_argument("swaps")
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--json", default="", help="write each diagnosis's JSON in this folder")
    ap.add_argument("--noise-with-bias", action="store_true",
                    help="the identifiability's noise level fitted with a free constant (an "
                         "oracle of a rule not adopted)")
    args = ap.parse_args(argv)
    for name in args.swaps.split(","):
        res, cpu = trace_one(args.vehicle, args.category, args.seed, args.dof, name,
                             args.duration, args.noise_with_bias)
        print("\n".join(lines(res, args.dof, name, cpu)), flush=True)
        if args.json:
            os.makedirs(args.json, exist_ok=True)
            tag = "_bias" if args.noise_with_bias else ""
            path = os.path.join(args.json, f"{args.seed}_{name}{tag}.json")
            with open(path, "w") as f:
                json.dump(res, f, default=str)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
