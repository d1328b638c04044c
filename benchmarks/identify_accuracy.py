"""Identification: speed per fit and accuracy of the error bars over seeded virtual experiments.

Run: python -m benchmarks.identify_accuracy [--seeds N]
Prints, for each method, the median in-process time of one fit and the fraction of estimates
within 2 sigma of the truth (nominal 95.4 % for Gaussian errors).
"""

import argparse
import statistics
import time

import numpy as np

from validation.experiments import (ROMEO_TRUTH, ROV2_BUOYANCY, ROV2_LENGTH, ROV2_MASS,
                                            ROV2_TRUTH, VIDEORAY_TRUTH, romeo_experiment,
                                            rov2_pendulum_log, videoray_yaw_log)
from stripcoef.identify.onestep import one_step_log
from stripcoef.identify.pendulum import pendulum_log
from stripcoef.identify.steady import fit_steady


def run(name, cases, fit, truth_of, keys):
    times, hits, total = [], 0, 0
    for case in cases:
        t0 = time.perf_counter()
        f = fit(case)
        times.append(time.perf_counter() - t0)
        truth = truth_of(case)
        for k in keys:
            hits += abs(f.value(k) - truth[k]) <= 2 * f.std[k]
            total += 1
    print(f"{name:<34} {1e3 * statistics.median(times):8.2f} ms   "
          f"{hits}/{total} = {100 * hits / total:5.1f} % within 2 sigma")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=100)
    n = ap.parse_args().seeds
    romeo = [romeo_experiment(1 + s % 5, seed=s) for s in range(n)]
    run("steady, eta model (ROMEO, 12 pts)", romeo, lambda c: fit_steady(c[0], "eta"),
        lambda c: dict(ROMEO_TRUTH, W=c[1]), ("k_w", "k_ww", "W", "eta"))
    yaw = [videoray_yaw_log(s) for s in range(n)]
    run("one-step, ma1 (VideoRay, 1080 s.)", yaw, lambda c: one_step_log(c, "yaw"),
        lambda c: VIDEORAY_TRUTH, tuple(VIDEORAY_TRUTH))
    run("one-step, iid (VideoRay, 1080 s.)", yaw,
        lambda c: one_step_log(c, "yaw", covariance="iid"), lambda c: VIDEORAY_TRUTH,
        tuple(VIDEORAY_TRUTH))
    kw = dict(mass=ROV2_MASS, buoyancy=ROV2_BUOYANCY, length=ROV2_LENGTH)
    pend = [rov2_pendulum_log(s) for s in range(max(n // 4, 5))]
    run("pendulum, equation error (ROV II)", pend, lambda c: pendulum_log(c, **kw),
        lambda c: ROV2_TRUTH, tuple(ROV2_TRUTH))
    run("pendulum, output error (ROV II)", pend, lambda c: pendulum_log(c, refine=True, **kw),
        lambda c: ROV2_TRUTH, tuple(ROV2_TRUTH))


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
