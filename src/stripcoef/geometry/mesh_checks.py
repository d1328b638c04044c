"""Checks of a mesh file's raw content, before trimesh's processing changes it.

trimesh's processing (``process=True``) drops the faces of non-finite vertices without a
word; the surface then has holes, which the repair closes: a NaN in a CAD export would give
a silently different body (issue 36). :func:`refuse_non_finite_vertices` reads the file
again unprocessed and names the first non-finite vertex.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from stripcoef.errors import InputError


def refuse_non_finite_vertices(path) -> None:
    """Raise an :class:`InputError` naming the first vertex of ``path`` with a NaN or an
    infinite coordinate (as stored in the file, before any processing); nothing if none."""
    import trimesh

    try:
        raw = trimesh.load(str(path), force="mesh", process=False)
    except Exception:  # noqa: BLE001 - read once already; a second failure says nothing new
        return
    vertices = np.asarray(getattr(raw, "vertices", np.zeros((0, 3))), dtype=float)
    bad = np.flatnonzero(~np.all(np.isfinite(vertices), axis=1))
    if bad.size:
        k = int(bad[0])
        raise InputError(f"non-finite vertex coordinates (in {bad.size} of {len(vertices)} "
                         "vertices)", file=str(Path(path)), key=f"vertex {k}",
                         value=vertices[k].tolist(),
                         expected="finite coordinates (no NaN or inf; check the CAD export)")
