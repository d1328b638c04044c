"""What a mesh file holds and what the loader changes in it: the report of ``stripcoef mesh``.

:func:`check_mesh` reads a mesh file twice -- as found (trimesh, no repair) and through
:func:`stripcoef.geometry.mesh.load_mesh` (every repair) -- and returns a
:class:`MeshCheck` with the counts before and after, the repairs in words, the body's extent
and volume, and the bodies united into one closed surface (manifold3d) when there are
several.  :func:`mesh_figure` draws the repaired surface in three views with the edges that
were open in the file.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from stripcoef.errors import ModelWarning


@dataclass(frozen=True)
class MeshCheck:
    """A mesh file as found and as the loader repaired it.

    Attributes
    ----------
    source : str
        The file.
    faces_found, vertices_found : int
        As read (trimesh, exact duplicates merged).
    open_edges_found : int
        Face edges not shared by exactly two faces in the file.
    faces, vertices : int
        After the repairs (and the union of several bodies).
    bodies : int
        Connected bodies after the repairs (before the union).
    watertight : bool
        The repaired surface is closed and consistently wound.
    extent : tuple of 3 floats
        Size along body x, y, z [m].
    volume : float
        Enclosed volume of the repaired (united) surface [m^3].
    repairs : tuple of str
        What was found and changed, in words.
    closed_parts : bool
        The file is refused as found (open after hole filling): the repair capped its open
        parts and united them (:mod:`stripcoef.geometry.mesh_close`); the other commands need
        the repaired copy (``--repair -o OUT``).
    """

    source: str
    faces_found: int
    vertices_found: int
    open_edges_found: int
    faces: int
    vertices: int
    bodies: int
    watertight: bool
    extent: tuple
    volume: float
    repairs: tuple = field(default_factory=tuple)
    closed_parts: bool = False

    def to_dict(self) -> dict:
        return {k: (list(v) if isinstance(v, tuple) else v) for k, v in self.__dict__.items()}


def _open_edges(faces):
    """(k, 2) vertex pairs of the edges not shared by exactly two faces."""
    f = np.asarray(faces, dtype=np.int64)
    e = np.sort(np.stack([f, np.roll(f, -1, axis=1)], axis=2).reshape(-1, 2), axis=1)
    uniq, count = np.unique(e, axis=0, return_counts=True)
    return uniq[count != 2]


def check_mesh(path, *, axis: str = "x", length_unit: str = "m", z_up: bool = False):
    """Read ``path`` as found and repaired (module docstring).

    Returns (MeshCheck, the repaired surface as a ``trimesh.Trimesh`` in body axes [m] with the
    file's origin, the file's open edges as (k, 2, 3) segments in body axes [m])."""
    from stripcoef.errors import InputError
    from stripcoef.geometry.mesh import EdgeTopology, _file_frame, _read, load_mesh

    path = Path(path)
    raw = _read(path)
    open_e = _open_edges(raw.faces)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ModelWarning)
        try:
            body = load_mesh(path, axis=axis, length_unit=length_unit, origin="file",
                             z_up=z_up)
            closed = False
        except InputError as exc:          # open after hole filling: the parts closed
            if "not watertight" not in str(exc):
                raise
            body = load_mesh(path, axis=axis, length_unit=length_unit, origin="file",
                             z_up=z_up, close_parts=True)
            closed = True
        surface = body.united()
    for w in caught:        # what is not a repair (the repairs are in the report): the axis
        text = str(w.message)
        if issubclass(w.category, ModelWarning) and not any(text.endswith(r) for r in
                                                            body.repairs):
            warnings.warn(text, ModelWarning, stacklevel=2)
    scale, rot, _, _ = _file_frame(raw.metadata, length_unit, axis, z_up)
    pts = (np.asarray(raw.vertices, float)[open_e] * scale) @ rot.T
    v = np.asarray(surface.vertices)
    report = MeshCheck(
        source=str(path), faces_found=len(raw.faces), vertices_found=len(raw.vertices),
        open_edges_found=len(open_e), faces=len(surface.faces), vertices=len(v),
        bodies=body.n_bodies, watertight=EdgeTopology(surface.faces).consistent,
        extent=tuple(float(x) for x in np.ptp(v, axis=0)), volume=float(surface.volume),
        repairs=tuple(body.repairs), closed_parts=closed)
    return report, surface, pts


def mesh_figure(surface, open_segments=(), *, title: str = "", key: str = "plot"):
    """Three views of a surface in body axes (FRD: side x-z with z down, top x-y, front y-z):
    its edges in grey, the edges that were open in the file in red."""
    from matplotlib.collections import LineCollection

    from stripcoef.figures import new_figure

    fig = new_figure(figsize=(12.0, 4.0), key=key)
    axes = fig.subplots(1, 3)
    v = np.asarray(surface.vertices)
    edges = np.asarray(surface.edges_unique)
    seg = v[edges]
    red = np.asarray(open_segments, dtype=float).reshape(-1, 2, 3)
    for ax, (i, j, name) in zip(axes, ((0, 2, "side (x, z)"), (0, 1, "top (x, y)"),
                                       (1, 2, "front (y, z)"))):
        ax.add_collection(LineCollection(seg[:, :, [i, j]], colors="0.6", linewidths=0.4))
        if len(red):
            ax.add_collection(LineCollection(red[:, :, [i, j]], colors="red", linewidths=1.2))
        ax.set_aspect("equal", adjustable="datalim")
        ax.autoscale_view()
        if j == 2:
            ax.invert_yaxis()               # z down
        ax.set_title(name)
        ax.set_xlabel("xyz"[i] + " [m]")
        ax.set_ylabel("xyz"[j] + " [m]")
    if title:
        fig.suptitle(title)
    return fig
