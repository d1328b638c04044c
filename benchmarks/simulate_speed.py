"""CPU time of `stripcoef.simulate.simulate` on the diagnosis benchmark's manoeuvre.

A 240 s log at 10 Hz of the Wang & Clark 2006 ROV (random steps on four thrusters, a sinusoid,
turns; zero-order hold, so the integrator restarts at every input jump), RK45 at
rtol 1e-6 / 1e-8 (the benchmark's setting) and 1e-8 (the default).

Usage: python -m benchmarks.simulate_speed [--repeat 5]
"""

import argparse
import time

import numpy as np

from validation.synthetic import manoeuvre, rov_model
from stripcoef.simulate import simulate


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    model = rov_model()
    rng = np.random.default_rng(0)
    t, cmds = manoeuvre(rng)
    jumps = int(np.sum(np.any(np.diff(np.column_stack(list(cmds.values())), axis=0) != 0,
                              axis=1)))
    for rtol, atol in ((1e-6, 1e-8), (1e-8, 1e-10)):
        times = []
        for _ in range(args.repeat):
            t0 = time.process_time()
            simulate(model, t, commands=cmds, rtol=rtol, atol=atol)
            times.append(time.process_time() - t0)
        print(f"240 s log, {t.size} samples, {jumps} input jumps, rtol {rtol:g}: "
              f"median {np.median(times):.2f} s CPU (min {min(times):.2f}, max {max(times):.2f})")


if __name__ == "__main__":
    main()
