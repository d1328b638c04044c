"""One-DOF thruster gains refused by their validation (issue 33, fresh33d): how often, and what the
diagnosis names with them.

``dof_gains`` fits the thrusters' gains in the diagnosed DOF's balance
(:mod:`stripcoef.diagnose.gains`); a significant fit is validated alone on the prior before the
selection (:func:`stripcoef.diagnose.gains.validated`). For each log of
``benchmarks.diagnose_independent`` (its seeding) this prints the one-DOF gains record (whether
significant, applied, the validation's sum of squared error ratios) and, where a significant fit
was refused, the effect named first and its parameters on the prior (the diagnosis as run) and on
the prior with the refused gains applied (``dof_gains=False``): what the selection would have
found had the gains been kept. No threshold of the diagnosis is changed.

Usage:
    python -m benchmarks.fresh33d_gains --seed S [--vehicles bluerov2_heavy] [--repeats 2]
        [--categories C,...]
"""

from __future__ import annotations

import argparse
import os
import time
import warnings

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


def _first(res: dict, dof: str) -> str:
    per = res.get("per_dof") or {dof: res}
    steps = per.get(dof, {}).get("steps", [])
    if not steps:
        return "nothing"
    s = steps[0]
    par = s.get("final_parameters") or s["parameters"]
    vals = ", ".join(f"{k} {v:.4g}" for k, v in par.items() if isinstance(v, (int, float)))
    return f"{s['effect']} ({vals}; z {float(s.get('z') or 0.0):.1f})"


def one(vehicle: str, category: str | None, seed: int, duration: float = 300.0) -> str:
    """The line of one log (module docstring)."""
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.effects import get_effect
    from validation.independent import OUTSIDE, STRENGTHS, generate

    from benchmarks.diagnose_independent import _prior
    prior = _prior(vehicle)
    dof = ({**STRENGTHS, **OUTSIDE}.get(category) or ("surge",))[0]
    log, _ = generate(prior.to_dict(), category, seed, duration=duration)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof=dof, time_limit=float("inf")).to_dict()
        rec = res.get("thruster_gains") or {}
        head = (f"{vehicle} {category or 'clean'} {seed} {dof}: gains "
                f"p {rec.get('test', {}).get('p_value', float('nan')):.2g}, applied "
                f"{bool(rec.get('applied'))}")
        ratio = (rec.get("validation") or {}).get("sum_squared_ratio")
        if ratio is not None:
            head += f", validation sum of squared ratios {ratio:.4f}"
        head += f"; named first {_first(res, dof)}"
        if rec.get("applied") or "removed by the validation" not in (rec.get("reason") or ""):
            return head
        model = get_effect("thruster_gain").apply(
            prior, None, {f"gain_{k}": float(g) for k, g in rec["gains"].items()})
        res2 = diagnose(log, model, dof=dof, time_limit=float("inf"), dof_gains=False).to_dict()
    return head + f"; with the refused gains applied: {_first(res2, dof)}"


def main(argv=None) -> int:
    from benchmarks.diagnose_independent import VEHICLES, log_seed, run_categories
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--vehicles", default=",".join(VEHICLES))
    ap.add_argument("--categories", default=None)
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--duration", type=float, default=300.0)
    args = ap.parse_args(argv)
    every = run_categories()
    cats = args.categories.split(",") if args.categories else every
    for rep in range(args.repeats):
        for v, vehicle in enumerate(VEHICLES):
            if vehicle not in args.vehicles.split(","):
                continue
            for cat in cats:
                # the seeding of benchmarks.diagnose_independent (a run of every category)
                seed = log_seed(args.seed, rep, v, every.index(cat))
                t0 = time.process_time()
                line = one(vehicle, None if cat == "clean" else cat, seed, args.duration)
                print(f"{line} [{time.process_time() - t0:.1f} s CPU]", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
