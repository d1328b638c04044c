"""Probe of a per-DOF tether's c_t against the thrust map's error (issue 33): on one log of
the independent simulator (``validation.independent``), the surge diagnosis of one DOF, then
its tether's c_t refitted in the same calibration with (a) the prior's thrust map (what a
one-DOF diagnosis writes), (b) the DOF's thrust scale fitted with it
(``stripcoef.effects.thrust.ThrustEffectiveness``: the gains' common part, the one thrust
nuisance a DOF can write) and (c) each thruster's gain free
(``stripcoef.diagnose.gainfree``: the retest's fit, not writable by one DOF), each against
the truth in the units the log determines it (``benchmarks.diagnose_independent``'s
``magnitude_truth``, at the fitted scale for (b), at the selection's own thrust scale, if it
wrote one, for (a) and (c); (b) is then not fitted). The selection's values are before the
validation (which may remove or refit steps): the benchmark's rows are after it.

Usage:
    python -m benchmarks.tether_gain_probe [--vehicle bluerov2_heavy] [--seed 28113028]
        [--duration 300]
"""

from __future__ import annotations

import argparse
import warnings


def probe(vehicle: str, seed: int, duration: float) -> dict:
    """The record of the probe (module docstring): the three fits' c_t and scale, the
    truth's c_t in the thrust's units for each, and the relative errors."""
    from benchmarks.diagnose_independent import _prior, magnitude_truth
    from stripcoef.diagnose.cross import moving_dofs
    from stripcoef.diagnose.fit import _evaluate
    from stripcoef.diagnose.gainfree import GAINS_FREE
    from stripcoef.diagnose.heldout import split
    from stripcoef.diagnose.select import diagnose_dof, select_dofs
    from stripcoef.diagnose.settings import VALIDATION_FRACTION, DiagnoseSettings
    from stripcoef.effects.laws import get_effect
    from stripcoef.effects.windows import window_data
    from validation.independent import generate

    prior = _prior(vehicle)
    settings = DiagnoseSettings(validation=VALIDATION_FRACTION)   # diagnose()'s default
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        log, truth = generate(prior.to_dict(), "tether_drag", seed, duration=duration)
        # the training part as stripcoef.diagnose.pipeline.run takes it
        fit_log = log if not settings.holdout else split(log, settings.holdout,
                                                         key="holdout")[0]
        train = fit_log if not settings.validation else split(fit_log, settings.validation,
                                                              key="validation")[0]
        data = window_data(train, prior, window=settings.window)
        excited, _ = select_dofs(data)
        res, fit = diagnose_dof(data, 0, settings, excited=excited, cross=moving_dofs(data))
        steps = [s.effect for s in res.steps]
        if "tether_drag" not in steps:
            return {"vehicle": vehicle, "seed": seed, "steps": steps, "tether": None}
        terms = list(fit.config.terms)
        k = next(i for i, (e, _) in enumerate(terms) if e.name == "tether_drag")
        others = terms[:k] + terms[k + 1:]
        scale = get_effect("thrust_effectiveness")
        out = {"vehicle": vehicle, "seed": seed, "steps": steps, "selected": next(
            s.final_parameters["c_t"] for s in res.steps if s.effect == "tether_drag"),
            # found by the retest with the gains free (gainfree.with_retest's signature)
            "retested": any("gain free" in (s.signature or "") for s in res.steps
                            if s.effect == "tether_drag")}
        # a thrust scale the selection already wrote in the DOF: the truth is compared at it
        # (magnitude_truth), and (b) is not fitted (a second scale is the same column)
        written = [float(s.final_parameters["scale"]) for s in res.steps
                   if s.effect == "thrust_effectiveness"]
        for name, extra in (("prior_map", []), ("thrust_scale", [(scale, None)]),
                            ("gains_free", None)):
            if extra and written:
                continue
            tether = GAINS_FREE if extra is None else terms[k][0]
            # the scale last (its shortfall profiled, _evaluate); it adds no linear column,
            # so the tether's c_t stays the last parameter
            cfg = fit.config.with_terms(others + [(tether, None)] + (extra or []))
            ev = _evaluate(cfg)
            s = float(scale.residual_scale(ev["hyper"])) if extra else (
                written[0] if written else 1.0)
            c_t = float(ev["full"]["theta"][-1])
            ref = magnitude_truth(truth, prior.to_dict(), "tether_drag", "surge", s, 1.0)
            out[name] = {"c_t": c_t, "scale": s, "truth": float(ref),
                         "error": (c_t - ref) / ref,
                         "held_out_error": float(ev["held_out_error"])}
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--vehicle", default="bluerov2_heavy")
    ap.add_argument("--seed", type=int, default=28113028)
    ap.add_argument("--duration", type=float, default=300.0)
    args = ap.parse_args(argv)
    rec = probe(args.vehicle, args.seed, args.duration)
    print(f"{rec['vehicle']} seed {rec['seed']}: surge steps {rec['steps']}, the "
          f"selection's c_t {rec.get('selected', float('nan')):.4f}, found by the retest with "
          f"the gains free: {rec.get('retested')}")
    for name in ("prior_map", "thrust_scale", "gains_free"):
        r = rec.get(name)
        if r:
            print(f"  {name:12s} c_t {r['c_t']:.4f}  scale {r['scale']:.4f}  truth "
                  f"{r['truth']:.4f}  error {100 * r['error']:+.1f} %  held-out error "
                  f"{r['held_out_error']:.4g}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
