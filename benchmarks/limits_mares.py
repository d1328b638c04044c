"""Wall-clock time of ``stripcoef limits geometry/mares.yaml`` (docs/performance.md).

Run from the repository root:

    python -m benchmarks.limits_mares [--repeat 5] [VEHICLE]

Each repeat is a fresh process (interpreter start, imports, strip-theory estimate,
limits with the default 40 radii, table printed to /dev/null).  Prints the median and the
range; the solver alone is timed in-process as well.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("vehicle", nargs="?", default=str(ROOT / "geometry" / "mares.yaml"))
    p.add_argument("--repeat", type=int, default=5)
    args = p.parse_args()

    cmd = [sys.executable, "-m", "stripcoef", "limits", args.vehicle]
    wall = []
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        wall.append(time.perf_counter() - t0)

    import stripcoef
    from stripcoef.limits.solver import solve_limits

    model = stripcoef.estimate(stripcoef.load_vehicle(args.vehicle))   # warm-up
    solver, nomunk = [], []
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        solve_limits(model)
        solver.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        solve_limits(model, munk=False)
        nomunk.append(time.perf_counter() - t0)

    print(f"command: stripcoef limits {args.vehicle}")
    print(f"  whole command   median {statistics.median(wall):.3f} s  "
          f"(min {min(wall):.3f}, max {max(wall):.3f}, {args.repeat} runs)")
    print(f"  solve_limits    median {statistics.median(solver):.3f} s  "
          f"(min {min(solver):.3f}, max {max(solver):.3f}; 40 radii, Munk on)")
    print(f"  solve_limits    median {statistics.median(nomunk):.3f} s  "
          f"(min {min(nomunk):.3f}, max {max(nomunk):.3f}; 40 radii, Munk off)")
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", "import stripcoef.limits.solver, stripcoef.assembly.estimate"],
                   check=True)
    print(f"  interpreter + imports {time.perf_counter() - t0:.3f} s (one run)")


if __name__ == "__main__":
    main()
