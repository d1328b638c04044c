"""Figures without pyplot: every plot function of stripcoef builds a
:class:`matplotlib.figure.Figure` directly, returns it, and writes a file only when asked.

No backend is selected or switched (a notebook keeps its own and shows a returned Figure
with IPython's display of matplotlib figures), and nothing is left in pyplot's registry of
open figures. matplotlib is optional (``pip install 'stripcoef[plot]'``): without it,
:func:`new_figure` is an :class:`~stripcoef.errors.InputError` naming the key.

Also here, for any log with the log format's columns: :func:`motion_figure` (trajectory,
attitude and velocities of a simulated or logged run).
"""

from __future__ import annotations

import numpy as np

from stripcoef.conventions import POSE, VELOCITIES
from stripcoef.errors import InputError
from stripcoef.files import atomic_path

#: File formats :func:`save_figure` writes, by suffix.
FORMATS = ("png", "pdf", "svg")


def new_figure(*, figsize=(8.0, 5.0), key: str = "plot"):
    """An empty :class:`matplotlib.figure.Figure` with constrained layout (no pyplot)."""
    try:
        from matplotlib.figure import Figure
    except ImportError:
        raise InputError("plotting needs matplotlib", key=key,
                         expected="pip install 'stripcoef[plot]'") from None
    return Figure(figsize=figsize, layout="constrained")


def check_plot_path(path, *, key: str = "plot") -> str:
    """The format of a figure file from its suffix (.png, .pdf or .svg), else an InputError."""
    text = str(path)
    fmt = text.rsplit(".", 1)[-1].lower() if "." in text else ""
    if fmt not in FORMATS:
        raise InputError("unknown plot format", key=key, value=text,
                         expected="a file name ending in .png, .pdf or .svg")
    return fmt


def save_figure(fig, path, *, key: str = "plot", dpi: int = 130) -> None:
    """Write ``fig`` to ``path`` atomically, in the format its suffix names."""
    fmt = check_plot_path(path, key=key)
    with atomic_path(path, key=key) as tmp:
        fig.savefig(tmp, format=fmt, dpi=dpi)


def motion_figure(log, *, title: str | None = None, key: str = "plot"):
    """Trajectory and velocities of a log (columns ``t``, ``x y z phi theta psi``,
    ``u v w p q r``; missing ones are zero).

    Panels: the track seen from above (north x [m] up, east y [m] right), depth z [m] and
    the attitude (roll, pitch, heading [deg]) against time [s], the linear velocities
    u, v, w [m/s] and the angular rates p, q, r [deg/s] against time [s].
    """
    t = log.require("t")
    col = {k: np.asarray(log.get(k, np.zeros(len(log))), float) for k in (*POSE, *VELOCITIES)}
    fig = new_figure(figsize=(11.0, 7.0), key=key)
    grid = fig.add_gridspec(3, 2, width_ratios=[1.0, 1.4])
    top = fig.add_subplot(grid[:, 0])
    top.plot(col["y"], col["x"], color="C0", lw=1.2, label="track")
    top.plot(col["y"][:1], col["x"][:1], "o", color="C2", label=f"start (t = {t[0]:g} s)")
    top.plot(col["y"][-1:], col["x"][-1:], "s", color="C3", label=f"end (t = {t[-1]:g} s)")
    top.set_xlabel("east y [m]")
    top.set_ylabel("north x [m]")
    top.set_aspect("equal", adjustable="datalim")
    top.set_title("track seen from above (NED)")
    top.legend(loc="upper left", bbox_to_anchor=(0.0, -0.08), ncol=1, fontsize=8)
    ax = fig.add_subplot(grid[0, 1])
    ax.plot(t, col["z"], color="C0", label="depth z [m]")
    ax.invert_yaxis()
    ax.set_ylabel("depth z [m]\n(down > 0)")
    att = ax.twinx()
    for k, (name, sym) in enumerate((("phi", "roll φ"), ("theta", "pitch θ"),
                                     ("psi", "heading ψ"))):
        att.plot(t, np.degrees(np.unwrap(col[name]) if name == "psi" else col[name]),
                 color=f"C{k + 1}", lw=0.9, label=f"{sym} [deg]")
    att.set_ylabel("attitude [deg]")
    lines = ax.get_legend_handles_labels()
    more = att.get_legend_handles_labels()
    ax.legend(lines[0] + more[0], lines[1] + more[1], loc="upper left",
              bbox_to_anchor=(1.2, 1.0), fontsize=8)
    lin = fig.add_subplot(grid[1, 1], sharex=ax)
    for k, name in enumerate(("u", "v", "w")):
        lin.plot(t, col[name], color=f"C{k}", lw=1.0, label=f"{name} [m/s]")
    lin.set_ylabel("linear velocity [m/s]")
    lin.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=8)
    rot = fig.add_subplot(grid[2, 1], sharex=ax)
    for k, name in enumerate(("p", "q", "r")):
        rot.plot(t, np.degrees(col[name]), color=f"C{k}", lw=1.0, label=f"{name} [deg/s]")
    rot.set_ylabel("angular rate [deg/s]")
    rot.set_xlabel("time t [s]")
    rot.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=8)
    for a in (top, ax, lin, rot):
        a.grid(True, alpha=0.3)
    fig.suptitle(title or f"{getattr(log, 'source', 'log')}: trajectory and velocities")
    return fig
