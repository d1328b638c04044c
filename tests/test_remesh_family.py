"""The remesh family refines on faceted bodies, and the thin-member benchmark's wings are
closed panellings of the NACA section (issue 32)."""

import numpy as np
import pytest


def test_a_faceted_cylinder_gets_a_family_that_refines():
    """A 30-sided cylinder (the Slocum glider's collision mesh is one): at the facet angle the
    creases hold the face count near their own, so levels at the asked edges do not refine by
    1.25x; the family shortens those levels' edges instead of being refused."""
    pytest.importorskip("pymeshlab")
    trimesh = pytest.importorskip("trimesh")
    from stripcoef.hull import remesh

    cyl = trimesh.creation.cylinder(radius=0.22, height=3.0, sections=30)
    v, f = np.asarray(cyl.vertices), np.asarray(cyl.faces)
    edges = [remesh.edge_for_panels(cyl.area, n) for n in (400, 800, 1600)]
    out = remesh.remesh_family(v, f, edges)
    assert out is not None
    levels, _ = out
    counts = [len(lv[1]) for lv in levels]
    assert all(b >= 1.25 * a for a, b in zip(counts, counts[1:])), counts
    assert max(counts) <= remesh.MAX_FACES
    for rv, rf in levels:
        assert remesh._volume(rv, rf) == pytest.approx(cyl.volume, rel=remesh.VOLUME_TOLERANCE)


def test_remesh_family_respects_its_face_limit():
    pytest.importorskip("pymeshlab")
    trimesh = pytest.importorskip("trimesh")
    from stripcoef.hull import remesh

    cyl = trimesh.creation.cylinder(radius=0.22, height=3.0, sections=30)
    v, f = np.asarray(cyl.vertices), np.asarray(cyl.faces)
    edges = [remesh.edge_for_panels(cyl.area, n) for n in (400, 800, 1600)]
    assert remesh.remesh_family(v, f, edges, max_faces=500) is None


def test_wing_panelling_is_a_closed_naca_wing():
    """Closed and consistently wound; its volume the section's area times the span, within
    what the section's polygon loses; the area 0.6849 t/c c^2, the thickness form's integral
    10 (0.2969 (2/3) - 0.1260/2 - 0.3516/3 + 0.2843/4 - 0.1036/5) (Abbott & von Doenhoff
    1959, eq. 6.2)."""
    pytest.importorskip("trimesh")
    from benchmarks.thin_members import naca_section, wing_panels

    tau, c, span = 0.03, 0.25, 0.8
    sec = naca_section(tau, c, 200)
    x, y = sec[:, 0], sec[:, 1]
    area = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    assert area == pytest.approx(0.6849 * tau * c * c, rel=0.01)
    for n, rel in ((1000, 0.03), (4000, 0.015)):       # the section's polygon: 18 and 36 points
        m = wing_panels(tau, c, span, n)
        assert m.is_watertight and m.is_winding_consistent
        assert 0.7 * n <= len(m.faces) <= 1.3 * n
        assert m.volume == pytest.approx(0.6849 * tau * c * c * span, rel=rel)
