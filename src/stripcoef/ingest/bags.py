"""ROS 1 and ROS 2 bags read directly with the pure-Python ``rosbags`` library (no ROS install;
the optional extra ``stripcoef[ros]``).

A stream with ``topic:`` reads one topic; its columns are field paths of the message
(``pose.pose.position.x``, ``twist.twist.angular.z``, ``wrench.force.x``, ``data[2]``), and
its times are the header stamps (``time: header``, the default) or the bag's receive times
(``time: bag``). A ROS 2 bag is a folder with ``metadata.yaml`` (or its ``.db3``/``.mcap``
file), a ROS 1 bag a ``.bag`` file. Messages of a ROS 2 bag are decoded with the ROS 2
Humble type store unless the bag embeds its definitions (ROS 1 bags always do).

References
----------
rosbags (Ternaris), the ``AnyReader`` interface; ROS REP 103 (units and frames).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from stripcoef.errors import InputError
from stripcoef.ingest.streams import Table, checked_table

BAG_SUFFIXES = (".bag", ".db3", ".mcap")
_INDEX = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)(?:\[(\d+)\])?$")


def is_bag(path) -> bool:
    """A ROS 1 bag file, a ROS 2 bag folder (with metadata.yaml) or a ROS 2 storage file."""
    p = Path(path)
    return p.suffix.lower() in BAG_SUFFIXES or (p.is_dir() and (p / "metadata.yaml").exists())


def _rosbags():
    try:
        from rosbags.highlevel import AnyReader
        from rosbags.typesys import Stores, get_typestore
    except ImportError:
        raise InputError("reading a ROS bag needs the optional package rosbags", key="log",
                         expected="pip install 'stripcoef[ros]'") from None
    return AnyReader, Stores, get_typestore


def field_value(msg, path: str):
    """The value at a dotted field path of a message (``a.b[2].c``); a Time becomes seconds."""
    value = msg
    for part in path.split("."):
        m = _INDEX.match(part)
        if m is None or not hasattr(value, m.group(1)):
            raise KeyError(part)
        value = getattr(value, m.group(1))
        if m.group(2) is not None:
            value = value[int(m.group(2))]
    return stamp_seconds(value) if hasattr(value, "sec") else float(value)


def stamp_seconds(stamp):
    """A ROS time (``sec`` and ``nanosec``) in seconds [s], extended precision."""
    return np.longdouble(stamp.sec) + np.longdouble(getattr(stamp, "nanosec", 0)) / 10 ** 9


def _fields(msg, prefix="") -> list:
    """Numeric field paths of a message (for error messages)."""
    out = []
    for name in getattr(msg, "__dataclass_fields__", {}):
        if name == "__msgtype__":
            continue
        v = getattr(msg, name)
        if hasattr(v, "__dataclass_fields__") and not hasattr(v, "sec"):
            out += _fields(v, prefix + name + ".")
        elif isinstance(v, (int, float)) or hasattr(v, "sec"):
            out.append(prefix + name)
    return out


def read_bag_streams(path, wanted) -> dict:
    """Tables of the topic streams ``wanted`` = [(StreamSpec, needed field paths)] of a bag.

    Raises
    ------
    InputError
        rosbags missing, an unreadable bag, a topic not in the bag (lists the topics), a
        field missing from the message (lists its numeric fields), a header time asked of a
        message without header, time going backwards.
    """
    AnyReader, Stores, get_typestore = _rosbags()
    path = Path(path)
    where = str(path)
    if not path.exists():
        raise InputError("bag not found", file=where, expected="a ROS 1 .bag file or a ROS 2 "
                         "bag folder")
    try:
        reader = AnyReader([path], default_typestore=get_typestore(Stores.ROS2_HUMBLE))
        reader.open()
    except Exception as exc:  # rosbags raises its own error classes per format
        raise InputError(f"cannot read the bag ({exc.__class__.__name__}: {exc})", file=where,
                         expected="a ROS 1 .bag file or a ROS 2 bag folder") from None
    try:
        topics = sorted({c.topic for c in reader.connections})
        out = {}
        for spec, needed in wanted:
            conns = [c for c in reader.connections if c.topic == spec.topic]
            if not conns:
                raise InputError(f"no topic {spec.topic!r} in the bag (stream {spec.name!r})",
                                 file=where, key=f"streams.{spec.name}.topic",
                                 expected="one of " + ", ".join(topics))
            fields = list(dict.fromkeys(needed))
            if spec.time.column:
                fields = list(dict.fromkeys([spec.time.column, *fields]))
            rows, times = [], []
            for k, (conn, stamp, raw) in enumerate(reader.messages(connections=conns)):
                msg = reader.deserialize(raw, conn.msgtype)
                if k == 0:
                    _check_fields(msg, spec, fields, where, conn.msgtype)
                values = [field_value(msg, f) for f in fields]
                if spec.time.column:
                    times.append(values[0])
                elif spec.time.rate is not None:
                    times.append(np.longdouble(spec.time.start)
                                 + k / np.longdouble(spec.time.rate))
                elif spec.time.source == "bag":
                    times.append(np.longdouble(stamp) / 10 ** 9)
                else:
                    times.append(stamp_seconds(msg.header.stamp))
                rows.append([float(v) for v in values])
            data = np.array(rows, dtype=float).reshape(len(rows), len(fields))
            t = np.asarray(times, dtype=np.longdouble) + np.longdouble(spec.time.offset)
            out[spec.name] = checked_table(spec, f"{where}:{spec.topic}", t,
                                           {f: data[:, j] for j, f in enumerate(fields)},
                                           time_key=spec.time.column or "header.stamp")
        return out
    finally:
        reader.close()


def _check_fields(msg, spec, fields, where, msgtype) -> None:
    for f in fields:
        try:
            field_value(msg, f)
        except (KeyError, IndexError, TypeError, ValueError):
            shown = _fields(msg)
            raise InputError(f"no numeric field {f!r} in {msgtype} (stream {spec.name!r})",
                             file=where, key=f, expected="one of " + ", ".join(shown[:16])
                             + (", ..." if len(shown) > 16 else "")) from None
    if spec.time.column is None and spec.time.rate is None and spec.time.source != "bag" \
            and not hasattr(getattr(msg, "header", None), "stamp"):
        raise InputError(f"{msgtype} has no header stamp (stream {spec.name!r})", file=where,
                         key=f"streams.{spec.name}.time",
                         expected="time: bag (the bag's receive times) for this topic")


__all__ = ["is_bag", "read_bag_streams", "Table"]
