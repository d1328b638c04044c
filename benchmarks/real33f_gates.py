"""What the forward split of a real-style log writes against the prior, and why its
validation kept it (issue 33, real33f; benchmarks/data/real33f_trace.md).

For real-style log K of :mod:`benchmarks.real_logs` (default 2, the BlueROV2-Heavy-like
current log) and seed S, forward split (``diagnose(..., holdout=0.3)``, as
:func:`benchmarks.real_logs.both_splits`):

1. every value of the written model's dictionary that differs from the prior's;
2. the thrusters' gains' validation record (``Diagnosis.thruster_gains["validation"]``);
3. the prior and the prior with the written changes on the fitting, validation and held-out
   parts, on consecutive 10-s segments (the held-out table's and the default validation's
   :func:`stripcoef.diagnose.heldout.segments`) and on 10-s segments restarted every 2 s
   (:func:`~stripcoef.diagnose.heldout.rolling_segments`): each DOF's RMS error [m/s or
   rad/s], the validation's score (DOFs worse, sum of squared ratios:
   :func:`stripcoef.diagnose.gaingate.score`), each DOF's Diebold-Mariano statistic
   (negative: the written model better) and the per-segment ratios of the consecutive ones;
4. with ``--current``: whether the truth's water current is visible in 10-s and 2-s free
   simulations: the prior, the prior with the truth's current, the truth's coefficients
   without and with it (:func:`benchmarks.real_logs.truth_model`), per part.

Run:  python -m benchmarks.real33f_gates [--log 2] [--seed 7] [--current | --current-only]
      [--gains-validation consecutive|rolling]
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import tempfile
import time
import warnings

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402


def _diff(a, b, path=""):
    """``(path, prior value, written value)`` of every leaf that differs."""
    if isinstance(a, dict) and isinstance(b, dict):
        return [d for k in sorted(set(a) | set(b), key=str)
                for d in _diff(a.get(k), b.get(k), f"{path}.{k}")]
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        return [d for k, (x, y) in enumerate(zip(a, b)) for d in _diff(x, y, f"{path}[{k}]")]
    return [] if a == b else [(path, a, b)]


def parts_table(parts: dict, prior, written, dofs) -> None:
    """Item 3 of the module docstring, printed."""
    from stripcoef.conventions import DOF
    from stripcoef.diagnose.gaingate import score
    from stripcoef.diagnose.heldout import (diebold_mariano, overlap_steps, rolling_segments,
                                            segment_squared_errors)

    names = [DOF[i] for i in dofs]
    for name, part in parts.items():
        t = np.asarray(part["t"], float)
        for kind, bounds, overlap in (("consecutive 10 s", None, 1),
                                      ("10 s every 2 s", rolling_segments(t), overlap_steps())):
            a = segment_squared_errors(part, prior, dofs, bounds=bounds)
            b = segment_squared_errors(part, written, dofs, bounds=bounds)
            if a is None or b is None:
                print(f"{name}, {kind}: a simulation diverged")
                continue
            ea = np.sqrt(a[0].sum(0) / a[1].sum())
            eb = np.sqrt(b[0].sum(0) / b[1].sum())
            worse, total = score(list(ea), list(eb))
            dm = [diebold_mariano(b[0][:, k] / b[1], a[0][:, k] / a[1],
                                  overlap=overlap)["statistic"] for k in range(len(dofs))]
            print(f"{name} ({t[0]:.1f}-{t[-1]:.1f} s), {kind}, {len(a[1])} segments: "
                  f"DOFs worse {worse}, sum of squared ratios {total:.3f} (n = {len(dofs)})")
            for k, d in enumerate(names):
                print(f"    {d:6s} prior {ea[k]:.4f}  written {eb[k]:.4f}  "
                      f"ratio {eb[k] / ea[k]:.3f}  DM {dm[k]:+.2f}")
            if bounds is None:
                ratios = np.sqrt(b[0] / b[1][:, None]) / np.sqrt(a[0] / a[1][:, None])
                for s, row in enumerate(ratios):
                    print(f"      segment {s}: " + " ".join(f"{x:.2f}" for x in row))


def current_table(parts: dict, prior, oracle) -> None:
    """Item 4 of the module docstring, printed (the truth's current as the oracle writes it,
    :func:`benchmarks.real_logs.oracle_effects`)."""
    from stripcoef.diagnose.heldout import compare

    vc = next(dict(e["parameters"]) for e in oracle.effects if e["name"] == "current")
    print(f"\nthe truth's current: north {vc['current_north']:+.4f}, east "
          f"{vc['current_east']:+.4f} m/s")
    bare = dataclasses.replace(oracle, effects=())
    models = {"prior": prior,
              "prior+current": prior.with_effects({"name": "current", "dof": "all",
                                                   "parameters": vc}),
              "truth_without_current": bare, "truth": oracle}
    for name, part in parts.items():
        for h in (10.0, 2.0):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                err = compare(part, models, list(range(6)), horizon=h)
            print(f"{name}, {h:g}-s segments:")
            for dof, e in err.items():
                print(f"    {dof:6s} " + "  ".join(f"{m} {v:.4f}" for m, v in e.items()))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--log", type=int, default=2, help="real-style log (0..3)")
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--gains-validation", default="consecutive",
                    choices=("consecutive", "rolling"))
    ap.add_argument("--current", action="store_true",
                    help="also the truth's current in free simulation (item 4)")
    ap.add_argument("--current-only", action="store_true",
                    help="only item 4 (no diagnosis)")
    args = ap.parse_args(argv)

    from benchmarks.real_logs import HOLDOUT, read_back, real_style_log, write_ros_chunks
    from stripcoef.diagnose import diagnose
    from stripcoef.diagnose.heldout import split
    from stripcoef.diagnose.settings import VALIDATION_FRACTION

    name, log, prior, widths, truth, oracle = real_style_log(args.log, args.duration,
                                                             args.seed, oracle=True)
    with tempfile.TemporaryDirectory() as tmp:
        read, _ = read_back(tmp, write_ros_chunks(log, tmp, seed=args.seed + args.log))
    fit_log, test_log = split(read, HOLDOUT)
    train, val = split(fit_log, VALIDATION_FRACTION, key="validation")
    current = args.current or args.current_only
    if current and (oracle is None or not any(e["name"] == "current" for e in oracle.effects)):
        raise SystemExit(f"{name}: no current in the truth")
    if args.current_only:
        current_table({"validation part": val, "held-out part": test_log,
                       "reverse held-out part": split(read, 1.0 - HOLDOUT)[0]}, prior, oracle)
        print(f"\n{time.process_time():.1f} s of CPU in all")
        return 0
    c0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(read, prior, dof="all", holdout=HOLDOUT, time_limit=float("inf"),
                       prior_widths=widths, gains_validation=args.gains_validation)
    print(f"{name}, seed {args.seed}, forward split, gains_validation "
          f"{args.gains_validation}: diagnosed in {time.process_time() - c0:.1f} s of CPU")
    written = type(res.model).from_dict(res.model.to_dict())
    print("\nthe written model against the prior (values that differ; provenance left out):")
    for path, a, b in _diff(prior.to_dict(), written.to_dict()):
        if not path.startswith((".provenance", ".name")):
            print(f"    {path}: {a} -> {b}")
    print("effects written: " + ("; ".join(f"{e['dof']} {e['name']}"
                                          for e in res.model.effects) or "none"))
    g = res.thruster_gains or {}
    print(f"\nthe gains: applied {g.get('applied')}; {g.get('reason')}")
    print(f"their validation record: {g.get('validation')}")
    print(f"the changes' validation removed: {(res.validation or {}).get('removed')}")
    parts = {"fitting part": train, "validation part": val, "held-out part": test_log}
    print()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        parts_table(parts, prior, written, list(res.diagnosed))
    if current:
        current_table({"validation part": val, "held-out part": test_log,
                       "reverse held-out part": split(read, 1.0 - HOLDOUT)[0]}, prior, oracle)
    print(f"\n{time.process_time():.1f} s of CPU in all")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
