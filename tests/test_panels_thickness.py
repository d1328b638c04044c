"""Member thickness (ray cast along the inward normal) and the thin-member panel family."""

import numpy as np
import pytest
import trimesh

from stripcoef.hull import remesh
from stripcoef.hull.panels import THIN_EDGE_RATIO, member_thickness, remeshed_levels


def test_plate_thickness_exact():
    """A box 0.3 x 0.4 x 0.012 m: most of its area is the two faces 12 mm apart."""
    box = trimesh.creation.box([0.3, 0.4, 0.012])
    assert member_thickness(box.vertices, box.faces) == pytest.approx(0.012, rel=1e-9)


def test_sphere_thickness_is_its_diameter():
    """Every inward ray from a centroid of a fine icosphere crosses it through the centre:
    the chord is 2 r cos(a) with a the small angle between the face normal and the radius."""
    s = trimesh.creation.icosphere(subdivisions=3, radius=0.2)
    assert member_thickness(s.vertices, s.faces) == pytest.approx(0.4, rel=0.01)


def test_frame_thickness_is_the_plates():
    """Two side plates 17 mm thick joined by a tube: the plates hold most of the area."""
    plates = [trimesh.creation.box([0.4, 0.017, 0.3],
                                   transform=trimesh.transformations.translation_matrix(
                                       [0, s * 0.2, 0])) for s in (-1, 1)]
    tube = trimesh.creation.cylinder(radius=0.03, height=0.417, sections=16,
                                     transform=trimesh.transformations.rotation_matrix(
                                         np.pi / 2, [1, 0, 0]))
    body = trimesh.boolean.union(plates + [tube], engine="manifold")
    assert member_thickness(body.vertices, body.faces) == pytest.approx(0.017, rel=1e-6)


def test_open_surface_has_no_thickness():
    tri = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float)
    assert member_thickness(tri, np.array([[0, 1, 2]])) == np.inf


@pytest.mark.skipif(not remesh.available(), reason="needs the remesh extra (pymeshlab)")
def test_thin_plate_family_keeps_its_faces_apart():
    """A plate 10 mm thick at 400 panels (edge ~ 36 mm > 10 mm): the family is remeshed in a
    thin-member mode (no flips), whose levels keep the plate's volume; at an edge below the
    thickness the default mode (flips) is kept."""
    box = trimesh.creation.box([0.3, 0.4, 0.01])
    levels, mode = remeshed_levels(box.vertices, box.faces, 400)
    assert remesh.edge_for_panels(box.area, 400) > THIN_EDGE_RATIO * 0.01
    assert not mode.flips
    for v, f in levels:
        assert trimesh.Trimesh(v, f).volume == pytest.approx(box.volume, rel=0.02)
    thick = trimesh.creation.box([0.3, 0.4, 0.2])
    assert remeshed_levels(thick.vertices, thick.faces, 400)[1].flips


def test_pre_asymptotic_levels_get_safety_three():
    """Levels converging exactly as 1/N look asymptotic (F_s = 1.25); with an edge longer
    than the member thickness the index takes F_s = 3 on the same order: 3/1.25 times."""
    from stripcoef.hull.convergence import SAFETY_THREE_GRIDS, grid_convergence_index

    counts = [400, 800, 1600]
    mats = [np.full((2, 2), 1.0 + 50.0 / n) for n in counts]
    gci, _, safety = grid_convergence_index(mats, counts)
    assert np.all(safety == SAFETY_THREE_GRIDS)
    wide, _, s = grid_convergence_index(mats, counts, asymptotic_possible=False)
    assert np.all(s == 3.0)
    np.testing.assert_allclose(wide, gci * 3.0 / SAFETY_THREE_GRIDS, rtol=1e-6)
