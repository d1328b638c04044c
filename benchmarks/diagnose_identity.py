"""Same diagnoses, less CPU: every `diagnose()` result of a set of seeded logs written once
and compared after a change that must not change what the diagnosis decides (issue 33,
speed; issue 31, the gains' CPU).

The cases are seeded logs of the independent 6-DOF simulator (``validation.independent``,
both vehicles, whole-log and per-DOF, clean and with a library effect) and the shipped
sample ``rov_tether.csv`` against ``rov_prior.json`` in surge (the tutorial's diagnosis).
For each case the whole JSON contract (:meth:`Diagnosis.to_dict`) and the written model
(``model.to_dict()``) are flattened to ``path -> value`` (the reference's checkout folder
in a string read as this checkout's). ``--compare`` then requires the
same paths, equal strings and booleans (the named, kept and removed steps, the reasons) and
numbers equal within ``--rtol`` relative to each number (with ``--atol`` for numbers near
0), and prints each case's CPU (``time.process_time``) before and after.

Usage (the reference from one checkout, the comparison from another):
    python -m benchmarks.diagnose_identity --write before.json [--quick]
    python -m benchmarks.diagnose_identity --compare before.json [--rtol 1e-9]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time
import warnings
from pathlib import Path

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

ROOT = Path(__file__).resolve().parent.parent

#: (name, vehicle, effect or None, seed, duration [s], dof); the first four are ``--quick``.
CASES = (
    ("bluerov2_clean_all", "bluerov2_heavy", None, 5, 120.0, "all"),
    ("videoray_lag_all", "videoray_pro3", "thruster_lag", 31, 120.0, "all"),
    ("sample_rov_tether_surge", "sample", None, 0, 0.0, "surge"),
    ("bluerov2_tether_all", "bluerov2_heavy", "tether_drag", 7, 120.0, "all"),
    ("videoray_deadband_all", "videoray_pro3", "deadband", 11, 120.0, "all"),
    ("bluerov2_current_surge", "bluerov2_heavy", "current", 3, 120.0, "surge"),
    ("videoray_delay_all", "videoray_pro3", "actuation_delay", 17, 120.0, "all"),
    # the per-thruster gains make this log's lag and delay both needed in every DOF: the
    # validation then simulates twelve timing laws (issue 31: +67 % CPU per whole-log run)
    ("bluerov2_lag_gains_all", "bluerov2_heavy", "thruster_lag", 725909, 120.0, "all"),
)


def _log_and_prior(vehicle, effect, seed, duration):
    from stripcoef.logfile import read_log
    from stripcoef.modelfile import load_model
    from stripcoef.samples import path

    if vehicle == "sample":
        return read_log(path("rov_tether.csv")), load_model(path("rov_prior.json"))
    import stripcoef
    from validation.independent import generate

    prior = stripcoef.estimate(ROOT / "geometry" / f"{vehicle}.yaml")
    log, _ = generate(prior.to_dict(), effect, seed, duration=duration)
    return log, prior


def flatten(value, prefix="", out=None) -> dict:
    """``value`` (plain JSON types) as ``path -> leaf``."""
    out = {} if out is None else out
    if isinstance(value, dict):
        for k, v in value.items():
            flatten(v, f"{prefix}/{k}", out)
    elif isinstance(value, (list, tuple)):
        for k, v in enumerate(value):
            flatten(v, f"{prefix}[{k}]", out)
    else:
        out[prefix] = value
    return out


def run_case(case) -> dict:
    """One case's diagnosis: its CPU [s] and flattened result."""
    from stripcoef.diagnose import diagnose
    from stripcoef.model import plain

    name, vehicle, effect, seed, duration, dof = case
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        log, prior = _log_and_prior(vehicle, effect, seed, duration)
        c0 = time.process_time()
        res = diagnose(log, prior, dof=dof, time_limit=float("inf"),
                       resimulate=vehicle == "sample")
        cpu = time.process_time() - c0
    flat = flatten(plain(res.to_dict()), "/result")
    flatten(plain(res.model.to_dict()), "/model", flat)
    steps = [f"{s.dof} {s.effect} kept={s.kept}" for s in res.steps]
    return {"cpu": cpu, "steps": steps, "flat": flat}


def _differs(a, b, rtol, atol) -> bool:
    if isinstance(a, bool) or isinstance(b, bool) or not isinstance(a, (int, float)) \
            or not isinstance(b, (int, float)):
        return a != b
    if math.isnan(a) or math.isnan(b):
        return not (math.isnan(a) and math.isnan(b))
    if math.isinf(a) or math.isinf(b):
        return a != b
    return abs(a - b) > atol + rtol * max(abs(a), abs(b))


def compare(ref: dict, new: dict, rtol: float, atol: float) -> tuple[list, float]:
    """``(differences, largest relative difference of the numbers)`` of two flat results."""
    out, worst = [], 0.0
    for key in sorted(set(ref) | set(new)):
        if key not in ref or key not in new:
            out.append(f"{key}: only in the {'reference' if key in ref else 'new run'}")
            continue
        a, b = ref[key], new[key]
        if _differs(a, b, rtol, atol):
            out.append(f"{key}: {a!r} -> {b!r}")
        elif isinstance(a, float) and isinstance(b, float) and math.isfinite(a) \
                and math.isfinite(b) and max(abs(a), abs(b)) > atol:
            worst = max(worst, abs(a - b) / max(abs(a), abs(b)))
    return out, worst


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    group = ap.add_mutually_exclusive_group(required=True)
    group.add_argument("--write", type=Path, help="write the reference results (JSON)")
    group.add_argument("--compare", type=Path, help="compare with these reference results")
    ap.add_argument("--quick", action="store_true", help="the first four cases only")
    ap.add_argument("--cases", help="comma-separated case names (default: all)")
    ap.add_argument("--rtol", type=float, default=1e-9)
    ap.add_argument("--atol", type=float, default=1e-12)
    args = ap.parse_args(argv)

    cases = CASES[:4] if args.quick else CASES
    if args.cases:
        cases = [c for c in CASES if c[0] in args.cases.split(",")]
    ref = json.loads(args.compare.read_text()) if args.compare else None
    if ref is not None:         # its checkout folder read as this one
        root = ref.pop("_root", None)
        for case in ref.values():
            case["flat"] = {k: v.replace(root, str(ROOT)) if root and isinstance(v, str)
                            else v for k, v in case["flat"].items()}
    results, bad, total = {}, 0, [0.0, 0.0]
    for case in cases:
        name = case[0]
        if ref is not None and name not in ref:
            print(f"{name}: not in {args.compare}, skipped")
            continue
        r = run_case(case)
        results[name] = r
        line = f"{name}: {r['cpu']:.2f} s CPU; steps: {'; '.join(r['steps']) or 'none'}"
        if ref is not None:
            diffs, worst = compare(ref[name]["flat"], r["flat"], args.rtol, args.atol)
            total[0] += ref[name]["cpu"]
            total[1] += r["cpu"]
            line += (f"\n  reference {ref[name]['cpu']:.2f} s CPU; {len(r['flat'])} values, "
                     f"{len(diffs)} differ beyond rtol {args.rtol:g}; largest relative "
                     f"difference {worst:.2g}")
            for d in diffs[:20]:
                line += f"\n    {d}"
            bad += bool(diffs)
        print(line, flush=True)
    if args.write:
        if args.write.exists() and args.cases:     # added to the reference
            results = {**json.loads(args.write.read_text()), **results}
        args.write.write_text(json.dumps({**results, "_root": str(ROOT)}))
    else:
        print(f"total CPU: reference {total[0]:.1f} s, this run {total[1]:.1f} s; "
              f"{bad} case(s) differ")
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
