r"""Whole-log rows of the independent benchmark under validation variants, one selection per
log (issue 33, closed33d; benchmarks/data/closed33d_trace.md).

The validation (:func:`stripcoef.diagnose.validate.validate_changes`) decides only what is
kept: the thrusters' gains, their validation and every DOF's selection come before it. So
each log is generated and selected once, and the diagnosis's later stages (validation,
written model, read-back) run once per variant on the same selection: the pipeline's
``fit_thruster_gains``, ``validate_gains`` and ``_fit_dofs`` are replayed from the first
variant's calls in their order (``--check`` runs the first variant again on the replayed
selection and fails if any number of its row differs). What a variant cannot change, by
construction: named first, spurious steps named, clean logs' steps, dry friction's gains.

Variants (``--variants``, comma-separated; the first runs the selection):

- ``default``: the code's default (every DOF simulated together, 10-s segments);
- ``correlation``: the same, each DOF's segments of its velocity's integral time scale
  (``validation_horizon="correlation"``, :mod:`stripcoef.diagnose.horizon`);
- ``each``: ``validation_others="each"`` (each DOF alone, the others logged, the skill
  veto; 10-s segments);
- ``each_correlation``: ``each`` on the correlation horizons;
- ``each_own``, ``each_correlation_own``: the same, each removal judged on the DOFs of the
  changes it removes (``validation_judge="own"``);
- ``each_correlation_own_comb``: ``each_correlation_own`` with the skill veto's reference,
  in a DOF whose prior has no skill, the least-squares combination of the prior and the
  trivial predictors (``validation_reference="combination"``, cut33f).

The rows are ``benchmarks.diagnose_independent``'s (``row`` lines with a ``variant`` key);
``python -m benchmarks.diagnose_independent --from-rows OUT --modes all`` summarises one
variant's rows once they are split by ``variant`` (``--split OUT`` writes OUT.<variant>).

Run: ``python -m benchmarks.closed33d_variants --seed 29112026 --repeats 2
--only-seeds 29113033,29113029 > OUT``.
"""
from __future__ import annotations

import argparse
import json
import os
import time
import warnings

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

VARIANTS = {"default": ("logged", {}),
            "correlation": ("logged", {"validation_horizon": "correlation"}),
            "each": ("each", {}),
            "each_correlation": ("each", {"validation_horizon": "correlation"}),
            "each_own": ("each", {"validation_judge": "own"}),
            "each_correlation_own": ("each", {"validation_horizon": "correlation",
                                              "validation_judge": "own"}),
            # cut33f: the skill veto's reference in a DOF the prior does not predict is the
            # prior combined with the trivial predictors (diagnose/combination.py)
            "each_correlation_own_comb": ("each", {"validation_horizon": "correlation",
                                                   "validation_judge": "own",
                                                   "validation_reference": "combination"})}

#: The pipeline's stages before the validation, replayed from the first variant's calls.
REPLAYED = ("fit_thruster_gains", "validate_gains", "_fit_dofs")


def _replaying(pipeline, store: dict, record: bool):
    """Patch :data:`REPLAYED` in ``pipeline``: record their results in call order
    (``record``) or return the recorded ones. Returns the originals."""
    originals = {name: getattr(pipeline, name) for name in REPLAYED}
    counters = {name: 0 for name in REPLAYED}

    def make(name):
        def call(*args, **kw):
            k = counters[name]
            counters[name] += 1
            if record:
                store.setdefault(name, []).append(originals[name](*args, **kw))
            return store[name][k]
        return call

    for name in REPLAYED:
        setattr(pipeline, name, make(name))
    return originals


def rows_of(vehicle, category, seed, duration, variants, check=False) -> list[dict]:
    """The whole-log row of one log under each variant (module docstring)."""
    import stripcoef.diagnose.pipeline as pipeline
    from benchmarks.diagnose_independent import (_background, _diagnosed, _prior,
                                                 truth_effects)
    from validation.independent import OUTSIDE, STRENGTHS, generate

    prior = _prior(vehicle)
    dof_name = ({**STRENGTHS, **OUTSIDE}.get(category) or ("surge",))[0]
    t0 = time.process_time()
    log, truth = generate(prior.to_dict(), category, seed, duration=duration)
    t_sim = time.process_time() - t0
    store, rows = {}, []
    order = list(variants) + ([variants[0]] if check else [])
    for k, name in enumerate(order):
        others, options = VARIANTS[name]
        originals = _replaying(pipeline, store, record=k == 0)
        originals["validate_changes"] = validate = pipeline.validate_changes
        seen = {}

        def validating(*a, _validate=validate, _seen=seen, **kw):
            excl, record = _validate(*a, **kw)
            _seen["record"] = record
            return excl, record

        pipeline.validate_changes = validating
        try:
            c0 = time.process_time()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                row = _diagnosed(log, truth, prior, vehicle, category, seed, "all", dof_name,
                                 t_sim, others, False, True, options or None)
            row["t_variant"] = time.process_time() - c0
        finally:
            for attr, f in originals.items():
                setattr(pipeline, attr, f)
        row.update(_background(truth, prior.to_dict()))
        row["truth_has"] = truth_effects(log, truth, prior, row)
        row["variant"] = name
        rec = seen.get("record") or {}
        # what the validation judged with: the horizons, each model's errors, the removals
        row["validation"] = {key: rec.get(key) for key in (
            "horizon_s", "prior", "all_changes", "kept_changes", "removed",
            "removed_for_own_dof", "trivial_predictor", "combined_reference")}
        if k == len(variants):          # --check: the first variant on the replay
            first = {key: v for key, v in rows[0].items() if not key.startswith("t_")}
            again = {key: v for key, v in row.items() if not key.startswith("t_")}
            if json.dumps(first, default=float) != json.dumps(again, default=float):
                raise AssertionError(f"seed {seed}: the replayed selection changes the row")
            print(f"  seed {seed}: replay check passed", flush=True)
            continue
        rows.append(row)
    return rows


def main(argv=None) -> int:
    from benchmarks.diagnose_independent import VEHICLES, _progress, log_seed, run_categories

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--categories", default=None)
    ap.add_argument("--vehicles", default=",".join(VEHICLES))
    ap.add_argument("--only-seeds", default=None)
    ap.add_argument("--variants", default="default,correlation")
    ap.add_argument("--check", action="store_true",
                    help="run the first variant again on the replayed selection")
    ap.add_argument("--split", default=None,
                    help="write the row lines of this output file per variant and exit")
    args = ap.parse_args(argv)
    if args.split:
        from stripcoef.files import read_text
        lines = [x for x in read_text(args.split, kind="benchmark output").splitlines()
                 if " row {" in x]
        for name in VARIANTS:
            mine = [x for x in lines if json.loads(x.split(" row ", 1)[1])["variant"] == name]
            if mine:
                with open(f"{args.split}.{name}", "w", encoding="utf-8") as f:
                    f.write("\n".join(mine) + "\n")
        return 0
    variants = args.variants.split(",")
    for v in variants:
        if v not in VARIANTS:
            ap.error(f"--variants: {v!r} is not one of {', '.join(VARIANTS)}")
    if args.seed is None:
        ap.error("--seed: required to run")
    every = run_categories()
    cats = args.categories.split(",") if args.categories else every
    jobs = [(vehicle, None if cat == "clean" else cat,
             log_seed(args.seed, rep, v, every.index(cat)))
            for rep in range(args.repeats) for v, vehicle in enumerate(args.vehicles.split(","))
            for cat in cats]
    if args.only_seeds:
        keep = {int(x) for x in args.only_seeds.split(",")}
        jobs = [j for j in jobs if j[2] in keep]
    print(f"seed {args.seed}: {len(jobs)} logs, variants {', '.join(variants)}", flush=True)
    t0 = time.process_time()
    for vehicle, cat, seed in jobs:
        for row in rows_of(vehicle, cat, seed, args.duration, variants, args.check):
            print(f"  variant {row['variant']} ({row['t_variant']:.1f} s CPU)", flush=True)
            _progress(row)
    print(f"CPU {time.process_time() - t0:.1f} s (user + sys of this process)", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
