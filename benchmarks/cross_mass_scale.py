r"""Whole-log spurious thrust scales of a closed loop's feed-forward, paired (issue 33).

Each log of the independent benchmark (``benchmarks.diagnose_independent``, its seeds: a
log's seed is ``seed + 100000 repeat + 1000 vehicle + category``) is generated once and
diagnosed whole-log twice, without and with the test of
:mod:`stripcoef.diagnose.crossscale` (a thrust scale identified apart from the other DOFs'
added masses, diagnose's ``cross_mass_scale``). Per log and run: the effect named first in
the effect's own DOF, the error cut there, and the spurious steps named and kept by the
benchmark's truth rule (``truth_effects``, ``spurious_steps``: a step in a DOF where the
truth's own change on the log is not that effect), each thrust scale's fitted change, z
and the truth's. The oracle (``validation.detectability``) is not run: this compares the
selection on the same logs, nothing else. CPU time (user + sys of the process) per log.

Run: ``python -m benchmarks.cross_mass_scale --seed 29112026 --only-seeds
29113033,29113030,29113031,29113026`` (the four BlueROV2-like logs of the issue-size run,
``benchmarks/data/diagnose_independent_300s.md``). Output: ``benchmarks/data/
cross_mass_scale.md``.
"""
from __future__ import annotations

import argparse
import json
import os
import time
import warnings

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


def paired(vehicle: str, category: str, log_seed: int, duration: float,
           arms=("off", "on")) -> dict:
    """One log (generated once) diagnosed whole-log without and with the test: ``{"off":
    row, "on": row}`` (the ``arms`` asked for), each row
    ``benchmarks.diagnose_independent``'s whole-log row with its ``truth_has`` and ``cpu``
    [s]."""
    from benchmarks.diagnose_independent import (_background, _diagnosed, _prior,
                                                 truth_effects)
    from validation.independent import OUTSIDE, STRENGTHS, generate

    prior = _prior(vehicle)
    cat = None if category == "clean" else category
    dof_name = ({**STRENGTHS, **OUTSIDE}.get(cat) or ("surge",))[0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        log, truth = generate(prior.to_dict(), cat, log_seed, duration=duration)
    out = {}
    for key, flag in (("off", False), ("on", True)):
        if key not in arms:
            continue
        t0 = time.process_time()
        row = {**_diagnosed(log, truth, prior, vehicle, cat, log_seed, "all", dof_name, 0.0,
                            options={"cross_mass_scale": flag}),
               **_background(truth, prior.to_dict())}
        row["truth_has"] = truth_effects(log, truth, prior, row)
        row["cpu"] = time.process_time() - t0
        out[key] = row
    return out


def _scales(row: dict) -> str:
    """The thrust scales of a row's steps outside its own DOF: DOF, fitted change, z,
    the truth's change, * when kept."""
    out = []
    for d, recs in row.get("truth_has", {}).items():
        for r in recs:
            if r["effect"] == "thrust_effectiveness":
                out.append(f"{d} {r['fitted']:+.3f} (z {r['z']:.1f}; truth {r['truth']:+.3f})"
                           + ("*" if r["kept"] else ""))
    return "; ".join(out) or "-"


def table(pairs: list) -> str:
    """The markdown table of the rows (each arm a pair holds, ``off`` / ``on``) and the
    totals."""
    from benchmarks.diagnose_independent import _spurious, spurious_steps
    arms = [k for k in ("off", "on") if all(k in p for p in pairs)]
    sep = " / ".join(arms)
    lines = [f"| log | named first {sep} | cut {sep} | spurious named {sep} | spurious kept "
             f"{sep} | other-DOF thrust scales {' -> '.join(arms)} | CPU {sep} [s] |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    tot = {k: [0, 0] for k in arms}
    lib = 0
    for p in pairs:
        a = p[arms[0]]
        s = {k: (_spurious(p[k], "step_effects"), _spurious(p[k], "step_effects_kept"))
             for k in arms}
        library = a["category"] not in ("clean", "coulomb_friction")
        lib += library
        for k in arms:
            if library:
                tot[k][0] += bool(s[k][0])
                tot[k][1] += bool(s[k][1])

        def yn(i):
            return " / ".join("yes" if s[k][i] else "no" for k in arms)
        lines.append(f"| {a['vehicle']} {a['category']} {a['seed']} | "
                     + " / ".join(str(p[k]["first"]) for k in arms) + " | "
                     + " / ".join(f"{p[k]['cut']:.2f}" for k in arms)
                     + f" | {yn(0)} | {yn(1)} | "
                     + " -> ".join(_scales(p[k]) for k in arms) + " | "
                     + " / ".join(f"{p[k]['cpu']:.1f}" for k in arms) + " |")
    lines += ["", "Library-effect logs with a spurious whole-log step (truth rule): named "
              + " -> ".join(str(tot[k][0]) for k in arms) + f" of {lib}, kept "
              + " -> ".join(str(tot[k][1]) for k in arms) + f" of {lib}.", ""]
    for k in arms:
        lines.append(f"Spurious steps, test {k}: "
                     + ("; ".join(spurious_steps([p[k] for p in pairs])) or "none") + ".")
    return "\n".join(lines)


def main(argv=None) -> int:
    from benchmarks.diagnose_independent import log_of
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, required=True, help="the run's base seed")
    ap.add_argument("--only-seeds", required=True, help="comma-separated log seeds")
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--arms", default="off,on",
                    help="off,on (paired) or on alone (the stored run of main is the 'off': "
                         "the diagnosis is unchanged without the test)")
    args = ap.parse_args(argv)
    arms = tuple(args.arms.split(","))
    pairs = []
    for s in (int(x) for x in args.only_seeds.split(",")):
        vehicle, category, _ = log_of(args.seed, s)
        p = paired(vehicle, category, s, args.duration, arms)
        print(f"{s} pair {json.dumps(p, default=str)}", flush=True)
        pairs.append(p)
    print(table(pairs))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
