"""Do the thrust scale's reported bands cover the truth, with and without the consider term?

Logs of the independent 6-DOF simulator (``validation.independent``: its own equations,
integrator, pilot and noise; every coefficient family of the truth scaled by U(0.75, 1.25),
within the calibration's bands, :data:`stripcoef.diagnose.settings.BANDS`), a clean log and a
thrust-effectiveness log per vehicle and repeat, each with its own seed (a fresh base seed
per run unless ``--seed``). In each log's surge DOF the fixed structure "calibration +
thrust scale" is fitted as the diagnosis fits it (the same window data, calibration, the
coefficients the log does not determine held at the prior: ``select._dof_calibration``,
``fit._evaluate``), and the scale s +- its standard deviation is compared with the truth's
thrust gain of the DOF (``benchmarks.diagnose_independent.thrust_gain``: the per-thruster
spread and the effectiveness):

- ``data``: the standard deviation of the data alone (the fit's covariance without the
  held coefficients, ``cov_data``: the band before issue 33's consider term);
- ``consider``: with the consider term of the held coefficients
  (``stripcoef.diagnose.consider``: Tapley, Schutz & Born 2004, sec. 6.3).

Printed per variant: the share of logs whose truth lies within 1 and 1.96 standard
deviations (claimed: 68.3 % and 95 %), each with its exact 95 % Clopper-Pearson interval, and
the RMS of the normalised error (s - gain)/sd (1 for a calibrated band).

Usage:
    python -m benchmarks.consider_coverage [--seed S] [--repeats 6] [--duration 120]
        [--vehicles videoray_pro3,bluerov2_heavy] [--write FILE.md]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings

import numpy as np

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

CATEGORIES = ("clean", "thrust_effectiveness")
#: Two-sided normal quantiles of the bands checked: 68.27 % and 95 % [-].
LEVELS = ((1.0, 0.6827), (1.959964, 0.95))


def one_log(vehicle: str, category: str, seed: int, duration: float) -> dict:
    """The scale fitted with the calibration in surge on one log, against the truth's gain."""
    from benchmarks.diagnose_independent import _prior, thrust_gain
    from stripcoef.diagnose.fit import _Config, _evaluate
    from stripcoef.diagnose.select import _dof_calibration, excited_dofs
    from stripcoef.diagnose.settings import DiagnoseSettings
    from stripcoef.effects import get_effect
    from stripcoef.effects.windows import window_data
    from validation.independent import generate

    prior = _prior(vehicle)
    log, truth = generate(prior.to_dict(), None if category == "clean" else category, seed,
                          duration=duration)
    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        data = window_data(log, prior)
        settings = DiagnoseSettings()
        excited = excited_dofs(data)
        cal, _ = _dof_calibration(data, 0, settings, excited, [j for j in excited if j != 0])
        cfg = _Config(data, 0, cal, [(get_effect("thrust_effectiveness"), None)],
                      settings=settings)
        full = _evaluate(cfg)["full"]
    return {"vehicle": vehicle, "category": category, "seed": seed,
            "scale": 1.0 + float(full["theta"][-1]),
            "sd_data": float(np.sqrt(max(full["cov_data"][-1, -1], 0.0))),
            "sd_consider": float(np.sqrt(max(full["cov"][-1, -1], 0.0))),
            "gain": float(thrust_gain(truth, prior.to_dict(), 0)),
            "held": list(cal.held_names), "cpu": time.process_time() - t0}


def summarise(rows: list[dict], seed: int, duration: float) -> str:
    """The coverage table of ``rows`` (:func:`one_log`)."""
    from scipy.stats import binomtest

    n = len(rows)
    lines = [f"Seed {seed}: {n} logs of {duration:g} s (surge; categories "
             f"{', '.join(CATEGORIES)}).", "",
             "| band | within 1 sd (claimed 68.3 %) | within 1.96 sd (claimed 95 %) "
             "| RMS of (s - gain)/sd |", "| --- | --- | --- | --- |"]
    lines[2] = "| logs " + lines[2]
    lines[3] = "| --- " + lines[3]
    groups = [("all", rows)] + [(v, [r for r in rows if r["vehicle"] == v])
                                for v in sorted({r["vehicle"] for r in rows})]
    for group, rs in groups:
        m = len(rs)
        for key, label in (("sd_data", "data alone (before)"),
                           ("sd_consider", "with the held coefficients (consider)")):
            z = np.array([(r["scale"] - r["gain"]) / r[key] if r[key] > 0 else np.inf
                          for r in rs])
            cells = []
            for q, _claim in LEVELS:
                k = int(np.sum(np.abs(z) <= q))
                ci = binomtest(k, m).proportion_ci(0.95, method="exact") if m else None
                cells.append(f"{k}/{m} ({100 * k / m:.0f} %, CI {100 * ci.low:.0f}-"
                             f"{100 * ci.high:.0f} %)" if m else "-")
            lines.append(f"| {group} | {label} | " + " | ".join(cells)
                         + f" | {float(np.sqrt(np.mean(z ** 2))):.2f} |")
    lines += ["", "| vehicle | category | seed | scale | sd data | sd consider | truth gain |",
              "| --- | --- | --- | --- | --- | --- | --- |"]
    for r in sorted(rows, key=lambda r: (r["vehicle"], r["category"], r["seed"])):
        lines.append(f"| {r['vehicle']} | {r['category']} | {r['seed']} | {r['scale']:.3f} | "
                     f"{r['sd_data']:.3f} | {r['sd_consider']:.3f} | {r['gain']:.3f} |")
    cpu = [r["cpu"] for r in rows if "cpu" in r]
    if cpu:
        lines += ["", f"Mean CPU time of a fit: {np.mean(cpu):.2f} s."]
    return "\n".join(lines)


def main(argv=None) -> int:
    from benchmarks.diagnose_independent import VEHICLES
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=None, help="base seed (default: a fresh one)")
    ap.add_argument("--repeats", type=int, default=6, help="logs per category and vehicle")
    ap.add_argument("--duration", type=float, default=120.0, help="log length [s]")
    ap.add_argument("--vehicles", default=",".join(VEHICLES))
    ap.add_argument("--write", default=None, help="write the table to this markdown file")
    ap.add_argument("--from-output", default=None,
                    help="summarise the per-log table of an earlier run's output instead of "
                         "running")
    args = ap.parse_args(argv)
    seed = args.seed if args.seed is not None else int(np.random.SeedSequence().entropy % 10**6)
    if args.from_output:
        from stripcoef.files import read_text
        rows = []
        for line in read_text(args.from_output, kind="benchmark output").splitlines():
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) == 7 and cells[1] in CATEGORIES:
                rows.append({"vehicle": cells[0], "category": cells[1], "seed": int(cells[2]),
                             **{k: float(v) for k, v in zip(
                                 ("scale", "sd_data", "sd_consider", "gain"), cells[3:])}})
        text = summarise(rows, seed, args.duration)
        print(text)
        if args.write:
            _write(args.write, argv, text)
        return 0
    print(f"seed {seed}", flush=True)
    rows = []
    for rep in range(args.repeats):
        for v, vehicle in enumerate(args.vehicles.split(",")):
            for c, cat in enumerate(CATEGORIES):
                r = one_log(vehicle, cat, seed + 100000 * rep + 1000 * v + c, args.duration)
                print(f"  {vehicle} {cat} seed {r['seed']}: scale {r['scale']:.3f} +- "
                      f"{r['sd_data']:.3f} (data) +- {r['sd_consider']:.3f} (consider), "
                      f"truth gain {r['gain']:.3f}", flush=True)
                rows.append(r)
    text = summarise(rows, seed, args.duration)
    print(text)
    if args.write:
        _write(args.write, argv, text)
    return 0


def _write(path, argv, text: str) -> None:
    """The markdown file of a run: its command, then the summary."""
    from stripcoef.files import write_text
    write_text(path, "# Thrust scale bands against the truth\n\nMeasured by "
               f"`python -m benchmarks.consider_coverage "
               f"{' '.join(sys.argv[1:] if argv is None else argv)}`.\n\n{text}\n")


if __name__ == "__main__":
    raise SystemExit(main())
