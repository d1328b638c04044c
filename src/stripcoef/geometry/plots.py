"""The body as strip theory sees it: its strips and some of their sections.

:func:`body_figure` builds and returns a :class:`matplotlib.figure.Figure` (no pyplot, no
backend switching, :mod:`stripcoef.figures`): the side view (x, z) and the top view (x, y)
of every part's extent over the strips, the strip edges, the centres of buoyancy and gravity
and the reference point, and the cross-sections (y, z) at a few stations. ``stripcoef
coefficients --plot FILE`` writes it.
"""

from __future__ import annotations

import numpy as np

from stripcoef.figures import new_figure
from stripcoef.geometry.shapes import shape_geometry
from stripcoef.strips import Strips

_ROLE_COLOUR = {"hull": "C0", "appendage": "C1", "fin": "C2"}


def _section_outline(part, k):
    """(y, z) outlines [m] of part ``part`` in its ``k``-th strip (the shape's outline,
    :data:`stripcoef.geometry.shapes.GEOMETRY`)."""
    return shape_geometry(part.shape).outline(part, k, 72)


def body_figure(strips: Strips, *, name: str = "", points: dict | None = None,
                sections: int = 4, key: str = "plot"):
    """Side view, top view and ``sections`` cross-sections of ``strips``.

    Parameters
    ----------
    strips : Strips
        The body cut into strips (``Vehicle.cut``), body axes FRD [m].
    points : dict, optional
        Label -> (3,) point [m] to mark (e.g. ``{"CB": ..., "CG": ..., "reference": ...}``).
    sections : int
        Number of stations drawn as cross-sections, evenly spread over the length.
    """
    fig = new_figure(figsize=(12.0, 7.5), key=key)
    grid = fig.add_gridspec(2, max(sections, 1), height_ratios=[1.25, 1.0])
    side = fig.add_subplot(grid[0, : max(sections, 1) // 2 or 1])
    top = fig.add_subplot(grid[0, max(sections, 1) // 2 or 1:], sharex=side)
    x0, x1 = strips.x_min, strips.x_max
    stations = np.linspace(x0, x1, sections + 2)[1:-1]
    drawn_roles = set()
    for part in strips.parts:
        x = strips.x[part.index]
        colour = _ROLE_COLOUR.get(part.role, "C3")
        label = part.role if part.role not in drawn_roles else None
        drawn_roles.add(part.role)
        side.fill_between(x, part.z - part.half_height, part.z + part.half_height,
                          color=colour, alpha=0.35, lw=0, step="mid", label=label)
        top.fill_between(x, part.y - part.half_breadth, part.y + part.half_breadth,
                         color=colour, alpha=0.35, lw=0, step="mid", label=label)
    edges = np.concatenate([[x0], strips.x + 0.5 * strips.dx])
    every = max(1, int(np.ceil(edges.size / 60)))
    for ax in (side, top):
        for e in edges[::every]:
            ax.axvline(e, color="0.75", lw=0.4, zorder=0)
        for s in stations:
            ax.axvline(s, color="k", lw=0.8, ls="--")
        for k, (label, p) in enumerate((points or {}).items()):
            p = np.asarray(p, float)
            ax.plot(p[0], p[2] if ax is side else p[1], "xo"[k % 2], color=f"C{4 + k}",
                    ms=7, mfc="none", label=f"{label} ({p[0]:.3g}, {p[1]:.3g}, {p[2]:.3g}) m")
        ax.set_xlabel("x [m] (forward)")
        ax.grid(True, alpha=0.25)
        ax.set_aspect("equal", adjustable="datalim")
    side.invert_yaxis()
    side.set_ylabel("z [m] (down)")
    side.set_title(f"side view, {strips.n} strips"
                   + (f" (every {every}th edge drawn)" if every > 1 else ""), fontsize=10)
    top.set_ylabel("y [m] (starboard)")
    top.invert_yaxis()
    top.set_title("top view", fontsize=10)
    top.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    for j, s in enumerate(stations):
        ax = fig.add_subplot(grid[1, j])
        i = int(np.clip(np.searchsorted(strips.x + 0.5 * strips.dx, s), 0, strips.n - 1))
        for part in strips.parts:
            k = np.nonzero(part.index == i)[0]
            if not k.size:
                continue
            for ring in _section_outline(part, int(k[0])):
                ax.fill(ring[:, 0], ring[:, 1], color=_ROLE_COLOUR.get(part.role, "C3"),
                        alpha=0.4, lw=0.8, ec="k")
        for h in strips.holes:
            if np.any(h.index == i):
                ax.text(0.02, 0.02, f"hole: {h.name}", transform=ax.transAxes, fontsize=7)
        ax.set_aspect("equal", adjustable="datalim")
        ax.invert_yaxis()
        ax.set_xlabel("y [m]")
        ax.set_ylabel("z [m]")
        ax.set_title(f"section at x = {strips.x[i]:.3g} m", fontsize=9)
        ax.grid(True, alpha=0.25)
    fig.suptitle((f"{name}: " if name else "")
                 + "the body in strips (FRD body axes; dashed: the sections drawn below)")
    return fig
