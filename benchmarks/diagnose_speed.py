"""CPU and wall time of a whole-log `diagnose` (``dof="all"``) on a long log (issue 33: a
one-hour 6-DOF log at 20 Hz, 72,000 rows, in under 2 minutes).

The log comes from the independent 6-DOF simulator of ``validation.independent`` (its own
integrator, thrusters, pilot and noise) for the BlueROV2-Heavy-like vehicle with one library
effect (default: tether drag) at 20 Hz; the prior is stripcoef's model of
``geometry/bluerov2_heavy.yaml``. Generating an hour takes a few minutes of CPU (a Python
RK4 at 10 ms): ``--save-log FILE.csv`` writes it once and ``--log FILE.csv`` reads it back
for the next runs. The diagnosis runs with its defaults (a quarter of the fitting log kept
for the validation by free simulation) and no time budget; each run prints its CPU
(``time.process_time``) and wall time and what it found.

Usage:
    python -m benchmarks.diagnose_speed [--duration 3600] [--rate 20] [--effect tether_drag]
        [--seed 5] [--repeat 1] [--save-log FILE.csv | --log FILE.csv]
"""

from __future__ import annotations

import argparse
import os
import time
import warnings
from pathlib import Path

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

ROOT = Path(__file__).resolve().parent.parent
VEHICLE = "bluerov2_heavy"


def prior_model():
    """The prior: stripcoef's model of geometry/bluerov2_heavy.yaml."""
    import stripcoef
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return stripcoef.estimate(ROOT / "geometry" / f"{VEHICLE}.yaml")


def make_log(prior, duration: float, rate: float, effect: str | None, seed: int):
    """A log of ``duration`` s at ``rate`` Hz from the independent simulator (and its CPU)."""
    from validation.independent import generate

    t0 = time.process_time()
    log, _ = generate(prior.to_dict(), effect, seed, duration=duration, rate=rate)
    return log, time.process_time() - t0


def run(log, prior) -> dict:
    """One whole-log diagnosis: CPU and wall time [s], the DOFs and the steps it found."""
    from stripcoef.diagnose import diagnose

    c0, w0 = time.process_time(), time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof="all", time_limit=float("inf"))
    cpu, wall = time.process_time() - c0, time.perf_counter() - w0
    return {"cpu": cpu, "wall": wall, "dofs": list(res.per_dof),
            "steps": [f"{s.dof} {s.effect}" for s in res.steps],
            "final_error": float(res.final_error)}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=3600.0, help="log length [s]")
    ap.add_argument("--rate", type=float, default=20.0, help="sampling rate [Hz]")
    ap.add_argument("--effect", default="tether_drag", help="library effect, or 'clean'")
    ap.add_argument("--seed", type=int, default=5)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--save-log", type=Path, help="write the generated log to this CSV")
    ap.add_argument("--log", type=Path, help="diagnose this CSV instead of generating one")
    args = ap.parse_args(argv)

    from stripcoef.logfile import read_log

    prior = prior_model()
    if args.log:
        log = read_log(args.log)
        print(f"log {args.log}: {len(log)} rows")
    else:
        log, gen = make_log(prior, args.duration, args.rate,
                            None if args.effect == "clean" else args.effect, args.seed)
        print(f"log: {len(log)} rows ({args.duration:g} s at {args.rate:g} Hz, "
              f"{args.effect}, seed {args.seed}), generated in {gen:.1f} s CPU")
        if args.save_log:
            log.write_csv(args.save_log)
    for k in range(args.repeat):
        r = run(log, prior)
        print(f"run {k + 1}: whole-log diagnose {r['cpu']:.1f} s CPU, {r['wall']:.1f} s wall; "
              f"DOFs {', '.join(r['dofs'])}; steps: {'; '.join(r['steps']) or 'none'}; "
              f"final error {r['final_error']:.4g}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
