"""Samples per second of an uncertainty study, per core and with 1 and 2 local workers.

Two workloads on a shipped vehicle: the model only (estimate: vehicle file -> HydroModel),
and the model plus the manoeuvre limits (6 turning radii). Each is timed as the whole study
call (sampling, pickling to the workers, evaluation, gathering), best of ``--repeat``.

Run: python -m benchmarks.study_throughput [--vehicle geometry/mares.yaml] [--samples 64]
The numbers and the sizing of a 10^6-sample study are in docs/performance.md.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

ROOT = Path(__file__).resolve().parent.parent

from stripcoef.study.uncertainty import uncertainty  # noqa: E402


def rate(vehicle, samples, limits, workers, repeat):
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        uncertainty(vehicle, samples=samples, seed=0, limits=limits, workers=workers,
                    progress=False)
        best = min(best, time.perf_counter() - t0)
    return samples / best


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--vehicle", default=str(ROOT / "geometry" / "mares.yaml"))
    ap.add_argument("--samples", type=int, default=64)
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args(argv)
    print(f"vehicle {Path(args.vehicle).name}, {args.samples} samples, best of {args.repeat}")
    print("| workload | 1 worker [samples/s] | 2 workers [samples/s] | speed-up |")
    print("|---|---|---|---|")
    for limits in (False, True):
        r1 = rate(args.vehicle, args.samples, limits, 1, args.repeat)
        r2 = rate(args.vehicle, args.samples, limits, 2, args.repeat)
        label = "estimate + limits" if limits else "estimate only"
        print(f"| {label} | {r1:.2f} | {r2:.2f} | {r2 / r1:.2f} |")
        if limits:
            per_core = r1
            for n in (10 ** 6,):
                core_hours = n / per_core / 3600
                print(f"\n{n:.0e} samples of estimate + limits: {core_hours:.0f} core-hours at "
                      f"{per_core:.2f} samples/s per core; on 100 cores {core_hours / 100:.1f} h "
                      f"(plus the scheduler's per-task overhead, small for batches of 8)")


if __name__ == "__main__":
    main()
