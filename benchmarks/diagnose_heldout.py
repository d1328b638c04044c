"""Held-out free-simulation error of `diagnose` on real-style logs (issue 16).

Each log is made by our own simulator run of a truth that differs from the prior the way
real logs do (every value is drawn per log, seeded):

- the truth: the VideoRay-like ROV of ``validation.synthetic.rov_model`` with every diagonal
  coefficient moved within half its band (``perturb_within_bands``);
- sampling: jittered, each interval uniform in [0.05, 0.10] s (10-20 Hz);
- thrust shortfall: only s in U(0.3, 0.5) of the commanded thrust acts (all thrusters);
- thruster lag: the thrust follows its command with a first-order lag, T in U(0.2, 0.5) s;
- a tether paid out from 2 m at 0.05-0.1 m/s, drag c_t L v|v| in surge, sway and heave,
  c_t in U(0.05, 0.15) N s^2/m^3;
- noise: ``validation.synthetic.NOISE`` (1 cm/s DVL, 0.003 rad/s gyro, ...);
- excitation: random steps on every thruster (surge, heave, yaw turns and, in the
  ``sway-off`` scenario, no lateral thruster: sway, roll and pitch are left unexcited;
  in ``all`` only roll and pitch are).

The logs come from ``validation.synthetic.real_style_log``; the thrust shortfall and lag of
the truth are implemented there, independently of the effects library (the truth's applied
force is a function of time passed to ``simulate``).

The diagnosis gets the unperturbed prior and the log, ``holdout=0.3`` (the last 30 % never
fitted). Reported per log and excited DOF: held-out free-simulation RMS error (10-s
simulations from the logged state) of the prior, of the calibrated model (read back from
its dictionary form, as written) and of hold-last-velocity; per log: whether any
coefficient of an unexcited DOF changed, whether any drag is negative and any added mass
outside its plausible range (``added_mass_bounds``).

``--priors method`` gives the calibration the Gaussian prior widths of the method table's
rows for the VideoRay Pro III vehicle file (shape class bluff; issue 19), as
``diagnose --vehicle videoray_pro3.yaml`` does, and checks the added mass against its 99.7 %
band; the default (``bands``) is a model file's fixed bands.

Run:  PYTHONPATH=src:. python -m benchmarks.diagnose_heldout [--seeds 2] [--duration 300]
      [--priors bands|method]
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from stripcoef.conventions import DOF
from stripcoef.diagnose.pipeline import added_mass_bounds, diagnose
from stripcoef.model import HydroModel
from validation.synthetic import real_style_log


def coefficients(model: HydroModel, i: int):
    return (float(model.added_mass[i, i]), float(model.linear_damping[i, i]),
            float(model.quadratic_damping[i, i]))


def run(seed: int, scenario: str, duration: float, widths=None) -> dict:
    log, prior, truth = real_style_log(seed, scenario, duration)
    t0 = time.perf_counter()
    # no time budget: a 300-s log of 4 DOFs may take minutes on a loaded machine
    res = diagnose(log, prior, dof="all", holdout=0.3, time_limit=float("inf"),
                   prior_widths=widths)
    elapsed = time.perf_counter() - t0
    model = res.model
    excited = [DOF.index(d) for d in res.per_dof]
    unexcited = [i for i in range(6) if i not in excited]
    changed = [DOF[i] for i in unexcited
               if coefficients(model, i) != coefficients(prior, i)
               or any(e.get("dof") == DOF[i] for e in model.effects)]
    negative = bool(np.any(np.diag(model.linear_damping) < 0)
                    or np.any(np.diag(model.quadratic_damping) < 0))
    sd = [None] * 6 if widths is None else widths.added_mass_sd
    outside = [DOF[i] for i in range(6) if prior.added_mass[i, i] != 0 and not (
        added_mass_bounds(i, prior.added_mass[i, i], sd[i])[0] * (1 - 1e-9)
        <= model.added_mass[i, i]
        <= added_mass_bounds(i, prior.added_mass[i, i], sd[i])[1] * (1 + 1e-9))]
    errors = res.holdout["errors"]
    beats = {d: (e["calibrated"] is not None and e["calibrated"] < e["prior"]
                 and e["calibrated"] < e["hold_last_velocity"]) for d, e in errors.items()}
    return {"log": log.source, "truth": truth, "seconds": round(elapsed, 1),
            "excited": [DOF[i] for i in excited], "unexcited_changed": changed,
            "negative_drag": negative, "added_mass_outside_bounds": outside, "errors": errors, "beats_prior_and_hold": beats,
            "effects": [(e["name"], e["dof"]) for e in model.effects],
            "removed_on_validation": (res.validation or {}).get("removed"),
            "bounds_hit": dict(res.bounds_hit)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seeds", type=int, default=2)
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--priors", choices=("bands", "method"), default="bands",
                    help="the calibration's prior widths: the fixed BANDS (a model file, "
                         "default) or the method table's rows of the VideoRay Pro III vehicle "
                         "file (shape class bluff), as with --vehicle videoray_pro3.yaml")
    args = ap.parse_args()
    widths = None
    if args.priors == "method":
        from stripcoef.diagnose.pipeline import prior_widths
        from stripcoef.samples import path

        widths = prior_widths(path("videoray_pro3.yaml"))
    rows = [run(seed, scenario, args.duration, widths) for scenario in ("all", "sway-off")
            for seed in range(args.seeds)]
    if args.json:
        print(json.dumps(rows, indent=1))
        return
    print("| log | shortfall | lag [s] | DOF | prior | calibrated | hold-last-velocity | "
          "beats both |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in rows:
        for d, e in r["errors"].items():
            print(f"| {r['log']} | {r['truth']['shortfall']:.2f} | {r['truth']['lag_s']:.2f} | "
                  f"{d} | {e['prior']:.4f} | {e['calibrated']:.4f} | "
                  f"{e['hold_last_velocity']:.4f} | {'yes' if r['beats_prior_and_hold'][d] else 'NO'} |")
    print()
    for r in rows:
        print(f"{r['log']}: excited {', '.join(r['excited'])}; unexcited DOFs changed: "
              f"{r['unexcited_changed'] or 'none'}; negative drag: {r['negative_drag']}; "
              f"added mass outside bounds: {r['added_mass_outside_bounds'] or 'none'}; "
              f"effects: {r['effects']}; removed on validation: {r['removed_on_validation']}; "
              f"bounds hit: {r['bounds_hit'] or 'none'}; "
              f"{r['seconds']} s")
    n = sum(len(r["beats_prior_and_hold"]) for r in rows)
    k = sum(sum(r["beats_prior_and_hold"].values()) for r in rows)
    print(f"\ncalibrated beats prior and hold-last-velocity in {k} of {n} excited DOFs")


if __name__ == "__main__":
    main()
