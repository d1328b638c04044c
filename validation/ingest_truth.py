"""A known truth for the log-ingestion tests: a 6-DOF simulation of a known model driven by a
50 Hz piecewise-constant wrench, and that truth written the ways real logs come (tests/
test_ingest_*.py, benchmarks/ingest_speed.py): a navigation CSV at an irregular ~10 Hz with nanosecond stamps, ENU
positions, FLU-body quaternions (x, y, z, w) and earth-fixed velocities, and a header-less
50 Hz wrench file in FLU axes."""

from __future__ import annotations

import numpy as np
from scipy.interpolate import CubicSpline

from stripcoef.conventions import axes_operator, world_axes_operator
from stripcoef.simulate import simulate

WRENCH_RATE = 50.0          # [Hz]
DURATION = 40.0             # [s]
EPOCH_NS = 1_700_000_000_000_000_000   # nav stamps: ROS epoch nanoseconds
WRENCH_LEAD = 0.5           # the wrench file starts this long before the navigation [s]
FLU = axes_operator("FLU").diagonal()
ENU = world_axes_operator("ENU")


class Truth:
    """The simulated motion, evaluated at any time by cubic splines of a 1 ms simulation."""

    def __init__(self, model, seed=0, duration=DURATION):
        rng = np.random.default_rng(seed)
        self.model = model
        n_w = int(duration * WRENCH_RATE) + 1
        # steps held 1-3 s, smoothed nowhere: a controller's piecewise-constant wrench
        levels = np.array([6.0, 8.0, 10.0, 0.3, 0.3, 0.4])   # [N, N m]
        hold = rng.integers(50, 150, size=64)
        edges = np.minimum(np.cumsum(np.concatenate([[0], hold])), n_w)
        w = np.zeros((n_w, 6))
        for a, b in zip(edges[:-1], edges[1:]):
            if a < b:
                w[a:b] = levels * rng.uniform(-1.0, 1.0, size=6)
        self.wrench = w                                   # FRD, at k / WRENCH_RATE
        t = np.arange(0.0, duration + 1e-9, 1e-3)
        idx = lambda time: np.minimum((np.asarray(time) * WRENCH_RATE + 1e-9).astype(int),
                                      n_w - 1)
        self.force_at = lambda time: w[idx(time)]
        log = simulate(model, t, forces=np.array([w[i] for i in idx(t)]), rtol=1e-9,
                       atol=1e-11)
        self.t = t
        self.log = log
        self.spline = {k: CubicSpline(t, log[k]) for k in log.names if k != "t"}

    def __call__(self, name, time):
        return self.spline[name](time)

    # --- the truth as real logs carry it ------------------------------------
    def nav_times(self, seed=1, rate=10.0, jitter=0.3):
        """Irregular ~rate Hz stamps (steps (1 +- jitter)/rate) inside [0.2, duration]."""
        rng = np.random.default_rng(seed)
        steps = (1.0 + rng.uniform(-jitter, jitter, size=int(self.t[-1] * rate * 2))) / rate
        t = 0.2 + np.cumsum(steps)
        return t[t < self.t[-1] - 0.2]

    def quaternion_enu_flu(self, time):
        """(n, 4) quaternions x, y, z, w of R_{ENU <- FLU} (the ROS convention)."""
        from stripcoef.ingest.attitude import euler_matrices
        r = euler_matrices(self("phi", time), self("theta", time), self("psi", time))
        r = np.einsum("ij,njk,kl->nil", ENU, r, np.diag(FLU[:3]))   # both their own inverse
        return np.array([matrix_to_quaternion(m) for m in r])

    def nav_rows(self, time):
        """ENU position, x y z w quaternion, ENU earth-fixed velocity, FLU body rates."""
        pos = np.column_stack([self(k, time) for k in ("x", "y", "z")]) @ ENU.T
        vb = np.column_stack([self(k, time) for k in ("u", "v", "w")])
        from stripcoef.ingest.attitude import euler_matrices
        r = euler_matrices(self("phi", time), self("theta", time), self("psi", time))
        v_ned = np.einsum("nij,nj->ni", r, vb)
        rates = np.column_stack([self(k, time) for k in ("p", "q", "r")]) * FLU[3:]
        return pos, self.quaternion_enu_flu(time), v_ned @ ENU.T, vb * FLU[:3], rates


def matrix_to_quaternion(m):
    """x, y, z, w of a rotation matrix (Shepperd's method), for writing test data only."""
    tr = np.trace(m)
    if tr > 0:
        s = 2.0 * np.sqrt(1.0 + tr)
        w, x, y, z = 0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, \
            (m[1, 0] - m[0, 1]) / s
    else:
        i = int(np.argmax(np.diag(m)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * np.sqrt(1.0 + m[i, i] - m[j, j] - m[k, k])
        q = np.zeros(3)
        q[i] = 0.25 * s
        q[j] = (m[j, i] + m[i, j]) / s
        q[k] = (m[k, i] + m[i, k]) / s
        w = (m[k, j] - m[j, k]) / s
        x, y, z = q
    return np.array([x, y, z, w])


def write_nav_csv(path, truth, time):
    """Stamps [ns], a string, ENU position, x y z w quaternion, ENU velocity and ENU angular
    velocity (earth-fixed, as some navigation filters give it)."""
    pos, q, v_enu, _, _ = truth.nav_rows(time)
    from stripcoef.ingest.attitude import euler_matrices
    r = euler_matrices(truth("phi", time), truth("theta", time), truth("psi", time))
    w_ned = np.einsum("nij,nj->ni", r, np.column_stack([truth(k, time) for k in "pqr"]))
    w_enu = w_ned @ ENU.T
    stamps = EPOCH_NS + np.round(time * 1e9).astype(np.int64)
    lines = ["stamp_ns,frame_id,px,py,pz,qx,qy,qz,qw,ve,vn,vu,wx,wy,wz"]
    for k in range(time.size):
        vals = [*pos[k], *q[k], *v_enu[k], *w_enu[k]]
        lines.append(f"{stamps[k]},odom," + ",".join(repr(float(v)) for v in vals))
    path.write_text("\n".join(lines) + "\n")


def write_wrench_csv(path, truth):
    """Header-less, 50 Hz, FLU axes: fx fy fz mx my mz (from t = 0 of the truth)."""
    w = truth.wrench * FLU
    path.write_text("\n".join(" , ".join(repr(float(v)) for v in row) for row in w) + "\n")


NAV_WRENCH_MAP = """\
# navigation (irregular ~10 Hz, ROS conventions) + header-less wrench at 50 Hz
frames: {world: ENU, body: FLU}
streams:
  nav:
    file: nav.csv
    time: {column: stamp_ns, unit: ns}
    rate: 10
  wrench:
    file: wrench.csv
    header: false
    columns: [fx, fy, fz, mx, my, mz]
    time: {rate: 50, start: %(start)r}
position: {stream: nav, columns: [px, py, pz]}
attitude: {stream: nav, quaternion: [qx, qy, qz, qw], order: xyzw}
velocity: {stream: nav, columns: [ve, vn, vu], frame: world}
rates: {from: attitude}
wrench: {stream: wrench, columns: [fx, fy, fz, mx, my, mz]}
"""


BAG_MAP = """\
# a ROS bag: nav_msgs/Odometry (ENU, twist in the FLU body), sensor_msgs/Imu (FLU rates),
# geometry_msgs/WrenchStamped (FLU) at 50 Hz
frames: {world: ENU, body: FLU}
streams:
  odom: {topic: /odom, rate: 10}
  imu: {topic: /imu, time: header}
  wrench: {topic: /wrench, rate: 50}
position: {stream: odom, columns: [pose.pose.position.x, pose.pose.position.y,
                                   pose.pose.position.z]}
attitude: {stream: odom, quaternion: [pose.pose.orientation.x, pose.pose.orientation.y,
                                      pose.pose.orientation.z, pose.pose.orientation.w],
           order: xyzw}
velocity: {stream: odom, columns: [twist.twist.linear.x, twist.twist.linear.y,
                                   twist.twist.linear.z], frame: body}
rates: {stream: imu, columns: [angular_velocity.x, angular_velocity.y, angular_velocity.z]}
wrench: {stream: wrench, columns: [wrench.force.x, wrench.force.y, wrench.force.z,
                                   wrench.torque.x, wrench.torque.y, wrench.torque.z]}
"""


def write_bag(path, truth, nav_t, *, ros: int = 2):
    """A ROS 2 (folder) or ROS 1 (.bag) bag of the truth: /odom and /imu at ``nav_t``,
    /wrench at 50 Hz from t = 0; stamps at EPOCH_NS + t."""
    import dataclasses

    from rosbags.typesys import Stores, get_typestore
    if ros == 2:
        from rosbags.rosbag2 import Writer
        ts = get_typestore(Stores.ROS2_HUMBLE)
        writer = Writer(path, version=9)
        ser = ts.serialize_cdr
    else:
        from rosbags.rosbag1 import Writer
        ts = get_typestore(Stores.ROS1_NOETIC)
        writer = Writer(path)
        ser = ts.serialize_ros1
    T_ = ts.types

    def zero(name):
        """A message of type ``name`` with every field zero (nested), to be filled in."""
        cls = T_[name]
        kw = {}
        for f in dataclasses.fields(cls):
            ann = str(f.type)
            if ann.startswith("ClassVar"):
                continue
            if ann in ("float", "int"):
                kw[f.name] = 0 if ann == "int" else 0.0
            elif ann == "str":
                kw[f.name] = ""
            elif "ndarray" in ann:
                kw[f.name] = np.zeros(36 if f.name == "covariance" else 9 if "covariance" in f.name else 0)
            else:
                kw[f.name] = zero(ann.replace("__", "/"))
        return cls(**kw)

    def header(tsec, frame):
        h = zero("std_msgs/msg/Header")
        ns = EPOCH_NS + int(round(tsec * 1e9))
        h = dataclasses.replace(h, frame_id=frame,
                                stamp=T_["builtin_interfaces/msg/Time"](sec=ns // 10 ** 9,
                                                                         nanosec=ns % 10 ** 9))
        return h, ns

    def vec(name, v):
        return T_[name](x=float(v[0]), y=float(v[1]), z=float(v[2]))

    pos, q, _, v_flu, rates = truth.nav_rows(nav_t)
    msgs = []
    for k, tk in enumerate(nav_t):
        h, ns = header(tk, "odom")
        odo = zero("nav_msgs/msg/Odometry")
        pose = dataclasses.replace(odo.pose.pose, position=vec("geometry_msgs/msg/Point", pos[k]),
                                   orientation=T_["geometry_msgs/msg/Quaternion"](
                                       x=q[k, 0], y=q[k, 1], z=q[k, 2], w=q[k, 3]))
        twist = T_["geometry_msgs/msg/Twist"](linear=vec("geometry_msgs/msg/Vector3", v_flu[k]),
                                              angular=vec("geometry_msgs/msg/Vector3", rates[k]))
        odo = dataclasses.replace(odo, header=h, child_frame_id="base_link",
                                  pose=dataclasses.replace(odo.pose, pose=pose),
                                  twist=dataclasses.replace(odo.twist, twist=twist))
        msgs.append(("/odom", "nav_msgs/msg/Odometry", ns, odo))
        imu = dataclasses.replace(zero("sensor_msgs/msg/Imu"), header=header(tk, "base_link")[0],
                                  angular_velocity=vec("geometry_msgs/msg/Vector3", rates[k]))
        msgs.append(("/imu", "sensor_msgs/msg/Imu", ns + 1000, imu))
    w = truth.wrench * FLU
    for k in range(w.shape[0]):
        h, ns = header(k / WRENCH_RATE, "base_link")
        ws = T_["geometry_msgs/msg/WrenchStamped"](
            header=h, wrench=T_["geometry_msgs/msg/Wrench"](
                force=vec("geometry_msgs/msg/Vector3", w[k, :3]),
                torque=vec("geometry_msgs/msg/Vector3", w[k, 3:])))
        msgs.append(("/wrench", "geometry_msgs/msg/WrenchStamped", ns, ws))
    msgs.sort(key=lambda m: m[2])
    with writer:
        conns = {}
        for topic, typ in dict.fromkeys((m[0], m[1]) for m in msgs):
            conns[topic] = writer.add_connection(topic, typ, typestore=ts)
        for topic, typ, ns, msg in msgs:
            writer.write(conns[topic], ns, ser(msg, typ))
