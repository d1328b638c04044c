"""Whole-log rows of two ``benchmarks.diagnose_independent`` outputs paired log by log (issue 33,
spur33f): every spurious step (an effect in a DOF the truth's effect is not in, the benchmark's
own rule, ``diagnose_independent._is_spurious``) with its z, fitted parameters and whether the
written model kept it, and every row whose failed criteria (``fresh_compare.row_failures``) or
right steps differ between the two runs.

``python -m benchmarks.spur33f_pairs BASE.log [OTHER.log] [--vehicles V,...]``

BASE, OTHER: the printed outputs (their ``row`` lines). With one output, the spurious steps
only. A right step is a whole-log step that is not spurious (the log's own effect in its DOF,
the truth's background, a thruster effect the truth has on the log's commands): a right step
named in BASE and missing in OTHER is a lost right step. Measured text:
benchmarks/data/spur33f_trace.md.
"""
from __future__ import annotations

import argparse
import json


def rows_of(path: str) -> dict:
    """``{(seed, mode): row}`` of the ``row`` lines of one output."""
    out = {}
    with open(path, encoding="utf-8") as f:
        for line in f:
            if " row {" in line:
                r = json.loads(line.split(" row ", 1)[1])
                out[(r["seed"], r["mode"])] = r
    return out


def steps_of(row: dict) -> tuple[list, list]:
    """``(spurious, right)``: the whole-log steps of ``row`` as ``(dof, effect, z, parameters,
    kept)``, split by the benchmark's rule."""
    from benchmarks.diagnose_independent import _is_spurious

    spurious, right = [], []
    for d, detail in row.get("step_detail", {}).items():
        for i, s in enumerate(detail):
            k = sum(x["effect"] == s["effect"] for x in detail[:i])
            rec = (d, s["effect"], s.get("z"), s.get("parameters", {}), s.get("kept", True))
            (spurious if _is_spurious(row, d, s["effect"], k) else right).append(rec)
    return spurious, right


def _text(rec) -> str:
    d, e, z, pars, kept = rec
    p = ", ".join(f"{k} {v:.4g}" for k, v in pars.items())
    return f"{d} {e} ({p}) z {z:.1f}" + (" kept" if kept else " removed")


def counts(rows: list[dict]) -> dict:
    """The whole-log criteria's counts over ``rows`` (the benchmark's rules)."""
    from benchmarks.fresh_compare import row_failures
    from validation.independent import OUTSIDE, STRENGTHS

    c = {"library rows": 0, "named first": 0, "magnitude within 15 %": 0, "error cut >= 3x": 0,
         "spurious named": 0, "spurious kept": 0, "clean rows": 0, "clean other": 0,
         "dry rows": 0, "dry not flagged": 0}
    for r in rows:
        fails = row_failures(r)
        if r["category"] in STRENGTHS:
            c["library rows"] += 1
            c["named first"] += not any(f.startswith("named first") for f in fails)
            c["magnitude within 15 %"] += not any(f.startswith("magnitude") for f in fails)
            c["error cut >= 3x"] += r["cut"] >= 3
            sp, _ = steps_of(r)
            c["spurious named"] += bool(sp)
            c["spurious kept"] += any(s[4] for s in sp)
        elif r["category"] == "clean":
            c["clean rows"] += 1
            c["clean other"] += bool(fails)
        elif r["category"] in OUTSIDE:
            c["dry rows"] += 1
            c["dry not flagged"] += bool(fails)
    return c


def main(argv=None) -> int:
    from benchmarks.fresh_compare import row_failures

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("base")
    ap.add_argument("other", nargs="?")
    ap.add_argument("--vehicles", default="", help="comma-separated: only these vehicles")
    args = ap.parse_args(argv)
    keep = set(args.vehicles.split(",")) if args.vehicles else None
    base = {k: r for k, r in rows_of(args.base).items()
            if k[1] == "all" and (keep is None or r["vehicle"] in keep)}
    other = None
    if args.other:
        other = {k: r for k, r in rows_of(args.other).items() if k[1] == "all"}
        base = {k: r for k, r in base.items() if k in other}
    print(f"# {len(base)} whole-log rows")
    for k in sorted(base, key=lambda k: (base[k]["vehicle"], base[k]["category"], k[0])):
        r = base[k]
        sp, right = steps_of(r)
        head = f"{r['vehicle']} {r['category']} {r['seed']}"
        if other is None:
            if sp:
                print(f"{head}: " + "; ".join(_text(s) for s in sp))
            continue
        o = other[k]
        osp, oright = steps_of(o)
        fb, fo = row_failures(r), row_failures(o)
        lost = [s for s in right if (s[0], s[1]) not in {(x[0], x[1]) for x in oright}]
        gained = [s for s in oright if (s[0], s[1]) not in {(x[0], x[1]) for x in right}]
        if fb != fo or lost or gained or [s[:2] for s in sp] != [s[:2] for s in osp]:
            print(f"{head}: cut {r['cut']:.2f} -> {o['cut']:.2f}")
            print(f"  base : {fb or 'passes'}")
            print(f"  other: {fo or 'passes'}")
            for s in sp:
                print(f"  base spurious: {_text(s)}")
            for s in osp:
                print(f"  other spurious: {_text(s)}")
            for s in lost:
                print(f"  right step lost: {_text(s)}")
            for s in gained:
                print(f"  right step gained: {_text(s)}")
    for name, rows in (("base", base), ("other", other)):
        if rows is not None:
            print(f"{name}: " + ", ".join(f"{k} {v}" for k, v in counts(list(rows.values()))
                                            .items()))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
