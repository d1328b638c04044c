"""Trace of one log of ``benchmarks.diagnose_independent`` (issue 33, fresh33g): the log diagnosed
in one mode, under the benchmark's default or under the six whole-log options together, against
the prior and against the prior with parts of the truth put in; for every DOF the calibration
(its change from the prior, in bands, kept or removed by the validation), every step (z,
held-out gain, parameters, kept) and the thrusters' gains, beside the truth's background.

``python -m benchmarks.fresh33g_trace VEHICLE:CATEGORY:SEED:MODE[,...] [--swaps none,maps,...]
[--options default|six] [--dofs surge,heave]``

MODE: ``all`` (whole-log) or ``dof`` (the effect's own DOF, as the benchmark's one-DOF row).
SWAP: as ``benchmarks.spur33d_trace`` (``none``: the vehicle file, as the benchmark; ``maps``: the
truth's thrust maps; ``truth``; ``without``; a group of :data:`benchmarks.cut_trace.GROUPS`,
e.g. ``buoyancy``: the truth's buoyancy in the prior). ``--options six``: the options the lead's
run of the fresh seed used (:data:`SIX`). A trace, not a model change: measured text in
benchmarks/data/fresh33g_compare.md.
"""
from __future__ import annotations

import argparse
import os
import time
import warnings

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

#: The six whole-log options of the lead's run (``--modes all --validation-others each
#: --validation-horizon correlation --validation-judge own --validation-reference combination
#: --noise-with-bias --linked-gains identified``) as keyword arguments of diagnose
SIX = {"validation_others": "each", "validation_horizon": "correlation",
       "validation_judge": "own", "validation_reference": "combination",
       "noise_with_bias": True, "linked_gains": "identified"}


def trace_one(vehicle: str, category: str, seed: int, mode: str, swap: str,
              options: str = "default", duration: float = 300.0) -> tuple[dict, dict, float]:
    """``(diagnosis JSON, truth record, CPU [s])`` of one log in ``mode`` against ``swap``
    under ``options`` (``default``: the benchmark's, ``validation_others="logged"``)."""
    from stripcoef.conventions import parse_dof
    from stripcoef.diagnose.pipeline import diagnose
    from validation.independent import OUTSIDE, STRENGTHS, generate

    from benchmarks.diagnose_independent import _background, _prior
    from benchmarks.spur33d_trace import swapped

    prior = _prior(vehicle)
    cat = None if category == "clean" else category
    dof_name = ({**STRENGTHS, **OUTSIDE}.get(cat) or ("surge",))[0]
    log, truth = generate(prior.to_dict(), cat, seed, duration=duration)
    model = swapped(prior, truth, swap, parse_dof(dof_name))
    kw = dict(SIX) if options == "six" else {"validation_others": "logged"}
    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, model, dof=dof_name if mode == "dof" else "all",
                       time_limit=float("inf"), **kw).to_dict()
    cpu = time.process_time() - t0
    info = {"strength": truth.strength, "dof": dof_name, **_background(truth, prior.to_dict())}
    return res, info, cpu


def _num(v) -> str:
    return f"{v:+.4g}" if isinstance(v, (int, float)) else str(v)


def lines(res: dict, info: dict, label: str, cpu: float, dofs=None) -> list[str]:
    """The trace's text: each DOF's errors, calibration and steps, then the gains."""
    from benchmarks.spur33d_trace import _step_text
    out = [f"## {label} (diagnosis CPU {cpu:.1f} s)",
           f"- truth: strength {info['strength']}, DOF {info['dof']}, buoyancy change "
           f"{info['buoyancy_change']:+.3f} N, thrust gain per DOF "
           + ", ".join(f"{d} {g:.3f}" for d, g in info["thrust_gain"].items())]
    per = res.get("per_dof") or {res.get("dof", "?"): res}
    for d, r in per.items():
        if dofs and d not in dofs:
            continue
        cal = r.get("calibration") or {}
        steps = "; ".join(_step_text(s) for s in r.get("steps", [])) or "-"
        out.append(f"- {d}: prior {r['baseline_error']:.4g}, calibrated "
                   f"{r.get('calibrated_error', float('nan')):.4g}, final "
                   f"{r['final_error']:.4g} | {steps}")
        if cal:
            out.append(f"  calibration (kept {cal.get('kept')}): "
                       + ", ".join(f"{k} {_num(v)} (band z {_num(cal['band_z'].get(k))})"
                                   for k, v in cal["parameters"].items())
                       + f"; at the prior: {sorted(cal.get('kept_at_prior') or {})}")
    gains = res.get("thruster_gains") or {}
    if gains:
        g = gains.get("gains") or {}
        out.append(f"- gains (applied {gains.get('applied')}): "
                   + ", ".join(f"{k} {v:.3f}" for k, v in g.items()))
        for link in gains.get("links") or ():
            out.append(f"  link {link}")
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("rows", help="VEHICLE:CATEGORY:SEED:MODE[,...]")
    ap.add_argument("--swaps", default="none")
    ap.add_argument("--options", default="default", choices=("default", "six"))
    ap.add_argument("--dofs", default="", help="comma-separated DOFs to print (default: all)")
    ap.add_argument("--duration", type=float, default=300.0)
    args = ap.parse_args(argv)
    dofs = set(args.dofs.split(",")) if args.dofs else None
    for spec in args.rows.split(","):
        vehicle, category, seed, mode = spec.split(":")
        for swap in args.swaps.split(","):
            res, info, cpu = trace_one(vehicle, category, int(seed), mode, swap, args.options,
                                       args.duration)
            label = f"{vehicle} {category} {seed} {mode}, {args.options}, swap {swap}"
            print("\n".join(lines(res, info, label, cpu, dofs)), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
