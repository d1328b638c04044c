"""geometry.mesh.EdgeTopology: one sort of the directed edges gives the checks the mesh
loader and the slicer need; checked against trimesh's own graph properties."""

import numpy as np
import trimesh
import pytest

from stripcoef.geometry.mesh import EdgeTopology, _FaceVectors


def _edge_set(edges):
    return {tuple(e) for e in np.sort(np.asarray(edges), axis=1)}


def test_closed_mesh_matches_trimesh():
    m = trimesh.creation.icosphere(subdivisions=2)
    t = EdgeTopology(m.faces)
    assert t.watertight and t.consistent
    assert _edge_set(t.edges) == _edge_set(m.edges_unique)
    # edge k of each face is vertex k -> k+1, as trimesh's faces_unique_edges
    f = np.asarray(m.faces)
    for k in range(3):
        e = t.edges[t.face_edges[:, k]]
        np.testing.assert_array_equal(np.sort(e, axis=1),
                                      np.sort(np.column_stack([f[:, k], f[:, (k + 1) % 3]]),
                                              axis=1))
    assert np.all(t.component_labels() == 0)


def test_open_mesh_is_not_watertight():
    m = trimesh.creation.box()
    t = EdgeTopology(np.asarray(m.faces)[1:])
    assert not t.watertight and not t.consistent
    assert t.open_edges == 3                    # the missing triangle's rim
    assert EdgeTopology(m.faces).open_edges == 0


def test_one_flipped_face_breaks_only_the_winding():
    f = np.asarray(trimesh.creation.box().faces).copy()
    f[0] = f[0][::-1]
    t = EdgeTopology(f)
    assert t.watertight and not t.consistent


def test_separate_bodies_are_separate_components():
    a = trimesh.creation.box()
    b = trimesh.creation.box()
    b.apply_translation([3.0, 0.0, 0.0])
    m = trimesh.util.concatenate([a, b])
    t = EdgeTopology(m.faces)
    labels = t.component_labels()
    assert t.watertight and t.consistent
    assert len(set(labels)) == 2
    assert set(labels[: len(a.faces)]) != set(labels[len(a.faces):])


def test_volume_centroid_is_translation_covariant():
    m = trimesh.creation.icosphere(subdivisions=2)
    m.apply_translation([0.3, -0.2, 0.5])
    np.testing.assert_allclose(_FaceVectors(m.vertices, m.faces).centroid(), [0.3, -0.2, 0.5],
                               atol=1e-12)
    np.testing.assert_allclose(_FaceVectors(m.vertices, m.faces).centroid(), m.center_mass,
                               atol=1e-12)


def test_nondegenerate_matches_trimesh():
    """The loader's degenerate-face test equals trimesh's nondegenerate_faces(height)."""
    rng = np.random.default_rng(3)
    m = trimesh.creation.icosphere(subdivisions=2)
    v = np.vstack([m.vertices, [[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1e-12, 0]]])
    n = len(m.vertices)
    extra = np.array([[n, n + 1, n + 2],        # collinear
                      [n, n, n + 1],            # repeated vertex
                      [n, n + 1, n + 3]])       # a sliver 1e-12 high
    f = np.vstack([m.faces, extra, rng.integers(0, n, size=(50, 3))])
    mesh = trimesh.Trimesh(v, f, process=False)
    for h in (1e-10, 1e-3):
        np.testing.assert_array_equal(_FaceVectors(v, f).nondegenerate(h), mesh.nondegenerate_faces(height=h))
    assert not _FaceVectors(v, f).nondegenerate(1e-10)[len(m.faces):len(m.faces) + 3].any()


def test_duplicate_face_hidden_in_a_closed_mesh_is_found():
    """Two faces on the same vertices form a closed two-face component of their own; the loader
    only searches for duplicates when such a component (or an open edge) exists."""
    import warnings
    from stripcoef.geometry.mesh import mesh_body
    m = trimesh.creation.icosphere(subdivisions=2)
    n = len(m.vertices)
    v = np.vstack([m.vertices, [[3, 0, 0], [3, 1, 0], [3, 0, 1]]])
    f = np.vstack([m.faces, [[n, n + 1, n + 2], [n, n + 2, n + 1]]])
    assert EdgeTopology(f).watertight                   # the pair hides in a closed mesh
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        body = mesh_body(trimesh.Trimesh(v, f, process=False))
    assert "removed 1 duplicate faces" in body.repairs


def test_rings_integrals_exact_on_square_triangle_hole():
    """The batched polygon integrals give the exact area and moments of a unit square and a
    triangle, and a clockwise hole's area negative."""
    from stripcoef.geometry.mesh import rings_integrals
    sq = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    tri = np.array([[2, 0], [3, 0], [2, 2]], float)
    hole = (0.25 + 0.5 * sq)[::-1]
    got = rings_integrals([sq, tri, hole])
    np.testing.assert_allclose(got[0], [1.0, 0.5, 0.5, 1 / 3, 1 / 3, 1 / 4], rtol=1e-14)
    assert got[2, 0] == pytest.approx(-0.25)
    np.testing.assert_allclose(got[1, 0], 1.0)
    np.testing.assert_allclose(got[1, 1], 1.0 * (2 + 3 + 2) / 3)        # area * y_centroid
    # triangle: int yz dA = A/12 (sum y_i z_i + sum y_i sum z_i) = (4 + 7 * 2) / 12
    np.testing.assert_allclose(got[1, 5], 18.0 / 12.0, rtol=1e-14)


def test_points_cut_from_flat_faces_are_dropped():
    """A subdivided box cuts into the same 4-point rectangles as the plain box: the points where
    the cut crosses edges inside a flat face are on a straight line and are dropped, corners
    and each ring's first point kept."""
    from stripcoef.geometry.mesh import _corner_points, mesh_body
    plain = trimesh.creation.box(extents=(1.0, 0.4, 0.2))
    fine = plain.subdivide().subdivide().subdivide()
    x = np.linspace(-0.45, 0.45, 7)
    for mesh in (plain, fine):
        secs = mesh_body(mesh, origin="file").sections(x)
        for rings in secs:
            (ring,) = rings
            assert len(ring) == 4
            np.testing.assert_allclose(np.sort(np.abs(ring), axis=0), [[0.2, 0.1]] * 4,
                                       atol=1e-15)
    # a square's side points (not corners) go; a fold-back point (a spike) stays
    t = np.linspace(0, 1, 5)[:-1]
    sq = np.concatenate([np.c_[t, 0 * t], np.c_[1 + 0 * t, t], np.c_[1 - t, 1 + 0 * t],
                         np.c_[0 * t, 1 - t]])
    assert list(np.flatnonzero(_corner_points(sq, np.zeros(len(sq), int)))) == [0, 4, 8, 12]
    spike = np.array([[0, 0], [2, 0], [1, 0], [1, 1]], float)
    assert _corner_points(spike, np.zeros(4, int)).all()
