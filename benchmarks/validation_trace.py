r"""Trace of the diagnosis's validation by free simulation on one log of the independent
simulator (issue 33): the changes it judged, every DOF's validation error with and without
each change, and the rule's decision.

For each log seed: the diagnosis (one DOF or whole-log) runs as
``benchmarks.diagnose_independent`` runs it; the arguments its validation
(:func:`stripcoef.diagnose.validate.validate_changes`) receives are kept and the
validation's free-simulation errors (:func:`stripcoef.diagnose.heldout.segment_squared_errors`,
the same segments and logged DOFs) are recomputed for the prior, all changes, each change
left out (with its partners, :func:`stripcoef.diagnose.validate.partners`), the
calibrations alone, and the prior with the truth's own change only in the effect's DOF
(``--truth-change``: the prior's surge added mass moved by the truth's change in the thrust's
units, :func:`benchmarks.diagnose_independent.magnitude_truth`). Per segment the squared
errors are printed for the effect's DOF so the paired difference can be read.

Run: ``python -m benchmarks.validation_trace --seeds 29113033 --modes dof,all`` (BlueROV2-like,
added mass, 300 s; a log of ``python -m benchmarks.diagnose_independent --seed 29112026
--repeats 2``). Output in ``benchmarks/data/val33_trace.md``.
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


def _errors(got):
    """Pooled RMS per DOF of :func:`segment_squared_errors`' output, None if it diverged."""
    if got is None:
        return None
    return [float(np.sqrt(v)) for v in np.sum(got[0], axis=0) / np.sum(got[1])]


def trace(seed: int, vehicle: str, category: str, mode: str) -> dict:
    """One log and mode's trace (module docstring) as a dict."""
    import stripcoef.diagnose.pipeline as pipeline
    from benchmarks.diagnose_independent import _prior, magnitude_truth
    from stripcoef.conventions import DOF, parse_dof
    from stripcoef.diagnose.calibrate import _changes, calibrated_model
    from stripcoef.diagnose.heldout import segment_squared_errors
    from stripcoef.diagnose.validate import partners
    from validation.independent import STRENGTHS, generate

    dof = STRENGTHS[category][0]
    i = parse_dof(dof)
    prior = _prior(vehicle)
    seen = {}
    original = pipeline.validate_changes

    def spy(val_log, model, per, fits, dofs, **kw):
        seen.update(val_log=val_log, model=model, per=per, fits=fits, dofs=list(dofs),
                    logged=list(kw.get("logged", ())))
        out = original(val_log, model, per, fits, dofs, **kw)
        seen["excl"], seen["record"] = out
        return out

    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        log, truth = generate(prior.to_dict(), category, seed, duration=300.0)
        pipeline.validate_changes = spy
        try:
            res = pipeline.diagnose(log, prior, dof=dof if mode == "dof" else "all",
                                    time_limit=float("inf")).to_dict()
        finally:
            pipeline.validate_changes = original
    cpu = time.process_time() - t0
    val_log, model, per, fits = seen["val_log"], seen["model"], seen["per"], seen["fits"]
    dofs, logged = seen["dofs"], seen["logged"]
    changes = _changes(per)
    k = dofs.index(i) if i in dofs else None

    def run(excl):
        m = calibrated_model(model, per, fits, frozenset(partners(set(excl), changes)))
        got = segment_squared_errors(val_log, m, dofs, logged=logged)
        return got, m

    base = segment_squared_errors(val_log, model, dofs, logged=logged)
    rows = {"prior": base}
    every, m_all = run(set())
    rows["all changes"] = every
    for c in changes:
        rows["without " + " ".join(map(str, c))] = run({c})[0]
    rows["calibrations only"] = run({c for c in changes if c[0] == "effect"})[0]
    truth_du = float(magnitude_truth(truth, prior.to_dict(), category, dof))
    # the prior's own added mass moved by the truth's change in the thrust's units: what the
    # validation would see of the correct change alone
    ma = np.array(model.added_mass, float)
    ma[i, i] += truth_du
    from dataclasses import replace
    truth_alone = replace(model, added_mass=ma, added_mass_error=None)
    rows["prior + truth's change alone"] = segment_squared_errors(val_log, truth_alone, dofs,
                                                                  logged=logged)
    cal_plus = run({c for c in changes if c[0] == "effect"})[1]
    ma2 = np.array(cal_plus.added_mass, float)
    ma2[i, i] = float(model.added_mass[i, i]) + truth_du
    rows["calibrations + truth's M_ii"] = segment_squared_errors(
        val_log, replace(cal_plus, added_mass=ma2, added_mass_error=None), dofs, logged=logged)
    # the truth's own model (validation.detectability.truth_model: its coefficients and
    # thrust maps) with and without the log's effect: what the validation makes of the
    # correct change where nothing else is wrong
    from validation.detectability import truth_model, truth_without
    rows["truth"] = segment_squared_errors(val_log, truth_model(prior, truth), dofs,
                                           logged=logged)
    rows["truth without the effect"] = segment_squared_errors(
        val_log, truth_model(prior, truth_without(prior, truth)), dofs, logged=logged)
    names = [DOF[j] for j in dofs]
    # the benchmark's cut: the window force residual of the effect's DOF on the fitting part
    # (benchmarks.diagnose_independent._prior_error's metric) for the same models
    from stripcoef.diagnose.heldout import split
    from stripcoef.diagnose.settings import VALIDATION_FRACTION
    from stripcoef.diagnose.written import window_errors
    train, _ = split(log, VALIDATION_FRACTION, key="validation")
    models = {"prior": model, "all changes": m_all, "calibrations only": cal_plus,
              "calibrations + truth's M_ii": replace(cal_plus, added_mass=ma2,
                                                     added_mass_error=None)}
    window = {name: float(window_errors(train, m, [i], window=res["window_s"])[dof])
              for name, m in models.items()}
    table = {name: (None if got is None else dict(zip(names, _errors(got))))
             for name, got in rows.items()}
    per_segment = {name: (None if got is None or k is None else
                          [float(x) for x in got[0][:, k] / got[1]])
                   for name, got in rows.items()}
    record = seen["record"]
    # whole-log: each DOF simulated alone, the others taken from the log (the one-DOF
    # validation's rule, settings.logged_dofs), for the same models
    alone = {}
    if len(dofs) > 1:
        for name, m in (("prior", model), ("all changes", m_all),
                        ("calibrations only", cal_plus),
                        ("truth", truth_model(prior, truth)),
                        ("truth without the effect",
                         truth_model(prior, truth_without(prior, truth)))):
            alone[name] = {DOF[j]: _errors(segment_squared_errors(
                val_log, m, [j], logged=[o for o in range(6) if o != j]))[0] for j in dofs}
    return {"seed": seed, "vehicle": vehicle, "category": category, "mode": mode,
            "validation_s": record["validation_s"], "logged_dofs": record["logged_dofs"],
            "diagnosed": names, "truth_change_thrust_units": truth_du,
            "prior_M_ii": float(model.added_mass[i, i]),
            "written_M_ii": float(m_all.added_mass[i, i]),
            "calibrations_only_M_ii": float(cal_plus.added_mass[i, i]),
            "calibrations_only_D": [float(cal_plus.linear_damping[i, i]),
                                    float(cal_plus.quadratic_damping[i, i])],
            "written_D": [float(m_all.linear_damping[i, i]),
                          float(m_all.quadratic_damping[i, i])],
            "prior_D": [float(model.linear_damping[i, i]), float(model.quadratic_damping[i, i])],
            "gains_applied": (res.get("thruster_gains") or {}).get("applied"),
            "changes": [" ".join(map(str, c)) for c in changes],
            "removed": record["removed"], "removed_for_own_dof": record["removed_for_own_dof"],
            "kept_changes_errors": record["kept_changes"],
            "errors": table, "window_force_rms_effect_dof": window,
            "errors_each_dof_others_logged": alone, "segment_mse_effect_dof": per_segment,
            "steps": {d: [(s["effect"], s.get("kept")) for s in r["steps"]]
                      for d, r in (res.get("per_dof") or {dof: res}).items()},
            "cpu_s": cpu}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seeds", default="29113033")
    ap.add_argument("--vehicle", default="bluerov2_heavy")
    ap.add_argument("--category", default="added_mass_error")
    ap.add_argument("--modes", default="dof,all")
    args = ap.parse_args(argv)
    for seed in (int(s) for s in args.seeds.split(",")):
        for mode in args.modes.split(","):
            print(json.dumps(trace(seed, args.vehicle, args.category, mode), default=float),
                  flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
