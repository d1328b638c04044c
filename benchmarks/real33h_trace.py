"""One real-style log's whole-log diagnosis traced through its validation (issue 33, real33h;
benchmarks/data/real33h_trace.md).

For real-style log K of :mod:`benchmarks.real_logs` (default 2, the BlueROV2-Heavy-like
current log), seed S and a split (forward: ``diagnose(..., holdout=0.3)``; reverse: the last
70 % diagnosed, the first 30 % held out, as :func:`benchmarks.real_logs.both_splits`), with
the options of :data:`benchmarks.real_logs.OPTION_FLAGS`: the thrusters' gains' record, every
step named per DOF (kept or removed by the validation), the water current fitted beside the
truth's, the effects written, the validation record (the prior's, all changes', the kept
changes' errors [m/s or rad/s], what was removed and why, each set the elimination scored
where the record holds them) and the written model's held-out errors beside the prior's and
the trivial predictors'.

Run:  python -m benchmarks.real33h_trace [--log 2] [--seed 7] [--split forward|reverse]
      [the six options, --validation-choice best_visited]
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
import warnings

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


def _fmt(d):
    if not d:
        return str(d)
    return ", ".join(f"{k} {v:.4f}" if isinstance(v, float) else f"{k} {v}"
                     for k, v in d.items())


def main(argv=None) -> int:
    from benchmarks.real_logs import OPTION_FLAGS, _options

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--log", type=int, default=2, help="real-style log (0..3)")
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--split", default="forward", choices=("forward", "reverse"))
    for flag, key, kw in OPTION_FLAGS:
        ap.add_argument(flag, dest=key, **kw)
    args = ap.parse_args(argv)
    options = _options(args)

    from benchmarks.real_logs import HOLDOUT, read_back, real_style_log, write_ros_chunks
    from stripcoef.diagnose import diagnose
    from stripcoef.diagnose.heldout import compare, split

    name, log, prior, widths, truth, _ = real_style_log(args.log, args.duration, args.seed,
                                                        oracle=True)
    with tempfile.TemporaryDirectory() as tmp:
        read, _ = read_back(tmp, write_ros_chunks(log, tmp, seed=args.seed + args.log))
    if args.split == "forward":
        fit, kw, test = read, {"holdout": HOLDOUT}, split(read, HOLDOUT)[1]
    else:
        test, fit = split(read, 1.0 - HOLDOUT)
        kw = {}
    print(f"{name} ({truth}), {args.split} split, options {options}")
    c0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(fit, prior, dof="all", time_limit=float("inf"), prior_widths=widths,
                       **kw, **options)
    cpu = time.process_time() - c0
    v = res.validation or {}
    written = type(res.model).from_dict(res.model.to_dict())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        held = compare(test, {"prior": prior, "written": written}, list(res.diagnosed))
    g = res.thruster_gains or {}
    print(f"diagnosis {cpu:.1f} s CPU; DOFs {res.diagnosed}; dropped {res.dropped_dofs}")
    print(f"gains applied {g.get('applied')}; significant {g.get('significant')}")
    if g.get("gains"):
        print("   gains: " + _fmt(g.get("gains")))
    if g.get("validation"):
        print("   gains' validation: " + _fmt({k: x for k, x in g["validation"].items()
                                                if k != "description"}))
    for d, r in res.per_dof.items():
        cal = r.calibration
        print(f"-- {d}: calibration kept {cal.kept}; steps: " + ("; ".join(
            f"{s.effect} (kept {s.kept})" for s in r.steps) or "none"))
    print("effects written: " + ("; ".join(f"{e['dof']} {e['name']} "
                                           + _fmt(e.get("parameters") or {})
                                           for e in res.model.effects) or "none"))
    print(f"bounds hit: {res.bounds_hit}")
    for key in ("horizon_s", "prior", "trivial_predictor", "combined_reference",
                "all_changes", "kept_changes"):
        if key in v:
            print(f"validation {key}: {_fmt(v.get(key))}")
    print(f"removed: {v.get('removed')}")
    print(f"removed for own DOF: {v.get('removed_for_own_dof')}")
    for key in ("choice", "visited"):
        if key in v:
            print(f"validation {key}:")
            for row in (v[key] if isinstance(v[key], list) else [v[key]]):
                print(f"   {row}")
    for dof, e in held.items():
        print(f"held out {dof:6s} " + "  ".join(
            f"{m} {x:.4f}" if x is not None else f"{m} None" for m, x in e.items()))
    print(f"\n{time.process_time():.1f} s of CPU in all")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
