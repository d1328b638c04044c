"""Design sweeps: the model and the limits over a grid of vehicle-file values.

``--vary KEY=LO:HI:N`` sets the number at key path KEY (``hull.profile[1].radius``,
``thrusters[0].max_forward``, ``mass.mass``; :mod:`stripcoef.geometry.keypaths`) to N values
evenly spaced from LO to HI; several keys make the full grid (the product), evaluated by the
same pipeline and runner as the uncertainty study, so a sweep runs locally or on a Dask
cluster alike. The result is a table: one row per grid point, one column per varied key and
per output.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from stripcoef.errors import InputError
from stripcoef.files import atomic_path, write_text
from stripcoef.study.evaluate import NOTE

#: Grid points per batch of parallel work.
BATCH = 4
#: Largest grid a sweep evaluates (each point is a full estimate, and limits if asked).
MAX_POINTS = 100_000


@dataclass(frozen=True)
class Vary:
    """One swept key: N values from LO to HI."""

    key: str
    lo: float
    hi: float
    n: int

    @property
    def values(self) -> np.ndarray:
        return np.linspace(self.lo, self.hi, self.n)


def parse_vary(text: str) -> Vary:
    """``"KEY=LO:HI:N"`` -> :class:`Vary` (an error names the part that is wrong)."""
    key, sep, rng = str(text).partition("=")
    if not sep or not key.strip():
        raise InputError("not a sweep", key="vary", value=text, expected="KEY=LO:HI:N")
    parts = rng.split(":")
    try:
        if len(parts) != 3:
            raise ValueError
        lo, hi, n = float(parts[0]), float(parts[1]), int(parts[2])
    except ValueError:
        raise InputError("cannot read the range", key=key.strip(), value=rng,
                         expected="LO:HI:N, e.g. 0.1:0.3:5") from None
    if not (math.isfinite(lo) and math.isfinite(hi)) or n < 1 or (n > 1 and hi == lo):
        raise InputError("bad range", key=key.strip(), value=rng,
                         expected="finite LO != HI and N >= 1")
    return Vary(key.strip(), lo, hi, n)


def sweep(vehicle, vary, *, limits: bool = True, radii=(0.5, 1.0, 2.0, 5.0, 10.0, 20.0),
          strips: int | None = None, workers: int | None = None, scheduler=None,
          progress: bool | None = None):
    """The grid of ``vary`` (Vary objects or "KEY=LO:HI:N" strings) as a pandas DataFrame.

    Every key is checked against the vehicle file before any work: it must exist and hold a
    number. Returns a DataFrame (pandas is needed: ``pip install 'stripcoef[study]'``) with one
    column per key and per output (:mod:`stripcoef.study.evaluate`).
    """
    try:
        import pandas as pd
    except ImportError:
        raise InputError("sweeps need pandas", key="vary",
                         expected="pip install 'stripcoef[study]'") from None
    from stripcoef.geometry.keypaths import nominal, set_value
    from stripcoef.geometry.vehicle import parse_vehicle, read_vehicle_data
    from stripcoef.study.evaluate import Job, evaluate_batch, notes, table
    from stripcoef.study.runner import run_batches

    file = str(vehicle)
    axes = [v if isinstance(v, Vary) else parse_vary(v) for v in vary]
    if not axes:
        raise InputError("nothing to sweep", key="vary", expected="at least one KEY=LO:HI:N")
    keys = [a.key for a in axes]
    if len(set(keys)) != len(keys):
        raise InputError("a key is swept twice", key="vary", value=keys,
                         expected="each key once")
    data = nominal(read_vehicle_data(vehicle), file=file)
    for a in axes:
        set_value(data, a.key, a.lo, file=file)  # the key exists and holds a number
    parse_vehicle(data, file=file)               # the nominal file is valid before any work
    points = list(itertools.product(*[a.values for a in axes]))
    if len(points) > MAX_POINTS:
        raise InputError("grid too large", key="vary", value=len(points),
                         expected=f"at most {MAX_POINTS} points")
    job = Job(data=data, file=file, paths=tuple(keys), limits=limits,
              radii=tuple(float(r) for r in radii), strips=strips)
    rows = [list(p) for p in points]
    batches = [(job, rows[i:i + BATCH]) for i in range(0, len(rows), BATCH)]
    results = [r for b in run_batches(evaluate_batch, batches, workers=workers,
                                      scheduler=scheduler, progress=progress, label="points")
               for r in b]
    names, arr = table(results)
    frame = pd.DataFrame(arr, columns=names)
    for k, key in enumerate(keys):
        frame.insert(k, key, [p[k] for p in points])
    why = notes(results)
    if why is not None:
        frame[NOTE] = why
    return frame


def blank_points(frame) -> dict[str, int]:
    """Why limits are blank in a sweep table: reason -> number of grid points (empty: none)."""
    if NOTE not in frame.columns:
        return {}
    counts: dict[str, int] = {}
    for note in frame[NOTE]:
        if note:
            counts[note] = counts.get(note, 0) + 1
    return counts


def write_table(frame, path, *, key: str = "path") -> None:
    """Write a sweep table atomically: ``.csv``, or ``.parquet`` (needs pyarrow)."""
    suffix = Path(path).suffix.lower()
    if suffix == ".csv":
        write_text(path, frame.to_csv(index=False), key=key)
    elif suffix == ".parquet":
        try:
            import pyarrow  # noqa: F401
        except ImportError:
            raise InputError("Parquet needs pyarrow", key=key, value=str(path),
                             expected="pip install pyarrow, or a .csv file") from None
        with atomic_path(path, key=key) as tmp:
            frame.to_parquet(tmp, index=False)
    else:
        raise InputError("unknown table format", key=key, value=str(path),
                         expected="a .csv or .parquet file")
