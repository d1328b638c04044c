"""The panel family of a fine smooth mesh is a rule about the mesh, not about what is installed
(remesh32h): stripcoef.hull.panels.fine_smooth_input keeps the input's coarsened levels
with and without the remesher (pymeshlab), and hands every other mesh to the remesher as
before."""

import sys
import types

import numpy as np
import pytest
import trimesh

from stripcoef.hull import remesh
from stripcoef.hull.bisection import surface_area
from stripcoef.hull.input_ladder import CLUSTER_CELL
from stripcoef.hull.lamb import ellipsoid_added_mass
from stripcoef.hull.panels import edge_features, fine_smooth_input, panel_added_mass

RHO = 1000.0
PANELS = 800


def _ellipsoid(a, b, c, subdivisions=4):
    m = trimesh.creation.icosphere(subdivisions=subdivisions)
    m.apply_scale([a, b, c])
    return m


def _rule(m, panels=PANELS):
    v, f = np.asarray(m.vertices, float), np.asarray(m.faces, np.int64)
    return fine_smooth_input(v, f, panels, edge_features(v, f))


def _remesher_that_fails():
    """A pymeshlab that imports (so remesh.available() is True) and fails on any use."""
    fake = types.ModuleType("pymeshlab")

    def used(*args, **kwargs):
        raise AssertionError("the remesher was used on a fine smooth mesh")

    fake.MeshSet = fake.Mesh = fake.PureValue = used
    return fake


def test_fine_smooth_mesh_same_family_with_and_without_the_remesher(monkeypatch):
    """A 5,120-face ellipsoid (every edge within the 800-panel level's clustering cell):
    the same levels, family and matrix whether pymeshlab imports or not, and the matrix
    within 1.5 % of Lamb's, each term within its estimated error (measured 0.04-0.8 % under
    estimates of 0.5-4.1 %)."""
    axes = (0.2, 0.12, 0.06)
    m = _ellipsoid(*axes)
    assert _rule(m)
    monkeypatch.setitem(sys.modules, "pymeshlab", None)          # import fails
    assert not remesh.available()
    a0, info0 = panel_added_mass(m, rho=RHO, panels=PANELS)
    monkeypatch.setitem(sys.modules, "pymeshlab", _remesher_that_fails())
    assert remesh.available()
    a1, info1 = panel_added_mass(m, rho=RHO, panels=PANELS)
    assert info0["family"] == info1["family"] == "refined/coarsened input"
    assert info0["fine_smooth"] and info1["fine_smooth"]
    assert info0["panels"] == info1["panels"]
    np.testing.assert_array_equal(a0, a1)
    exact = ellipsoid_added_mass(*axes, rho=RHO)
    np.testing.assert_allclose(np.diag(a1), exact, rtol=0.015)
    assert np.all(np.abs(np.diag(a1) - exact) <= np.diag(info1["error"]))


def test_other_meshes_still_go_to_the_remesher(monkeypatch):
    """A fine box (sharp edges) is not kept on the input family: with a pymeshlab that
    imports, the remesher is asked for it (the fake one fails when used)."""
    box = trimesh.creation.box((0.3, 0.2, 0.1))
    v, f = trimesh.remesh.subdivide_to_size(box.vertices, box.faces, max_edge=0.01)
    fine_box = trimesh.Trimesh(v, f)
    assert len(fine_box.faces) > PANELS and not _rule(fine_box)
    monkeypatch.setitem(sys.modules, "pymeshlab", _remesher_that_fails())
    # (a box is panelled graded towards its edges, remesher or not: a box with a bump is not)
    bump = _ellipsoid(0.05, 0.05, 0.05, subdivisions=3)
    bump.apply_translation((0.0, 0.0, 0.05))
    body = trimesh.boolean.union([fine_box, bump], engine="manifold")
    assert not _rule(body)
    with pytest.raises(AssertionError, match="remesher was used"):
        panel_added_mass(body, rho=RHO, panels=PANELS)


def test_rule_reads_face_count_edges_smoothness_and_thickness():
    """Each condition of fine_smooth_input: face count, edges within the cell, a smooth
    surface, no member thinner than the panels."""
    m = _ellipsoid(0.2, 0.12, 0.1)
    assert _rule(m)
    # fewer faces than the finest level: the remesher's levels refine it
    assert not _rule(m, panels=len(m.faces))
    # a smooth mesh of many faces with edges longer than the cell (16 meridians, 39 mm
    # across against a cell of about 29 mm)
    uv = trimesh.creation.uv_sphere(radius=0.2, count=[200, 16])
    h = remesh.edge_for_panels(surface_area(uv.vertices, uv.faces), PANELS)
    tri = uv.vertices[uv.faces]
    assert np.abs(tri - np.roll(tri, 1, axis=1)).max() >= CLUSTER_CELL * h
    assert len(uv.faces) > PANELS and edge_features(uv.vertices, uv.faces).turning == 0.0
    assert not _rule(uv)
    # a smooth ring thinner than the finest level's edge (a 12-mm tube, 14-mm panels) is
    # left to the remesher's thin-member modes (its coarsened level loses a quarter of its
    # volume); a 100-mm tube at 3000 panels (21-mm edges) is kept
    ring = trimesh.creation.torus(0.3, 0.006, major_sections=200, minor_sections=16)
    assert len(ring.faces) > PANELS and edge_features(ring.vertices, ring.faces).turning == 0.0
    assert not _rule(ring)
    assert _rule(trimesh.creation.torus(0.3, 0.05, major_sections=200, minor_sections=32),
                 panels=3000)
