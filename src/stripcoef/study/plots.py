"""Figures of studies: u_max(R) bands, a swept output over one or two keys.

matplotlib ``Figure`` objects from :mod:`stripcoef.figures` (no pyplot, no backend switching);
written to a file only when a path is given (atomically).
"""

from __future__ import annotations

import numpy as np

from stripcoef.errors import InputError
from stripcoef.figures import new_figure, save_figure
from stripcoef.study.evaluate import NOTE
from stripcoef.views import coefficient_unit, key_unit, with_unit


def band_figure(result, *, path=None, key: str = "path"):
    """u_max(R) [m/s] vs R [m]: median, 50 % and 95 % bands, and the nominal model."""
    cols = [(float(n.split("=", 1)[1]), n) for n in result.names if n.startswith("u_max@R=")]
    if not cols:
        raise InputError("no turning radii in the study", key="limits",
                         expected="an uncertainty study with limits")
    cols.sort()
    radii = np.array([r for r, _ in cols])
    data = np.column_stack([result.column(n) for _, n in cols])
    fig = new_figure(figsize=(7.0, 4.2), key=key)
    ax = fig.add_subplot()
    with np.errstate(all="ignore"):
        p = np.nanpercentile(data, [2.5, 25, 50, 75, 97.5], axis=0)
    ax.fill_between(radii, p[0], p[4], alpha=0.25, label="95 % band (P2.5-P97.5)")
    ax.fill_between(radii, p[1], p[3], alpha=0.45, label="50 % band (P25-P75)")
    ax.plot(radii, p[2], "-", label="median")
    ax.plot(radii, [result.nominal.get(n, np.nan) for _, n in cols], "k--", label="nominal model")
    ax.set_xlabel("turning radius R [m]")
    ax.set_ylabel("largest surge speed on the circle u_max [m/s]")
    ax.set_title(f"{result.vehicle}: u_max(R), {result.samples.shape[0]} samples")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small")
    if path is not None:
        save_figure(fig, path, key=key, dpi=150)
    return fig


def sweep_figure(frame, keys, output: str, *, path=None, key: str = "path"):
    """One output over one swept key (a line) or two (filled contours), with units in labels."""
    if output not in frame.columns or output == NOTE:
        raise InputError("unknown output", key="output", value=output,
                         expected="one of " + ", ".join(c for c in frame.columns
                                                       if c not in keys and c != NOTE))
    fig = new_figure(figsize=(6.5, 4.2), key=key)
    ax = fig.add_subplot()
    if len(keys) == 1:
        ax.plot(frame[keys[0]], frame[output], "o-")
        ax.set_xlabel(with_unit(keys[0], key_unit(keys[0])))
        ax.set_ylabel(with_unit(output, coefficient_unit(output)))
    else:
        x, y = np.unique(frame[keys[0]]), np.unique(frame[keys[1]])
        z = frame.pivot_table(index=keys[1], columns=keys[0], values=output).to_numpy()
        if len(x) < 2 or len(y) < 2:
            raise InputError("a contour needs two values of each key", key="vary",
                             expected="N >= 2 for both keys")
        cs = ax.contourf(x, y, z, levels=12)
        fig.colorbar(cs, ax=ax, label=with_unit(output, coefficient_unit(output)))
        ax.set_xlabel(with_unit(keys[0], key_unit(keys[0])))
        ax.set_ylabel(with_unit(keys[1], key_unit(keys[1])))
    ax.set_title(f"{output} over {', '.join(keys)}")
    ax.grid(True, alpha=0.3)
    if path is not None:
        save_figure(fig, path, key=key, dpi=150)
    return fig
