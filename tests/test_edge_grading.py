"""Panellings graded towards sharp edges (stripcoef.hull.remesh.graded_remesh, issue 32): the
sizing field is the algebraic grading it says, the bisection meets it without changing the
surface, and the defaults of the remesh family are untouched."""

import numpy as np
import pytest

from stripcoef.hull.bisection import bisect_graded, bisect_longest, enclosed_volume, surface_area
from stripcoef.hull.remesh import (MODES, distance_to_segments, edge_graded_size, sharp_edges)


def _box(a=0.4, b=0.3, c=0.02):
    trimesh = pytest.importorskip("trimesh")
    m = trimesh.creation.box([a, b, c])
    return np.asarray(m.vertices, float), np.asarray(m.faces, np.int64)


def _edge_lengths(v, f):
    t = v[f]
    return np.linalg.norm(t[:, [1, 2, 0]] - t, axis=2)


def test_sharp_edges_of_a_box_are_its_twelve_edges():
    """A box of 12 triangles has 18 edges; the 6 face diagonals are flat (dihedral 0)."""
    v, f = _box()
    seg = sharp_edges(v, f)
    assert len(seg) == 12
    assert np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1).sum() == pytest.approx(
        4 * (0.4 + 0.3 + 0.02), rel=1e-12)
    assert len(sharp_edges(v, f, angle=95.0)) == 0


def test_distance_to_segments_is_the_clamped_projection():
    seg = np.array([[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]])
    p = np.array([[0.5, 2.0, 0.0], [-3.0, 0.0, 4.0], [2.0, 0.0, 0.0]])
    np.testing.assert_allclose(distance_to_segments(p, seg), [2.0, 5.0, 1.0], rtol=1e-12)
    assert np.isinf(distance_to_segments(p, np.zeros((0, 2, 3)))).all()


def test_graded_size_is_the_algebraic_grading():
    """h(d) = h (max(d, d0)/L)^(1 - 1/beta), h beyond L, d0 = L (h/L)^beta where h(d0) = d0;
    beta = 1 is the uniform mesh."""
    seg = np.array([[[0.0, -1.0, 0.0], [0.0, 1.0, 0.0]]])
    h, L = 0.05, 0.2
    d = np.array([0.0, 1e-4, L * (h / L) ** 2, 0.05, 0.2, 0.5])
    pts = np.column_stack([d, np.zeros_like(d), np.zeros_like(d)])
    got = edge_graded_size(pts, seg, h, L, beta=2.0)
    d0 = L * (h / L) ** 2
    want = np.where(d < L, h * np.sqrt(np.maximum(d, d0) / L), h)
    np.testing.assert_allclose(got, want, rtol=1e-12)
    assert got[2] == pytest.approx(d0, rel=1e-12)
    np.testing.assert_allclose(edge_graded_size(pts, seg, h, L, beta=1.0), h, rtol=1e-12)


def test_graded_bisection_meets_the_field_and_keeps_the_surface():
    """Every face's longest edge within the field at its centroid, smaller near the rims than
    away from them, the surface (area, volume) exactly the input's, the mesh closed."""
    from stripcoef.geometry.mesh import EdgeTopology

    v, f = _box()
    seg = sharp_edges(v, f)
    h, L = 0.05, 0.1
    size = lambda c: edge_graded_size(c, seg, h, L, beta=2.0)  # noqa: E731
    gv, gf = bisect_graded(*bisect_longest(v, f, h), size)
    c = gv[gf].mean(axis=1)
    assert (_edge_lengths(gv, gf).max(axis=1) <= size(c) * (1 + 1e-12)).all()
    assert surface_area(gv, gf) == pytest.approx(surface_area(v, f), rel=1e-12)
    assert enclosed_volume(gv, gf) == pytest.approx(enclosed_volume(v, f), rel=1e-12)
    assert EdgeTopology(gf).consistent
    d = distance_to_segments(c, seg)
    area = 0.5 * np.linalg.norm(np.cross(gv[gf][:, 1] - gv[gf][:, 0],
                                         gv[gf][:, 2] - gv[gf][:, 0]), axis=1)
    assert area[d < 0.01].mean() < 0.2 * area[d > L].mean()


def test_bisect_longest_unchanged_by_the_graded_rule():
    """The uniform bound is the graded rule with a constant field."""
    v, f = _box()
    a = bisect_longest(v, f, 0.03)
    b = bisect_graded(v, f, lambda c: np.full(len(c), 0.03))
    np.testing.assert_array_equal(a[1], b[1])
    np.testing.assert_allclose(a[0], b[0], rtol=0, atol=0)


def test_graded_remesh_is_an_option_not_a_default():
    """The remesh family's modes do not grade; a graded remesh of a plate is closed, keeps
    its area and volume, and puts its extra faces near the rims."""
    pytest.importorskip("pymeshlab")
    from stripcoef.hull import remesh

    assert all(not hasattr(m, "grading") for m in MODES)
    v, f = _box()
    out = remesh.graded_for_panels(v, f, 1500)
    assert out is not None
    gv, gf = out
    assert 0.8 * 1500 <= len(gf) <= 1.25 * 1500
    assert surface_area(gv, gf) == pytest.approx(surface_area(v, f),
                                                 rel=remesh.AREA_TOLERANCE)
    assert enclosed_volume(gv, gf) == pytest.approx(enclosed_volume(v, f),
                                                    rel=remesh.VOLUME_TOLERANCE)
