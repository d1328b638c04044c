"""The CAD shapes' edge-graded references on three mirror planes (benchmarks.graded_cad, issue
32) and the observed orders of the BlueROV2 Heavy's levels (benchmarks.frame_order)."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from benchmarks import frame_order as FO
from benchmarks import graded_cad as GC
from validation import ROOT
from validation.cad_shapes import GRADED_CAD, read_graded_levels


def test_the_whole_body_of_an_eighth_has_the_bodys_area_and_volume():
    """The x, y, z >= 0 eighth of a box 0.4 x 0.3 x 0.2 m about the origin (its three outer
    faces, open on the planes) mirrored in the three planes: the box's area and volume
    exactly, its normals outward (positive volume)."""
    box = trimesh.creation.box([0.4, 0.3, 0.2])
    eighth = GC.GM.half_mesh(box, (0, 1, 2))
    v, f = np.asarray(eighth.vertices, float), np.asarray(eighth.faces)
    assert v.min() >= -1e-12
    c = GC.check(v, f, box)
    assert abs(c["area"]) < 1e-12
    assert abs(c["volume"]) < 1e-12


def test_the_memory_rule_of_the_quarter_solve():
    """24 N^2 bytes + 0.5 GB (measured 2.98 GB at 10,760 faces in a fresh process): above the
    measurement, 14,728 faces fit 8 GB, shape 18's 18,624 (H = 0.034 m) do not."""
    assert 2.98 < GC.predicted_gb(10760) < 1.15 * 2.98
    assert GC.predicted_gb(14728) < GC.MAX_GB < GC.predicted_gb(18624)


@pytest.mark.slow
def test_the_graded_eighth_of_the_ellipsoid_is_the_faceted_body():
    """Shape 14 of seed 1375923287 (a 192-face low-polygon ellipsoid) meshed by gmsh on its
    eighth with every facet edge a patch boundary and its corners kept: the whole body's area
    and volume within 1e-7 of the facets' (the panels lie on the facets and cut no crease),
    more faces at a smaller H."""
    pytest.importorskip("gmsh")
    body, _ = GC.surface(14)
    counts = []
    for H in (0.16, 0.12):
        v, f = GC.GM.graded_mesh(body, H, angle=GC.ANGLE, patch_angle=GC.ANGLE,
                                 planes=(0, 1, 2), curve_angle=GC.ANGLE)
        c = GC.check(v, f, body)
        assert abs(c["area"]) < 1e-7 and abs(c["volume"]) < 1e-7
        assert np.all(v >= 0.0)
        counts.append(c["faces"])
    assert counts[1] > counts[0]


def test_observed_orders_of_an_exact_power_law():
    """phi = 2 + 3 h^1.3 on four levels (h ~ N^-1/2): each three consecutive levels' observed
    order (Celik et al. 2008) and Eça & Hoekstra's free order are 1.3, their limit 2."""
    counts = [1000, 2300, 5000, 11000]
    h = np.asarray(counts, float) ** -0.5
    levels = np.column_stack([2.0 + 3.0 * h ** 1.3, 5.0 - h ** 1.3])
    trip, eh = FO.orders(counts, levels)
    assert trip.shape == (2, 2)
    assert np.allclose(trip, 1.3, atol=1e-6)
    assert [g.order for g in eh] == pytest.approx([1.3, 1.3], abs=1e-4)
    assert eh[0].extrapolated == pytest.approx(2.0, abs=1e-6)
    assert eh[1].extrapolated == pytest.approx(5.0, abs=1e-6)


def test_the_stored_graded_cad_levels_are_the_faceted_shapes_14_and_18():
    """reference_tables/bem/graded_cad_1375923287.csv: shapes 14 and 18, four levels or more
    each, faces increasing with the level, every diagonal term positive, the couplings the
    three mirror planes forbid zero."""
    if not GRADED_CAD.exists():
        pytest.skip("no stored graded CAD levels")
    lv = read_graded_levels(GRADED_CAD)
    assert set(lv) == {14, 18}
    for k, levels in lv.items():
        keys = sorted(levels)
        assert len(keys) >= 4
        faces = [levels[x][0] for x in keys]
        assert faces == sorted(faces) and len(set(faces)) == len(faces)
        for x in keys:
            a = levels[x][1]
            assert np.all(np.diag(a) > 0)
            off = a - np.diag(np.diag(a))
            assert np.abs(off).max() < 1e-6 * np.abs(np.diag(a)).max()
    assert GRADED_CAD.parent == ROOT / "reference_tables" / "bem"


@pytest.mark.slow
def test_the_eighth_solve_equals_the_full_solve_of_the_same_panels():
    """Shape 14's graded eighth at H = 0.12 m (2,808 faces) solved on the xOz and yOz planes
    with the z < 0 half mirrored, and the same panels mirrored into the whole body solved as one
    mesh: every term within 1e-4 of sqrt(A_ii A_jj) (measured 3.2e-5: the full solve's own
    couplings that the planes forbid); in the eighth's solve those couplings are below 1e-5 of
    the scale (the z < 0 half is mirrored as panels, not solved on a plane: surge-pitch 1.7e-6,
    the vertical planes' couplings at round-off)."""
    pytest.importorskip("capytaine")
    pytest.importorskip("gmsh")
    import capytaine as cpt

    from benchmarks.plate_graded import capytaine_eighth, solve_added_mass

    body, _ = GC.surface(14)
    v, f = GC.GM.graded_mesh(body, 0.12, angle=GC.ANGLE, patch_angle=GC.ANGLE,
                             planes=(0, 1, 2), curve_angle=GC.ANGLE)
    a, n, _ = capytaine_eighth(v, f)
    wv, wf = GC.whole(v, f)
    assert n == len(wf)
    b = solve_added_mass(cpt.Mesh(vertices=wv, faces=np.column_stack([wf, wf[:, 2]])))
    d = np.sqrt(np.outer(np.abs(np.diag(b)), np.abs(np.diag(b))))
    assert np.abs((a - b) / d).max() < 1e-4
    assert np.abs((a - np.diag(np.diag(a))) / d).max() < 1e-5
