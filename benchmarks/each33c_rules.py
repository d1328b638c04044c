r"""Whole-log rows of the independent benchmark under variants of the validation
``validation_others="each"`` (issue 33, each33c; benchmarks/data/each33c_trace.md).

Variants (``--variant``):

- ``each``: every diagnosed DOF simulated alone, the five others logged, the prior the
  veto's only reference (:func:`stripcoef.diagnose.validate.validate_changes` with
  ``skill=False``), as measured in benchmarks/data/diagnose_independent_300s_each.md;
- ``skill``: the same with the skill veto (the veto's reference the best of the prior,
  hold-last-velocity and zero velocity; ``skill=True``, the code's default);
- ``skill_joint_gains``: ``skill``, and the thrusters' gains
  (:func:`stripcoef.diagnose.gains.validated`) validated by the joint simulation of every
  DOF, as the default validation does, instead of each DOF alone;
- ``score_joint_gains``: the same, and a DOF where the prior has no skill left out of the
  summed score too (``skill="score"``, a trial).

The rows are ``benchmarks.diagnose_independent``'s (the same seeds: a log's seed names its
vehicle and category), printed as its ``row`` lines, so that ``python -m
benchmarks.diagnose_independent --from-rows OUT --modes all`` summarises them.

Run: ``python -m benchmarks.each33c_rules --seed 29112026 --repeats 2 --variant skill
--only-seeds 29113029,29212026 > OUT``.
"""
from __future__ import annotations

import argparse
import functools
import os
import time


for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

VARIANTS = ("each", "skill", "skill_joint_gains", "score_joint_gains")


def rows_of(job, variant: str, with_oracle: bool = False) -> list[dict]:
    """``benchmarks.diagnose_independent.run_one(*job)``'s whole-log rows under ``variant``
    (module docstring); ``with_oracle``: with the truth's detectability columns."""
    import benchmarks.diagnose_independent as independent
    import stripcoef.diagnose.pipeline as pipeline
    from benchmarks.diagnose_independent import run_one
    from stripcoef.diagnose.heldout import EACH

    original, original_gains = pipeline.validate_changes, pipeline.validated

    def gains_validated(gains, val_log, prior, dofs, logged=()):
        # whole-log: the gains judged by the joint simulation (skill_joint_gains) or by each
        # DOF alone (each, skill), whatever the code's default
        if len(dofs) > 1:
            logged = [] if variant.endswith("joint_gains") else EACH
        return original_gains(gains, val_log, prior, dofs, logged)

    pipeline.validate_changes = functools.partial(
        original, skill="score" if variant.startswith("score") else variant != "each")
    pipeline.validated = gains_validated
    oracle = independent._oracle
    if not with_oracle:     # the truth's detectability and cut: not what the variants change
        independent._oracle = lambda log, prior, truth: {}
    try:
        return run_one(*job)
    finally:
        pipeline.validate_changes, pipeline.validated = original, original_gains
        independent._oracle = oracle


def main(argv=None) -> int:
    from benchmarks.diagnose_independent import VEHICLES, _progress, log_seed, run_categories

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--categories", default=None)
    ap.add_argument("--vehicles", default=",".join(VEHICLES))
    ap.add_argument("--only-seeds", default=None)
    ap.add_argument("--variant", choices=VARIANTS, default="skill")
    ap.add_argument("--oracle", action="store_true",
                    help="also the truth's detectability and cut (validation.detectability)")
    args = ap.parse_args(argv)
    every = run_categories()
    cats = args.categories.split(",") if args.categories else every
    jobs = [(vehicle, None if cat == "clean" else cat,
             log_seed(args.seed, rep, v, c), args.duration, ("all",), "each")
            for rep in range(args.repeats) for v, vehicle in enumerate(args.vehicles.split(","))
            for c, cat in enumerate(cats)]
    if args.only_seeds:
        keep = {int(x) for x in args.only_seeds.split(",")}
        jobs = [j for j in jobs if j[2] in keep]
    print(f"seed {args.seed}: {len(jobs)} logs, variant {args.variant}", flush=True)
    t0 = time.process_time()
    for job in jobs:
        for row in rows_of(job, args.variant, args.oracle):
            row["variant"] = args.variant
            _progress(row)
    print(f"CPU {time.process_time() - t0:.1f} s (user + sys of this process)", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
