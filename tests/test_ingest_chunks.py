"""Real logs as users have them (issue 33): a stream in many chunk files (a folder or a glob),
two loggers' clocks offset by a constant, and a header-less stream timed only by its bursty
receive times. Every log is generated with a known truth: the chunks' contents, the offset
(recovered within one sample) and the source's period."""

import re
import warnings

import numpy as np
import pytest

from stripcoef.errors import InputError, SamplingWarning
from stripcoef.ingest import read_mapped_log
from stripcoef.ingest.clock import estimate_offset, retime

EPOCH = 1_700_000_000.0       # stamps in seconds since 1970 [s]
NAV_RATE = 20.0               # [Hz]
CMD_RATE = 10.0               # [Hz]
DURATION = 120.0              # [s]
OFFSET = 0.8372               # the command logger's clock is this far behind the navigation's [s]


def heading(t):
    """A pilot's heading [deg]: slow turns and a few sharp steps (a shared, varying signal)."""
    return 30.0 * np.sin(0.05 * t) + 10.0 * np.sign(np.sin(0.4 * t)) + 5.0 * np.sin(1.3 * t)


def surge(t):
    return 0.5 + 0.2 * np.sin(0.21 * t)


def force(t):
    return 40.0 * np.sign(np.sin(0.33 * t))


def nav_rows(t):
    return [f"{EPOCH + tk:.6f},{float(surge(tk))!r},{float(heading(tk))!r}" for tk in t]


def write_nav_chunks(folder, *, overlap=5, gap=60):
    """Six chunk files of 20 s, named out of time order, each repeating the last ``overlap``
    rows of the one before, but the fourth, whose first ``gap`` rows are missing (a gap of
    3 s between chunks). Returns the times of the samples written, once each."""
    folder.mkdir()
    t = np.arange(0.0, DURATION, 1.0 / NAV_RATE)
    bounds = np.linspace(0, t.size, 7).astype(int)
    names = ["f", "c", "a", "e", "b", "d"]
    kept = []
    for i, (a, b) in enumerate(zip(bounds[:-1], bounds[1:])):
        kept.append(t[a + gap:b] if i == 3 else t[a:b])
        a = a + gap if i == 3 else max(0, a - overlap) if i else a
        (folder / f"nav_{names[i]}.csv").write_text(
            "stamp,u,yaw\n" + "\n".join(nav_rows(t[a:b])) + "\n")
    return np.concatenate(kept)


def write_cmd(path, *, offset=OFFSET, noise=0.0, seed=0):
    """Header-less commands: the logger's stamp, the surge force and the heading it held."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, DURATION, 1.0 / CMD_RATE)
    psi = heading(t) + noise * rng.standard_normal(t.size)
    path.write_text("\n".join(f"{EPOCH + tk - offset:.6f},{float(force(tk))!r},{float(p)!r}"
                              for tk, p in zip(t, psi)) + "\n")
    return t


MAP = """\
streams:
  nav:
    file: %(nav)s
    time: {column: stamp}
    max_gap: 0.5
  cmd:
    file: cmd.csv
    header: false
    columns: [stamp, fx, psi_cmd]
    time: {column: stamp}
    %(align)s
velocity: {stream: nav, columns: [u, null, null]}
attitude: {stream: nav, euler: [null, null, yaw], unit: deg}
wrench: {stream: cmd, columns: [fx, null, null, null, null, null]}
output: {rate: 20, time_origin: absolute}
"""


def write_map(tmp_path, nav="nav", align="align: {to: nav, signal: [psi_cmd, yaw], max: 3}"):
    p = tmp_path / "map.yaml"
    p.write_text(MAP % {"nav": nav, "align": align})
    return p


def read(*args):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        log = read_mapped_log(*args)
    return log, [str(w.message) for w in caught if issubclass(w.category, SamplingWarning)]


@pytest.mark.parametrize("nav", ["nav", "nav/nav_*.csv"])
def test_chunks_joined_by_time_and_offset_recovered(tmp_path, nav):
    """Chunk files given as a folder or a glob: ordered by time (not name), the overlapping
    rows dropped once (5 rows of 4 chunks), the missing 3 s reported as a gap between chunks; the command stream's
    clock offset recovered within one sample (of the finer stream, 0.05 s) and the merged
    surge force switches where the truth does."""
    t_nav = write_nav_chunks(tmp_path / "nav")
    write_cmd(tmp_path / "cmd.csv")
    log, warned = read(tmp_path / "cmd.csv", write_map(tmp_path, nav))
    meta = log.meta["streams"]
    assert meta["nav"]["chunks"] == 6 and meta["nav"]["overlap_dropped"] == 20
    assert meta["nav"]["samples"] == t_nav.size
    (gap,) = meta["nav"]["gaps"]
    assert gap["from"] - EPOCH == pytest.approx(60.0 - 1 / NAV_RATE, abs=1e-6)
    assert gap["to"] - EPOCH == pytest.approx(63.0, abs=1e-6) and gap["before"] == "nav_e.csv"
    assert any("6 chunk files joined" in w and "20 sample(s)" in w and "1 gap(s)" in w
               for w in warned)
    est = meta["cmd"]["clock_offset"]
    assert est["method"] == "cross-correlation" and est["correlation"] > 0.99
    assert abs(est["offset_s"] - OFFSET) < 1.0 / NAV_RATE
    assert any("clock offset" in w and "streams.cmd.align.offset" in w for w in warned)
    # the navigation read through the chunks is the truth on every row (the gap's rows dropped)
    tt = log["t"] - EPOCH
    assert not np.any((tt > 60.0 - 1 / NAV_RATE) & (tt < 63.0))
    np.testing.assert_allclose(log["u"], surge(tt), atol=1e-6)
    # the held force is the truth's wherever the truth did not switch within one sample
    steady = np.abs(force(tt) - force(tt - 0.15)) == 0
    assert np.mean(log["X"][steady] == force(tt[steady])) > 0.99


def test_offset_given_overrides_the_estimate(tmp_path):
    write_nav_chunks(tmp_path / "nav")
    write_cmd(tmp_path / "cmd.csv")
    log, _ = read(tmp_path / "cmd.csv", write_map(
        tmp_path, align="align: {to: nav, signal: [psi_cmd, yaw], offset: 0.8}"))
    assert log.meta["streams"]["cmd"]["clock_offset"] == {"offset_s": 0.8, "to": "nav",
                                                          "method": "given"}


def test_offset_of_noisy_signals_within_one_sample():
    """Several seeded draws of a noisy shared signal (noise 1 deg): each offset within one
    sample of the coarser stream and within 0.3 of a sample of the finer one."""
    for seed, off in ((1, 0.8372), (2, -1.234), (3, 0.02)):
        rng = np.random.default_rng(seed)
        t_ref = np.arange(0.0, 90.0, 0.05)
        t = np.arange(0.0, 90.0, 0.1)
        est = estimate_offset(t - off, heading(t) + rng.normal(0, 1.0, t.size),
                              t_ref, heading(t_ref) + rng.normal(0, 1.0, t_ref.size),
                              max_offset=3.0)
        assert abs(est.offset - off) < 0.3 * 0.05, (seed, est)


def test_uncorrelated_or_edge_offsets_are_one_line_errors():
    rng = np.random.default_rng(0)
    t = np.arange(0.0, 60.0, 0.1)
    with pytest.raises(InputError, match="do not correlate.*align.offset"):
        estimate_offset(t, rng.normal(size=t.size), t, rng.normal(size=t.size),
                        max_offset=2.0)
    with pytest.raises(InputError, match="edge of the search"):
        estimate_offset(t - 1.5, heading(t), t, heading(t), max_offset=1.0)
    with pytest.raises(InputError, match="constant signal"):
        estimate_offset(t, np.ones(t.size), t, heading(t), max_offset=1.0)


def test_bursty_receive_times_retimed(tmp_path):
    """A 10 Hz source received in bursts (groups of 1-8 samples delivered together, with
    latencies up to 0.8 s): re-timed at its period within 1e-6 relative, every stamp within
    the smallest latency of the truth (here 0: the last of each burst arrives on time)."""
    rng = np.random.default_rng(4)
    n = 3000
    true_t = 50.0 + np.arange(n) / CMD_RATE
    recv = np.empty(n)
    k = 0
    while k < n:
        m = int(rng.integers(1, 9))
        recv[k:k + m] = true_t[min(k + m, n) - 1]
        k += m
    lines = [f"{EPOCH + r:.6f},{float(surge(tt))!r},{float(heading(tt))!r}" for r, tt in zip(recv, true_t)]
    (tmp_path / "imu.csv").write_text("\n".join(lines) + "\n")
    (tmp_path / "map.yaml").write_text(
        "streams:\n  imu:\n    header: false\n    columns: [recv, u, yaw]\n"
        "    time: {column: recv, retime: true}\n"
        "velocity: {columns: [u, null, null]}\n")
    log, warned = read(tmp_path / "imu.csv", tmp_path / "map.yaml")
    info = log.meta["streams"]["imu"]["retimed"]
    assert info["period_s"] == pytest.approx(1.0 / CMD_RATE, rel=1e-6)
    assert 0.0 <= info["max_latency_s"] <= 0.8
    assert log.meta["rate"] == pytest.approx(CMD_RATE, rel=1e-6) and len(log) == n
    np.testing.assert_allclose(log["u"], surge(true_t), atol=1e-6)
    assert not any("burst" in w for w in warned)
    r = retime(recv)
    np.testing.assert_allclose(np.asarray(r.t, float), true_t, atol=1e-6)


def test_chunk_errors_name_the_file(tmp_path):
    write_nav_chunks(tmp_path / "nav")
    write_cmd(tmp_path / "cmd.csv")
    with pytest.raises(InputError, match="no file of stream 'nav'"):
        read_mapped_log(tmp_path / "cmd.csv", write_map(tmp_path, "navx_*.csv"))
    bad = tmp_path / "nav" / "nav_c.csv"
    rows = bad.read_text().splitlines()
    rows[3], rows[4] = rows[4], rows[3]
    bad.write_text("\n".join(rows) + "\n")
    with pytest.raises(InputError, match="nav_c.csv.*time goes backwards at line 5"):
        read_mapped_log(tmp_path / "cmd.csv", write_map(tmp_path))
    m = tmp_path / "map.yaml"
    m.write_text(MAP % {"nav": "nav", "align": "align: {to: wrench, signal: [a, b]}"})
    with pytest.raises(InputError, match="streams.cmd.align.to: unknown stream"):
        read_mapped_log(tmp_path / "cmd.csv", m)


def test_the_command_line_reports_chunks_and_offset(tmp_path, capsys):
    """``stripcoef identify FOLDER --map MAP``: the chunk folder is the log; the joined chunks,
    their gap and the estimated offset (with its override key) are printed as warnings."""
    from stripcoef.cli import main

    write_nav_chunks(tmp_path / "nav")
    write_cmd(tmp_path / "cmd.csv")
    m = write_map(tmp_path)
    rc = main(["identify", str(tmp_path / "nav"), "--map", str(m), "--method", "one-step",
               "--dof", "surge", "--json"])
    err = capsys.readouterr().err
    assert rc == 0, err
    assert "6 chunk files joined by time" in err and "1 gap(s) between chunks" in err
    assert "clock offset +0.8" in err and "streams.cmd.align.offset" in err
    assert re.search(r"gap in t from 17000000(59\.9\d*) to 17000000(63|62\.9\d*) s", err), err


def test_offset_from_a_command_and_the_rate_of_its_response(tmp_path):
    """No shared signal: the commanded force X and the measured surge velocity u of
    m du/dt = X(t - tau) - d u (exact between the steps of a held command). With
    ``response: rate`` the offset found is the clock offset plus the actuator delay tau,
    within one sample of the finer stream."""
    m_, d_, tau, h = 30.0, 12.0, 0.3, 1.0 / NAV_RATE
    fine = np.arange(0.0, DURATION, 1e-3)
    x = force(fine - tau)
    u = np.empty(fine.size)
    u[0] = 0.0
    decay = np.exp(-d_ / m_ * 1e-3)
    for k in range(1, fine.size):                  # exact for a force held over each step
        u[k] = u[k - 1] * decay + x[k - 1] / d_ * (1.0 - decay)
    t_nav = np.arange(0.0, DURATION, h)
    u_nav = np.interp(t_nav, fine, u)
    (tmp_path / "nav.csv").write_text("stamp,u\n" + "".join(
        f"{EPOCH + a:.6f},{float(b)!r}\n" for a, b in zip(t_nav, u_nav)))
    t_cmd = np.arange(0.0, DURATION, 1.0 / CMD_RATE)
    (tmp_path / "cmd.csv").write_text("".join(f"{EPOCH + a - OFFSET:.6f},{float(force(a))!r},0\n"
                                              for a in t_cmd))
    m = tmp_path / "map.yaml"
    m.write_text(MAP % {"nav": "nav.csv", "align": "align: {to: nav, signal: [fx, u], "
                        "response: rate, max: 3}"})
    m.write_text(m.read_text().replace("attitude: {stream: nav, euler: [null, null, yaw], "
                                       "unit: deg}\n", ""))
    log, warned = read(tmp_path / "cmd.csv", m)
    est = log.meta["streams"]["cmd"]["clock_offset"]
    assert abs(est["offset_s"] - (OFFSET + tau)) < h, est
    assert est["method"] == "response fit"
    assert any("best fit of the rate of nav.u" in w and "actuator delay" in w for w in warned)
