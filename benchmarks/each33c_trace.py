r"""Trace of the whole-log validation with ``validation_others="each"`` on logs of the
independent simulator (issue 33, each33c): which steps it keeps, and why their DOF's
decoupled free simulation passes them.

For each log seed (a log of ``python -m benchmarks.diagnose_independent --seed 29112026
--repeats 2``: its seed names the vehicle and the category) the whole-log diagnosis runs as
the benchmark runs it with ``validation_others="each"`` (or ``--others``); the arguments of
its validation (:func:`stripcoef.diagnose.validate.validate_changes`) and of the thruster
gains' validation (:func:`stripcoef.diagnose.gains.validated`) are kept. For every change the
validation judged, the DOFs' decoupled free-simulation errors (each DOF alone, the five
others logged, :data:`stripcoef.diagnose.heldout.EACH`) of the kept model with and without
that change are recomputed, with the per-segment paired difference of the squared errors in
the change's own DOF (mean, its standard error over the segments, and the Diebold-Mariano
statistic of :func:`stripcoef.diagnose.heldout.diebold_mariano`).

Run: ``python -m benchmarks.each33c_trace --seeds 29113029,29212026,29113033`` (one JSON line
per log). Output in ``benchmarks/data/each33c_trace.md``.
"""
from __future__ import annotations

import argparse
import json
import os
import time
import warnings

import numpy as np

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

#: The benchmark's vehicles in the order of its seeds' thousands digit.
VEHICLES = ("videoray_pro3", "bluerov2_heavy")


def log_of(seed: int, base: int = 29112026) -> tuple[str, str | None]:
    """``(vehicle, category)`` of a log seed of ``benchmarks.diagnose_independent``'s run
    from ``base`` (:func:`benchmarks.diagnose_independent.log_of`)."""
    from benchmarks.diagnose_independent import log_of as run_log

    vehicle, cat, _ = run_log(base, seed)
    return vehicle, (None if cat == "clean" else cat)


def trace(seed: int, others: str = "each", options: dict | None = None) -> dict:
    """One log's trace (module docstring) as a dict."""
    import stripcoef.diagnose.pipeline as pipeline
    from benchmarks.diagnose_independent import _prior
    from stripcoef.conventions import DOF
    from stripcoef.diagnose.calibrate import _changes, calibrated_model
    from stripcoef.diagnose.heldout import (EACH, diebold_mariano, hold_last_velocity_errors,
                                            segment_squared_errors, zero_velocity_errors)
    from stripcoef.diagnose.validate import partners
    from validation.independent import generate

    vehicle, category = log_of(seed)
    prior = _prior(vehicle)
    seen = {}
    original, original_gains = pipeline.validate_changes, pipeline.validated

    def spy(val_log, model, per, fits, dofs, **kw):
        seen.update(val_log=val_log, model=model, per=per, fits=fits, dofs=list(dofs),
                    logged=kw.get("logged", ()))
        out = original(val_log, model, per, fits, dofs, **kw)
        seen["excl"], seen["record"] = out
        return out

    def spy_gains(gains, val_log, model, dofs, logged=()):
        out = original_gains(gains, val_log, model, dofs, logged)
        seen["gains"] = {"applied": bool(out.applied), "validation": out.validation}
        return out

    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        log, truth = generate(prior.to_dict(), category, seed, duration=300.0)
        pipeline.validate_changes, pipeline.validated = spy, spy_gains
        try:
            res = pipeline.diagnose(log, prior, dof="all", time_limit=float("inf"),
                                    validation_others=others, **(options or {})).to_dict()
        finally:
            pipeline.validate_changes, pipeline.validated = original, original_gains
    cpu = time.process_time() - t0
    val_log, model, per, fits = seen["val_log"], seen["model"], seen["per"], seen["fits"]
    dofs, excl = seen["dofs"], set(seen["excl"])
    changes = _changes(per)

    def run(ex):
        m = calibrated_model(model, per, fits, frozenset(partners(set(ex), changes)))
        return segment_squared_errors(val_log, m, dofs, logged=EACH)

    def rms(got):
        return None if got is None else {
            DOF[j]: float(np.sqrt(v)) for j, v in zip(dofs, np.sum(got[0], axis=0)
                                                       / np.sum(got[1]))}

    base, kept = run(set(changes)), run(excl)
    judged = {}
    for c in changes:
        name = " ".join(map(str, c))
        if c in excl:       # a removed change: the kept model with it (and its partners)
            back = {p for p in excl if p == c or (c[0] == "calibration" and p[1] == c[1])}
            judged[name] = {"removed": True, "with": rms(run(excl - back))}
            continue
        without = run(excl | {c})
        k = dofs.index(DOF.index(c[1]))
        entry = {"without": rms(without)}
        if without is not None and kept is not None:
            d = (kept[0][:, k] - without[0][:, k]) / kept[1]
            entry["paired_mse_difference"] = [float(d.mean()),
                                              float(d.std(ddof=1) / np.sqrt(d.size))]
            entry["dm_kept_vs_without"] = diebold_mariano(kept[0][:, k], without[0][:, k])
            entry["segments_better"] = int(np.sum(d < 0))
            entry["segments"] = int(d.size)
        judged[name] = entry
    steps = {d: [{"effect": s["effect"], "kept": s.get("kept"),
                  "parameters": s.get("final_parameters") or s.get("parameters"),
                  "z": s.get("z"), "held_out_gain": s.get("held_out_gain")}
                 for s in r["steps"]] for d, r in (res.get("per_dof") or {}).items()
             if r["steps"]}
    return {"seed": seed, "vehicle": vehicle, "category": category, "others": others,
            "options": options or {}, "diagnosed": [DOF[j] for j in dofs],
            "gains": seen.get("gains"), "steps": steps,
            "removed": seen["record"]["removed"],
            "removed_for_own_dof": seen["record"]["removed_for_own_dof"],
            "prior": rms(base), "kept": rms(kept), "judged": judged,
            "hold_last_velocity": dict(zip([DOF[j] for j in dofs],
                                           hold_last_velocity_errors(val_log, dofs))),
            "zero_velocity": dict(zip([DOF[j] for j in dofs],
                                      zero_velocity_errors(val_log, dofs))),
            "per_dof_test": seen["record"].get("per_dof_test"), "cpu_s": cpu}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seeds", default="29113029,29212026,29113033")
    ap.add_argument("--others", default="each", choices=("logged", "each"))
    args = ap.parse_args(argv)
    for seed in (int(s) for s in args.seeds.split(",")):
        print(json.dumps(trace(seed, args.others), default=float), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
