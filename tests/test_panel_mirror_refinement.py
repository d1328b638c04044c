"""The panel method's refinement judges an added level by the panels it solves: a mirrored
level's caps (on the planes, dropped before the solve) do not count towards the refinement
ratio (issue 32: the Slocum glider's eighth, whose caps let a level of 1.22 times the finest's
panels pass as 1.30 and its surge added mass be extrapolated 5 % off;
benchmarks/data/slocum32s_trace.md)."""

import numpy as np
import pytest

trimesh = pytest.importorskip("trimesh")
pytest.importorskip("pymeshlab")
pytest.importorskip("manifold3d")

from stripcoef.hull import remesh  # noqa: E402
from stripcoef.hull.mirror_panels import capped_part, drop_caps  # noqa: E402
from stripcoef.hull.panels import _solved_panels, panel_added_mass  # noqa: E402


def _cylinder():
    """A 31-sided cylinder 3 m long along x, radius 0.22 m (the Slocum collision mesh's
    size and faces, 124)."""
    c = trimesh.creation.cylinder(radius=0.22, height=3.0, sections=31)
    c.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0]))
    return c


def _caps_split(v, f, planes):
    """(v, f) with every cap face (all three vertices on one of ``planes`` through the
    origin) split in three at its centroid: more faces, the same solved panels (twice: nine
    times the cap's faces)."""
    v = np.asarray(v, float)
    f = np.asarray(f, np.int64)
    on = np.zeros(len(v), bool)
    scale = float(np.ptp(v, axis=0).max())
    for p in planes:
        on |= np.abs(v[:, "xyz".index(p)]) <= 1e-9 * scale
    cap = on[f].all(axis=1)
    c = v[f[cap]].mean(axis=1)
    ids = len(v) + np.arange(len(c))
    a, b, d = f[cap].T
    new = np.concatenate([np.stack([a, b, ids], 1), np.stack([b, d, ids], 1),
                          np.stack([d, a, ids], 1)])
    return np.vstack([v, c]), np.vstack([f[~cap], new])


def test_solved_panels_leave_the_caps_out():
    c = _cylinder()
    planes = ("x", "y", "z")
    part = capped_part(c.vertices, c.faces, planes)
    lv = remesh.remesh_isotropic(*part, remesh.edge_for_panels(c.area, 800))
    assert lv is not None
    solved = drop_caps(*lv, planes)
    assert _solved_panels(lv, planes, (0.0, 0.0, 0.0)) == 8 * len(solved[1])
    assert _solved_panels(lv, planes, (0.0, 0.0, 0.0)) < 8 * len(lv[1])
    assert _solved_panels(lv, (), (0.0, 0.0, 0.0)) == len(lv[1])


def test_added_level_refines_in_solved_panels(monkeypatch):
    """A remesh whose faces grow only on the caps is not an added level: the refinement grows
    one (remesh.grown_level) that refines the solved panels by at least LEAST_FACE_RATIO.
    Before: the caps' faces passed it, and the solve found no refinement (an error)."""
    planes = ("x", "y", "z")
    original = remesh.remesh_isotropic

    def caps_only(v, f, edge, **kw):
        # the remesh at the edge of half the panels asked (about the finest level's), its
        # caps split twice: many more faces, about the same solved panels
        lv = original(v, f, edge * np.sqrt(2.0), **kw)
        return None if lv is None else _caps_split(*_caps_split(*lv, planes), planes)

    monkeypatch.setattr(remesh, "remesh_isotropic", caps_only)
    _, info = panel_added_mass(_cylinder(), rho=1000.0, panels=400, mirrors=planes)
    counts = info["panels"]
    assert len(counts) >= 4
    assert all(b >= remesh.LEAST_FACE_RATIO * a for a, b in zip(counts, counts[1:]))
