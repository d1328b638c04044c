"""Strip-count convergence and wall time of `estimate` on the shipped vehicles.

Run:  .venv/bin/python -m benchmarks.strip_convergence
Prints, per vehicle and strip count, the largest relative difference of any non-zero diagonal
term of M_A, D_Q and D_L against 6400 strips, and the median wall time of 5 runs.
"""

import statistics
import time
from pathlib import Path

import numpy as np

import stripcoef

ROOT = Path(__file__).resolve().parent.parent


def max_rel(a, b):
    d = np.diag(b)
    mask = d != 0
    return float(np.max(np.abs(np.diag(a)[mask] / d[mask] - 1))) if mask.any() else 0.0


def main():
    print("| vehicle | strips | M_A | D_Q | D_L | median time [s] |")
    print("|---|---|---|---|---|---|")
    for name in ("mares", "videoray_pro3", "capsule", "spheroid"):
        v = stripcoef.load_vehicle(ROOT / "geometry" / f"{name}.yaml")
        ref = stripcoef.estimate(v, strips=6400)
        for n in (100, 200, 400, 1000, 2000):
            times = []
            for _ in range(5):
                t0 = time.perf_counter()
                m = stripcoef.estimate(v, strips=n)
                times.append(time.perf_counter() - t0)
            print(f"| {name} | {n} | {max_rel(m.added_mass, ref.added_mass):.1e} | "
                  f"{max_rel(m.quadratic_damping, ref.quadratic_damping):.1e} | "
                  f"{max_rel(m.linear_damping, ref.linear_damping):.1e} | "
                  f"{statistics.median(times):.3f} |")


if __name__ == "__main__":
    main()
