"""One whole-log (or one-DOF) diagnosis of the independent benchmark's logs with every model the
validation scored printed: which changes were left out and each DOF's free-simulation error
(issue 33, adopt33g: the six whole-log options' kept spurious steps traced,
benchmarks/data/adopt33g_trace.md).

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.adopt33g_trace BASE LOG:CONFIG[:MODE] ...

``BASE`` is the run's base seed, ``LOG`` a log seed of it (``benchmarks.diagnose_independent.
log_of`` names its vehicle and category), ``CONFIG`` ``default``, ``bundle`` (the six options:
``validation_others="each"``, ``validation_horizon="correlation"``, ``validation_judge="own"``,
``validation_reference="combination"``, ``noise_with_bias``, ``linked_gains="identified"``),
``-a,b`` (the bundle less options a, b) or ``+a,b`` (the default plus a, b); ``MODE`` ``all``
(default) or ``dof``. Each diagnosis's result is written to ``--json DIR`` when given.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import time
import warnings

BUNDLE = {"validation_others": "each", "validation_horizon": "correlation",
          "validation_judge": "own", "validation_reference": "combination",
          "noise_with_bias": True, "linked_gains": "identified"}
DEFAULTS = {"validation_others": "logged", "validation_horizon": 10.0,
            "validation_judge": "all", "validation_reference": "trivial",
            "noise_with_bias": False, "linked_gains": False}


def options(config: str) -> dict:
    """The diagnosis's options of a ``CONFIG`` word (module docstring)."""
    if config == "default":
        return dict(DEFAULTS)
    if config == "bundle":
        return dict(BUNDLE)
    if config[:1] in "+-":
        out = dict(DEFAULTS if config[0] == "+" else BUNDLE)
        for name in filter(None, config[1:].split(",")):
            out[name] = (BUNDLE if config[0] == "+" else DEFAULTS)[name]
        return out
    raise SystemExit(f"not a configuration: {config!r}; expected default, bundle, -a,b or +a,b")


@contextlib.contextmanager
def scored(lines: list):
    """The validation's scored models recorded in ``lines`` (each: the changes left out and
    the DOFs' errors), by wrapping the model surgery and the free-simulation losses."""
    from stripcoef.conventions import DOF
    from stripcoef.diagnose import horizon, validate

    state = {"key": None}
    made, losses = validate.calibrated_model, horizon.dof_losses

    def model(prior, per, fits, key=frozenset()):
        state["key"] = key
        return made(prior, per, fits, key)

    def dof_losses(val_log, m, dofs, **kw):
        got = losses(val_log, m, dofs, **kw)
        left = sorted(f"{c[2]}/{c[1]}" if c[0] == "effect" else f"{c[1]} calibration"
                      for c in (state["key"] or ()))
        err = None if got is None else horizon.rms(got)
        lines.append(f"   left out {left or 'nothing'}: " + (
            "diverges" if err is None else
            ", ".join(f"{DOF[i]} {v:.4f}" for i, v in zip(dofs, err))))
        state["key"] = None
        return got

    validate.calibrated_model, horizon.dof_losses = model, dof_losses
    try:
        yield lines
    finally:
        validate.calibrated_model, horizon.dof_losses = made, losses


def trace(base: int, log_seed: int, config: str, mode: str = "all", logs=None) -> tuple:
    """``(text, result)``: the diagnosis of log ``log_seed`` of base seed ``base`` with the
    options of ``config`` (:func:`options`), its steps, gains, validation record and every
    scored model (:func:`scored`); ``logs`` caches the generated logs."""
    from benchmarks.diagnose_independent import _prior, log_of
    from stripcoef.diagnose.pipeline import diagnose
    from validation.independent import STRENGTHS, generate

    vehicle, category, _ = log_of(base, log_seed)
    logs = {} if logs is None else logs
    if log_seed not in logs:
        prior = _prior(vehicle)
        logs[log_seed] = (prior, *generate(prior.to_dict(),
                                           None if category == "clean" else category,
                                           log_seed, duration=300.0))
    prior, log, truth = logs[log_seed]
    dof = (STRENGTHS.get(category) or ("surge",))[0]
    out = [f"## {vehicle} {category} {log_seed}, {config}, {mode} (truth {truth.strength:.4g})"]
    t0 = time.process_time()
    with warnings.catch_warnings(), scored(out):
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof="all" if mode == "all" else dof,
                       time_limit=float("inf"), **options(config)).to_dict()
    out.append(f"   ({time.process_time() - t0:.1f} s of CPU)")
    gains = res.get("thruster_gains") or {}
    if gains.get("gains"):
        out.append("   gains " + ("applied " if gains.get("applied") else "not applied ")
                   + ", ".join(f"{k} {float(v):.3f}" for k, v in gains["gains"].items()))
    for link in gains.get("links") or ():
        out.append(f"   link {link['groups']} through {link['dofs']}: information ratio "
                   f"{link['information_ratio']:.3f}, linked {link['linked']}")
    per = res.get("per_dof") or {dof: res}
    for d, r in per.items():
        cal = r.get("calibration") or {}
        out.append(f"   {d}: calibration kept {cal.get('kept')}")
        for s in r["steps"]:
            out.append(f"     {s['effect']} kept {s.get('kept')} z {s.get('z', 0):.2f} "
                       f"held-out gain {s.get('held_out_gain')} "
                       f"{s.get('final_parameters', s['parameters'])}")
        for w in r.get("withdrawn") or ():
            out.append(f"     withdrawn {w['effect']} {w['parameters']}: {w['reason']}")
    val = res.get("validation") or {}
    for key in ("horizon_s", "prior", "trivial_predictor", "combined_reference", "all_changes",
                "kept_changes", "removed_for_own_dof", "removed"):
        if key in val:
            out.append(f"   validation {key}: {val[key]}")
    return "\n".join(out), res


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("base", type=int)
    ap.add_argument("jobs", nargs="+", help="LOG:CONFIG[:MODE]")
    ap.add_argument("--json", default=None, help="folder for each diagnosis's result")
    args = ap.parse_args(argv)
    logs = {}
    for job in args.jobs:
        parts = job.split(":")
        text, res = trace(args.base, int(parts[0]), parts[1],
                          parts[2] if len(parts) > 2 else "all", logs)
        print(text, flush=True)
        if args.json:
            from pathlib import Path
            path = Path(args.json) / f"{parts[0]}_{parts[1]}.json"
            path.write_text(json.dumps(res, default=str))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
