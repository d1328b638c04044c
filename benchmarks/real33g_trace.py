"""Both passes of ``gains_judge="written_all"`` on one real-style log (issue 33, real33g;
benchmarks/data/real33g_trace.md).

For real-style log K of :mod:`benchmarks.real_logs` (default 2, the BlueROV2-Heavy-like
current log), seed S and a split (forward: ``diagnose(..., holdout=0.3)``; reverse: the last
70 % diagnosed, the first 30 % held out, as :func:`benchmarks.real_logs.both_splits`), the
whole-log diagnosis with the thrusters' gains applied unvalidated (``gains_judge="none"``)
and without them (``"off"``), the two passes :func:`stripcoef.diagnose.gainjudge.judged`
compares: each pass's written effects, bounds hit, validation record (the prior's, all
changes', the kept changes' errors [m/s or rad/s], what was removed), its score
(:func:`stripcoef.diagnose.gainjudge.score` against the file's prior, the rule's) and its
written model's held-out errors beside the prior's and the trivial predictors'.

Run:  python -m benchmarks.real33g_trace [--log 2] [--seed 7] [--split forward|reverse]
"""

from __future__ import annotations

import argparse
import os
import time
import warnings

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--log", type=int, default=2, help="real-style log (0..3)")
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--split", default="forward", choices=("forward", "reverse"))
    args = ap.parse_args(argv)

    from benchmarks.real_logs import fmt_record, traced_split
    from stripcoef.diagnose import diagnose
    from stripcoef.diagnose.gainjudge import score
    from stripcoef.diagnose.heldout import compare

    name, truth, prior, widths, _, fit, kw, test = traced_split(args.log, args.duration,
                                                                args.seed, args.split)
    print(f"{name} ({truth}), {args.split} split")
    passes = {}
    for judge in ("none", "off"):
        c0 = time.process_time()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = diagnose(fit, prior, dof="all", time_limit=float("inf"),
                           prior_widths=widths, gains_judge=judge, **kw)
        passes[judge] = (res, time.process_time() - c0)
    prior_val = (passes["off"][0].validation or {}).get("prior")
    for judge, (res, cpu) in passes.items():
        v = res.validation or {}
        written = type(res.model).from_dict(res.model.to_dict())
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            held = compare(test, {"prior": prior, "written": written}, list(res.diagnosed))
        g = res.thruster_gains or {}
        print(f"\n== pass gains_judge={judge!r}: {cpu:.1f} s CPU; gains applied "
              f"{g.get('applied')}")
        if g.get("applied"):
            print("   gains: " + fmt_record(g.get("gains")))
        print("   effects written: " + ("; ".join(f"{e['dof']} {e['name']} "
                                                 + fmt_record(e.get("parameters") or {})
                                                 for e in res.model.effects) or "none"))
        print(f"   bounds hit: {res.bounds_hit}")
        print("   steps: " + "; ".join(f"{s.dof} {s.effect}" for s in res.steps))
        for key in ("prior", "all_changes", "kept_changes"):
            print(f"   validation {key}: {fmt_record(v.get(key))}")
        print(f"   removed: {v.get('removed')}; removed for own DOF: "
              f"{v.get('removed_for_own_dof')}")
        print(f"   score against the file's prior (rule): "
              f"{score(v.get('kept_changes'), prior_val)}")
        for dof, e in held.items():
            print(f"   held out {dof:6s} " + "  ".join(
                f"{m} {x:.4f}" if x is not None else f"{m} None" for m, x in e.items()))
    print(f"\n{time.process_time():.1f} s of CPU in all")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
