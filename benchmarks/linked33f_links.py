"""The identified mode's link decision on logs of ``benchmarks.diagnose_independent``, without
the diagnosis (linked33f, issue 33).

    python -m benchmarks.linked33f_links --seed S --logs LOG1,LOG2,... [--duration 300]

For each log seed (of the benchmark's job numbering, ``seed + 100000 rep + 1000 v + c``; the
category from the full list of the benchmark, as without ``--categories``): the log is
generated as the benchmark does, split as a whole-log ``diagnose`` splits it (the validation
part, ``VALIDATION_FRACTION``), windowed on the prior, its DOFs selected, and the whole-log
gains fitted with ``linked_gains="identified"`` exactly as the pipeline does before any
effect; printed: each pair of thruster groups that shares a diagnosed DOF, its information
ratio against the bench band (the decision) and against the log's spread (recorded only).

Where the vehicle has two default groups (both shipped vehicles), the identified mode's
whole-log row is therefore the default's (not linked) or ``linked_gains=True``'s (linked): the
rest of the diagnosis is the same code on the same groups. A full run's rows carry the same
record (``gain_links``), which checks this script against the pipeline.
"""

from __future__ import annotations

import argparse
import time
import warnings


def links(seed: int, log_seed: int, duration: float) -> dict:
    """The log's vehicle, category and the gains' ``links`` record (or None)."""
    from benchmarks.diagnose_independent import _prior, log_of
    from stripcoef.diagnose.gains import fit_thruster_gains
    from stripcoef.diagnose.heldout import split
    from stripcoef.diagnose.select import select_dofs
    from stripcoef.diagnose.settings import VALIDATION_FRACTION, DiagnoseSettings
    from stripcoef.effects.laws import model_window_data
    from validation.independent import generate

    vehicle, category, _ = log_of(seed, log_seed)
    prior = _prior(vehicle)
    settings = DiagnoseSettings(linked_gains="identified")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        log, _ = generate(prior.to_dict(), None if category == "clean" else category, log_seed,
                          duration=duration)
        train, _ = split(log, VALIDATION_FRACTION, key="validation")
        data = model_window_data(train, prior, window=settings.window)
        excited, _ = select_dofs(data)
        fit = fit_thruster_gains(data, excited, settings, excited=excited)
    rec = fit.to_dict() if fit is not None else {}
    return {"vehicle": vehicle, "category": category, "seed": log_seed,
            "links": rec.get("links")}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--logs", required=True, help="comma-separated log seeds")
    ap.add_argument("--duration", type=float, default=300.0)
    args = ap.parse_args(argv)
    for s in args.logs.split(","):
        t0 = time.process_time()
        got = links(args.seed, int(s), args.duration)
        text = "; ".join(
            f"{'+'.join(map(str, lk['groups'][0]))} vs {'+'.join(map(str, lk['groups'][1]))} "
            f"via {','.join(lk['dofs'])}: ratio {lk['information_ratio']:.3f} (spread "
            f"{lk['information_ratio_spread']:.3f}){' linked' if lk['linked'] else ''}"
            for lk in got["links"] or ())
        print(f"{got['vehicle']} {got['category']} {got['seed']}: {text or 'no pair'} "
              f"({time.process_time() - t0:.1f} s CPU)", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
