"""Wall and CPU time of reading real-style logs through a column map (stripcoef.ingest).

A 10-minute pool run as loggers write it: a navigation CSV at an irregular ~10 Hz (6,000
rows; nanosecond stamps, ENU position, x y z w quaternion, ENU velocity, a string column)
and a header-less 50 Hz wrench CSV (30,000 rows), and the same run as a ROS 2 bag
(nav_msgs/Odometry, sensor_msgs/Imu at ~10 Hz, geometry_msgs/WrenchStamped at 50 Hz),
each read with the maps of validation/ingest_truth.py (rates derived from the attitude for the
CSV, IMU rates for the bag). The signals are smooth random motions (the reading cost does
not depend on the physics).

Usage: python -m benchmarks.ingest_speed [--minutes 10] [--repeat 3]
"""

import argparse
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

from stripcoef.ingest import read_mapped_log
from validation import ingest_truth as T


class RandomMotion:
    """Smooth random 6-DOF motion with the interface of validation.ingest_truth.Truth that the writers
    use (a call per signal and time, ``nav_rows``, ``wrench``, ``t``)."""

    def __init__(self, minutes, seed=0):
        rng = np.random.default_rng(seed)
        self.t = np.array([0.0, 60.0 * minutes])
        self.k = {name: (rng.normal(size=4), rng.uniform(0.05, 0.5, size=4))
                  for name in ("x", "y", "z", "phi", "theta", "psi", "u", "v", "w",
                               "p", "q", "r")}
        self.wrench = rng.normal(size=(int(60 * minutes * T.WRENCH_RATE) + 1, 6))

    def __call__(self, name, time):
        a, f = self.k[name]
        scale = 0.3 if name in ("phi", "theta") else 1.0
        return scale * sum(ai * np.sin(fi * np.asarray(time) + i) for i, (ai, fi)
                           in enumerate(zip(a, f)))

    nav_rows = T.Truth.nav_rows
    quaternion_enu_flu = T.Truth.quaternion_enu_flu
    nav_times = T.Truth.nav_times


def timed(fn, repeat):
    wall, cpu = [], []
    for _ in range(repeat):
        w0, c0 = time.perf_counter(), time.process_time()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            log = fn()
        wall.append(time.perf_counter() - w0)
        cpu.append(time.process_time() - c0)
    return log, float(np.median(wall)), float(np.median(cpu))


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--minutes", type=float, default=10.0)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    motion = RandomMotion(args.minutes)
    nav_t = motion.nav_times(seed=1, rate=10.0, jitter=0.3)
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        T.write_nav_csv(d / "nav.csv", motion, nav_t)
        T.write_wrench_csv(d / "wrench.csv", motion)
        (d / "map.yaml").write_text(T.NAV_WRENCH_MAP % {"start": T.EPOCH_NS * 1e-9})
        log, wall, cpu = timed(lambda: read_mapped_log(d / "nav.csv", d / "map.yaml"),
                               args.repeat)
        print(f"CSV: nav {nav_t.size} rows + wrench {motion.wrench.shape[0]} rows -> "
              f"{len(log)} x {len(log.names)} log: {wall:.2f} s wall, {cpu:.2f} s CPU "
              f"(median of {args.repeat})")
        try:
            import rosbags  # noqa: F401
        except ImportError:
            print("bag: rosbags not installed (pip install 'stripcoef[ros]')")
            return
        T.write_bag(d / "bag", motion, nav_t, ros=2)
        (d / "bagmap.yaml").write_text(T.BAG_MAP)
        n_msgs = 2 * nav_t.size + motion.wrench.shape[0]
        log, wall, cpu = timed(lambda: read_mapped_log(d / "bag", d / "bagmap.yaml"),
                               args.repeat)
        print(f"ROS 2 bag: {n_msgs} messages -> {len(log)} x {len(log.names)} log: "
              f"{wall:.2f} s wall, {cpu:.2f} s CPU (median of {args.repeat})")


if __name__ == "__main__":
    main()
