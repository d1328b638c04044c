r"""Streams through a column map into one :class:`~stripcoef.logfile.Log` on a common time grid.

The rules (docs/logs.md):

1. Each stream is read with its own times (:mod:`.streams`, :mod:`.bags`); values become SI
   (``scale * (raw - offset)``, angle and time units), the package's frames (NED, FRD:
   :mod:`.attitude`), and the derived quantities are computed on the stream's own samples:
   body rates from the attitude (:func:`.attitude.body_rates`), earth-fixed velocity from the
   position (central differences, ``numpy.gradient``). A stream with ``align`` is moved onto
   its reference stream's clock first (:func:`align_clocks`, :mod:`.clock`).
2. The log spans the overlap of every stream used, [max of the first times, min of the last
   times]; an empty overlap is an error listing each stream's span. Nothing is extrapolated.
3. The grid is uniform at ``output.rate`` (default: the fastest rate of the state streams,
   else of all streams: each stream's stated rate, else its median rate), starting at the
   start of the overlap.
4. States (position, attitude, velocity, rates, and channels with ``hold: linear``) are
   interpolated linearly (Euler angles unwrapped); inputs (wrench, thruster commands, channels
   with ``hold: previous``) are held from their last sample (zero-order hold), as a
   controller sends them and as :func:`stripcoef.simulate.simulate` applies them.
5. Earth-fixed velocities and angular velocities are rotated into the body on the grid,
   :math:`v_b = R^T(\Theta) v_n` (Fossen 2011, eq. 2.18).
6. ``exclude`` ranges (seconds of the output time) are dropped, and so are the rows inside a
   gap of a stream longer than its ``max_gap`` (instead of bridging it by interpolation); a
   hole inside the log leaves a gap in ``t`` (a :class:`~stripcoef.errors.SamplingWarning`
   says where).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from pathlib import Path

import numpy as np

from stripcoef.conventions import FORCES, POSE, VELOCITIES, axes_operator, world_axes_operator
from stripcoef.errors import InputError, ModelWarning, SamplingWarning
from stripcoef.ingest.attitude import (body_rates, euler_from_matrices, euler_matrices,
                                       quaternion_matrices, to_ned_frd)
from stripcoef.ingest.bags import is_bag, read_bag_streams
from stripcoef.ingest.mapfile import LogMap, load_map
from stripcoef.files import MAX_TEXT_BYTES
from stripcoef.ingest.streams import read_csv_stream, stream_files
from stripcoef.logfile import COMMAND_PREFIX, Log, check_magnitudes, read_log


#: Rows of a stream turned into rotation matrices at a time [-]: the matrices and their
#: temporaries (about 300 bytes a row) stay near 60 MB however long the log.
BLOCK_ROWS = 200_000


def _needed(logmap: LogMap) -> dict:
    need = {name: [] for name in logmap.streams}
    for _, block in logmap.blocks():
        if block.stream:
            need[block.stream] += [c for c in block.columns if c is not None]
    for name, spec in logmap.streams.items():
        if spec.align is not None and spec.align.to is not None:
            need[name].append(spec.align.signal[0])
            need[spec.align.to].append(spec.align.signal[1])
    return {k: list(dict.fromkeys(v)) for k, v in need.items()}


def align_clocks(logmap: LogMap, tables: dict) -> dict:
    """The tables with every ``align``-ed stream's stamps shifted onto its reference stream's
    clock (:mod:`.clock`: the offset given, else estimated by cross-correlation of the shared
    signal); a stream aligned to an aligned stream follows it (a chain), a cycle is an error.
    Each shift is reported: the table's ``info["clock_offset"]`` and a
    :class:`~stripcoef.errors.SamplingWarning` naming the override key."""
    from stripcoef.ingest.clock import estimate_offset, estimate_response_offset

    todo = {k: s.align for k, s in logmap.streams.items() if s.align is not None}
    tables = dict(tables)
    while todo:
        ready = [k for k, a in todo.items() if a.to is None or a.to not in todo]
        if not ready:
            raise InputError("streams aligned to each other in a cycle", file=logmap.path,
                             key="streams", value=sorted(todo),
                             expected="align.to chains that end at a stream without align")
        for name in ready:
            a = todo.pop(name)
            tb = tables[name]
            key = f"streams.{name}.align"
            if a.offset is not None:
                info = {"offset_s": a.offset, "to": a.to, "method": "given"}
            else:
                ref = tables[a.to]
                base = np.floor(min(tb.t[0], ref.t[0]))
                how = estimate_response_offset if a.response == "rate" else estimate_offset
                est = how(np.asarray(tb.t - base, float), tb.column(a.signal[0]),
                          np.asarray(ref.t - base, float), ref.column(a.signal[1]),
                          max_offset=a.max, where=logmap.path, key=key)
                info = {"offset_s": est.offset, "to": a.to,
                        "method": "response fit" if a.response == "rate" else
                        "cross-correlation",
                        "signal": list(a.signal), "correlation": est.correlation,
                        "lag_step_s": est.step}
                rate = a.response == "rate"
                what = (f"the best fit of the rate of {a.to}.{a.signal[1]} by "
                        f"{name}.{a.signal[0]} (multiple correlation" if rate else
                        f"cross-correlation of {name}.{a.signal[0]} with {a.to}.{a.signal[1]} "
                        "(peak")
                warnings.warn(f"{logmap.path}: stream {name!r}: clock offset "
                              f"{est.offset:+.4f} s to stream {a.to!r} estimated by {what} "
                              f"{est.correlation:.3f}, lag step {est.step:.4g} s"
                              f"{'; it includes the actuator delay' if rate else ''}); "
                              f"to override: {key}.offset",
                              SamplingWarning, stacklevel=3)
            tables[name] = dataclasses.replace(
                tb, t=tb.t + np.longdouble(info["offset_s"]),
                info={**tb.info, "clock_offset": info})
    return tables


def read_streams(source, logmap: LogMap) -> dict:
    """Every stream of the map as a Table: relative ``file`` paths are in the folder that
    holds ``source`` (without a source: the map's folder), a stream without ``file`` reads
    ``source`` itself, topics read the bag ``source``."""
    source = Path(source) if source is not None else None
    need = _needed(logmap)
    tables, topics, paths = {}, [], []
    for name, spec in logmap.streams.items():
        if spec.topic is not None:
            if source is None or not is_bag(source):
                raise InputError(f"stream {name!r} reads topic {spec.topic!r} of a bag",
                                 file=logmap.path, key=f"streams.{name}.topic",
                                 value=str(source), expected="a ROS bag as the log (.bag "
                                 "file or ROS 2 bag folder)")
            topics.append((spec, need[name]))
            continue
        if spec.file is None:
            if source is None or is_bag(source):
                raise InputError(f"stream {name!r} has no file", file=logmap.path,
                                 key=f"streams.{name}.file", value=str(source),
                                 expected="a CSV log given as LOG, or file: NAME in the map")
            path = source
        else:
            path = Path(spec.file)
            if not path.is_absolute():          # in the folder that holds LOG (else the map)
                base = source.parent if source is not None else Path(logmap.path).parent
                path = base / path
        paths.append((name, spec, path))
    files = {f.resolve() for _, spec, path in paths for f in stream_files(path, spec)
             if f.is_file()}                     # a file two streams read counts once
    total = sum(f.stat().st_size for f in files)
    if total > MAX_TEXT_BYTES:
        raise InputError(f"the streams' files total {total / 2**20:.0f} MiB", file=logmap.path,
                         key="streams", expected=f"at most {MAX_TEXT_BYTES // 2**20} MiB "
                         "together (they are merged in memory): fewer chunk files, a shorter "
                         "log or a decimated one")
    for name, spec, path in paths:
        tables[name] = read_csv_stream(path, spec, need[name])
    if topics:
        tables.update(read_bag_streams(source, topics))
    return align_clocks(logmap, tables)


def _values(block, table) -> np.ndarray:
    """(n, k) SI values of a block's columns (NaN for a null column)."""
    n = table.t.size
    out = np.full((n, len(block.columns)), np.nan)
    for j, col in enumerate(block.columns):
        if col is not None:
            out[:, j] = block.scale[j] * (table.column(col) - block.offset[j])
    return out


def _attitude_matrices(logmap, table):
    block = logmap.attitude
    vals = _values(block, table)
    if block.kind == "quaternion":
        q = vals if block.order == "wxyz" else vals[:, [3, 0, 1, 2]]
        r = quaternion_matrices(q, file=table.where, key=block.columns[0])
    else:
        if np.isnan(vals).any() and (logmap.world, logmap.body) != ("NED", "FRD"):
            raise InputError("Euler angles in ENU/FLU frames need all three angles",
                             file=logmap.path, key="attitude.euler",
                             value=list(block.columns), expected="roll, pitch and yaw columns")
        r = euler_matrices(*np.nan_to_num(vals).T)
    return to_ned_frd(r, world=logmap.world, body=logmap.body)


def _grid(logmap, tables, base=0.0):
    starts = {k: float(tb.t[0]) for k, tb in tables.items()}
    ends = {k: float(tb.t[-1]) for k, tb in tables.items()}
    t0, t1 = max(starts.values()), min(ends.values())
    if not t1 > t0:
        spans = "; ".join(f"{k} {starts[k] + float(base):.3f}..{ends[k] + float(base):.3f} s"
                          for k in tables)
        raise InputError("the streams do not overlap in time", file=logmap.path, key="streams",
                         value=spans, expected="streams that share a time span (check the "
                         "time units, offsets and start times)")
    rate = logmap.rate
    if rate is None:
        states = {b.stream for b in (logmap.position, logmap.attitude, logmap.velocity,
                                     logmap.rates) if b is not None and b.stream}
        rate = max(logmap.streams[k].rate or logmap.streams[k].time.rate
                   or tables[k].median_rate for k in (states or tables))
    n = int(math.floor((t1 - t0) * rate + 1e-6)) + 1     # 1e-6: round-off of the stamps
    if n < 2:
        raise InputError("overlap shorter than one output sample", file=logmap.path,
                         key="output.rate", value=rate,
                         expected=f"a rate above {1.0 / (t1 - t0):.4g} Hz")
    return t0 + np.arange(n) / rate, rate


def _linear(table_t, values, grid):
    return np.column_stack([np.interp(grid, table_t, v) for v in np.atleast_2d(values.T)])


#: A sample stamped within this share of its stream's median step after an output time
#: counts as at it in the zero-order hold [-]: the output times (t0 + k / rate) and the
#: parsed stamps carry different round-off (a few ulp of the relative time, ~1e-15 s), and
#: a command resampled onto its own grid (a 50-Hz CSV mapped at 50 Hz) otherwise takes the
#: previous command at about one sample in 250 where the two round differently (found on a
#: file of the layout of the public BlueROV2 tank logs, tests/test_real_logs.py). Small
#: enough (2e-11 s at 50 Hz) to leave stamps that differ by a nanosecond in order.
HOLD_TOLERANCE = 1e-9


def _held(table_t, values, grid):
    """Zero-order hold: each output time takes the last sample at or before it
    (:data:`HOLD_TOLERANCE`)."""
    step = float(np.median(np.diff(table_t))) if table_t.size > 1 else 0.0
    k = np.clip(np.searchsorted(table_t, grid + HOLD_TOLERANCE * step, side="right") - 1,
                0, table_t.size - 1)
    return values[k]


def _to_body(r_grid, world_values_on_grid) -> np.ndarray:
    r"""Earth-fixed (NED) vectors into the body, :math:`v_b = R^T v_n` (Fossen 2011, eq. 2.18)."""
    return np.einsum("nji,nj->ni", r_grid, world_values_on_grid)


def _attitude_columns(logmap, tables, grid, cols):
    """phi theta psi on the grid (the logged ones) and R on the grid (None without attitude)."""
    block = logmap.attitude
    if block is None:
        return None
    tb = tables[block.stream]
    euler = np.empty((tb.t.size, 3))
    for a in range(0, tb.t.size, BLOCK_ROWS):     # in blocks: bounded memory (issue 36)
        part = dataclasses.replace(tb, t=tb.t[a:a + BLOCK_ROWS],
                                   columns={k: v[a:a + BLOCK_ROWS] for k, v in
                                            tb.columns.items()})
        euler[a:a + BLOCK_ROWS] = euler_from_matrices(_attitude_matrices(logmap, part))
    euler[:, 0] = np.unwrap(euler[:, 0])
    euler[:, 2] = np.unwrap(euler[:, 2])          # across the blocks' seams
    euler_grid = _linear(tb.t, euler, grid)
    present = [True] * 3 if block.kind == "quaternion" else [c is not None for c in block.columns]
    for i in range(3):
        if present[i]:
            cols[POSE[3 + i]] = euler_grid[:, i]
    missing = [POSE[3 + i] for i in range(3) if not present[i]]
    for name, b, what in (("velocity", logmap.velocity, "rotate earth-fixed velocities into "
                           "the body"), ("rates", logmap.rates, "derive or rotate the body rates")):
        if missing and b is not None and (b.frame == "world" or b.derive):
            warnings.warn(f"{logmap.path}: attitude has no {', '.join(missing)}: taken as 0 to "
                          f"{what}", ModelWarning, stacklevel=4)
    r_grid = np.empty((grid.size, 3, 3))
    for a in range(0, grid.size, BLOCK_ROWS):
        r_grid[a:a + BLOCK_ROWS] = euler_matrices(*euler_grid[a:a + BLOCK_ROWS].T)
    return r_grid


def _position_columns(logmap, tables, grid, cols, a_w):
    """x y z (NED) on the grid (the logged ones); the NED position on its own samples."""
    block = logmap.position
    if block is None:
        return None
    tb = tables[block.stream]
    vals = _values(block, tb)
    if np.isnan(vals).any() and logmap.world != "NED":
        raise InputError("an ENU position needs all three columns", file=logmap.path,
                         key="position.columns", value=list(block.columns),
                         expected="x, y and z columns")
    pos_ned = vals @ a_w.T
    p_grid = _linear(tb.t, np.nan_to_num(pos_ned), grid)
    for i, c in enumerate(block.columns):
        if c is not None:                        # an ENU position has all three (above)
            cols[POSE[i]] = p_grid[:, i]
    return pos_ned


def _velocity_columns(logmap, tables, grid, cols, r_grid, pos_ned, a_w, sign):
    """u v w on the grid: body columns, earth-fixed columns rotated, or from the position."""
    v = logmap.velocity
    if v is None:
        return
    if v.derive:
        tb = tables[logmap.position.stream]
        if np.isnan(pos_ned).any():
            raise InputError("velocity from a position needs all three position columns",
                             file=logmap.path, key="position.columns",
                             value=list(logmap.position.columns), expected="x, y and z")
        body = _to_body(r_grid, _linear(tb.t, np.gradient(pos_ned, tb.t, axis=0), grid))
    elif v.frame == "world":
        tb = tables[v.stream]
        body = _to_body(r_grid, _linear(tb.t, _values(v, tb) @ a_w.T, grid))
    else:
        tb = tables[v.stream]
        body = _linear(tb.t, np.nan_to_num(_values(v, tb)) * sign[:3], grid)
    for i in range(3):
        if v.derive or v.frame == "world" or v.columns[i] is not None:
            cols[VELOCITIES[i]] = body[:, i]


def _rate_columns(logmap, tables, grid, cols, r_grid, a_w, sign):
    """p q r on the grid: body columns, earth-fixed columns rotated, or from the attitude."""
    w = logmap.rates
    if w is None:
        return
    present = [True] * 3
    if w.derive:
        tb = tables[logmap.attitude.stream]
        om = _linear(tb.t, body_rates(tb.t, _attitude_matrices(logmap, tb)), grid)
    elif w.frame == "world":
        tb = tables[w.stream]
        om = _to_body(r_grid, _linear(tb.t, _values(w, tb) @ a_w.T, grid))
    else:
        tb = tables[w.stream]
        om = _linear(tb.t, np.nan_to_num(_values(w, tb)) * sign[3:], grid)
        present = [c is not None for c in w.columns]
    for i in range(3):
        if present[i]:
            cols[VELOCITIES[3 + i]] = om[:, i]


def _input_columns(logmap, tables, grid, cols, sign):
    """X..N and n_<thruster> held (zero-order hold); channels as their ``hold`` says."""
    if logmap.wrench is not None:
        tb = tables[logmap.wrench.stream]
        f = _held(tb.t, np.nan_to_num(_values(logmap.wrench, tb)) * sign, grid)
        for i, c in enumerate(logmap.wrench.columns):
            if c is not None:
                cols[FORCES[i]] = f[:, i]
    for name, b in logmap.thrusters.items():
        tb = tables[b.stream]
        cols[COMMAND_PREFIX + name] = _held(tb.t, _values(b, tb)[:, 0], grid)
    for name, b in logmap.channels.items():
        tb = tables[b.stream]
        vals = _values(b, tb)[:, 0]
        cols[name] = np.interp(grid, tb.t, vals) if b.hold == "linear" else \
            _held(tb.t, vals, grid)


def _kept_rows(logmap, t, grid, tables) -> np.ndarray:
    """Indices of the rows outside every ``exclude`` range and inside no gap longer than its
    stream's ``max_gap``; a hole left inside the log warns."""
    keep = np.ones(t.size, dtype=bool)
    for a, b in logmap.exclude:
        keep &= ~((t >= a) & (t <= b))
    for name, tb in tables.items():
        limit = logmap.streams[name].max_gap
        if limit is None:
            continue
        for k in np.nonzero(np.diff(tb.t) > limit)[0]:
            keep &= ~((grid > tb.t[k]) & (grid < tb.t[k + 1]))   # not bridged by interpolation
    if keep.sum() < 2:
        raise InputError("excluded ranges leave fewer than 2 samples", file=logmap.path,
                         key="exclude", value=[list(r) for r in logmap.exclude],
                         expected=f"ranges that keep part of t = {t[0]:.6g}..{t[-1]:.6g} s")
    idx = np.nonzero(keep)[0]
    for k in np.nonzero(np.diff(idx) > 1)[0]:
        warnings.warn(f"{logmap.path}: excluded range or stream gap leaves a gap in t from "
                      f"{t[idx[k]]:.12g} to {t[idx[k + 1]]:.12g} s (methods that difference "
                      "consecutive samples span it)", SamplingWarning, stacklevel=4)
    return idx


def build_log(logmap: LogMap, tables: dict, *, source: str = "<streams>") -> Log:
    """The merged log of the streams' tables (module docstring, rules 2-6)."""
    base = np.floor(min(tb.t[0] for tb in tables.values()))   # whole seconds
    tables = {k: dataclasses.replace(tb, t=np.asarray(tb.t - base, dtype=float))
              for k, tb in tables.items()}
    grid, rate = _grid(logmap, tables, base)
    a_w = world_axes_operator(logmap.world)
    sign = axes_operator(logmap.body).diagonal()        # FLU -> FRD: its own inverse
    cols = {}
    r_grid = _attitude_columns(logmap, tables, grid, cols)
    pos_ned = _position_columns(logmap, tables, grid, cols, a_w)
    _velocity_columns(logmap, tables, grid, cols, r_grid, pos_ned, a_w, sign)
    _rate_columns(logmap, tables, grid, cols, r_grid, a_w, sign)
    _input_columns(logmap, tables, grid, cols, sign)
    t = grid - grid[0] if logmap.time_origin == "start" else grid + float(base)
    idx = _kept_rows(logmap, t, grid, tables)
    out = {"t": t[idx], **{k: np.asarray(c)[idx] for k, c in cols.items()}}
    meta = {"map": logmap.path, "time_base": int(base), "t0": float(grid[0]),
            "rate": float(rate),
            "streams": {k: {"samples": int(tb.t.size), "median_rate": tb.median_rate,
                            "span": [float(tb.t[0] + base), float(tb.t[-1] + base)],
                            **tb.info}
                        for k, tb in tables.items()},
            "excluded": [list(r) for r in logmap.exclude]}
    return Log(out, source=source, meta=meta)


def read_mapped_log(source, logmap) -> Log:
    """A log from a CSV file, several CSV files or a ROS bag through a column map.

    Parameters
    ----------
    source : str or Path or None
        The log given on the command line: a CSV file (streams without ``file`` read it;
        relative ``file`` paths are next to it) or a ROS bag (topic streams read it).
    logmap : LogMap or str or Path
        The map (:func:`stripcoef.ingest.mapfile.load_map`).
    """
    if not isinstance(logmap, LogMap):
        logmap = load_map(logmap)
    tables = read_streams(source, logmap)
    name = str(source) if source is not None else logmap.path
    return build_log(logmap, tables, source=name)


def read_any_log(path, *, column_map=None, required=()) -> Log:
    """The log of a command: the log CSV format (:func:`stripcoef.logfile.read_log`), or
    through a column map a CSV or a ROS bag; a bag without a map is an error."""
    if column_map is not None:
        log = read_mapped_log(path, column_map)
        check_magnitudes(log)            # in SI units once mapped (as read_log does)
        log.require(*required) if required else None
        return log
    if is_bag(path):
        raise InputError("a ROS bag needs a column map", key="map", value=str(path),
                         expected="a column map (YAML) naming its topics and fields "
                         "(docs/logs.md)")
    return read_log(path, required=required)
