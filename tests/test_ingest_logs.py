"""Real-style logs through a column map (stripcoef.ingest) against a known truth.

The truth is a 6-DOF simulation of a known model (validation/ingest_truth.py) driven by a 50 Hz
wrench; it is written the ways real logs come: a navigation CSV with nanosecond stamps, ENU
positions, FLU-body quaternions (x, y, z, w) and ENU earth-fixed velocities, a header-less
50 Hz wrench file in FLU axes, and ROS 1 / ROS 2 bags (nav_msgs/Odometry, sensor_msgs/Imu,
geometry_msgs/WrenchStamped) written with rosbags' writer.
"""

import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest

from validation import ingest_truth as T  # noqa: E402
from stripcoef.errors import InputError, SamplingWarning  # noqa: E402
from stripcoef.ingest import load_map, parse_map, read_mapped_log  # noqa: E402
from stripcoef.ingest.attitude import (body_rates, euler_from_matrices,  # noqa: E402
                                       euler_matrices, quaternion_matrices)
from test_simulate_dynamics import make_model  # noqa: E402

STATES = ("x", "y", "z", "phi", "theta", "psi", "u", "v", "w")


@pytest.fixture(scope="module")
def truth():
    return T.Truth(make_model(coupled=True), seed=0, duration=20.0)


def nav_wrench(tmp_path, truth, nav_t, extra_map=""):
    T.write_nav_csv(tmp_path / "nav.csv", truth, nav_t)
    T.write_wrench_csv(tmp_path / "wrench.csv", truth)
    (tmp_path / "map.yaml").write_text(T.NAV_WRENCH_MAP % {"start": T.EPOCH_NS * 1e-9}
                                       + extra_map)
    return tmp_path / "nav.csv", tmp_path / "map.yaml"


def truth_times(log):
    """Times of the log's rows in the truth's clock [s]."""
    return log["t"] + log.meta["t0"] + (log.meta["time_base"] - T.EPOCH_NS // 10 ** 9)


def read_quiet(*args):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        log = read_mapped_log(*args)
    return log, [str(w.message) for w in caught if issubclass(w.category, SamplingWarning)]


# --- exact: output samples on the navigation samples ---------------------------------------

def test_regular_streams_are_read_exactly(tmp_path, truth):
    """At a regular 10 Hz the grid falls on the navigation samples: pose (ENU -> NED,
    quaternion xyzw of FLU -> Euler of FRD), earth-fixed velocities rotated into the body and
    the held 50 Hz wrench (FLU -> FRD) equal the truth up to the float precision of epoch
    nanosecond stamps (2.4e-7 s), and the wrench exactly."""
    nav_t = 0.3 + np.arange(190) * 0.1
    log, warned = read_quiet(*nav_wrench(tmp_path, truth, nav_t))
    assert warned == []
    assert log.meta["rate"] == 10.0 and len(log) == 190
    ta = truth_times(log)
    np.testing.assert_allclose(ta, nav_t, atol=1e-6)
    for k in STATES:
        np.testing.assert_allclose(log[k], truth(k, ta), atol=2e-5, err_msg=k)
    for i, k in enumerate("XYZKMN"):
        np.testing.assert_array_equal(log[k], truth.force_at(ta)[:, i], err_msg=k)
    # rates from the attitude: second-order differences of a 10 Hz attitude (next test)
    for k in "pqr":
        assert np.sqrt(np.mean((log[k] - truth(k, ta)) ** 2)) < 0.1 * np.std(truth(k, ta))
    # earth-fixed (ENU) angular velocity rotated into the body: exact like the velocities
    m = tmp_path / "map.yaml"
    m.write_text(m.read_text().replace("rates: {from: attitude}",
                                       "rates: {stream: nav, columns: [wx, wy, wz], "
                                       "frame: world}"))
    log, _ = read_quiet(tmp_path / "nav.csv", m)
    for k in "pqr":
        np.testing.assert_allclose(log[k], truth(k, ta), atol=2e-5, err_msg=k)


def test_irregular_navigation_within_the_interpolation_bound(tmp_path, truth):
    """Irregular ~10 Hz stamps (steps 0.1 s +- 30 %): linearly interpolated pose stays within
    the bound of linear interpolation, |e| <= h^2/8 max|f''| (h the longest step)."""
    nav_t = truth.nav_times(seed=3, rate=10.0, jitter=0.3)
    log, warned = read_quiet(*nav_wrench(tmp_path, truth, nav_t))
    ta = truth_times(log)
    h = np.diff(nav_t).max()
    fine = np.linspace(ta[0], ta[-1], 20001)
    for k in ("x", "y", "z", "phi", "theta", "psi"):
        bound = h ** 2 / 8 * np.abs(truth.spline[k](fine, 2)).max()
        err = np.abs(log[k] - truth(k, ta)).max()
        assert err <= bound + 2e-6, (k, err, bound)
    for i, k in enumerate("XYZKMN"):      # zero-order hold of a 50 Hz wrench: exact
        np.testing.assert_array_equal(log[k], truth.force_at(ta)[:, i])


def test_body_rates_from_attitude_exact_for_a_constant_rate_and_second_order():
    """dR/dt = R S(omega): the matrix logarithm of R_k^T R_{k+1} is exact for a constant body
    rate; for omega(t) = a sin(t) the error falls as h^2 (ratio ~4 when h halves)."""
    from scipy.linalg import expm

    from stripcoef.conventions import skew
    omega = np.array([0.3, -0.7, 1.1])
    t = np.sort(np.random.default_rng(0).uniform(0, 5, 60))
    r0 = euler_matrices(0.2, -0.1, 2.0)[0]
    r = np.array([r0 @ expm(skew(omega) * tk) for tk in t])
    np.testing.assert_allclose(body_rates(t, r), np.tile(omega, (t.size, 1)), atol=1e-10)

    def err(h):
        tt = np.arange(0.0, 6.0, h)
        a = np.array([0.5, -0.8, 0.6])
        # integrate dR/dt = R S(a sin t) finely to get R(t)
        sub = 200
        rs, rk, tau = [], r0.copy(), 0.0
        for _ in tt:
            rs.append(rk.copy())
            for _ in range(sub):
                rk = rk @ expm(skew(a * np.sin(tau + 0.5 * h / sub)) * (h / sub))
                tau += h / sub
        got = body_rates(tt, np.array(rs))[1:-1]
        return np.abs(got - np.outer(np.sin(tt[1:-1]), a)).max()
    ratio = err(0.1) / err(0.05)
    assert 3.5 < ratio < 4.5, ratio


def test_quaternion_and_euler_matrices_agree_and_euler_round_trips():
    rng = np.random.default_rng(1)
    ang = np.column_stack([rng.uniform(-3, 3, 50), rng.uniform(-1.4, 1.4, 50),
                           rng.uniform(-3, 3, 50)])
    r = euler_matrices(*ang.T)
    q = np.array([T.matrix_to_quaternion(m) for m in r])          # x y z w
    np.testing.assert_allclose(quaternion_matrices(q[:, [3, 0, 1, 2]]), r, atol=1e-12)
    back = euler_from_matrices(r)
    np.testing.assert_allclose(euler_matrices(*back.T), r, atol=1e-12)
    with pytest.raises(InputError, match="not a unit quaternion at sample 1"):
        quaternion_matrices(2 * q[:, [3, 0, 1, 2]], file="f.csv", key="qw")


# --- ROS bags ------------------------------------------------------------------------------

@pytest.mark.parametrize("ros", [2, 1])
def test_bag_round_trip(tmp_path, truth, ros):
    """A bag written with rosbags' writer reads back through a map to the truth (Odometry
    pose + body twist in FLU, Imu rates, WrenchStamped at 50 Hz)."""
    pytest.importorskip("rosbags")
    nav_t = 0.3 + np.arange(150) * 0.1
    bag = tmp_path / ("run" if ros == 2 else "run.bag")
    T.write_bag(bag, truth, nav_t, ros=ros)
    (tmp_path / "map.yaml").write_text(T.BAG_MAP)
    log, warned = read_quiet(bag, tmp_path / "map.yaml")
    assert warned == []
    ta = truth_times(log)
    for k in STATES + ("p", "q", "r"):
        np.testing.assert_allclose(log[k], truth(k, ta), atol=1e-4, err_msg=k)
    for i, k in enumerate("XYZKMN"):
        np.testing.assert_array_equal(log[k], truth.force_at(ta)[:, i])


def test_bag_errors_name_the_topic_and_field(tmp_path, truth):
    pytest.importorskip("rosbags")
    bag = tmp_path / "run"
    T.write_bag(bag, truth, 0.3 + np.arange(20) * 0.1, ros=2)
    bad = tmp_path / "bad.yaml"
    bad.write_text(T.BAG_MAP.replace("/imu", "/gyro"))
    with pytest.raises(InputError, match=r"no topic '/gyro'.*one of /imu, /odom, /wrench"):
        read_mapped_log(bag, bad)
    bad.write_text(T.BAG_MAP.replace("angular_velocity.z", "angular_velocity.w"))
    with pytest.raises(InputError, match=r"angular_velocity.w.*one of .*angular_velocity.z"):
        read_mapped_log(bag, bad)


# --- sampling warnings, merge rules, exclusions ------------------------------------------

def test_sampling_warnings_name_gaps_bursts_irregularity_and_rate(tmp_path, truth):
    nav_t = 0.3 + np.arange(190) * 0.1
    gappy = np.concatenate([nav_t[:50], nav_t[60:]])                 # a 1.1 s gap
    _, warned = read_quiet(*nav_wrench(tmp_path, truth, gappy))
    assert len(warned) == 1 and "1 gap(s)" in warned[0] and "1.1 s" in warned[0]
    bursty = np.sort(np.concatenate([nav_t, nav_t[100:110] + 0.01]))
    _, warned = read_quiet(*nav_wrench(tmp_path, truth, bursty))
    assert len(warned) == 1 and "10 step(s) shorter" in warned[0]
    irregular = truth.nav_times(seed=2, rate=10.0, jitter=0.6)
    _, warned = read_quiet(*nav_wrench(tmp_path, truth, irregular))
    assert len(warned) == 1 and "irregular sampling" in warned[0]
    fast = 0.3 + np.arange(700) * 0.025
    _, warned = read_quiet(*nav_wrench(tmp_path, truth, fast))
    assert len(warned) == 1 and "median rate 40 Hz, not the stated 10 Hz" in warned[0]


def test_exclusions_and_time_origin(tmp_path, truth):
    nav_t = 0.3 + np.arange(190) * 0.1
    extra = "exclude: [[null, 2.0], [5.0, 6.0]]\noutput: {rate: 20}\n"
    log, warned = read_quiet(*nav_wrench(tmp_path, truth, nav_t, extra))
    t = log["t"]
    assert log.meta["rate"] == 20.0
    assert t[0] > 2.0 and not np.any((t >= 5.0) & (t <= 6.0))
    assert len(warned) == 1 and "gap in t from 4.95 to 6.05 s" in warned[0]


def test_max_gap_drops_rows_inside_a_stream_gap(tmp_path, truth):
    """A 1.1 s dropout of the navigation: bridged by linear interpolation (warned) by
    default; with max_gap: 0.5 the output rows inside it are dropped instead."""
    nav_t = 0.3 + np.arange(190) * 0.1
    gappy = np.concatenate([nav_t[:50], nav_t[61:]])         # samples 5.3 .. 6.3 s missing
    nav, m = nav_wrench(tmp_path, truth, gappy)
    m.write_text(m.read_text().replace("    rate: 10\n", "    rate: 10\n    max_gap: 0.5\n", 1))
    log, warned = read_quiet(nav, m)
    ta = truth_times(log)
    assert not np.any((ta > 5.2 + 1e-6) & (ta < 6.4 - 1e-6))
    assert np.any(np.isclose(ta, 5.2)) and np.any(np.isclose(ta, 6.4))
    assert any("gap in t from 4.9 to 6.1 s" in w for w in warned), warned
    np.testing.assert_allclose(log["x"], truth("x", ta), atol=2e-5)
    np.testing.assert_allclose(log["x"], truth("x", truth_times(log)), atol=1e-2)


def test_empty_overlap_is_an_error(tmp_path, truth):
    nav, m = nav_wrench(tmp_path, truth, 0.3 + np.arange(50) * 0.1)
    m.write_text(m.read_text().replace(f"start: {T.EPOCH_NS * 1e-9!r}", "start: 0.0"))
    with pytest.raises(InputError, match="do not overlap.*nav 1700000000.300..1700000005.200 s; wrench 0.000..20.000 s"):
        read_mapped_log(nav, m)


def test_body_velocity_euler_degrees_and_missing_drop(tmp_path, truth):
    """Another common layout: one CSV, NED/FRD, Euler angles in degrees, body velocities and
    deg/s gyro rates, thruster-free wrench columns, rows of another topic left empty."""
    t = 0.3 + np.arange(120) * 0.1
    lines = ["time,roll,pitch,yaw,u,v,w,gx,gy,gz,X,Y,Z,K,M,N,depth"]
    for k, tk in enumerate(t):
        vals = [tk, *(np.degrees([truth(a, tk) for a in ("phi", "theta", "psi")])),
                *[truth(a, tk) for a in "uvw"], *np.degrees([truth(a, tk) for a in "pqr"]),
                *truth.force_at(np.array([tk]))[0], truth("z", tk)]
        lines.append(",".join(repr(float(v)) for v in vals))
        if k % 7 == 3:
            lines.append(f"{float(tk) + 0.05!r},,,,,,,,,,,,,,,,{float(truth('z', tk + 0.05))!r}")
    (tmp_path / "one.csv").write_text("\n".join(lines) + "\n")
    (tmp_path / "m.yaml").write_text(
        "streams: {log: {time: time, missing: drop}}\n"
        "attitude: {euler: [roll, pitch, yaw], unit: deg}\n"
        "velocity: {columns: [u, v, w]}\n"
        "rates: {columns: [gx, gy, gz], unit: deg/s}\n"
        "wrench: {columns: [X, Y, Z, K, M, N]}\n"
        "channels: {depth_sensor: {column: depth}}\n")
    log, _ = read_quiet(tmp_path / "one.csv", tmp_path / "m.yaml")
    tt = log["t"] + log.meta["t0"] + log.meta["time_base"]
    for k in ("phi", "theta", "psi", "u", "v", "w", "p", "q", "r"):
        np.testing.assert_allclose(log[k], truth(k, tt), atol=1e-9, err_msg=k)
    assert "x" not in log and "depth_sensor" in log


# --- bad maps and bad columns: one-line errors naming file, key, value ---------------------

GOOD = {"streams": {"nav": {"file": "nav.csv", "time": {"column": "t"}}},
        "velocity": {"stream": "nav", "columns": ["u", "v", "w"]}}


@pytest.mark.parametrize("patch, match", [
    ({"velocity": {"stream": "gps", "columns": ["u", "v", "w"]}},
     r"m.yaml: velocity.stream: unknown stream; got 'gps'; expected one of nav"),
    ({"velocity": {"stream": "nav", "columns": ["u", "v"]}},
     r"velocity.columns: wrong columns; got \['u', 'v'\]; expected a list of 3"),
    ({"velocity": {"stream": "nav", "columns": ["u", "v", "w"], "frame": "ned"}},
     r"velocity.frame: unknown value; got 'ned'; expected one of body, world"),
    ({"velocity": {"stream": "nav", "columns": ["u", "v", "w"], "frame": "world"}},
     r"velocity: earth-fixed or derived values need the attitude"),
    ({"rates": {"from": "attitude"}}, r"rates: earth-fixed or derived values need the "
                                      r"attitude"),
    ({"attitude": {"stream": "nav", "euler": ["r", "p", "y"]},
      "rates": {"stream": "nav", "columns": ["p", None, "r"], "frame": "world"}},
     r"rates.columns: earth-fixed values need all three columns"),
    ({"attitude": {"stream": "nav", "quaternion": ["a", "b", "c", "d"]}},
     r"attitude.order: missing key; expected wxyz or xyzw"),
    ({"attitude": {"stream": "nav", "euler": ["r", "p", "y"], "unit": "grad"}},
     r"attitude.unit: unknown value; got 'grad'; expected one of rad, deg"),
    ({"streams": {"nav": {"file": "nav.csv", "time": {"column": "t", "unit": "min"}}}},
     r"streams.nav.time.unit: unknown value; got 'min'; expected one of s, ms, us, ns"),
    ({"streams": {"nav": {"file": "nav.csv", "header": False}}},
     r"streams.nav.columns: a file without header needs its column names"),
    ({"streams": {"nav": {"file": "nav.csv"}}}, r"streams.nav.time: missing key"),
    ({"streams": {"nav": {"file": "nav.csv", "time": {"column": "t", "rate": 5}}}},
     r"streams.nav.time: one time source needed"),
    ({"exclude": [[5, 2]]}, r"exclude\[0\]: empty time range; got \[5, 2\]"),
    ({"frames": {"world": "NWU"}}, r"frames.world: unknown value; got 'NWU'; expected one "
                                   r"of NED, ENU"),
    ({"velocty": {}}, r"velocty: unknown key; got 'velocty'; expected one of version"),
    ({"channels": {"u": {"stream": "nav", "column": "speed"}}},
     r"channels.u: a channel cannot take a state, force or command name"),
    ({"thrusters": {"stream": "nav", "columns": {"port": "pwm1"}, "scale": "x"}},
     r"thrusters.scale: not a number; got 'x'"),
])
def test_bad_maps_get_one_line_errors(patch, match):
    data = {**GOOD, **patch}
    with pytest.raises(InputError, match=match) as info:
        parse_map(data, path="m.yaml")
    assert "\n" not in str(info.value)


def test_bad_columns_and_cells_name_file_column_and_line(tmp_path):
    (tmp_path / "m.yaml").write_text(
        "streams: {nav: {time: {column: t}, rate: 10}}\nvelocity: {columns: [u, v, w]}\n")
    csv = tmp_path / "log.csv"
    csv.write_text("t,u,v\n0,1,2\n0.1,1,2\n")
    with pytest.raises(InputError, match=r"log.csv: w: no column 'w' in stream 'nav'; "
                                         r"expected one of the file's columns \(t, u, v\)"):
        read_mapped_log(csv, tmp_path / "m.yaml")
    csv.write_text("t,u,v,w\n0,1,2,3\n0.1,1,x,3\n")
    with pytest.raises(InputError, match=r"log.csv: v: non-numeric cell in line 3; got 'x'"):
        read_mapped_log(csv, tmp_path / "m.yaml")
    csv.write_text("t,u,v,w\n0,1,2,3\n0.1,1,,3\n")
    with pytest.raises(InputError, match=r"v: missing or non-finite value in line 3.*missing: "
                                         r"drop"):
        read_mapped_log(csv, tmp_path / "m.yaml")
    csv.write_text("t,u,v,w\n0,1,2,3\n0.2,1,2,3\n0.1,1,2,3\n")
    with pytest.raises(InputError, match=r"log.csv: t: time goes backwards at line 4; "
                                         r"got 0.1"):
        read_mapped_log(csv, tmp_path / "m.yaml")
    with pytest.raises(InputError, match=r"nope.yaml: file not found"):
        load_map(tmp_path / "nope.yaml")
    (tmp_path / "bad.yaml").write_text("streams: [\n")
    with pytest.raises(InputError, match=r"bad.yaml: line 2: not valid YAML"):
        load_map(tmp_path / "bad.yaml")


def test_repeated_timestamps_keep_the_first_sample_and_warn(tmp_path):
    (tmp_path / "m.yaml").write_text(
        "streams: {nav: {time: {column: t}}}\nvelocity: {columns: [u, null, null]}\n")
    csv = tmp_path / "log.csv"
    csv.write_text("t,u\n0,1\n0.1,2\n0.1,9\n0.2,3\n0.3,4\n")
    log, warned = read_quiet(csv, tmp_path / "m.yaml")
    assert "1 repeated timestamp(s)" in warned[0]
    np.testing.assert_allclose(log["u"], [1, 2, 3, 4])
    assert "v" not in log and "w" not in log       # a null column is absent, never zeros


def test_bag_without_map_is_an_error(tmp_path):
    from stripcoef.ingest import read_any_log
    with pytest.raises(InputError, match="a ROS bag needs a column map"):
        read_any_log(tmp_path / "run.bag")
    shutil.rmtree(tmp_path, ignore_errors=True)


def test_every_map_in_docs_logs_md_is_valid():
    """The maps shown in docs/logs.md parse (a renamed key would fail here)."""
    import re

    import yaml
    text = (Path(__file__).parent.parent / "docs" / "logs.md").read_text()
    blocks = re.findall(r"```yaml\n(.*?)```", text, flags=re.S)
    assert len(blocks) == 4
    for block in blocks:
        m = parse_map(yaml.safe_load(block), path="docs/logs.md")
        assert m.streams


def test_velocity_from_position_and_thruster_commands(tmp_path, truth):
    """Velocity differenced from the ENU position and rotated into the body tracks the truth
    (central differences of a 10 Hz position: RMS under 5 % of each velocity's spread; a frame
    or sign error would be of the order of the velocity itself); PWM thruster commands
    become n_<name> = scale (pwm - offset), held."""
    nav_t = 0.3 + np.arange(190) * 0.1
    nav, m = nav_wrench(tmp_path, truth, nav_t)
    text = m.read_text().replace("velocity: {stream: nav, columns: [ve, vn, vu], frame: world}",
                                 "velocity: {from: position}")
    pwm = 1500 + 400 * np.sin(np.arange(truth.wrench.shape[0]) / 37.0)
    (tmp_path / "pwm.csv").write_text("".join(f"{k / 50.0!r};{float(p)!r};{float(3000 - p)!r}\n"
                                              for k, p in enumerate(pwm)))
    text = text.replace("position:", "  pwm:\n    file: pwm.csv\n    header: false\n"
                        "    delimiter: ';'\n    columns: [time, a, b]\n"
                        f"    time: {{column: time, offset: {T.EPOCH_NS // 10 ** 9}}}\n"
                        "position:", 1)
    text += ("thrusters: {stream: pwm, columns: {port: a, starboard: b}, offset: 1500,\n"
             "            scale: {port: 0.05, starboard: -0.05}}\n")
    m.write_text(text)
    log, _ = read_quiet(nav, m)
    ta = truth_times(log)
    for k in "uvw":
        rms = np.sqrt(np.mean((log[k] - truth(k, ta)) ** 2))
        assert rms < 0.05 * np.std(truth(k, ta)), (k, rms)
    k = np.minimum((ta * 50.0 + 1e-9).astype(int), pwm.size - 1)
    np.testing.assert_allclose(log["n_port"], 0.05 * (pwm[k] - 1500), rtol=1e-12)
    np.testing.assert_allclose(log["n_starboard"], -0.05 * (1500 - pwm[k]), rtol=1e-12)


def test_bag_array_commands_without_header(tmp_path):
    """Thruster commands published as std_msgs/Float64MultiArray (no header: the bag's
    receive time) are indexed as data[i]; asking a header stamp of them is an error."""
    pytest.importorskip("rosbags")
    from rosbags.rosbag2 import Writer
    from rosbags.typesys import Stores, get_typestore
    ts = get_typestore(Stores.ROS2_HUMBLE)
    Ty = ts.types
    layout = Ty["std_msgs/msg/MultiArrayLayout"](dim=[], data_offset=0)
    with Writer(tmp_path / "bag", version=9) as w:
        cmd = w.add_connection("/cmd", "std_msgs/msg/Float64MultiArray", typestore=ts)
        vel = w.add_connection("/vel", "geometry_msgs/msg/TwistStamped", typestore=ts)
        for k in range(100):                     # 20 Hz commands, 10 Hz velocity
            ns = 10 ** 9 + k * 50_000_000
            msg = Ty["std_msgs/msg/Float64MultiArray"](layout=layout,
                                                       data=np.array([k, -2.0 * k]))
            w.write(cmd, ns, ts.serialize_cdr(msg, "std_msgs/msg/Float64MultiArray"))
            if k % 2 == 0:
                hdr = Ty["std_msgs/msg/Header"](stamp=Ty["builtin_interfaces/msg/Time"](
                    sec=ns // 10 ** 9, nanosec=ns % 10 ** 9), frame_id="base_link")
                v3 = Ty["geometry_msgs/msg/Vector3"]
                tw = Ty["geometry_msgs/msg/TwistStamped"](header=hdr, twist=Ty[
                    "geometry_msgs/msg/Twist"](linear=v3(x=0.01 * k, y=0.0, z=0.0),
                                               angular=v3(x=0.0, y=0.0, z=0.0)))
                w.write(vel, ns, ts.serialize_cdr(tw, "geometry_msgs/msg/TwistStamped"))
    m = tmp_path / "m.yaml"
    m.write_text("streams:\n  cmd: {topic: /cmd, time: bag}\n  vel: {topic: /vel}\n"
                 "velocity: {stream: vel, columns: [twist.linear.x, null, null]}\n"
                 "thrusters: {stream: cmd, columns: {port: 'data[0]', starboard: 'data[1]'}}\n")
    log, warned = read_quiet(tmp_path / "bag", m)
    assert warned == [] and log.meta["rate"] == pytest.approx(10.0)   # the median rate
    np.testing.assert_allclose(log["u"], 0.01 * np.arange(0, 99, 2), atol=1e-12)
    np.testing.assert_allclose(log["n_port"], np.arange(0, 99, 2), atol=1e-12)
    np.testing.assert_allclose(log["n_starboard"], -2.0 * np.arange(0, 99, 2), atol=1e-12)
    m.write_text(m.read_text().replace("time: bag", "time: header"))
    with pytest.raises(InputError, match=r"Float64MultiArray has no header stamp \(stream "
                                         r"'cmd'\).*expected time: bag"):
        read_mapped_log(tmp_path / "bag", m)


def test_heading_only_attitude_warns_when_it_rotates(tmp_path):
    """A navigation with heading only: psi is logged, phi and theta are absent (not zeros);
    rotating earth-fixed velocities with it says that it takes them as 0."""
    from stripcoef.errors import ModelWarning
    csv = tmp_path / "nav.csv"
    t = np.arange(0.0, 5.0, 0.1)
    csv.write_text("t,hdg,vn,ve,vd\n" + "".join(f"{float(tk)!r},90,1,0,0\n" for tk in t))
    m = tmp_path / "m.yaml"
    m.write_text("streams: {nav: {time: t}}\nattitude: {euler: [null, null, hdg], unit: deg}\n"
                 "velocity: {columns: [vn, ve, vd], frame: world}\n")
    with pytest.warns(ModelWarning, match="attitude has no phi, theta: taken as 0 to rotate"):
        log = read_mapped_log(csv, m)
    assert "phi" not in log and "theta" not in log
    np.testing.assert_allclose(log["psi"], np.pi / 2)
    np.testing.assert_allclose(log["u"], 0.0, atol=1e-15)     # heading east, moving north:
    np.testing.assert_allclose(log["v"], -1.0)                 # sideways to port


def test_iso_date_time_stamps(tmp_path):
    """ISO 8601 stamps (a telemetry export): read to the nanosecond, a UTC offset converted,
    a bad one named by line."""
    csv = tmp_path / "tel.csv"
    csv.write_text("Timestamp,speed\n2024-05-02 10:15:30.000,0.5\n2024-05-02T10:15:30.25Z,0.6\n"
                   "2024-05-02T12:15:30.500000001+02:00,0.7\n2024-05-02T10:15:30.75,0.8\n")
    m = tmp_path / "m.yaml"
    m.write_text("streams: {tel: {time: {column: Timestamp, unit: iso}}}\n"
                 "velocity: {columns: [speed, null, null]}\noutput: {rate: 4}\n")
    log, _ = read_quiet(csv, m)
    np.testing.assert_allclose(log["t"], [0.0, 0.25, 0.5, 0.75])
    np.testing.assert_allclose(log["u"], [0.5, 0.6, 0.7, 0.8], atol=1e-8)
    assert log.meta["time_base"] == 1714644930
    csv.write_text("Timestamp,speed\n2024-05-02 10:15:30,0.5\n2024-13-02 10:15:31,0.6\n")
    with pytest.raises(InputError, match=r"tel.csv: Timestamp: bad time in line 3; got "
                                         r"'2024-13-02 10:15:31'; expected an ISO 8601"):
        read_mapped_log(csv, m)


def test_iso_stamps_by_the_standard_library():
    """ISO 8601 text -> ns since the epoch by datetime.fromisoformat (offsets, 'Z', no offset
    = UTC), the fraction kept to the nanosecond; no numpy warning to suppress."""
    import warnings

    from stripcoef.ingest.streams import iso_ns
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert iso_ns("1970-01-01T00:00:00.000000001Z") == 1
        assert iso_ns("1970-01-01T02:00:01.5+02:00") == 1_500_000_000
        assert iso_ns("1970-01-01 00:00:01,25") == 1_250_000_000
        assert iso_ns("2024-05-02T12:15:30.500000001+02:00") == 1714644930_500000001
    with pytest.raises(ValueError):
        iso_ns("2024-13-02 10:15:31")
