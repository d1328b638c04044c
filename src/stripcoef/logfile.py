"""The log format: one CSV contract shared by simulate, identify and diagnose.

A CSV file with one header row, SI units, radians:

- ``t`` [s] for time series (absent for a table of steady-state points);
- velocities ``u v w p q r`` [m/s, rad/s], pose ``x y z phi theta psi`` [m, rad],
  and for a pendulum ``theta_pendulum`` [rad];
- applied generalized forces ``X Y Z K M N`` [N, N m] and/or thruster commands
  ``n_<thruster name>``, and control-surface deflections ``delta_<surface name>`` [rad];
- any other column (``tether_length``, ``depth``...) is kept.

Reading validates: numeric cells, no NaN, strictly increasing time (no
duplicates); errors name the file, the column and the (1-based, header = row 1)
row.
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from stripcoef.conventions import FORCES, POSE, VELOCITIES
from stripcoef.errors import InputError
from stripcoef.files import check_size, read_text, write_text
from stripcoef.fluid import MAX_VEHICLE_SPEED

KNOWN_COLUMNS = ("t",) + VELOCITIES + POSE + FORCES + ("theta_pendulum",)
COMMAND_PREFIX = "n_"
DEFLECTION_PREFIX = "delta_"


@dataclass
class Log:
    """Columns of a log, each a float array of the same length, in file order.

    Attributes
    ----------
    columns : dict[str, ndarray]
    source : str
        File name (for error messages) or a description.
    meta : dict
        Free-form metadata (not written to CSV).
    """

    columns: dict[str, np.ndarray]
    source: str = "<memory>"
    meta: dict = field(default_factory=dict)

    def __post_init__(self):
        n = None
        cols = {}
        for name, values in self.columns.items():
            arr = np.asarray(values, dtype=float).reshape(-1)
            if n is None:
                n = arr.size
            elif arr.size != n:
                raise InputError("column length differs from the others", file=self.source,
                                 key=name, value=arr.size, expected=f"{n} rows")
            cols[str(name)] = arr
        self.columns = cols

    # -- access -------------------------------------------------------------
    def __contains__(self, name: str) -> bool:
        return name in self.columns

    def __getitem__(self, name: str) -> np.ndarray:
        return self.require(name)

    def __len__(self) -> int:
        return 0 if not self.columns else next(iter(self.columns.values())).size

    @property
    def names(self) -> list[str]:
        return list(self.columns)

    @property
    def is_time_series(self) -> bool:
        return "t" in self.columns

    def require(self, *names: str) -> np.ndarray:
        """Column(s) by name; a missing one is an InputError naming it and listing what exists."""
        for name in names:
            if name not in self.columns:
                raise InputError("missing required column", file=self.source, key=name,
                                 expected="a column named " + repr(name) + " (present: "
                                 + ", ".join(self.columns) + ")")
        if len(names) == 1:
            return self.columns[names[0]]
        return np.column_stack([self.columns[n] for n in names])

    def get(self, name: str, default=None):
        return self.columns.get(name, default)

    def deflections(self) -> dict:
        """Control-surface deflections by surface name (columns ``delta_<name>``) [rad]."""
        return {k[len(DEFLECTION_PREFIX):]: v for k, v in self.columns.items()
                if k.startswith(DEFLECTION_PREFIX)}

    def commands(self) -> dict[str, np.ndarray]:
        """Thruster commands by thruster name (columns ``n_<name>``)."""
        return {k[len(COMMAND_PREFIX):]: v for k, v in self.columns.items()
                if k.startswith(COMMAND_PREFIX)}

    def forces(self) -> np.ndarray | None:
        """(n, 6) generalized forces if all of X..N are present (missing ones as 0 if any)."""
        present = [f for f in FORCES if f in self.columns]
        if not present:
            return None
        return np.column_stack([self.columns.get(f, np.zeros(len(self))) for f in FORCES])

    def velocities(self) -> np.ndarray:
        """(n, 6) body velocities, missing components as 0."""
        return np.column_stack([self.columns.get(v, np.zeros(len(self))) for v in VELOCITIES])

    def slice(self, start: int, stop: int) -> "Log":
        return Log({k: v[start:stop] for k, v in self.columns.items()}, source=self.source,
                   meta=dict(self.meta))

    # -- files --------------------------------------------------------------
    def to_csv_text(self) -> str:
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(self.names)
        cols = [self.columns[n] for n in self.names]
        for i in range(len(self)):
            w.writerow([repr(float(c[i])) for c in cols])
        return buf.getvalue()

    def write_csv(self, path) -> None:
        """Write atomically (a failed write leaves any earlier file untouched)."""
        write_text(path, self.to_csv_text(), key="log")


def _fast_table(rows, width):
    """All cells as floats in one numpy conversion, or None when some row or cell is wrong
    (then the cell-by-cell loop of :func:`read_log` finds and names it). A 200,000-row,
    18-column log read in 7.7 s instead of 10.6 s on the loaded project machine."""
    if any(len(r) != width for r in rows):
        return None
    try:
        data = np.array(rows, dtype=float)
    except ValueError:
        return None
    return data if np.all(np.isfinite(data)) else None


def _parsed_table(path: Path, name: str):
    """Header and data of a log CSV cell by cell, each bad cell named (the text in memory at
    about ten times its size: used for files up to :data:`PARSED_BYTES`, and to name the
    first bad cell of a file :func:`_numeric_table` could not read)."""
    text = read_text(path, kind="CSV log")
    reader = csv.reader(io.StringIO(text))
    try:
        rows = list(reader)
    except csv.Error as exc:  # e.g. a cell over the csv module's field limit (128 kB)
        raise InputError(f"unreadable CSV ({exc})", file=name, key=f"row {reader.line_num}",
                         expected="comma-separated numbers, one row per line") from None
    rows = [r for r in rows if any(c.strip() for c in r)]
    if not rows:
        raise InputError("empty file", file=name, expected="a header row and data rows")
    header = [h.strip() for h in rows[0]]
    _check_header(header, name)
    if len(rows) < 2:
        raise InputError("no data rows", file=name, expected="at least one row after the header")
    data = _fast_table(rows[1:], len(header))
    for i, row in enumerate(rows[1:] if data is None else ()):
        if i == 0:
            data = np.empty((len(rows) - 1, len(header)))
        if len(row) != len(header):
            raise InputError(f"row {i + 2} has {len(row)} cells", file=name,
                             key=f"row {i + 2}", expected=f"{len(header)} cells like the header")
        for j, cell in enumerate(row):
            try:
                v = float(cell)
            except ValueError:
                raise InputError(f"non-numeric cell in row {i + 2}", file=name, key=header[j],
                                 value=cell, expected="a number (SI units, radians)") from None
            if math.isnan(v) or math.isinf(v):
                raise InputError(f"missing or non-finite value in row {i + 2}", file=name,
                                 key=header[j], value=cell, expected="a finite number (no gaps)")
            data[i, j] = v
    return header, data


def _check_header(header, name: str) -> None:
    for h in header:
        if not h:
            raise InputError("empty column name in the header", file=name, key="row 1",
                             expected="a name for every column")
    if len(set(header)) != len(header):
        dup = sorted({h for h in header if header.count(h) > 1})
        raise InputError("duplicated column name", file=name, key=dup[0],
                         expected="each column once")


#: Largest log read cell by cell in memory [bytes] (about ten times its size in memory);
#: a larger log is read by :func:`_numeric_table` at about its numbers' size (8 bytes a cell).
PARSED_BYTES = 32 * 2**20


def _numeric_table(path: Path):
    """``(header, data)`` of a log CSV over :data:`PARSED_BYTES`, read by numpy's C parser
    (``numpy.loadtxt``, in blocks) at about 8 bytes a cell: a 256 MiB log in well under 2 GB
    (docs/reliability.md). None for a smaller file (:func:`_parsed_table` reads it and names
    any bad cell). A bad row or cell of a large file is one error with numpy's row (counted
    from 0 after the header) and column."""
    check_size(path, kind="CSV log")
    try:
        if path.stat().st_size <= PARSED_BYTES:
            return None
        f = open(path, encoding="utf-8", newline="")
    except OSError:
        return None                              # read_text names the failure
    name = str(path)
    with f:
        try:
            first = f.readline()
            while first and not first.strip():
                first = f.readline()
            header = [h.strip() for h in next(csv.reader([first]))] if first else []
            _check_header(header, name)
            data = np.loadtxt(f, delimiter=",", dtype=float, ndmin=2, quotechar='"')
        except (ValueError, UnicodeDecodeError, csv.Error) as exc:
            if isinstance(exc, InputError):
                raise
            msg = str(exc).splitlines()[0] if str(exc) else exc.__class__.__name__
            raise InputError(f"unreadable CSV ({msg})", file=name,
                             expected="a header row, then comma-separated finite numbers in "
                             "every row (SI units, radians)") from None
    if not header or data.size == 0:
        return None                              # _parsed_table names what is missing
    if data.shape[1] != len(header):
        raise InputError(f"rows have {data.shape[1]} cells", file=name, key="row 2",
                         expected=f"{len(header)} cells like the header")
    bad = np.argwhere(~np.isfinite(data))
    if bad.size:
        i, j = (int(x) for x in bad[0])
        raise InputError(f"missing or non-finite value in row {i + 2}", file=name,
                         key=header[j], value=float(data[i, j]),
                         expected="a finite number (no gaps)")
    return header, data


def read_log(path, *, required=()) -> Log:
    """Read and validate a log CSV.

    Parameters
    ----------
    path : str or Path
    required : iterable of str
        Columns that must be present.

    Raises
    ------
    InputError
        Unreadable file, empty file, duplicated or empty header names, a non-numeric or
        NaN cell (names column and row), non-monotonic or duplicated time, missing columns.
    """
    path = Path(path)
    name = str(path)
    fast = _numeric_table(path)
    if fast is not None:
        header, data = fast
        _check_header(header, name)
    else:
        header, data = _parsed_table(path, name)
    log = Log({h: data[:, j] for j, h in enumerate(header)}, source=name)
    if "t" in log.columns:
        t = log.columns["t"]
        if t.size < 2:
            raise InputError("a time series of one row", file=name, key="t", value=t.size,
                             expected="at least 2 rows (a time series has a time step)")
        d = np.diff(t)
        bad = np.nonzero(d <= 0)[0]
        if bad.size:
            k = int(bad[0])
            what = "duplicated timestamp" if d[k] == 0 else "time goes backwards"
            raise InputError(f"{what} at row {k + 3}", file=name, key="t", value=float(t[k + 1]),
                             expected=f"strictly increasing time (previous {float(t[k]):g})")
    check_magnitudes(log)
    log.require(*required) if required else None
    return log


#: Largest magnitude of each kind of log column (SI units), with the reason: beyond it the
#: value is in other units or corrupt, and a command would grind or answer nonsense.
MAGNITUDE_BOUNDS = {
    "velocity": (MAX_VEHICLE_SPEED, "m/s", "faster than any underwater vehicle"),
    "rate": (100.0, "rad/s", "about 16 turns a second"),
    "angle": (1.0e4, "rad", "over 1500 turns"),
    "position": (1.0e8, "m", "over twice the Earth's circumference"),
    "force": (1.0e9, "N or N m", "a thousand times a submarine's thrust"),
    "other": (1.0e12, "", "no physical quantity of a vehicle log"),
}
#: Shortest median time step of a time series [s] (100 kHz; nanosecond stamps read as
#: seconds give 1e-10 s).
MIN_TIME_STEP = 1e-5
#: Integer time stamps with a median step of at least this many "seconds" over at least
#: :data:`MS_ROWS` rows are taken for milliseconds (a 10 Hz log in ms has steps of 100).
MS_STEP = 10.0
MS_ROWS = 100


def _column_kind(name: str) -> str:
    if name in VELOCITIES[:3]:
        return "velocity"
    if name in VELOCITIES[3:]:
        return "rate"
    if name in POSE[3:] or name == "theta_pendulum":
        return "angle"
    if name in POSE[:3]:
        return "position"
    if name in FORCES:
        return "force"
    return "other"


def check_magnitudes(log: Log) -> None:
    """Refuse a log whose values are in other units or corrupt (issue 36).

    Each column's largest magnitude within :data:`MAGNITUDE_BOUNDS` (velocities 100 m/s,
    rates 100 rad/s, angles 1e4 rad, positions 1e8 m, forces 1e9 N, anything else 1e12),
    and for a time series a median step of at least :data:`MIN_TIME_STEP` (100 kHz) and no
    integer stamps that look like milliseconds (steps of :data:`MS_STEP` or more over
    :data:`MS_ROWS` rows or more). The error names the file, the column, the row and the
    value.
    """
    for name, values in log.columns.items():
        if name == "t" or not values.size:
            continue
        kind = _column_kind(name)
        bound, unit, why = MAGNITUDE_BOUNDS[kind]
        k = int(np.argmax(np.abs(values)))
        if abs(values[k]) > bound:
            raise InputError(f"absurd magnitude in row {k + 2} ({why})", file=log.source,
                             key=name, value=float(values[k]),
                             expected=f"|{name}| <= {bound:g}{' ' + unit if unit else ''} "
                                      "(SI units, radians)")
    t = log.columns.get("t")
    if t is None or t.size < 2:
        return
    step = float(np.median(np.diff(t)))
    if step < MIN_TIME_STEP:
        raise InputError("time step too short: the time is not in seconds", file=log.source,
                         key="t", value=f"median step {step:.3g} s over {t.size} rows",
                         expected=f"time in seconds (a step >= {MIN_TIME_STEP:g} s, i.e. "
                                  "sampled at 100 kHz or slower)")
    if step >= MS_STEP and t.size >= MS_ROWS and np.allclose(t, np.round(t), rtol=1e-12, atol=1e-9):
        raise InputError("time looks like milliseconds", file=log.source, key="t",
                         value=f"integer stamps {t[0]:g}..{t[-1]:g}, median step {step:g}",
                         expected="time in seconds (divide by 1000)")


# --- the inputs of a log: the one replay rule ---------------------------------------------------

@dataclass(frozen=True)
class LogInputs:
    r"""The inputs of a log as a simulation replays them (:func:`log_inputs`, the one replay
    rule shared by ``simulate --from-log``, held-out validation and diagnose's window residual).

    Attributes
    ----------
    t : (n,) array
        Times [s].
    forces : (n, 6) array or None
        Applied generalized forces ``X..N`` replayed as such [N, N m]: only in a log without
        thruster commands (see :func:`log_inputs`).
    commands : dict
        Thruster name -> commands (n,) [command units], through the model's thruster map.
    deflections : dict
        Control surface name -> deflections (n,) [rad].
    channels : dict
        Other columns (``tether_length``...) that effects read [their units].
    recorded_forces : (n, 6) array or None
        The log's ``X..N`` when it also has thruster commands: the record of the applied force
        (thrust included), not replayed [N, N m].
    thrust_mismatch : float
        Largest ``|X..N - B T(n)|`` of ``recorded_forces`` against the model's thrust of the
        commands [N or N m] (0 without them): above round-off, the log's forces hold something
        the commands do not (forces beyond the thrust, or another thruster map), which the
        replay does not apply.
    ignored : tuple of str
        Columns not replayed (``delta_<surface>`` of a model without control surfaces).
    """

    t: np.ndarray
    forces: np.ndarray | None
    commands: dict
    deflections: dict
    channels: dict
    recorded_forces: np.ndarray | None = None
    thrust_mismatch: float = 0.0
    ignored: tuple = ()

    def window(self, a: int, b: int) -> "LogInputs":
        """The inputs of rows a..b-1."""
        cut = {k: v[a:b] for k, v in self.commands.items()}
        return LogInputs(self.t[a:b], None if self.forces is None else self.forces[a:b], cut,
                         {k: v[a:b] for k, v in self.deflections.items()},
                         {k: v[a:b] for k, v in self.channels.items()},
                         None if self.recorded_forces is None else self.recorded_forces[a:b],
                         self.thrust_mismatch, self.ignored)

    def at(self, times, interpolation: str = "previous") -> "LogInputs":
        """The inputs at other ``times`` [s], held (``previous``: the value of the last sample
        at or before each time) or interpolated (``linear``) as a simulation holds them."""
        times = np.asarray(times, dtype=float)
        t = self.t

        def resample(values):
            values = np.asarray(values)
            if interpolation == "linear":
                if values.ndim == 2:
                    return np.column_stack([np.interp(times, t, c) for c in values.T])
                return np.interp(times, t, values)
            k = np.clip(np.searchsorted(t, times, side="right") - 1, 0, len(t) - 1)
            return values[k]

        return LogInputs(times, None if self.forces is None else resample(self.forces),
                         {k: resample(v) for k, v in self.commands.items()},
                         {k: resample(v) for k, v in self.deflections.items()},
                         {k: resample(v) for k, v in self.channels.items()},
                         None if self.recorded_forces is None else resample(self.recorded_forces),
                         self.thrust_mismatch, self.ignored)

    def simulate_inputs(self) -> dict:
        """Keyword arguments of :func:`stripcoef.simulate.simulate` (``forces``, ``commands``, ``deflections``,
        ``channels``)."""
        return {"forces": self.forces, "commands": self.commands or None,
                "deflections": self.deflections or None, "channels": self.channels or None}


def log_inputs(log, model) -> LogInputs:
    r"""The inputs of ``log`` for a simulation of ``model``: the one log-replay rule.

    - thruster commands ``n_<thruster>`` act through the model's thruster map,
      :math:`\tau = B\,T(n)` (:meth:`Thruster.thrust`);
    - ``X Y Z K M N`` are the log's applied generalized force, the thrust of its commanded
      thrusters included (as :func:`stripcoef.simulate.simulate` writes them and :mod:`stripcoef.identify` reads
      them). In a log without commands they are replayed as the applied force; in a log with
      commands they are its record and are *not* replayed (the thrust would count twice:
      issue 31, a REMUS log turned -297 deg instead of -0.7 deg). Diagnose's window residual
      (:func:`stripcoef.effects.windows.window_data`) reads a log the same way.
      :attr:`LogInputs.thrust_mismatch` says how far the record is from the model's thrust;
    - deflections ``delta_<surface>`` [rad] act through the model's control matrix
      (:meth:`HydroModel.control_force`); a model without control surfaces ignores them
      (listed in :attr:`LogInputs.ignored`), a surface the model lacks is an error;
    - every other column (``tether_length``...) is a channel that effects read.

    Raises
    ------
    InputError
        Fewer than two rows, no input at all, a thruster or control surface the model lacks.

    References
    ----------
    Fossen (2011), eq. 11.3 (tau = B T(n)); Prestero (2001), sec. 3.7 (control forces).
    """
    t_in = log.require("t")
    if len(t_in) < 2:
        raise InputError("too few rows", file=log.source, key="t", value=len(t_in),
                         expected="at least 2 time samples")
    cmds = log.commands()
    defl = log.deflections()
    forces = log.forces()
    names = [th.name for th in model.thrusters]
    for name in cmds:
        if name not in names:
            raise InputError("unknown thruster", file=log.source, key=COMMAND_PREFIX + name,
                             expected="one of " + ", ".join(COMMAND_PREFIX + n for n in names))
    snames = [sf.name for sf in getattr(model, "control_surfaces", ())]
    ignored = ()
    if defl and not snames:
        ignored = tuple(DEFLECTION_PREFIX + k for k in defl)
        defl = {}
    if not cmds and forces is None and not defl:
        raise InputError("no inputs", file=log.source,
                         expected="thruster commands n_<name> (thrusters: "
                         + ", ".join(th.name for th in model.thrusters)
                         + "), deflections delta_<surface> and/or forces X Y Z K M N")
    for name in defl:
        if name not in snames:
            raise InputError("unknown control surface", file=log.source,
                             key=DEFLECTION_PREFIX + name,
                             expected="one of " + ", ".join(DEFLECTION_PREFIX + n
                                                            for n in snames))
    recorded, mismatch = None, 0.0
    if cmds and forces is not None:
        recorded, forces = forces, None
        n = np.column_stack([cmds.get(k, np.zeros(len(t_in))) for k in names])
        thrust = np.column_stack([np.asarray(th.thrust(n[:, k]), float).reshape(-1)
                                  for k, th in enumerate(model.thrusters)])
        mismatch = float(np.max(np.abs(recorded - thrust @ model.allocation().T)))
    skip = set(KNOWN_COLUMNS)
    channels = {k: v for k, v in log.columns.items()
                if k not in skip and not k.startswith((COMMAND_PREFIX, DEFLECTION_PREFIX))}
    return LogInputs(np.asarray(t_in, dtype=float), forces, dict(cmds), dict(defl), channels,
                     recorded, mismatch, ignored)
