"""Tabulated curves as data with their source (src/stripcoef/data/*.csv).

Interpolation is linear (in log10 of the abscissa where the file says so).
Outside a table's range the value is clamped to the end point and an
:class:`~stripcoef.errors.ExtrapolationWarning` names the table, the value and the range:
never silent extrapolation.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

import numpy as np

from stripcoef.errors import ExtrapolationWarning


@dataclass(frozen=True)
class Table:
    name: str
    columns: tuple[str, ...]
    data: np.ndarray
    source: str

    def column(self, name: str) -> np.ndarray:
        return self.data[:, self.columns.index(name)]

    def interp(self, x, column: str, *, log_x: bool = False, what: str = ""):
        """Interpolate ``column`` at ``x``; clamp and warn outside the table."""
        xs = self.data[:, 0]
        ys = self.column(column)
        x = np.asarray(x, dtype=float)
        lo, hi = xs[0], xs[-1]
        eps = 1e-9 * max(abs(lo), abs(hi), 1e-300)      # round-off at the ends is not outside
        out = (x < lo - eps) | (x > hi + eps)
        if np.any(out):
            bad = x[out]
            warnings.warn(
                f"{self.name}: {what or self.columns[0]} = {bad.min():.3g}..{bad.max():.3g} is "
                f"outside the table range {lo:.3g}..{hi:.3g} ({np.count_nonzero(out)} value(s) "
                f"clamped to the end points)", ExtrapolationWarning, stacklevel=3)
        xc = np.clip(x, lo, hi)
        if log_x:
            y = np.interp(np.log10(xc), np.log10(xs), ys)
        else:
            y = np.interp(xc, xs, ys)
        return float(y) if y.ndim == 0 else y


@lru_cache(maxsize=None)
def load_table(name: str) -> Table:
    """Load ``data/<name>.csv``: '#' comment lines (the source), a header, numeric rows."""
    text = resources.files("stripcoef.data").joinpath(f"{name}.csv").read_text()
    comments, rows, header = [], [], None
    for line in text.splitlines():
        if line.startswith("#"):
            comments.append(line[1:].strip())
        elif line.strip():
            if header is None:
                header = tuple(h.strip() for h in line.split(","))
            else:
                rows.append([float(v) for v in line.split(",")])
    return Table(name=name, columns=header, data=np.asarray(rows), source=" ".join(comments))
