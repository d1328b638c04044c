"""Whole-log dead bands per DOF (issue 33, fresh33g): in each whole-log row of
``benchmarks.diagnose_independent`` outputs, the DOFs where a dead band step was named, its value
and whether the written model kept it; and the count of logs whose written model holds a dead
band in some DOFs and not in others. In the independent simulator every thruster has the same
dead band (``validation.independent``: the truth's ``deadband`` set on each thruster), and a dead
zone is the thruster's own (Yoerger, Cooke & Slotine 1990), so a written model that keeps it in
one DOF and removes it, or never names it, in another DOF the same thrusters drive is not one
vehicle's model. A count, not a model change: benchmarks/data/fresh33g_compare.md section 2.7.

``python -m benchmarks.deadband_consistency OUTPUT[,OUTPUT...] [--category deadband]``

``--run BASE:SEED[,BASE:SEED...]``: the oracle of a rule not adopted. Each log (a log seed of the
benchmark's base seed BASE) is diagnosed whole-log as ``benchmarks.diagnose_independent`` does
(its ``run_one``, the default options), with the dead band one change of every DOF that holds
it in the validation (:func:`one_change`: :func:`stripcoef.diagnose.validate._shared` also
returns ``deadband`` when more than one DOF holds it, as it does for the current; removed in
all its DOFs when removed in one, and not removed with a DOF's calibration, refitted without
it), inside the run only; its ``row`` lines are printed for ``--from-rows`` and
``fresh_compare --rows``. ``--effect thrust_effectiveness``: the same oracle for the thrust
scale (one change of every DOF that names one).
"""
from __future__ import annotations

import argparse
import contextlib
import json
import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


@contextlib.contextmanager
def one_change(effect: str = "deadband"):
    """``stripcoef.diagnose.validate._shared`` with ``effect`` (a thruster effect: the dead
    band, or the thrust effectiveness of section 2.6) among the effects that are one change
    of several DOFs (module docstring), inside the block only."""
    from stripcoef.diagnose import validate
    original = validate._shared

    def shared(changes):
        n = sum(1 for c in changes if c[0] == "effect" and c[2] == effect)
        return original(changes) | ({effect} if n > 1 else set())

    validate._shared = shared
    try:
        yield
    finally:
        validate._shared = original


def rows_of(paths: list[str]) -> list[dict]:
    """The whole-log ``row`` JSON of the outputs ``paths``."""
    from stripcoef.files import read_text
    out = []
    for path in paths:
        for line in read_text(path, kind="benchmark output").splitlines():
            if " row {" in line:
                r = json.loads(line.split(" row ", 1)[1])
                if r["mode"] == "all":
                    out.append(r)
    return out


def dead_bands(row: dict) -> dict:
    """``{dof: (value, kept)}`` of the row's dead band steps (the first in each DOF)."""
    out = {}
    for d, steps in (row.get("step_detail") or {}).items():
        for s in steps:
            if s["effect"] == "deadband" and d not in out:
                out[d] = (float(s["parameters"]["deadband"]), bool(s.get("kept", True)))
    return out


def classify(row: dict) -> str:
    """``none`` (no dead band named), ``all kept``, ``all removed``, ``mixed`` (kept in some
    DOFs, removed in others) or ``own DOF missing`` (named elsewhere, not in the row's own
    DOF, where the truth's effect is)."""
    bands = dead_bands(row)
    if not bands:
        return "none"
    if row["category"] == "deadband" and row["dof"] not in bands:
        return "own DOF missing"
    kept = {k for _, k in bands.values()}
    return "mixed" if kept == {True, False} else ("all kept" if kept == {True} else "all removed")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("outputs", nargs="?", default="",
                    help="comma-separated printed outputs (their 'row' lines)")
    ap.add_argument("--run", default="",
                    help="BASE:SEED[,...]: diagnose these logs whole-log with one dead band "
                         "change (the oracle; module docstring) and print their rows")
    ap.add_argument("--effect", default="deadband",
                    help="with --run: the effect made one change (deadband, "
                         "thrust_effectiveness)")
    ap.add_argument("--category", default="deadband",
                    help="only rows of this category ('any': every row that names a dead band)")
    args = ap.parse_args(argv)
    if args.run:
        import time

        from benchmarks.diagnose_independent import log_of, run_one
        for spec in args.run.split(","):
            base, seed = (int(x) for x in spec.split(":"))
            vehicle, category, _ = log_of(base, seed)
            t0 = time.process_time()
            with one_change(args.effect):
                rows = run_one(vehicle, None if category == "clean" else category, seed,
                               300.0, ("all",))
            for r in rows:
                print(f"  {vehicle} {category} seed {seed} all: first {r['first']}, cut "
                      f"{r['cut']:.2f} ({time.process_time() - t0:.1f} s CPU) row "
                      + json.dumps(r, default=float), flush=True)
        return 0
    rows = rows_of(args.outputs.split(","))
    if args.category != "any":
        rows = [r for r in rows if r["category"] == args.category]
    rows = [r for r in rows if args.category != "any" or dead_bands(r)]
    counts = {}
    for r in sorted(rows, key=lambda r: (r["vehicle"], r["seed"])):
        kind = classify(r)
        counts[kind] = counts.get(kind, 0) + 1
        text = ", ".join(f"{d} {v:.4g} {'kept' if k else 'removed'}"
                         for d, (v, k) in dead_bands(r).items()) or "-"
        truth = f" (truth {r['truth']:.4g})" if r["category"] == "deadband" else ""
        print(f"- {r['vehicle']} {r['category']} {r['seed']}{truth}: {kind}: {text}")
    print(f"{len(rows)} whole-log rows: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
