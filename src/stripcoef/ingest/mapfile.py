"""The column map (YAML): which column of which stream is what, in which unit and frame.

Read once into typed, validated dataclasses (:class:`LogMap`); every error names the map
file and the key path (``streams.nav.time.unit``), the value and what was expected.
docs/logs.md documents every key with examples.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from stripcoef.conventions import AXES, WORLD_FRAMES
from stripcoef.errors import InputError
from stripcoef.files import read_text
from stripcoef.ingest.attitude import QUATERNION_ORDERS
from stripcoef.logfile import COMMAND_PREFIX, KNOWN_COLUMNS

#: Time units of a time column and their factor to seconds [s per unit].
TIME_UNITS = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9, "iso": 1e-9}
#   ("iso": ISO 8601 date-time strings, read as nanoseconds since 1970-01-01 UTC)
#: Angle units and their factor to radians [rad per unit].
ANGLE_UNITS = {"rad": 1.0, "deg": math.pi / 180.0}
#: Angular-rate units and their factor to rad/s.
RATE_UNITS = {"rad/s": 1.0, "deg/s": math.pi / 180.0}
VELOCITY_FRAMES = ("body", "world")
MISSING = ("error", "drop")
HOLDS = ("linear", "previous")
TIME_ORIGINS = ("start", "absolute")
#: How the reference column of ``align.signal`` follows this stream's column: ``value`` (the
#: same quantity logged twice) or ``rate`` (its rate of change does: a commanded force and the
#: measured velocity; biased by the actuator's delay, :mod:`stripcoef.ingest.clock`).
ALIGN_RESPONSES = ("value", "rate")
BAG_TIMES = ("header", "bag")

_TOP_KEYS = ("version", "frames", "streams", "position", "attitude", "velocity", "rates",
             "wrench", "thrusters", "channels", "exclude", "output")


@dataclass(frozen=True)
class TimeSpec:
    """How a stream's sample times are found: a column (with unit and offset), a fixed
    rate from a start time, or (bags) the message header stamp or the bag's receive time."""
    column: str | None = None
    unit: str = "s"
    offset: float = 0.0
    rate: float | None = None
    start: float = 0.0
    source: str | None = None
    retime: bool = False


@dataclass(frozen=True)
class Align:
    """A stream's clock offset to another stream's clock [s]: ``offset`` given (it overrides
    any estimate), or estimated by cross-correlation of ``signal`` (this stream's column, the
    reference stream's column) within +-``max`` seconds (:mod:`stripcoef.ingest.clock`)."""
    to: str | None = None
    signal: tuple = ()
    max: float = 5.0
    offset: float | None = None
    response: str = "value"


@dataclass(frozen=True)
class StreamSpec:
    """One stream: a CSV file (or the LOG given on the command line) or a bag topic."""
    name: str
    file: str | None = None
    topic: str | None = None
    header: bool = True
    columns: tuple | None = None
    delimiter: str = ","
    comment: str = "#"
    missing: str = "error"
    time: TimeSpec = field(default_factory=TimeSpec)
    rate: float | None = None
    max_gap: float | None = None
    align: Align | None = None


@dataclass(frozen=True)
class Block:
    """Columns of one stream that make one quantity: SI value = scale * (raw - offset)."""
    stream: str
    columns: tuple = ()
    scale: tuple = ()
    offset: tuple = ()
    unit: str = ""
    frame: str = "body"
    derive: str | None = None
    kind: str = ""
    order: str = ""
    hold: str = "linear"
    key: str = ""


@dataclass(frozen=True)
class LogMap:
    """A validated column map (module docstring)."""
    path: str
    world: str = "NED"
    body: str = "FRD"
    streams: dict = field(default_factory=dict)
    position: Block | None = None
    attitude: Block | None = None
    velocity: Block | None = None
    rates: Block | None = None
    wrench: Block | None = None
    thrusters: dict = field(default_factory=dict)
    channels: dict = field(default_factory=dict)
    exclude: tuple = ()
    rate: float | None = None
    time_origin: str = "start"

    def blocks(self) -> list:
        """Every mapped quantity (name, Block), states first."""
        out = [(k, getattr(self, k)) for k in ("position", "attitude", "velocity", "rates",
                                                "wrench") if getattr(self, k) is not None]
        out += [(f"thrusters.{k}", b) for k, b in self.thrusters.items()]
        out += [(f"channels.{k}", b) for k, b in self.channels.items()]
        return out


class _Reader:
    """Typed access to the map's mapping with errors naming the file and key path."""

    def __init__(self, path: str):
        self.path = path

    def err(self, key, what, value=InputError._MISSING, expected=None):
        return InputError(what, file=self.path, key=key, value=value, expected=expected)

    def mapping(self, obj, key, allowed):
        if not isinstance(obj, dict):
            raise self.err(key, "not a mapping", obj, "key: value pairs")
        for k in obj:
            if k not in allowed:
                raise self.err(f"{key}.{k}" if key else str(k), "unknown key", k,
                               "one of " + ", ".join(allowed))
        return obj

    def number(self, obj, key, *, positive=False, allow_none=False):
        if obj is None and allow_none:
            return None
        if isinstance(obj, bool) or not isinstance(obj, (int, float)) or not math.isfinite(obj):
            raise self.err(key, "not a number", obj, "a finite number")
        if positive and obj <= 0:
            raise self.err(key, "not positive", obj, "a number > 0")
        return float(obj)

    def choice(self, obj, key, choices):
        if obj not in choices:
            raise self.err(key, "unknown value", obj, "one of " + ", ".join(choices))
        return obj

    def name(self, obj, key, *, allow_none=False):
        if obj is None and allow_none:
            return None
        if isinstance(obj, bool) or not isinstance(obj, (str, int)) or str(obj) == "":
            raise self.err(key, "not a column name", obj, "a column name (or a field path "
                           "of a bag message)")
        return str(obj)

    def per_column(self, obj, key, n, default):
        """A number for every column, or one number for all."""
        if obj is None:
            return (default,) * n
        if isinstance(obj, list):
            if len(obj) != n:
                raise self.err(key, f"{len(obj)} values for {n} columns", obj,
                               f"one number or a list of {n}")
            return tuple(self.number(v, f"{key}[{i}]") for i, v in enumerate(obj))
        return (self.number(obj, key),) * n


def _time_spec(r: _Reader, obj, key, *, topic: bool) -> TimeSpec:
    if obj is None:
        if topic:
            return TimeSpec(source="header")
        raise r.err(key, "missing key", expected="time: {column: NAME, unit: s} or "
                    "{rate: HZ, start: S}")
    if isinstance(obj, str):
        obj = {"source": obj} if topic and obj in BAG_TIMES else {"column": obj}
    r.mapping(obj, key, ("column", "unit", "offset", "rate", "start", "source", "retime"))
    has_col, has_rate, has_src = "column" in obj, "rate" in obj, "source" in obj
    if has_col + has_rate + has_src != 1:
        raise r.err(key, "one time source needed", sorted(obj),
                    "exactly one of column, rate" + (", source" if topic else ""))
    if has_src and not topic:
        raise r.err(f"{key}.source", "applies to bag topics only", obj["source"],
                    "column or rate for a CSV stream")
    unit = r.choice(obj.get("unit", "s"), f"{key}.unit", tuple(TIME_UNITS))
    retime = obj.get("retime", False)
    if not isinstance(retime, bool):
        raise r.err(f"{key}.retime", "not true/false", retime, "true or false")
    if retime and not has_col:
        raise r.err(f"{key}.retime", "re-times the stamps of a time column", retime,
                    "a time column (receive times) with it")
    return TimeSpec(retime=retime,column=r.name(obj["column"], f"{key}.column") if has_col else None,
                    unit=unit, offset=r.number(obj.get("offset", 0.0), f"{key}.offset"),
                    rate=r.number(obj["rate"], f"{key}.rate", positive=True) if has_rate
                    else None,
                    start=r.number(obj.get("start", 0.0), f"{key}.start"),
                    source=r.choice(obj["source"], f"{key}.source", BAG_TIMES) if has_src
                    else None)


def _stream(r: _Reader, name, obj) -> StreamSpec:
    key = f"streams.{name}"
    r.mapping(obj or {}, key, ("file", "topic", "header", "columns", "delimiter", "comment",
                               "missing", "time", "rate", "max_gap", "align"))
    obj = obj or {}
    if "file" in obj and "topic" in obj:
        raise r.err(key, "both file and topic", expected="a CSV file or a bag topic")
    topic = r.name(obj["topic"], f"{key}.topic") if "topic" in obj else None
    header = obj.get("header", True)
    if not isinstance(header, bool):
        raise r.err(f"{key}.header", "not true/false", header, "true or false")
    columns = obj.get("columns")
    if not header:
        if not isinstance(columns, list) or not columns:
            raise r.err(f"{key}.columns", "a file without header needs its column names",
                        columns, "a list of names, one per column of the file")
        columns = tuple(r.name(c, f"{key}.columns[{i}]") for i, c in enumerate(columns))
        if len(set(columns)) != len(columns):
            raise r.err(f"{key}.columns", "duplicated column name", list(columns),
                        "each name once")
    elif columns is not None:
        raise r.err(f"{key}.columns", "columns names a header-less file's columns", columns,
                    "header: false with it, or no columns key (the header names them)")
    delim = obj.get("delimiter", ",")
    if not isinstance(delim, str) or not delim or (len(delim) != 1 and delim != "whitespace"):
        raise r.err(f"{key}.delimiter", "not a delimiter", delim,
                    "one character (',', ';', '\\t') or 'whitespace'")
    comment = obj.get("comment", "#")
    if not isinstance(comment, str):
        raise r.err(f"{key}.comment", "not a string", comment, "a line prefix such as '#'")
    return StreamSpec(
        name=str(name), file=str(obj["file"]) if "file" in obj else None, topic=topic,
        header=header, columns=columns, delimiter=delim, comment=comment,
        missing=r.choice(obj.get("missing", "error"), f"{key}.missing", MISSING),
        time=_time_spec(r, obj.get("time"), f"{key}.time", topic=topic is not None),
        rate=r.number(obj.get("rate"), f"{key}.rate", positive=True, allow_none=True),
        max_gap=r.number(obj.get("max_gap"), f"{key}.max_gap", positive=True,
                         allow_none=True),
        align=_align(r, obj.get("align"), f"{key}.align") if "align" in obj else None)


def _align(r: _Reader, obj, key) -> Align:
    """``align: {to: STREAM, signal: [COLUMN, REFERENCE_COLUMN], max: S}`` (estimated) and/or
    ``align: {offset: S}`` (given: overrides the estimate)."""
    r.mapping(obj, key, ("to", "signal", "max", "offset", "response"))
    offset = r.number(obj.get("offset"), f"{key}.offset", allow_none=True)
    if "to" not in obj and offset is None:
        raise r.err(key, "nothing to align with", sorted(obj),
                    "to: STREAM with signal: [COLUMN, REFERENCE_COLUMN] (estimated), or "
                    "offset: SECONDS (given)")
    signal = ()
    if "to" in obj:
        sig = obj.get("signal")
        if not isinstance(sig, list) or len(sig) != 2:
            raise r.err(f"{key}.signal", "not two column names", sig,
                        "[a column of this stream, the column of stream "
                        f"{obj['to']!r} that logs the same quantity]")
        signal = (r.name(sig[0], f"{key}.signal[0]"), r.name(sig[1], f"{key}.signal[1]"))
    return Align(to=r.name(obj["to"], f"{key}.to") if "to" in obj else None, signal=signal,
                 max=r.number(obj.get("max", 5.0), f"{key}.max", positive=True),
                 offset=offset,
                 response=r.choice(obj.get("response", "value"), f"{key}.response",
                                   ALIGN_RESPONSES))


def _columns(r, obj, key, n, *, allow_null=True):
    cols = obj.get("columns")
    if not isinstance(cols, list) or len(cols) != n:
        raise r.err(f"{key}.columns", "wrong columns", cols, f"a list of {n} column names"
                    + (" (null for one the log does not have)" if allow_null else ""))
    out = tuple(r.name(c, f"{key}.columns[{i}]", allow_none=allow_null)
                for i, c in enumerate(cols))
    if all(c is None for c in out):
        raise r.err(f"{key}.columns", "every column is null", cols, "at least one column")
    return out


def _stream_ref(r, obj, key, streams):
    s = obj.get("stream")
    if s is None and len(streams) == 1:
        return next(iter(streams))
    if s not in streams:
        raise r.err(f"{key}.stream", "unknown stream", s, "one of " + ", ".join(streams))
    return s


def _block(r, obj, key, streams, allowed, n, *, units=None, unit_default="", frames=None,
           derive=None, **extra) -> Block | None:
    if obj is None:
        return None
    r.mapping(obj, key, allowed)
    if derive and "from" in obj:
        src = r.choice(obj["from"], f"{key}.from", (derive,))
        if len(obj) != 1:
            raise r.err(key, "a derived quantity takes no other key", sorted(obj),
                        f"only from: {derive}")
        return Block(stream="", derive=src, key=key)
    stream = _stream_ref(r, obj, key, streams)
    cols = _columns(r, obj, key, n)
    unit = r.choice(obj.get("unit", unit_default), f"{key}.unit", tuple(units)) if units \
        else ""
    frame = r.choice(obj.get("frame", "body"), f"{key}.frame", frames) if frames else "body"
    return Block(stream=stream, columns=cols,
                 scale=r.per_column(obj.get("scale"), f"{key}.scale", n, 1.0),
                 offset=r.per_column(obj.get("offset"), f"{key}.offset", n, 0.0),
                 unit=unit, frame=frame, key=key, **extra)


def _attitude(r, obj, streams) -> Block | None:
    if obj is None:
        return None
    key = "attitude"
    r.mapping(obj, key, ("stream", "euler", "quaternion", "order", "unit"))
    if ("euler" in obj) == ("quaternion" in obj):
        raise r.err(key, "one attitude form needed", sorted(obj),
                    "euler: [roll, pitch, yaw] or quaternion: [4 columns] with order")
    stream = _stream_ref(r, obj, key, streams)
    if "euler" in obj:
        cols = _columns(r, {"columns": obj["euler"]}, key, 3)
        unit = r.choice(obj.get("unit", "rad"), f"{key}.unit", tuple(ANGLE_UNITS))
        if "order" in obj:
            raise r.err(f"{key}.order", "applies to quaternions", obj["order"],
                        "no order with euler (always roll, pitch, yaw: zyx convention)")
        return Block(stream=stream, columns=cols, scale=(ANGLE_UNITS[unit],) * 3,
                     offset=(0.0,) * 3, unit=unit, kind="euler", key=key)
    cols = _columns(r, {"columns": obj["quaternion"]}, key, 4, allow_null=False)
    if "unit" in obj:
        raise r.err(f"{key}.unit", "applies to Euler angles", obj["unit"],
                    "no unit with a quaternion")
    if "order" not in obj:
        raise r.err(f"{key}.order", "missing key", expected="wxyz or xyzw: the order of the "
                    "four quaternion columns listed (ROS stores x, y, z, w)")
    order = r.choice(obj["order"], f"{key}.order", QUATERNION_ORDERS)
    return Block(stream=stream, columns=cols, scale=(1.0,) * 4, offset=(0.0,) * 4,
                 kind="quaternion", order=order, key=key)


def parse_map(data, *, path: str = "<map>") -> LogMap:
    """A :class:`LogMap` from the parsed YAML mapping ``data`` (module docstring)."""
    r = _Reader(path)
    r.mapping(data, "", _TOP_KEYS)
    version = data.get("version", 1)
    if version != 1:
        raise r.err("version", "unsupported map version", version, "1")
    frames = r.mapping(data.get("frames") or {}, "frames", ("world", "body"))
    world = r.choice(frames.get("world", "NED"), "frames.world", WORLD_FRAMES)
    body = r.choice(frames.get("body", "FRD"), "frames.body", AXES)
    raw = data.get("streams")
    if not isinstance(raw, dict) or not raw:
        raise r.err("streams", "missing or empty", raw,
                    "a mapping of stream names to a CSV file or a bag topic")
    streams = {str(k): _stream(r, k, v) for k, v in raw.items()}
    position = _block(r, data.get("position"), "position", streams,
                      ("stream", "columns", "scale", "offset"), 3)
    attitude = _attitude(r, data.get("attitude"), streams)
    velocity = _block(r, data.get("velocity"), "velocity", streams,
                      ("stream", "columns", "scale", "offset", "frame", "from"), 3,
                      frames=VELOCITY_FRAMES, derive="position")
    rates = _block(r, data.get("rates"), "rates", streams,
                   ("stream", "columns", "scale", "offset", "unit", "frame", "from"), 3,
                   units=RATE_UNITS, unit_default="rad/s", frames=VELOCITY_FRAMES,
                   derive="attitude")
    if rates is not None and rates.derive is None:
        f = RATE_UNITS[rates.unit]
        rates = Block(**{**rates.__dict__, "scale": tuple(s * f for s in rates.scale)})
    wrench = _block(r, data.get("wrench"), "wrench", streams,
                    ("stream", "columns", "scale", "offset"), 6)
    for name, b in (("velocity", velocity), ("rates", rates)):
        if b is not None and (b.frame == "world" or b.derive) and attitude is None:
            raise r.err(name, "earth-fixed or derived values need the attitude",
                        expected=f"an attitude block (or frame: body {name})")
        if b is not None and b.frame == "world" and None in b.columns:
            raise r.err(f"{name}.columns", "earth-fixed values need all three columns",
                        list(b.columns), "x, y and z of frames.world")
    if position is None and velocity is not None and velocity.derive:
        raise r.err("velocity.from", "no position to derive from",
                    expected="a position block (or velocity columns)")
    if rates is not None and rates.derive and attitude is None:
        raise r.err("rates.from", "no attitude to derive from",
                    expected="an attitude block (or rate columns)")
    thrusters = {}
    tobj = data.get("thrusters")
    if tobj is not None:
        r.mapping(tobj, "thrusters", ("stream", "columns", "scale", "offset"))
        cols = tobj.get("columns")
        if not isinstance(cols, dict) or not cols:
            raise r.err("thrusters.columns", "not a mapping", cols,
                        "thruster name: column name, for each commanded thruster")
        stream = _stream_ref(r, tobj, "thrusters", streams)
        for k, (tname, col) in enumerate(cols.items()):
            def one(v, what, default, _t=tname):
                if isinstance(v, dict):
                    return r.number(v.get(_t, default), f"thrusters.{what}.{_t}")
                return r.per_column(v, f"thrusters.{what}", 1, default)[0]
            thrusters[str(tname)] = Block(
                stream=stream, columns=(r.name(col, f"thrusters.columns.{tname}"),),
                scale=(one(tobj.get("scale"), "scale", 1.0),),
                offset=(one(tobj.get("offset"), "offset", 0.0),), key=f"thrusters.{tname}")
    channels = {}
    cobj = data.get("channels")
    if cobj is not None:
        r.mapping(cobj, "channels", tuple(cobj) if isinstance(cobj, dict) else ())
        for cname, c in cobj.items():
            key = f"channels.{cname}"
            if str(cname) in KNOWN_COLUMNS or str(cname).startswith(COMMAND_PREFIX):
                raise r.err(key, "a channel cannot take a state, force or command name",
                            cname, "another name (map those through their own blocks)")
            r.mapping(c, key, ("stream", "column", "scale", "offset", "hold"))
            channels[str(cname)] = Block(
                stream=_stream_ref(r, c, key, streams),
                columns=(r.name(c.get("column"), f"{key}.column"),),
                scale=r.per_column(c.get("scale"), f"{key}.scale", 1, 1.0),
                offset=r.per_column(c.get("offset"), f"{key}.offset", 1, 0.0),
                hold=r.choice(c.get("hold", "linear"), f"{key}.hold", HOLDS), key=key)
    exclude = []
    for i, rng in enumerate(data.get("exclude") or []):
        key = f"exclude[{i}]"
        if not isinstance(rng, list) or len(rng) != 2:
            raise r.err(key, "not a time range", rng, "[start, end] in seconds (null: open)")
        a = -math.inf if rng[0] is None else r.number(rng[0], f"{key}[0]")
        b = math.inf if rng[1] is None else r.number(rng[1], f"{key}[1]")
        if not a < b:
            raise r.err(key, "empty time range", rng, "start < end")
        exclude.append((a, b))
    out = r.mapping(data.get("output") or {}, "output", ("rate", "time_origin"))
    blocks = [position, attitude, velocity, rates, wrench, *thrusters.values(),
              *channels.values()]
    used = {b.stream for b in blocks if b is not None and b.stream}
    for name, spec in streams.items():
        if spec.align is not None and spec.align.to is not None:
            if spec.align.to not in streams or spec.align.to == name:
                raise r.err(f"streams.{name}.align.to", "unknown stream", spec.align.to,
                            "another stream of the map: "
                            + ", ".join(k for k in streams if k != name))
            if name in used:
                used.add(spec.align.to)
    if not used:
        raise r.err("", "nothing mapped", expected="at least one of position, attitude, "
                    "velocity, rates, wrench, thrusters, channels")
    return LogMap(path=path, world=world, body=body,
                  streams={k: v for k, v in streams.items() if k in used},
                  position=position, attitude=attitude, velocity=velocity, rates=rates,
                  wrench=wrench, thrusters=thrusters, channels=channels,
                  exclude=tuple(exclude),
                  rate=r.number(out.get("rate"), "output.rate", positive=True,
                                allow_none=True),
                  time_origin=r.choice(out.get("time_origin", "start"), "output.time_origin",
                                       TIME_ORIGINS))


def load_map(path) -> LogMap:
    """Read and validate a column map (YAML); errors name the file and the key path."""
    path = str(path)
    text = read_text(Path(path), kind="column map (YAML)")
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"line {mark.line + 1}" if mark is not None else None
        raise InputError("not valid YAML", file=path, key=where,
                         expected="a YAML mapping (docs/logs.md)") from None
    return parse_map(data, path=path)

