"""Which of the prior's errors hides an effect at the first step (issue 33): the oracle's test
on the prior, repeated with one group of the prior's coefficients taken from the truth.

``validation.detectability`` calls a named-first miss "hidden by the prior's other errors" when
the effect is detectable on the truth's own model but its own first-step test
(``first_step_on_prior``) fails on the prior. This benchmark names the error: for one log of
``benchmarks.diagnose_independent`` (vehicle, category, seed) it runs the same test
(``validation.detectability._test``: the effect's coefficient free with its nuisance, every
gate of a step, the evidence gate) on the fitting part of the log against

- the prior (the oracle's ``prior`` record);
- the prior with one group of :data:`benchmarks.cut_trace.GROUPS` (the DOF's own added mass,
  its own drags, the other DOFs' added masses, the other drags, the buoyancy, the thrust map)
  taken from the truth's model without the effect (``validation.detectability.truth_without``);
- the truth's model without the effect with one group taken from the prior;
- the truth's model without the effect (the oracle's ``truth`` record).

A group whose swap into the prior makes the test pass is an error that hides the effect by
itself; one whose swap into the truth makes it fail is an error enough to hide it. No
threshold of the diagnosis is changed; the effect's true window force is the oracle's.

Usage:
    python -m benchmarks.hidden_trace --rows VEHICLE:CATEGORY:SEED[,...] [--duration 300]
"""

from __future__ import annotations

import argparse
import os
import time
import warnings

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


def trace(vehicle: str, category: str, seed: int, duration: float = 300.0) -> dict:
    """The test of one log's effect on the prior, on the prior with each group swapped for
    the truth's (without the effect), and on the truth's model: ``{label: record}``, each
    record ``validation.detectability._test``'s with ``passes`` (every gate and the one-DOF
    evidence level)."""
    from stripcoef.conventions import parse_dof
    from stripcoef.diagnose.heldout import split
    from stripcoef.diagnose.settings import DEFAULT_WINDOW, VALIDATION_FRACTION, DiagnoseSettings
    from stripcoef.effects.windows import window_data
    from stripcoef.model import HydroModel
    from validation.detectability import _test, effect_force, truth_model, truth_without
    from validation.independent import STRENGTHS, generate

    from benchmarks.cut_trace import GROUPS, _swap
    from benchmarks.diagnose_independent import _prior

    prior = _prior(vehicle)
    i = parse_dof(STRENGTHS[category][0])
    log, truth = generate(prior.to_dict(), category, seed, duration=duration)
    train, _ = split(log, VALIDATION_FRACTION, key="validation")
    settings = DiagnoseSettings()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        without, force, _ = effect_force(train, prior, truth)
        source = truth_model(prior, truth_without(prior, truth)).to_dict()
        models = {"prior": prior.to_dict()}
        groups = [g for g in GROUPS if g != "force_effects"]
        models.update({f"prior <- truth {g}": _swap(prior.to_dict(), source, g, i)
                       for g in groups})
        models.update({f"truth <- prior {g}": _swap(source, prior.to_dict(), g, i)
                       for g in groups})
        out = {}
        for label, d in models.items():
            data = window_data(train, HydroModel.from_dict(d), window=DEFAULT_WINDOW)
            out[label] = _test(data, i, category, force[:, i], settings)
        out["truth without the effect"] = _test(without, i, category, force[:, i], settings)
    for rec in out.values():
        rec["passes"] = bool(rec["significant"] and rec["p_value"] <= rec["level"])
    return out


def _text(vehicle: str, category: str, seed: int, rec: dict) -> list[str]:
    lines = [f"{vehicle} {category} {seed}:", "",
             "| model | passes | estimate | z | held-out gain | p (level) | fails |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    for label, r in rec.items():
        lines.append(f"| {label} | {'yes' if r['passes'] else 'no'} | {r['estimate']:.3g} | "
                     f"{r['z']:.1f} | {100 * r['held_out_gain']:.1f} % | {r['p_value']:.2g} "
                     f"({r['level']:.2g}) | {'; '.join(r['rejected_because']) or '-'} |")
    return lines


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", required=True, help="VEHICLE:CATEGORY:SEED[,...]")
    ap.add_argument("--duration", type=float, default=300.0)
    args = ap.parse_args(argv)
    for item in args.rows.split(","):
        vehicle, category, seed = item.split(":")
        t0 = time.process_time()
        rec = trace(vehicle, category, int(seed), args.duration)
        print("\n".join(_text(vehicle, category, int(seed), rec)))
        print(f"\n({time.process_time() - t0:.1f} s of CPU)\n", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
