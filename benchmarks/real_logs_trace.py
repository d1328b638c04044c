"""Why a real-style log's calibrated model loses a held-out cell (issue 33): the changes of
one diagnosis, taken apart on the validation part it was judged on and on the held-out
part it is scored on.

``benchmarks.real_logs`` scores the written model of each (log, split). This script reruns
one diagnosis of that benchmark (same log, same split, same prior) and, at the moment the
validation (:func:`stripcoef.diagnose.validate.validate_changes`) receives the changes,
builds from them (:func:`stripcoef.diagnose.calibrate.calibrated_model`):

- the prior the changes were fitted on (the original prior with the thrusters' gains when
  they were kept, :mod:`stripcoef.diagnose.gains`), and the original prior;
- every change; every change but the effects; the effects alone;
- each DOF's calibration alone beside the effects;
- the truth's coefficients (``benchmarks.real_logs.truth_model``),

and prints each one's RMS free-simulation error [m/s or rad/s] per DOF on the validation
part (the end of the fitting part) and on the held-out part, then the diagonal of the
model with every change against the prior and the truth. Nothing is fitted to the
benchmark: it only reads what the diagnosis fitted.

``--current-in-prior`` (a what-if, not the diagnosis's rule): the diagnosis run again with
the water current the first one found written into the prior (``effects``, ``dof: all``), so
that the thrusters' gains (:mod:`stripcoef.diagnose.gains`, fitted before any effect) are
fitted beside it; the held-out errors of its written model against the prior's.

Run:  python -m benchmarks.real_logs_trace --log 2 --split forward [--duration 300] [--seed 7]
      [--current-in-prior] [--gains-beside-current]
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
import warnings

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402

from benchmarks import real_logs as R  # noqa: E402
from benchmarks.diagnose_flags import add_flags, given  # noqa: E402


def variants(prior, model, per, fits, oracle) -> dict:
    """Name -> model: the diagnosis's changes taken apart (module docstring)."""
    from stripcoef.diagnose.calibrate import _changes, calibrated_model

    ch = _changes(per)
    cal = [c for c in ch if c[0] == "calibration"]
    eff = [c for c in ch if c[0] == "effect"]
    out = {"prior": prior, "prior the changes were fitted on": model,
           "every change": calibrated_model(model, per, fits, frozenset()),
           "every change but the effects": calibrated_model(model, per, fits, frozenset(eff)),
           "the effects alone": calibrated_model(model, per, fits, frozenset(cal))}
    for c in cal:
        out[f"{c[1]} calibration + the effects"] = calibrated_model(
            model, per, fits, frozenset(set(cal) - {c}))
    if oracle is not None:
        out["truth's coefficients"] = oracle
    return out


def with_current(prior, effects):
    """``prior`` (a model) with the ``current`` entry of ``effects`` (a written model's
    ``effects`` list) added to its effects; None when there is none."""
    import copy

    from stripcoef.model import HydroModel

    found = [e for e in effects if e["name"] == "current"]
    if not found:
        return None
    d = copy.deepcopy(prior.to_dict())
    d["effects"] = list(d.get("effects", [])) + [
        {"name": "current", "dof": "all", "parameters": dict(found[0]["parameters"])}]
    return HydroModel.from_dict(d)


def trace(k: int, split_name: str, duration: float, seed: int,
          current_in_prior: bool = False, **options) -> dict:
    """The trace of real-style log ``k`` on ``split_name`` (``forward``/``reverse``):
    ``{"changes", "errors": {variant: (validation, held-out)}, "diagonals", "cpu_s"}``;
    ``options``: keyword options of :func:`stripcoef.diagnose.diagnose` (e.g.
    ``gains_beside_current=True``)."""
    import stripcoef.diagnose.pipeline as pipeline
    from stripcoef.diagnose import diagnose
    from stripcoef.diagnose.calibrate import _changes
    from stripcoef.diagnose.heldout import compare, split
    from stripcoef.diagnose.validate import validation_errors

    name, log, prior, widths, truth, oracle = R.real_style_log(k, duration, seed, oracle=True)
    with tempfile.TemporaryDirectory() as tmp:
        read, _ = R.read_back(tmp, R.write_ros_chunks(log, tmp, seed=seed + k))
    if split_name == "forward":
        fit_log, part, holdout = read, split(read, R.HOLDOUT)[1], R.HOLDOUT
    else:
        part, fit_log = split(read, 1.0 - R.HOLDOUT)
        holdout = None
    got = {}
    original = pipeline.validate_changes

    def spy(val_log, model, per, fits, dofs, **kw):
        ms = variants(prior, model, per, fits, oracle)
        errs = {}
        for nm, m in ms.items():
            v = validation_errors(val_log, m, dofs, kw.get("logged", ()))
            h = compare(part, {"m": m}, dofs)
            errs[nm] = (v, {d: h[d]["m"] for d in h})
        trivial = compare(part, {}, dofs)
        errs["hold-last-velocity"] = (None, {d: trivial[d]["hold_last_velocity"] for d in trivial})
        errs["zero velocity"] = (None, {d: trivial[d]["zero_velocity"] for d in trivial})
        every = ms["every change"]
        diag = {}
        for key, attr in (("M_A", "added_mass"), ("D_L", "linear_damping"),
                          ("D_Q", "quadratic_damping")):
            p = np.diag(np.asarray(getattr(prior, attr), float))
            diag[key] = {"every change / prior": np.diag(np.asarray(getattr(every, attr), float))
                         / np.where(p == 0, np.nan, p),
                         "truth / prior": (np.diag(np.asarray(getattr(oracle, attr), float))
                                           / np.where(p == 0, np.nan, p))
                         if oracle is not None else None}
        got.update(changes=_changes(per), errors=errs, diagonals=diag,
                   every_change_effects=every.to_dict().get("effects", []),
                   validation_s=(float(val_log["t"][0]), float(val_log["t"][-1])))
        return original(val_log, model, per, fits, dofs, **kw)

    c0 = time.process_time()
    pipeline.validate_changes = spy
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = diagnose(fit_log, prior, dof="all", holdout=holdout, time_limit=float("inf"),
                           prior_widths=widths, **options)
    finally:
        pipeline.validate_changes = original
    got.update(log=name, truth=truth, split=split_name, cpu_s=time.process_time() - c0,
               held_out_s=(float(part["t"][0]), float(part["t"][-1])),
               gains=res.thruster_gains)
    prior_c = (with_current(prior, got["every_change_effects"]) if current_in_prior
               else None)
    if prior_c is not None:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            again = diagnose(fit_log, prior_c, dof="all", holdout=holdout,
                             time_limit=float("inf"), prior_widths=widths)
        written = type(again.model).from_dict(again.model.to_dict())
        dofs = list(again.diagnosed)
        h = compare(part, {"prior": prior, "prior with the current": prior_c,
                           "calibrated beside the current": written}, dofs)
        got["what_if"] = {"current": prior_c.to_dict()["effects"][-1]["parameters"],
                          "gains": again.thruster_gains, "errors": h,
                          "effects": [f"{e['dof']} {e['name']}" for e in written.effects]}
    return got


def _row(values) -> str:
    return " | ".join("-" if v is None else f"{v:.4f}" for v in values)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--log", type=int, default=2, help="real-style log (0..3)")
    ap.add_argument("--split", choices=("forward", "reverse"), default="forward")
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--current-in-prior", action="store_true",
                    help="what-if: diagnose again with the current found written into the prior")
    add_flags(ap)      # diagnose's options (e.g. --gains-beside-current), its defaults if left out
    args = ap.parse_args(argv)
    current_in_prior = args.current_in_prior
    opts = given(args)
    t = trace(args.log, args.split, args.duration, args.seed, current_in_prior, **opts)
    dofs = list(next(iter(t["errors"].values()))[1])
    print(f"{t['log']} ({t['truth']}), {t['split']}: validation {t['validation_s'][0]:.0f}-"
          f"{t['validation_s'][1]:.0f} s, held out {t['held_out_s'][0]:.0f}-"
          f"{t['held_out_s'][1]:.0f} s; {t['cpu_s']:.1f} s of CPU")
    g = t["gains"]
    if g is not None:
        print(f"thruster gains: {'written' if g.get('applied') else 'not written'} "
              f"({g.get('reason', '')})")
    print("changes: " + ", ".join(" ".join(c[1:][::-1]) for c in t["changes"]))
    print("\n| model | " + " | ".join(f"validation {d}" for d in dofs) + " | "
          + " | ".join(f"held-out {d}" for d in dofs) + " |")
    print("|---" * (1 + 2 * len(dofs)) + "|")
    for nm, (v, h) in t["errors"].items():
        print(f"| {nm} | " + _row([None] * len(dofs) if v is None else [v[d] for d in dofs])
              + " | " + _row([h[d] for d in dofs]) + " |")
    print()
    for key, rows in t["diagonals"].items():
        for what, vals in rows.items():
            if vals is not None:
                print(f"{key} {what}: " + " ".join(f"{x:.3f}" for x in vals))
    w = t.get("what_if")
    if current_in_prior and w is None:
        print("\nno current found: no what-if")
    elif w is not None:
        c = w["current"]
        g = w["gains"]
        print(f"\nwhat-if, the current ({c['current_north']:.4f}, {c['current_east']:.4f}) m/s "
              f"N, E in the prior: thruster gains {'written' if g and g.get('applied') else 'not written'}; "
              "effects written: " + ("; ".join(w["effects"]) or "none"))
        names = list(next(iter(w["errors"].values())))
        print("\n| DOF | " + " | ".join(names) + " | calibrated beats all three |")
        print("|---" * (len(names) + 2) + "|")
        for d, e in w["errors"].items():
            c = e["calibrated beside the current"]
            beats = (c is not None and c < e["prior"]
                     and c < min(e["hold_last_velocity"], e["zero_velocity"]))
            print(f"| {d} | " + _row([e[n] for n in names]) + f" | {'yes' if beats else 'no'} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
