"""The one-DOF thruster gains validated alone on the prior or inside the written model (issue 33,
gains33f): each log of ``benchmarks.diagnose_independent`` (its seeding) simulated once and
diagnosed one DOF with ``gains_judge="prior"`` (the default) and ``"written"``
(:mod:`stripcoef.diagnose.gainjudge`), the two rows side by side.

Each variant's rows are printed as ``benchmarks.diagnose_independent`` prints them
(``<variant> ... row {json}``) and, with ``--rows-out PREFIX``, written to ``PREFIX_prior.txt``
and ``PREFIX_written.txt`` for ``python -m benchmarks.diagnose_independent --from-rows`` and
``python -m benchmarks.fresh_compare --rows``. Per log: the gains' record in each variant (p,
applied, the validation's numbers), the effect named first, the magnitude error, the cut, the
criteria failed, and each diagnosis's CPU time. No threshold of the diagnosis is changed.

Usage:
    python -m benchmarks.gains33f_compare --seed S [--vehicles bluerov2_heavy] [--repeats 2]
        [--categories C,...] [--only-seeds A,B] [--rows-out PREFIX]
"""

from __future__ import annotations

import argparse
import json
import os
import time

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

VARIANTS = {"prior": {"gains_judge": "prior"}, "written": {"gains_judge": "written"}}


def _gains_text(row: dict, res_gains: dict | None) -> str:
    rec = res_gains or {}
    if not rec:
        return "gains none"
    v = rec.get("validation") or {}
    extra = ""
    if "sum_squared_ratio" in v:
        extra = f", alone on the prior {v['sum_squared_ratio']:.4f}"
    elif "score_with_gains" in v:
        extra = (f", written with {v['score_with_gains'][1]:.4f} / without "
                 f"{v['score_without_gains'][1]:.4f}")
    return (f"gains p {rec.get('test', {}).get('p_value', float('nan')):.2g} applied "
            f"{bool(rec.get('applied'))}{extra}")


def one(vehicle: str, category: str | None, seed: int, duration: float) -> dict:
    """The rows of one log in each variant (module docstring)."""
    import warnings

    from benchmarks.diagnose_independent import (_background, _diagnosed, _oracle, _prior,
                                                 truth_effects)  # noqa: F401
    from validation.independent import OUTSIDE, STRENGTHS, generate
    prior = _prior(vehicle)
    dof = ({**STRENGTHS, **OUTSIDE}.get(category) or ("surge",))[0]
    t0 = time.process_time()
    log, truth = generate(prior.to_dict(), category, seed, duration=duration)
    t1 = time.process_time()
    found = _oracle(log, prior, truth)
    out = {}
    for name, options in VARIANTS.items():
        from stripcoef.diagnose import pipeline
        captured = {}
        real = pipeline.diagnose

        def spy(*a, **k):
            res = real(*a, **k)
            captured["gains"] = res.thruster_gains
            return res
        pipeline.diagnose = spy
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                row = {**_diagnosed(log, truth, prior, vehicle, category, seed, "dof", dof,
                                    t1 - t0, "logged", False, True, options),
                       **_background(truth, prior.to_dict()), **found}
        finally:
            pipeline.diagnose = real
        out[name] = (row, captured.get("gains"))
    return out


def main(argv=None) -> int:
    from benchmarks.diagnose_independent import VEHICLES, log_seed, run_categories
    from benchmarks.fresh_compare import row_failures

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--vehicles", default=",".join(VEHICLES))
    ap.add_argument("--categories", default=None)
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--only-seeds", default=None)
    ap.add_argument("--rows-out", default=None)
    args = ap.parse_args(argv)
    every = run_categories()
    cats = args.categories.split(",") if args.categories else every
    keep = None if not args.only_seeds else {int(x) for x in args.only_seeds.split(",")}
    files = ({n: open(f"{args.rows_out}_{n}.txt", "w", encoding="utf-8") for n in VARIANTS}
             if args.rows_out else {})
    try:
        for rep in range(args.repeats):
            for vehicle in args.vehicles.split(","):
                v = VEHICLES.index(vehicle)    # the full run's seeding
                for cat in cats:
                    seed = log_seed(args.seed, rep, v, every.index(cat))
                    if keep is not None and seed not in keep:
                        continue
                    got = one(vehicle, None if cat == "clean" else cat, seed, args.duration)
                    for name, (row, gains) in got.items():
                        fails = row_failures(row)
                        print(f"  {name} {vehicle} {cat} {seed} {row['dof']}: "
                              f"{_gains_text(row, gains)}; first {row['first']}, magnitude "
                              f"error {row.get('magnitude_error', float('nan')):.3f}, cut "
                              f"{row['cut']:.2f}, CPU {row['t_diagnose']:.1f} s; fails: "
                              f"{'; '.join(fails) or 'none'}", flush=True)
                        if name in files:
                            files[name].write(f"  {name} row " + json.dumps(row, default=float)
                                              + "\n")
                            files[name].flush()
    finally:
        for f in files.values():
            f.close()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
