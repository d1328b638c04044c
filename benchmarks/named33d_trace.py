r"""The first steps of named-first misses of the independent benchmark traced (issue 33,
named33d): what each step records for the candidates that compete for the effect's DOF --
the scale-vs-added-mass choice (``diagnose.scalechoice.choose``: each effect's test in the
model holding both, Atkinson 1970 / Davidson & MacKinnon 1981, Holm 1979), the linear
drag's test with and without the buoyancy change free (``diagnose.gainfree``), and why each
candidate was refused.

For one log of ``benchmarks.diagnose_independent`` (vehicle, category, seed; 300 s) the
diagnosis of the effect's DOF (one DOF or whole-log) is run with diagnose's defaults, or
with ``--option NAME=VALUE`` (a keyword argument of ``stripcoef.diagnose.pipeline.diagnose``)
and prints one JSON line: the steps named in the effect's DOF (effect, parameters, z, the
choice or comparison record) and the first step's candidates ``--effects`` (held-out gain,
z, the step test's p and Holm-adjusted p, why refused).

Usage:
    python -m benchmarks.named33d_trace --rows VEHICLE:CATEGORY:SEED:MODE[,...]
        [--effects thrust_effectiveness,added_mass_error,linear_drag] [--option K=V ...]

Output summarised in ``benchmarks/data/named33d_trace.md``.
"""

from __future__ import annotations

import argparse
import json
import os
import time
import warnings

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


def _value(text: str):
    """A command-line option's value: a bool, a number or the text."""
    low = text.lower()
    if low in ("true", "false"):
        return low == "true"
    try:
        return float(text) if "." in text else int(text)
    except ValueError:
        return text


def trace(vehicle: str, category: str, seed: int, mode: str, effects, options: dict,
          duration: float = 300.0) -> dict:
    """One diagnosis's record of the effect's DOF (module docstring)."""
    from stripcoef.diagnose.pipeline import diagnose
    from validation.independent import OUTSIDE, STRENGTHS, generate

    from benchmarks.diagnose_independent import _prior

    prior = _prior(vehicle)
    dof_name = (STRENGTHS.get(category) or OUTSIDE.get(category) or ("surge",))[0]
    log, truth = generate(prior.to_dict(), None if category == "clean" else category, seed,
                          duration=duration)
    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof=dof_name if mode == "dof" else "all",
                       time_limit=float("inf"), **options).to_dict()
    cpu = time.process_time() - t0
    r = (res.get("per_dof") or {dof_name: res})[dof_name]
    cands = [{"effect": c["effect"], "held_out_gain": c["held_out_gain"], "z": c["z"],
              "p": (c.get("evidence") or {}).get("p_value"),
              "p_holm": (c.get("evidence") or {}).get("p_adjusted"),
              "parameters": c["parameters"], "significant": c["significant"],
              "signature": c.get("signature"),
              "rejected_because": c["rejected_because"]}
             for c in r["candidates"] if c.get("applicable") and c["effect"] in effects]
    steps = [{"effect": s["effect"], "parameters": s["parameters"], "z": s["z"],
              "held_out_gain": s["held_out_gain"], "signature": s.get("signature"),
              "choice": s.get("choice"), "ambiguous_with": s.get("ambiguous_with")}
             for s in r["steps"]]
    every = {d: [s["effect"] for s in x["steps"]]
             for d, x in (res.get("per_dof") or {dof_name: res}).items() if x["steps"]}
    return {"vehicle": vehicle, "category": category, "seed": seed, "mode": mode,
            "dof": dof_name, "truth": truth.strength, "options": options, "cpu_s": cpu,
            "baseline_error": r["baseline_error"], "final_error": r["final_error"],
            "steps": steps, "steps_every_dof": every, "candidates": cands}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", required=True, help="VEHICLE:CATEGORY:SEED:MODE[,...]")
    ap.add_argument("--effects", default="thrust_effectiveness,added_mass_error,linear_drag")
    ap.add_argument("--option", action="append", default=[],
                    help="NAME=VALUE, a keyword argument of diagnose (repeatable)")
    ap.add_argument("--duration", type=float, default=300.0)
    args = ap.parse_args(argv)
    options = {}
    for o in args.option:
        k, _, v = o.partition("=")
        options[k] = _value(v)
    effects = set(args.effects.split(","))
    for row in args.rows.split(","):
        vehicle, category, seed, mode = row.split(":")
        rec = trace(vehicle, category, int(seed), mode, effects, options, args.duration)
        print(json.dumps(rec, default=float), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
