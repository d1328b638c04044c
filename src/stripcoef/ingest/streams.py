"""Streams of a log: the columns a map asks for, with their sample times in seconds.

A stream is a CSV file (with a header, or header-less with its column names in the map), the
chunk files of a folder or a glob pattern (joined by time: :func:`join_chunks`), or a topic of
a ROS bag (:mod:`stripcoef.ingest.bags`); either becomes a :class:`Table`.
Sample times are checked: time going backwards is an error naming the row; repeated
timestamps keep the first sample; irregular sampling, gaps, bursts and a rate off the stated
one are each a :class:`~stripcoef.errors.SamplingWarning` (thresholds below, docs/logs.md).
"""

from __future__ import annotations

import calendar
import csv
import dataclasses
import glob
import io
import math
import re
import warnings
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from stripcoef.errors import InputError, SamplingWarning
from stripcoef.files import check_size, read_text
from stripcoef.ingest.clock import retime
from stripcoef.ingest.mapfile import TIME_UNITS, StreamSpec
from stripcoef.logfile import PARSED_BYTES
from stripcoef.progress import track

#: A step longer than GAP_FACTOR nominal periods is a gap [-].
GAP_FACTOR = 2.5
#: A step shorter than BURST_FACTOR nominal periods is part of a burst [-].
BURST_FACTOR = 0.25
#: Irregular: standard deviation of the steps (gaps and bursts left out) over their median [-].
IRREGULAR_CV = 0.2
#: A median rate off the stated rate by more than this fraction warns [-].
RATE_TOLERANCE = 0.1
#: A re-timed sample received more than this many periods after its stamp warns [-].
MAX_LATENCY_PERIODS = 10.0


@dataclass(frozen=True)
class Table:
    """Samples of one stream: ``t`` [s] strictly increasing and each used column (raw units).

    ``t`` is in extended precision (``numpy.longdouble``) as read: epoch stamps in
    nanoseconds (1.7e18) keep their nanoseconds, which float64 rounds to 256 ns (and to
    0.24 us once in seconds); :mod:`.merge` subtracts a whole-second time base before it
    works in float64."""
    name: str
    where: str
    t: np.ndarray
    columns: dict
    info: dict = dataclasses.field(default_factory=dict)

    def column(self, name: str) -> np.ndarray:
        return self.columns[name]

    @property
    def median_rate(self) -> float:
        """1 / median sample step [Hz] (inf for one sample)."""
        return 1.0 / float(np.median(np.diff(self.t).astype(float))) if self.t.size > 1 \
            else math.inf


def _split_lines(text: str, spec: StreamSpec):
    """(line number, cells) of the non-blank, non-comment lines."""
    lines = text.splitlines()
    if spec.delimiter == "whitespace":
        rows = ((i + 1, ln.split()) for i, ln in enumerate(lines))
    else:
        reader = csv.reader(io.StringIO(text), delimiter=spec.delimiter)
        rows = ((reader.line_num, [c.strip() for c in row]) for row in reader)
    for num, cells in rows:
        if not any(c.strip() for c in cells):
            continue
        if spec.comment and cells[0].lstrip().startswith(spec.comment):
            continue
        yield num, cells


def stream_files(path, spec: StreamSpec) -> list:
    """The files of a stream: ``path`` itself, the files a glob pattern in it matches
    (``nav_*.csv``), or the files of a folder (hidden ones left out), in name order."""
    text = str(path)
    p = Path(text)
    if p.is_dir():
        files = sorted(f for f in p.iterdir() if f.is_file() and not f.name.startswith("."))
        what = f"the folder {text}"
    elif glob.has_magic(text):
        files = sorted(Path(f) for f in glob.glob(text) if Path(f).is_file())
        what = f"the pattern {text}"
    else:
        return [p]
    if not files:
        raise InputError(f"no file of stream {spec.name!r} in {what}", file=text,
                         key=f"streams.{spec.name}.file",
                         expected="a CSV file, a folder of chunk files or a glob pattern "
                         "(nav_*.csv) that matches files")
    return files


def read_csv_stream(path, spec: StreamSpec, needed) -> Table:
    """The ``needed`` columns (and the time) of a CSV stream (module docstring): one file,
    or the chunk files of a glob pattern or a folder (:func:`stream_files`), joined by time
    (:func:`join_chunks`).

    Raises
    ------
    InputError
        Missing file or column, a row with a wrong number of cells, a non-numeric or empty
        cell (with ``missing: error``), time going backwards within a file; each names the
        file, the column and the line.
    """
    want = list(dict.fromkeys(([spec.time.column] if spec.time.column else []) + list(needed)))
    files = stream_files(path, spec)
    name = str(path)
    parts = [(str(f), *_read_csv_file(f, spec, want)) for f in
             (track(files, desc=f"stream {spec.name}", unit="file") if len(files) > 1
              else files)]
    info = {}
    if len(parts) > 1:
        if not spec.time.column:
            raise InputError(f"chunk files of stream {spec.name!r} without a time column",
                             file=name, key=f"streams.{spec.name}.time",
                             expected="a time column to order and join the chunks by")
        stamps, data, lines, info = join_chunks(spec, parts)
        where = name
    else:
        where, stamps, data, lines = parts[0]
    if spec.time.column:
        t = stamps * np.longdouble(TIME_UNITS[spec.time.unit]) + np.longdouble(spec.time.offset)
        # ("iso" stamps are read in ns: TIME_UNITS["iso"] = 1e-9)
    else:
        t = np.longdouble(spec.time.start) + np.arange(data.shape[0]) / np.longdouble(
            spec.time.rate)
    cols = {c: data[:, j] for j, c in enumerate(want)}
    if spec.time.retime:
        t, cols, lines, info["retimed"] = _retimed(spec, where, t, cols, lines)
    table = checked_table(spec, where, t, cols, lines=lines if len(parts) == 1 else None,
                          time_key=spec.time.column or "t")
    return dataclasses.replace(table, info=info) if info else table


def _retimed(spec, where, t, cols, lines):
    """Receive times re-timed on the source's period (:func:`.clock.retime`); repeated receive
    times are samples too (a burst), so nothing is dropped."""
    back = np.nonzero(np.diff(t) < 0)[0]
    if back.size:
        k = int(back[0])
        raise InputError(f"receive time goes backwards at line {int(lines[k + 1])}", file=where,
                         key=spec.time.column, value=float(t[k + 1]),
                         expected=f"non-decreasing receive times (previous {float(t[k]):.9g})")
    r = retime(t, where=where, key=f"streams.{spec.name}.time")
    if r.max_latency > MAX_LATENCY_PERIODS * r.period:
        warnings.warn(f"{where}: stream {spec.name!r}: re-timed at {1.0 / r.period:.6g} Hz, but "
                      f"a sample was received {r.max_latency:.4g} s after its re-timed stamp "
                      f"(over {MAX_LATENCY_PERIODS:g} periods): samples may have been lost, "
                      "which re-timing assumes they were not", SamplingWarning, stacklevel=4)
    return r.t, cols, lines, {"period_s": r.period, "max_latency_s": r.max_latency}


def join_chunks(spec: StreamSpec, parts):
    """One stream from its chunk files ``[(file, stamps, data, lines), ...]``: ordered by
    their first time (not their names); time must not go backwards within a file; where a
    chunk overlaps the chunks before it, its samples up to their last time are dropped (the
    earlier chunk is kept: duplicated rows of rotated logs and the overlap of restarted
    loggers); the gaps between chunks (over ``GAP_FACTOR`` median steps) are listed. Returns
    ``(stamps, data, lines, info)`` with ``info``: chunk count, samples dropped, gaps
    [stamp units] (and a :class:`SamplingWarning` says so)."""
    for file, stamps, _, lines in parts:
        if stamps.size == 0:
            continue
        back = np.nonzero(np.diff(stamps) < 0)[0]
        if back.size:
            k = int(back[0])
            raise InputError(f"time goes backwards at line {int(lines[k + 1])}", file=file,
                             key=spec.time.column, value=float(stamps[k + 1]),
                             expected=f"non-decreasing time within a chunk file (previous "
                             f"{float(stamps[k]):.9g})")
    parts = sorted((p for p in parts if p[1].size), key=lambda p: p[1][0])
    if not parts:
        raise InputError("no data rows", file=str(spec.file),
                         expected="at least two samples in the chunk files")
    kept, dropped, gaps, end = [], 0, [], None
    steps = np.concatenate([np.diff(p[1]).astype(float) for p in parts])
    step = float(np.median(steps[steps > 0])) if np.any(steps > 0) else 0.0
    for file, stamps, data, lines in parts:
        keep = np.ones(stamps.size, dtype=bool) if end is None else stamps > end
        dropped += int(stamps.size - keep.sum())
        if not keep.any():
            continue
        if end is not None and step > 0 and float(stamps[keep][0] - end) > GAP_FACTOR * step:
            gaps.append({"before": Path(file).name, "from": float(end),
                         "to": float(stamps[keep][0])})
        kept.append((stamps[keep], data[keep], lines[keep]))
        end = stamps[keep][-1]
    info = {"chunks": len(parts), "overlap_dropped": dropped, "gaps": gaps}
    msg = f"{len(parts)} chunk files joined by time"
    if dropped:
        msg += (f"; {dropped} sample(s) of chunks overlapping earlier ones dropped (the earlier "
                "chunk kept)")
    if gaps:
        g = max(gaps, key=lambda x: x["to"] - x["from"])
        msg += (f"; {len(gaps)} gap(s) between chunks, the longest "
                f"{(g['to'] - g['from']) * TIME_UNITS[spec.time.unit]:.4g} s before {g['before']}")
    if dropped or gaps:
        warnings.warn(f"{spec.file}: stream {spec.name!r}: {msg}", SamplingWarning, stacklevel=4)
    return (np.concatenate([k[0] for k in kept]), np.concatenate([k[1] for k in kept]),
            np.concatenate([k[2] for k in kept]), info)


def _column_index(header, want, spec, name) -> dict:
    idx = {}
    for col in want:
        if col not in header:
            shown = ", ".join(header[:12]) + (", ..." if len(header) > 12 else "")
            raise InputError(f"no column {col!r} in stream {spec.name!r}", file=name, key=col,
                             expected=f"one of the file's columns ({shown})")
        idx[col] = header.index(col)
    return idx


def _loadtxt_file(path: Path, spec: StreamSpec, want):
    """:func:`_read_csv_file` of a file over :data:`stripcoef.logfile.PARSED_BYTES` by numpy's
    C parser (``numpy.loadtxt``: only the mapped columns, in extended precision, 16 bytes a
    cell, each cell through a converter that strips blanks and reads an empty cell as
    missing). None for a smaller file or
    one it does not read (ISO 8601 stamps: read cell by cell). Line numbers count the data
    rows from the header (exact without comment or blank lines)."""
    name = str(path)
    check_size(path, kind=f"CSV file of stream {spec.name!r}")
    try:
        if spec.time.unit == "iso" or path.stat().st_size <= PARSED_BYTES:
            return None
        f = open(path, encoding="utf-8", newline="")
    except OSError:
        return None                              # read_text names the failure
    delimiter = None if spec.delimiter == "whitespace" else spec.delimiter
    with f:
        first, skipped = "", 0
        if spec.header:
            while not first.strip() or (spec.comment and first.lstrip().startswith(spec.comment)):
                first = f.readline()
                skipped += 1
                if not first:
                    raise InputError("empty file", file=name,
                                     expected="a header row and data rows")
            cells = first.split() if delimiter is None else next(csv.reader([first],
                                                                          delimiter=delimiter))
            header = [h.strip() for h in cells]
        else:
            header = list(spec.columns)
        idx = _column_index(header, want, spec, name)

        def cell(text):                         # blanks around a number; empty: missing
            text = text.strip()
            return np.longdouble(text) if text else np.longdouble("nan")

        try:
            data = np.loadtxt(f, delimiter=delimiter, comments=spec.comment or None,
                              usecols=[idx[c] for c in want], dtype=np.longdouble, ndmin=2,
                              quotechar='"', converters=cell)
        except (ValueError, UnicodeDecodeError) as exc:
            msg = str(exc).splitlines()[0] if str(exc) else exc.__class__.__name__
            m = re.search(r"could not convert string '(.*)' to \w+ at row (\d+), column (\d+)",
                          msg)
            if m and 1 <= int(m.group(3)) <= len(want):     # numpy: column of usecols, 1-based
                raise InputError(f"non-numeric cell in line {int(m.group(2)) + skipped + 1}",
                                 file=name, key=want[int(m.group(3)) - 1], value=m.group(1),
                                 expected="a number") from None
            raise InputError(f"unreadable CSV ({msg}; rows counted from 0 after the header)",
                             file=name, expected=f"{len(header)} cells of finite numbers in "
                             "every row") from None
    lines = np.arange(data.shape[0]) + skipped + 1
    finite = np.isfinite(data).all(axis=1)
    if not finite.all():
        if spec.missing != "drop":
            i = int(np.nonzero(~finite)[0][0])
            j = int(np.nonzero(~np.isfinite(data[i]))[0][0])
            raise InputError(f"missing or non-finite value in line {int(lines[i])}", file=name,
                             key=want[j], value=str(data[i, j]), expected="a finite number "
                             f"(or streams.{spec.name}.missing: drop to skip such rows)")
        data, lines = data[finite], lines[finite]
    if data.shape[0] == 0:
        raise InputError("no data rows", file=name, expected="at least two samples")
    stamps = data[:, 0].copy() if spec.time.column else None
    return stamps, np.asarray(data, dtype=float), lines


def _read_csv_file(path, spec: StreamSpec, want):
    """``(stamps, data, lines)`` of one CSV file of a stream: the raw time stamps (extended
    precision, in the time unit; None without a time column), the (n, len(want)) values and
    the line numbers of the rows (a file over 32 MiB: :func:`_loadtxt_file`)."""
    name = str(path)
    fast = _loadtxt_file(Path(path), spec, want)
    if fast is not None:
        return fast
    text = read_text(Path(path), kind=f"CSV file of stream {spec.name!r}")
    rows = list(_split_lines(text, spec))
    if spec.header:
        if not rows:
            raise InputError("empty file", file=name, expected="a header row and data rows")
        header = [h.strip() for h in rows[0][1]]
        rows = rows[1:]
    else:
        header = list(spec.columns)
    idx = _column_index(header, want, spec, name)
    if not rows:
        raise InputError("no data rows", file=name, expected="at least two samples")
    data = np.empty((len(rows), len(want)))
    stamps = np.empty(len(rows), dtype=np.longdouble)
    keep = np.ones(len(rows), dtype=bool)
    for i, (num, cells) in enumerate(rows):
        if len(cells) != len(header):
            raise InputError(f"line {num} has {len(cells)} cells", file=name, key=f"line {num}",
                             expected=f"{len(header)} cells like the "
                             + ("header" if spec.header else "map's columns list"))
        for j, col in enumerate(want):
            cell = cells[idx[col]]
            if j == 0 and spec.time.column:
                stamp = _stamp(cell, spec.time.unit)
                if stamp is None:
                    if spec.missing == "drop" and cell.strip().lower() in ("", "nan"):
                        keep[i] = False
                        break
                    raise InputError(f"bad time in line {num}", file=name, key=col, value=cell,
                                     expected="an ISO 8601 date-time (2024-05-02T10:15:30.25Z)"
                                     if spec.time.unit == "iso" else "a finite number")
                stamps[i] = stamp
                data[i, 0] = float(stamp)
                continue
            try:
                v = float(cell) if cell.strip() else math.nan
            except ValueError:
                raise InputError(f"non-numeric cell in line {num}", file=name, key=col,
                                 value=cell, expected="a number") from None
            if not math.isfinite(v):
                if spec.missing == "drop" and cell.strip().lower() in ("", "nan"):
                    keep[i] = False
                    break
                raise InputError(f"missing or non-finite value in line {num}", file=name,
                                 key=col, value=cell, expected="a finite number (or "
                                 f"streams.{spec.name}.missing: drop to skip such rows)")
            data[i, j] = v
    data, stamps = data[keep], stamps[keep]
    lines = np.array([num for (num, _), k in zip(rows, keep) if k])
    return (stamps if spec.time.column else None), data, lines


#: The fractional seconds of an ISO 8601 time of day (kept to the nanosecond, which
#: ``datetime`` would cut to the microsecond).
_FRACTION = re.compile(r"(?<=\d{2}:\d{2}:\d{2})[.,](\d+)")


def iso_ns(cell: str) -> int:
    """An ISO 8601 date-time as integer nanoseconds since 1970-01-01 UTC.

    ``datetime.fromisoformat`` reads the date, time and offset (``Z``, ``+02:00``; none
    means UTC); the fractional seconds are read from the text to the nanosecond. A text that
    is not an ISO date-time raises ``ValueError``.
    """
    m = _FRACTION.search(cell)
    digits = m.group(1) if m else ""
    stamp = datetime.fromisoformat(_FRACTION.sub("", cell, count=1) if m else cell)
    if stamp.tzinfo is None:
        stamp = stamp.replace(tzinfo=timezone.utc)
    seconds = calendar.timegm(stamp.utctimetuple())
    return seconds * 10**9 + int((digits + "0" * 9)[:9])


def _stamp(cell: str, unit: str):
    """A time cell as an extended-precision number in ``unit`` (ISO 8601 date-times in ns
    since 1970-01-01 UTC, an explicit offset such as +02:00 converted to UTC); None if it is
    empty or not a finite number / date-time."""
    cell = cell.strip()
    if not cell:
        return None
    try:
        if unit == "iso":
            return np.longdouble(iso_ns(cell))
        value = np.longdouble(cell)
    except (ValueError, TypeError, OverflowError):
        return None
    return value if np.isfinite(value) else None


def checked_table(spec: StreamSpec, where: str, t, columns, *, lines=None,
                  time_key: str = "t") -> Table:
    """A :class:`Table` after the time checks (module docstring): backwards time is an
    error, repeated times keep the first sample, sampling problems warn."""
    t = np.asarray(t, dtype=np.longdouble)
    if t.size < 2:
        raise InputError(f"stream {spec.name!r} has {t.size} sample(s)", file=where,
                         expected="at least two samples")
    d = np.diff(t).astype(float)
    back = np.nonzero(d < 0)[0]
    if back.size:
        k = int(back[0])
        row = f"line {int(lines[k + 1])}" if lines is not None else f"sample {k + 2}"
        raise InputError(f"time goes backwards at {row}", file=where, key=time_key,
                         value=float(t[k + 1]), expected=f"non-decreasing time (previous "
                         f"{float(t[k]):.9g})")
    dup = np.nonzero(d == 0)[0] + 1
    if dup.size:
        warnings.warn(f"{where}: stream {spec.name!r}: {dup.size} repeated timestamp(s) "
                      f"(the first at {float(t[dup[0]] - t[0]):.6g} s into the stream); kept "
                      "the first sample of each",
                      SamplingWarning, stacklevel=3)
        keep = np.ones(t.size, dtype=bool)
        keep[dup] = False
        t = t[keep]
        columns = {k: v[keep] for k, v in columns.items()}
        if t.size < 2:
            raise InputError(f"stream {spec.name!r} has one distinct time", file=where,
                             key=time_key, expected="at least two sample times")
    if spec.time.rate is None:
        sampling_warnings(t, spec.rate, f"{where}: stream {spec.name!r}")
    return Table(name=spec.name, where=where, t=t, columns=columns)


def sampling_warnings(t, stated_rate=None, where: str = "") -> list:
    """Warn (:class:`SamplingWarning`) on a stream's sampling; returns the messages.

    A median rate off the stated one by more than ``RATE_TOLERANCE``; with the nominal step
    h = 1/stated rate (the median step when there is no stated rate or it is off): steps longer than ``GAP_FACTOR`` h (gaps); steps
    shorter than ``BURST_FACTOR`` h (bursts); and, among the other steps, a standard
    deviation above ``IRREGULAR_CV`` of their median (irregular sampling).
    """
    t = np.asarray(t, dtype=np.longdouble)
    d = np.diff(t).astype(float)
    med = float(np.median(d))
    out = []
    h = med
    if stated_rate is not None:
        if abs(1.0 / med - stated_rate) > RATE_TOLERANCE * stated_rate:
            out.append(f"median rate {1.0 / med:.4g} Hz, not the stated {stated_rate:g} Hz "
                       "(gaps and bursts below are judged on the median step)")
        else:
            h = 1.0 / stated_rate
    gaps = np.nonzero(d > GAP_FACTOR * h)[0]
    if gaps.size:
        k = int(gaps[np.argmax(d[gaps])])
        out.append(f"{gaps.size} gap(s) longer than {GAP_FACTOR:g} sample periods, the "
                   f"longest {d[k]:.4g} s at {float(t[k] - t[0]):.6g} s into the stream")
    bursts = np.nonzero(d < BURST_FACTOR * h)[0]
    if bursts.size:
        out.append(f"{bursts.size} step(s) shorter than {BURST_FACTOR:g} sample periods "
                   f"(bursts), the first at {float(t[bursts[0]] - t[0]):.6g} s into the stream")
    normal = d[(d <= GAP_FACTOR * h) & (d >= BURST_FACTOR * h)]
    if normal.size > 2:
        cv = float(np.std(normal) / np.median(normal))
        if cv > IRREGULAR_CV:
            out.append(f"irregular sampling: step {np.median(normal):.4g} s +- "
                       f"{np.std(normal):.3g} s ({100 * cv:.0f} % > {100 * IRREGULAR_CV:g} %)")
    for msg in out:
        warnings.warn(f"{where}: {msg}" if where else msg, SamplingWarning, stacklevel=3)
    return out
