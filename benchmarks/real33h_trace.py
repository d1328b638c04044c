"""One real-style log's whole-log diagnosis traced through its validation (issue 33, real33h;
benchmarks/data/real33h_trace.md).

For real-style log K of :mod:`benchmarks.real_logs` (default 2, the BlueROV2-Heavy-like
current log), seed S and a split (forward: ``diagnose(..., holdout=0.3)``; reverse: the last
70 % diagnosed, the first 30 % held out, as :func:`benchmarks.real_logs.both_splits`), with
the options of :mod:`benchmarks.diagnose_flags`: the thrusters' gains' record, every
step named per DOF (kept or removed by the validation), the water current fitted beside the
truth's, the effects written, the validation record (the prior's, all changes', the kept
changes' errors [m/s or rad/s], what was removed and why, each set the elimination scored
where the record holds them) and the written model's held-out errors beside the prior's and
the trivial predictors'.

Run:  python -m benchmarks.real33h_trace [--log 2] [--seed 7] [--split forward|reverse]
      [the six options, --validation-choice best_visited]
"""

from __future__ import annotations

import argparse
import os
import time
import warnings

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


def main(argv=None) -> int:
    from benchmarks.diagnose_flags import add_flags, given

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--log", type=int, default=2, help="real-style log (0..3)")
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--split", default="forward", choices=("forward", "reverse"))
    ap.add_argument("--ablate", action="store_true",
                    help="also the written model taken apart (:func:`ablate`)")
    add_flags(ap)
    args = ap.parse_args(argv)
    options = given(args)

    from benchmarks.real_logs import HOLDOUT, fmt_record, traced_split
    from stripcoef.diagnose import diagnose
    from stripcoef.diagnose.heldout import compare, split

    name, truth, prior, widths, truth_coefficients, fit, kw, test = traced_split(
        args.log, args.duration, args.seed, args.split)
    print(f"{name} ({truth}), {args.split} split, options {options}")
    c0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(fit, prior, dof="all", time_limit=float("inf"), prior_widths=widths,
                       **kw, **options)
    cpu = time.process_time() - c0
    v = res.validation or {}
    written = type(res.model).from_dict(res.model.to_dict())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        held = compare(test, {"prior": prior, "written": written}, list(res.diagnosed))
    g = res.thruster_gains or {}
    print(f"diagnosis {cpu:.1f} s CPU; DOFs {res.diagnosed}; dropped {res.dropped_dofs}")
    print(f"gains applied {g.get('applied')}; significant {g.get('significant')}")
    if g.get("gains"):
        print("   gains: " + fmt_record(g.get("gains")))
    if g.get("validation"):
        print("   gains' validation: " + fmt_record({k: x for k, x in g["validation"].items()
                                                if k != "description"}))
    for d, r in res.per_dof.items():
        cal = r.calibration
        print(f"-- {d}: calibration kept {cal.kept}; steps: " + ("; ".join(
            f"{s.effect} (kept {s.kept})" for s in r.steps) or "none"))
    print("effects written: " + ("; ".join(f"{e['dof']} {e['name']} "
                                           + fmt_record(e.get("parameters") or {})
                                           for e in res.model.effects) or "none"))
    print(f"bounds hit: {res.bounds_hit}")
    for key in ("horizon_s", "prior", "trivial_predictor", "combined_reference",
                "all_changes", "kept_changes"):
        if key in v:
            print(f"validation {key}: {fmt_record(v.get(key))}")
    print(f"removed: {v.get('removed')}")
    print(f"removed for own DOF: {v.get('removed_for_own_dof')}")
    for key in ("choice", "visited"):
        if key in v:
            print(f"validation {key}:")
            for row in (v[key] if isinstance(v[key], list) else [v[key]]):
                print(f"   {row}")
    for dof, e in held.items():
        print(f"held out {dof:6s} " + "  ".join(
            f"{m} {x:.4f}" if x is not None else f"{m} None" for m, x in e.items()))
    if args.ablate:
        ablate(res, prior, split(fit, HOLDOUT)[0] if args.split == "forward" else fit,
               test, truth_coefficients, options)
    print(f"\n{time.process_time():.1f} s of CPU in all")
    return 0


def ablate(res, prior, fit, test, oracle, options) -> None:
    """The written model taken apart: the prior, the prior with the thrusters' gains, and the
    gained prior with the water current and the kept calibrations, each alone and together
    (:func:`stripcoef.diagnose.calibrate.calibrated_model`), and the truth's coefficients
    (the oracle), each simulated with every DOF free over 10-s segments
    (:func:`stripcoef.diagnose.heldout.compare`) on the validation part and on the held-out
    part, and by the validation's own rule on the validation part
    (:func:`stripcoef.diagnose.validate.validation_errors` with the options' logged DOFs and
    horizons) [m/s or rad/s]."""
    from stripcoef.conventions import DOF
    from stripcoef.diagnose.calibrate import _changes, calibrated_model
    from stripcoef.diagnose.heldout import compare, split
    from stripcoef.diagnose.settings import VALIDATION_FRACTION, DiagnoseSettings
    from stripcoef.diagnose.validate import partners, validation_errors
    from stripcoef.effects import get_effect

    g = res.thruster_gains or {}
    gained = (get_effect("thruster_gain").apply(
        prior, None, {f"gain_{k}": float(v) for k, v in g["gains"].items()})
        if g.get("applied") else prior)
    per, fits, dofs = res.per_dof, res.fits, list(res.diagnosed)
    changes = _changes(per)
    cals = {c for c in changes if c[0] == "calibration"}
    current = {c for c in changes if c[0] == "effect" and c[2] == "current"}
    kept = {c for c in changes if c not in {("calibration", d) for d, r in per.items()
                                            if not r.calibration.kept}
            and not (c[0] == "effect" and not next(s.kept for s in per[c[1]].steps
                                                   if s.effect == c[2]))}
    removed = set(changes) - kept

    def model(without):
        return calibrated_model(gained, per, fits, frozenset(partners(set(without), changes)))

    models = {"prior": prior, "prior + gains": gained}
    if current:
        models["gains + current"] = model(set(changes) - (current & kept))
        models["prior + current (no gains)"] = calibrated_model(
            prior, per, fits, frozenset(partners(set(changes) - (current & kept), changes)))
    if cals & kept:
        models["gains + kept calibrations"] = model(removed | current)
    models["written (gains + kept changes)"] = model(removed)
    if oracle is not None:
        models["truth's coefficients"] = oracle
    settings = DiagnoseSettings(**{k: v for k, v in options.items()
                                   if k in DiagnoseSettings.__dataclass_fields__})
    # the diagnosis's validation part: the last quarter of the part it was fitted on
    val = split(fit, VALIDATION_FRACTION)[1]
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        on_val = compare(val, models, dofs)
        on_test = compare(test, models, dofs)
        rule = {name: validation_errors(val, m, dofs, settings.logged_dofs(dofs),
                                        settings.validation_horizons(val, dofs))
                for name, m in models.items()}
    print(f"\nablation (kept changes: {sorted(kept)}):")
    for title, table in (("validation part, every DOF free, 10 s", on_val),
                         ("held-out part, every DOF free, 10 s", on_test)):
        print(f"  {title}:")
        print("    " + " / ".join(DOF[i] for i in dofs) + "   (hold; zero)")
        for name in models:
            print(f"    {name:32s} " + " / ".join(
                "None" if table[DOF[i]][name] is None else f"{table[DOF[i]][name]:.4f}"
                for i in dofs))
        print("    trivial: " + " / ".join(
            f"{table[DOF[i]]['hold_last_velocity']:.4f}; {table[DOF[i]]['zero_velocity']:.4f}"
            for i in dofs))
    print("  validation part, the validation's own simulations (logged DOFs, horizons):")
    for name, e in rule.items():
        print(f"    {name:32s} " + ("None" if e is None else " / ".join(
            f"{e[DOF[i]]:.4f}" for i in dofs)))


if __name__ == "__main__":
    raise SystemExit(main())
