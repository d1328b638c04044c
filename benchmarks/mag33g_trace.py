r"""Why a named effect's value within 15 % of the truth is not what the written model holds
(issue 33, mag33g): one log of ``benchmarks.diagnose_independent`` diagnosed again, with
the validation's record and the written model read for the effect's DOF.

For each log (vehicle, category, seed, mode) the diagnosis is run as the benchmark runs it
(``benchmarks.diagnose_independent._diagnosed``'s call; ``--options`` adds diagnose's
keyword arguments, e.g. the six whole-log options) and prints, for the effect's DOF:

- every step: its value as selected (the naming step's fit, ``selected_parameters``), as
  refitted with the DOF's other steps (``final_parameters``) and whether the written model
  holds it (``kept``);
- the validation's record: the changes it removed, the DOFs whose own changes it vetoed
  (``removed_for_own_dof``), and the DOF's free-simulation errors of the prior, of every
  change, of the kept changes and of the better trivial predictor;
- the benchmark's magnitude (:func:`benchmarks.diagnose_independent.magnitude_truth`, the
  truth in the written model's units) and the effect's magnitude in the written model
  itself (:func:`benchmarks.written_held.written_magnitude`): the written model's change of the coefficient the
  effect changes (the inertia, the linear drag, the restoring force, the thrust), or the
  written effect's own parameter (its DOF's entry or the thrusters' one shared entry); 0
  when the written model holds none.

``--rescore ROWS[,ROWS...] [--traces TRACES[,...]]`` diagnoses nothing: it counts the
stored rows' "held by the written model" again by the written model's own magnitude
(:func:`benchmarks.written_held.held`). A row of a step the validation kept holds its
value; a removed step's written magnitude is read from the row where the row determines it
(:func:`from_row`: a removed thrust scale leaves the DOF's kept scales, a removed dead band
the dead band other DOFs' kept steps wrote on the DOF's thrusters, :func:`row_deadband`, a
removed force, timing or thruster effect nothing), and from a trace of the same log, mode and options
where the calibration can carry it (:data:`benchmarks.written_held.CALIBRATED`). It prints,
per file, the count by the step's ``kept`` and by the written model, and every row whose
step is within 15 % but not kept.

Usage:
    python -m benchmarks.mag33g_trace --rows VEHICLE:CATEGORY:SEED:MODE[,...]
        [--duration 300] [--options six]
    python -m benchmarks.mag33g_trace --rescore ROWS[,ROWS...] [--traces TRACES[,...]]
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

#: The six whole-log options of the closed loop measured together at stop 54
#: (``--validation-others each --validation-horizon correlation --validation-judge own
#: --validation-reference combination --noise-with-bias --linked-gains identified``)
SIX = {"validation_others": "each", "validation_horizon": "correlation",
       "validation_judge": "own", "validation_reference": "combination",
       "noise_with_bias": True, "linked_gains": "identified"}


#: One prior per vehicle in a run of several logs (HydroModel is frozen)
_PRIORS: dict = {}


def put_back_errors(log, prior, res, category: str, dof_name: str, options: dict) -> dict:
    """The validation's free-simulation RMS errors per DOF [m/s or rad/s] of the written
    changes (``written``: every change the validation kept) and of the same with the removed
    step ``category`` of DOF ``dof_name`` put back (``put_back``; the DOF's calibration
    refitted with it, :func:`stripcoef.diagnose.calibrate.calibrated_model`), on the
    diagnosis's validation part with its horizons and logged DOFs (the validation's own
    :func:`stripcoef.diagnose.horizon.dof_losses`). For a diagnosis without applied
    whole-log gains only (its changes are then the prior's)."""
    from stripcoef.conventions import DOF
    from stripcoef.diagnose.calibrate import calibrated_model
    from stripcoef.diagnose.heldout import split
    from stripcoef.diagnose.horizon import dof_losses, rms
    from stripcoef.diagnose.settings import VALIDATION_FRACTION, DiagnoseSettings
    from stripcoef.diagnose.validate import partners
    from stripcoef.diagnose.calibrate import _changes

    settings = DiagnoseSettings(**{k: v for k, v in options.items()
                                   if k in DiagnoseSettings.__dataclass_fields__})
    _, val_log = split(log, VALIDATION_FRACTION, key="validation")
    dofs = [DOF.index(d) if isinstance(d, str) else int(d) for d in res.diagnosed]
    removed = set((res.validation or {}).get("removed") or ())
    changes = _changes(res.per_dof)
    excl = {c for c in changes if (c[0] == "calibration" and f"{c[1]} calibration" in removed)
            or (c[0] == "effect" and not next(s.kept for s in res.per_dof[c[1]].steps
                                              if s.effect == c[2]))}
    target = ("effect", dof_name, category)
    back = partners(excl - {target}, changes)
    from stripcoef.diagnose.heldout import HORIZON
    horizon = settings.validation_horizons(val_log, dofs)
    horizon = HORIZON if horizon is None else horizon          # as validate_changes does
    logged = settings.logged_dofs(dofs)
    out = {}
    for name, ex in (("written", excl), ("put_back", back)):
        model = calibrated_model(prior, res.per_dof, res.fits, frozenset(ex))
        e = rms(dof_losses(val_log, model, dofs, logged=logged, horizon=horizon))
        out[name] = {DOF[i]: float(v) for i, v in zip(dofs, e)}
    out["prior"] = {DOF[i]: float(v) for i, v in zip(dofs, rms(dof_losses(
        val_log, prior, dofs, logged=logged, horizon=horizon)))}
    return out


def trace(vehicle: str, category: str, seed: int, mode: str, duration: float,
          options: dict, put_back: bool = False) -> dict:
    """One log's trace (module docstring): a JSON-able record (``put_back``: with
    :func:`put_back_errors` where the step was removed)."""
    from benchmarks.diagnose_independent import (_prior, held_scales, magnitude_truth,
                                                 written_gain)
    from benchmarks.written_held import written_magnitude
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.effects import get_effect
    from validation.independent import STRENGTHS, generate

    prior = _PRIORS.get(vehicle)
    if prior is None:
        prior = _PRIORS[vehicle] = _prior(vehicle)
    dof_name = STRENGTHS[category][0]
    log, truth = generate(prior.to_dict(), category, seed, duration=duration)
    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof=dof_name if mode == "dof" else "all",
                       time_limit=float("inf"), **options)
    cpu = time.process_time() - t0
    d = res.to_dict()
    per = d.get("per_dof") or {dof_name: d}
    steps = per.get(dof_name, {}).get("steps", [])
    g_w = written_gain(d, prior.to_dict(), dof_name)
    match = [s for s in steps if s["effect"] == category]
    out = {"vehicle": vehicle, "category": category, "seed": seed, "mode": mode,
           "dof": dof_name, "cpu_s": cpu, "written_gain": g_w,
           "steps": [{"effect": s["effect"], "kept": s.get("kept"),
                      "selected": s.get("selected_parameters"),
                      "final": s.get("final_parameters") or s["parameters"]}
                     for s in steps],
           "calibration": {k: v for k, v in (per.get(dof_name, {}).get("calibration")
                                             or {}).items()
                           if k in ("written", "final_parameters", "prior")}}
    val = d.get("validation") or {}
    out["validation"] = {k: val.get(k) for k in ("removed", "removed_for_own_dof",
                                                 "refitted")}
    out["validation_errors"] = {k: (val.get(k) or {}).get(dof_name) for k in (
        "prior", "all_changes", "kept_changes", "trivial_predictor", "combined_reference")
        if isinstance(val.get(k), dict)}
    kept = bool(match[0].get("kept", True)) if match else True
    ref = magnitude_truth(truth, prior.to_dict(), category, dof_name,
                          held_scales(steps, kept), g_w)
    # the reference of the written model as it is: its kept scales (held_scales(kept=True))
    ref_written = magnitude_truth(truth, prior.to_dict(), category, dof_name,
                                  held_scales(steps, True), g_w)
    out["reference"] = float(ref)
    out["reference_written"] = float(ref_written)
    if match:
        est = get_effect(category).magnitude(match[0].get("final_parameters")
                                             or match[0]["parameters"])
        sel = get_effect(category).magnitude(match[0].get("selected_parameters")
                                             or match[0]["parameters"])
        out["estimate"] = float(est)
        out["estimate_error"] = abs(abs(est) - abs(ref)) / abs(ref)
        out["selected"] = float(sel)
        out["selected_error"] = abs(abs(sel) - abs(ref)) / abs(ref)
        out["kept"] = kept
    if put_back and match and not kept and not (d.get("thruster_gains") or {}).get("applied"):
        out["put_back"] = put_back_errors(log, prior, res, category, dof_name, options)
    wm = written_magnitude(res.model, prior, category, dof_name)
    out["written_magnitude"] = wm
    out["written_error"] = abs(abs(wm) - abs(ref_written)) / abs(ref_written)
    return out


def row_deadband(row: dict) -> float:
    """The dead band the written model of a stored row holds in the row's DOF [command
    units], from the row's kept dead-band steps in every DOF (``step_detail``): each
    thruster's the largest of the kept steps of the DOFs it acts in
    (:meth:`stripcoef.effects.thrust.Deadband.apply`), their mean over the thrusters acting
    in the row's DOF (:func:`benchmarks.written_held.written_magnitude`'s rule), on the
    prior's allocation (the prior has no dead band)."""
    from benchmarks.diagnose_independent import _prior
    from stripcoef.conventions import parse_dof
    prior = _PRIORS.get(row["vehicle"])
    if prior is None:
        prior = _PRIORS[row["vehicle"]] = _prior(row["vehicle"])
    b = prior.allocation()
    band = np.zeros(len(prior.thrusters))
    for d, steps in (row.get("step_detail") or {}).items():
        for st in steps:
            if st["effect"] == "deadband" and st["kept"]:
                i = parse_dof(d)
                for k in range(len(band)):
                    if abs(b[i, k]) > 1e-9:
                        band[k] = max(band[k], st["parameters"]["deadband"])
    act = [k for k in range(len(band)) if abs(b[parse_dof(row["dof"]), k]) > 1e-9]
    return float(np.mean(band[act])) if act else 0.0


def from_row(row: dict) -> dict | None:
    """``row`` (a stored row of ``benchmarks.diagnose_independent``, converted to the written
    model's units) with ``written_magnitude`` and ``written_magnitude_error`` where the row
    alone determines them (module docstring); None where a trace is needed (a removed step
    of :data:`benchmarks.written_held.CALIBRATED`) or no magnitude is claimed."""
    from benchmarks.diagnose_independent import held_scales
    from benchmarks.written_held import CALIBRATED
    if "estimate" not in row or "written_magnitude_error" in row:
        return row if "written_magnitude_error" in row else None
    if row["category"] == "deadband":
        wm = row_deadband(row)
        ref = float(row["magnitude_truth"])
        return {**row, "written_magnitude": wm,
                "written_magnitude_error": abs(abs(wm) - abs(ref)) / abs(ref)}
    if row.get("magnitude_written", True):
        return {**row, "written_magnitude": row["estimate"],
                "written_magnitude_error": row["magnitude_error"]}
    if row["category"] in CALIBRATED:
        return None
    steps = (row.get("step_detail") or {}).get(row["dof"], [])
    # a removed thrust scale: the written model holds the DOF's kept scales (its reference,
    # g / g_w, has no scale in it); any other removed effect: nothing
    wm = held_scales(steps, True) if row["category"] == "thrust_effectiveness" else 0.0
    ref = float(row["magnitude_truth"])
    return {**row, "written_magnitude": wm,
            "written_magnitude_error": abs(abs(wm) - abs(ref)) / abs(ref)}


def rescore(rows: list[dict], traces: list[dict]) -> tuple[list[dict], list[dict]]:
    """``(rows, gap)``: ``rows`` with the written model's magnitude where known
    (:func:`from_row`, else the trace of the same vehicle, category, seed and mode), and the
    rows whose step is within 15 % and not kept, each with its ``written_magnitude`` (None
    when neither gives it)."""
    by = {(t["vehicle"], t["category"], t["seed"], t["mode"]): t for t in traces}
    out, gap = [], []
    for r in rows:
        got = from_row(r)
        t = by.get((r["vehicle"], r["category"], r["seed"], r["mode"]))
        if got is None and t is not None and "estimate" in r:
            got = {**r, "written_magnitude": t["written_magnitude"],
                   "written_magnitude_error": t["written_error"]}
        got = got or r
        out.append(got)
        if r.get("magnitude_error", np.inf) <= 0.15 and not r.get("magnitude_written", True):
            gap.append(got)
    return out, gap


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", default=None, help="VEHICLE:CATEGORY:SEED:MODE[,...]")
    ap.add_argument("--rescore", default=None,
                    help="comma-separated outputs of benchmarks.diagnose_independent")
    ap.add_argument("--traces", default=None,
                    help="comma-separated outputs of this module (their 'trace' lines)")
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--options", default="default", choices=("default", "six"),
                    help="'six': the six whole-log options (SIX)")
    ap.add_argument("--put-back", action="store_true",
                    help="also the validation errors with the removed step put back "
                         "(put_back_errors)")
    args = ap.parse_args(argv)
    options = SIX if args.options == "six" else {}
    if args.rescore:
        from benchmarks.diagnose_independent import converted_rows
        from benchmarks.written_held import held
        from stripcoef.files import read_text

        def lines(paths, mark):
            return [json.loads(line.split(mark, 1)[1]) for path in (paths or "").split(",")
                    if path for line in read_text(path, kind="benchmark output").splitlines()
                    if mark in line]
        traces = lines(args.traces, "trace ")
        for path in args.rescore.split(","):
            rows, gap = rescore(converted_rows(lines(path, " row ")), traces)
            lib = [r for r in rows if "magnitude_truth" in r or r.get("magnitude_not_claimed")
                   or r["category"] not in ("clean", "coulomb_friction")]
            old = sum(r.get("magnitude_error", np.inf) <= 0.15
                      and r.get("magnitude_written", True) for r in lib)
            print(f"{path}: within 15 % {sum(r.get('magnitude_error', np.inf) <= 0.15 for r in lib)}"
                  f"; held by the written model: by the step kept {old}, by the written "
                  f"model's magnitude {sum(held(r) for r in lib)} ({len(gap)} rows within 15 % "
                  f"and not kept, {sum(g.get('written_magnitude') is None for g in gap)} "
                  f"without a written magnitude)")
            for g in gap:
                wm = g.get("written_magnitude")
                print(f"  {g['vehicle']} {g['category']} {g['seed']} {g['mode']}: step "
                      f"{g['estimate']:+.4g} ({100 * g['magnitude_error']:.1f} %), written "
                      + ("?" if wm is None else
                         f"{wm:+.4g} ({100 * g['written_magnitude_error']:.1f} %)"))
        return 0
    if not args.rows:
        ap.error("--rows or --rescore")
    for spec in args.rows.split(","):
        vehicle, category, seed, mode = spec.split(":")
        got = trace(vehicle, category, int(seed), mode, args.duration, options, args.put_back)
        print("trace " + json.dumps(got, default=float), flush=True)
        print(f"  {vehicle} {category} {seed} {mode} ({args.options}): "
              f"estimate {got.get('estimate', np.nan):+.4g} (selected "
              f"{got.get('selected', np.nan):+.4g}) kept {got.get('kept')}; reference "
              f"{got['reference']:+.4g}, error {100 * got.get('estimate_error', np.nan):.1f} %; "
              f"written model {got['written_magnitude']:+.4g} against "
              f"{got['reference_written']:+.4g}: {100 * got['written_error']:.1f} %; "
              f"removed {got['validation']['removed']}, vetoed "
              f"{got['validation']['removed_for_own_dof']}; {got['cpu_s']:.1f} s CPU",
              flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
