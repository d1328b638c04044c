"""What the diagnosis names on clean logs of the independent simulator, and what the truth holds
there (issue 33: "no effect on clean logs").

A clean log of ``validation.independent`` has no effect added, but its truth is not the prior:
every coefficient family is scaled by U(0.75, 1.25), the buoyancy by U(0.98, 1.02) and each
thruster's coefficient by its own factor f_k (both branches; the thrusters' positions and
directions are the prior's). So a step on a clean log is either a real difference of the
truth from the prior (a *background*) or a false positive. The benchmark's own rule
(``benchmarks.diagnose_independent.background``) knows the buoyancy and one thrust gain per
DOF, the mean of the f_k weighted by each thruster's reach; it does not see that the f_k
differ between the thrusters that push a DOF forward and those that push it backward (a
thrust asymmetry of the truth in that DOF), nor which thrusters a log's commands use.

For each step of a whole-log diagnosis of a clean log this module measures the truth's own
thrust in the step's DOF against the prior's map on the log's commands:

- ``eta_forward``, ``eta_backward``: the least-squares factors of the truth's thruster force
  in the DOF on the two parts of the prior's, :math:`F^+_i` and :math:`F^-_i` (the thrusters
  pushing forward and backward, as :class:`stripcoef.effects.thrust.ThrustAsymmetry` splits
  them), i.e. the truth's thrust asymmetry on this log; ``gain``, the one factor on
  :math:`F^+_i + F^-_i` (the truth's thrust effectiveness);
- ``other``: the RMS of the truth's thrust in the DOF that the two factors on the prior's
  parts do not explain, relative to its RMS [-] (the thrusters' own f_k within a branch);
- the verdict: a thrust asymmetry is the truth's when its fitted change
  :math:`\\eta_-/\\eta_+ - 1` is within a factor 2 of the truth's (the same direction,
  between half and twice it), a thrust effectiveness likewise with :math:`s - 1` against
  :math:`g - 1`, a buoyancy offset when the truth's buoyancy differs from the prior's
  (always, it is drawn); any other effect is a false positive. (The benchmark's own rule
  asks the truth's gain to differ from 1 by more than ``THRUST_BAND``, 5 %: an asymmetry of
  2.6 % found as 2.5 % is then counted spurious.)

Usage:
    python -m benchmarks.clean_background --seed S [--repeats 2] [--vehicles videoray_pro3,...]
        [--duration 300]

The seeds are those of ``python -m benchmarks.diagnose_independent --seed S --categories
clean --repeats R`` (the same logs); ``--category-index 11`` gives those of a run of every
category (clean is the twelfth).
"""

from __future__ import annotations

import argparse
import os
import time
import warnings

from benchmarks.diagnose_independent import truth_factors, truth_thrust  # noqa: F401

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


def verdict(effect: str, factors: dict, buoyancy_change: float, parameters: dict) -> str:
    """``background`` or ``false positive`` for a step naming ``effect`` with ``parameters``
    (module docstring); a thrust asymmetry or effectiveness whose fitted change goes the
    other way from the truth's is a false positive (``wrong direction``)."""
    if effect == "buoyancy_offset":
        return "background" if buoyancy_change != 0.0 else "false positive"
    if effect == "thrust_asymmetry":
        truth = factors["eta_backward"] / factors["eta_forward"] - 1.0
        fitted = parameters["eta_backward"] / parameters["eta_forward"] - 1.0
    elif effect == "thrust_effectiveness":
        truth, fitted = factors["gain"] - 1.0, parameters["scale"] - 1.0
    else:
        return "false positive"
    if truth * fitted <= 0.0:
        return "false positive (wrong direction)"
    return "background" if 0.5 < fitted / truth < 2.0 else "false positive"


def trace(vehicle: str, seed: int, duration: float) -> list[dict]:
    """Every step of the whole-log diagnosis of the clean log (``vehicle``, ``seed``): its DOF,
    effect, parameters, kept or not, the truth's factors there and the verdict."""
    from benchmarks.diagnose_independent import _prior
    from stripcoef.conventions import parse_dof
    from stripcoef.diagnose.pipeline import diagnose
    from validation.independent import GRAVITY, generate

    prior = _prior(vehicle)
    p = prior.to_dict()
    log, truth = generate(p, None, seed, duration=duration)
    db = float(truth.buoyancy - float(p["density"]) * float(p["volume"]) * GRAVITY)
    c0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof="all", time_limit=float("inf")).to_dict()
    cpu = time.process_time() - c0
    rows = []
    for d, r in res["per_dof"].items():
        for s in r["steps"]:
            f = truth_factors(log, truth, prior, parse_dof(d))
            par = s.get("final_parameters") or s["parameters"]
            rows.append({"vehicle": vehicle, "seed": seed, "dof": d, "effect": s["effect"],
                         "kept": bool(s.get("kept", True)),
                         "parameters": {k: float(v) for k, v in par.items()
                                        if isinstance(v, (int, float))},
                         "held_out_gain": s.get("held_out_gain"),
                         "buoyancy_change": db, **f,
                         "verdict": verdict(s["effect"], f, db, par), "cpu_s": cpu})
    if not rows:
        rows.append({"vehicle": vehicle, "seed": seed, "dof": None, "effect": None,
                     "cpu_s": cpu})
    return rows


def main(argv=None) -> int:
    from benchmarks.diagnose_independent import VEHICLES, log_seed
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--vehicles", default=",".join(VEHICLES))
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--category-index", type=int, default=0,
                    help="the clean category's place in the run's list of categories (0 with "
                         "--categories clean; 11 in a run of every category)")
    args = ap.parse_args(argv)
    print("| vehicle | seed | DOF | effect | kept | parameters | truth eta+ | truth eta- "
          "| truth eta-/eta+ | truth gain | truth thrust not on the prior's (RMS share) "
          "| buoyancy change [N] | verdict |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    cpu = 0.0
    for rep in range(args.repeats):
        # the seeds of diagnose_independent's clean logs
        for v, vehicle in enumerate(args.vehicles.split(",")):
            rows = trace(vehicle, log_seed(args.seed, rep, v, args.category_index),
                         args.duration)
            cpu += rows[0]["cpu_s"]
            for r in rows:
                if r["effect"] is None:
                    print(f"| {vehicle} | {r['seed']} | - | none | - | - | - | - | - | - | - "
                          f"| - | - |")
                    continue
                par = ", ".join(f"{k} {v:.3g}" for k, v in r["parameters"].items())
                ratio = r["eta_backward"] / r["eta_forward"]
                print(f"| {vehicle} | {r['seed']} | {r['dof']} | {r['effect']} "
                      f"| {'yes' if r['kept'] else 'no'} | {par} | {r['eta_forward']:.3f} "
                      f"| {r['eta_backward']:.3f} | {ratio:.3f} | {r['gain']:.3f} "
                      f"| {r['other']:.3f} | {r['buoyancy_change']:+.3f} | {r['verdict']} |",
                      flush=True)
    print(f"\nDiagnosis CPU {cpu:.1f} s in all.")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
