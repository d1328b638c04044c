"""Before/after of ``stripcoef.diagnose.undetermined`` on one log of the independent simulator
(issue 33): the one-DOF diagnosis of the effect's DOF with the rule (a tether found only with
each thruster's gain free is named, its c_t not determined by one DOF, nothing written) and
without it (``diagnose(..., not_determined=False)``: the tether written from the fit with
the prior's thrust map, as before), each reported as the written model: whether the tether is written, its c_t
against the truth in the thrust's units (``benchmarks.diagnose_independent.magnitude_truth``),
the error cut (baseline / final window error of the written model) and the validation's
free-simulation error of the written model.

Usage:
    python -m benchmarks.undetermined_probe [--vehicle bluerov2_heavy] [--seeds 28113028 ...]
        [--duration 300]
"""

from __future__ import annotations

import argparse
import time
import warnings


def compare(vehicle: str, seed: int, duration: float) -> dict:
    """The record of one log: for ``rule`` and ``no_rule``, the written c_t (None when not
    written), its relative error, the reported not-determined record, the cut, the
    validation error of the written model and the CPU time [s]."""
    from benchmarks.diagnose_independent import _prior, magnitude_truth
    from stripcoef.diagnose import pipeline
    from stripcoef.diagnose.written import written_effects
    from validation.independent import generate

    prior = _prior(vehicle)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        log, truth = generate(prior.to_dict(), "tether_drag", seed, duration=duration)
    ref = magnitude_truth(truth, prior.to_dict(), "tether_drag", "surge")
    out = {"vehicle": vehicle, "seed": seed, "truth": float(ref)}
    for name, rule in (("rule", True), ("no_rule", False)):
        t0 = time.process_time()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = pipeline.diagnose(log, prior, dof="surge", time_limit=float("inf"),
                                    not_determined=rule)
        r = res.per_dof["surge"]
        step = next((s for s in r.steps if s.effect == "tether_drag"), None)
        written = written_effects(res.model, "surge").get("tether_drag")
        c_t = None if written is None else float(written["c_t"])
        out[name] = {"named": step is not None, "first": r.steps[0].effect if r.steps else None,
                     "written_c_t": c_t,
                     "error": None if c_t is None else (c_t - ref) / ref,
                     "not_determined": None if step is None or not step.not_determined else
                     {k: step.not_determined[k] for k in ("gains_free", "gains_free_std",
                                                          "prior_map", "z")},
                     "cut": float(r.baseline_error / r.final_error),
                     "validation_error": (res.validation or {}).get("kept_changes",
                                                                    {}).get("surge"),
                     "prior_validation_error": (res.validation or {}).get("prior",
                                                                          {}).get("surge"),
                     "cpu_s": time.process_time() - t0}
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--vehicle", default="bluerov2_heavy")
    ap.add_argument("--seeds", type=int, nargs="+", default=[28113028])
    ap.add_argument("--duration", type=float, default=300.0)
    args = ap.parse_args(argv)
    print("| log | truth c_t | rule: written c_t / gain-free (error) / cut / validation | "
          "no rule: written c_t (error) / cut / validation | prior's validation |")
    print("| --- | --- | --- | --- | --- |")
    for seed in args.seeds:
        rec = compare(args.vehicle, seed, args.duration)
        a, b = rec["rule"], rec["no_rule"]

        def c(x):
            return ("-" if x["written_c_t"] is None
                    else f"{x['written_c_t']:.3f} ({100 * x['error']:+.1f} %)")
        nd = a["not_determined"]
        gf = ("" if nd is None else f" / {nd['gains_free']:.3f} ± {nd['gains_free_std']:.3f} "
              f"({100 * (nd['gains_free'] - rec['truth']) / rec['truth']:+.1f} %)")
        val = (lambda x: "-" if x is None else f"{x:.4g}")
        print(f"| {seed} | {rec['truth']:.4f} | {c(a)}{gf} / {a['cut']:.2f} / "
              f"{val(a['validation_error'])} | {c(b)} / {b['cut']:.2f} / "
              f"{val(b['validation_error'])} | {val(a['prior_validation_error'])} |",
              flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
