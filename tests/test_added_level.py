"""The panel method's refinement adds a level at Celik et al.'s r >= 1.3 over the finest
(stripcoef.hull.remesh.added_level; issue 32, frames whose finest pair refined by r = 1.14-1.20)."""

import numpy as np
import pytest


def _box(seed: int):
    """A seeded box of random sides 0.2-0.6 m (its 12 faces), (vertices, faces, area)."""
    trimesh = pytest.importorskip("trimesh")
    rng = np.random.default_rng(seed)
    box = trimesh.creation.box(extents=rng.uniform(0.2, 0.6, 3))
    return np.asarray(box.vertices), np.asarray(box.faces), float(box.area)


@pytest.mark.parametrize("seed", [3, 32])
def test_an_added_level_refines_the_finest_by_celiks_ratio(seed):
    """Where the remesh at the doubled target refines the finest level by only 1.1-1.5 times its
    panels (the creases of a frame's plates made its finest level overshoot), the added level
    is grown to at least 1.69 times (r >= 1.3), within the face limit; the former rule
    (ratio = LEAST_FACE_RATIO) took the short remesh."""
    pytest.importorskip("pymeshlab")
    from stripcoef.hull import remesh

    v, f, area = _box(seed)
    mode = remesh.MODES[0]
    edge = remesh.edge_for_panels(area, 1600)
    plain = len(remesh.remesh_isotropic(v, f, edge, feature_angle=mode)[1])
    finest = plain / np.random.default_rng(seed).uniform(1.3, 1.5)
    new = remesh.added_level(v, f, edge, mode, finest)
    assert new is not None
    assert remesh.MIN_FACE_RATIO * finest <= len(new[1]) <= remesh.MAX_FACES
    former = remesh.added_level(v, f, edge, mode, finest, ratio=remesh.LEAST_FACE_RATIO)
    assert len(former[1]) == plain
    # a remesh that already refines by 1.69: taken as it is
    same = remesh.added_level(v, f, edge, mode, plain / 1.8)
    assert len(same[1]) == plain


def test_where_celiks_ratio_does_not_fit_the_family_step_is_kept():
    """No level of 1.69 times the finest fits within the face limit: the remesh at the target
    is taken where it refines by LEAST_FACE_RATIO, and no level is added where it does not."""
    pytest.importorskip("pymeshlab")
    from stripcoef.hull import remesh

    v, f, area = _box(7)
    mode = remesh.MODES[0]
    edge = remesh.edge_for_panels(area, 5000)
    plain = len(remesh.remesh_isotropic(v, f, edge, feature_angle=mode)[1])
    assert remesh.MIN_FACE_RATIO * plain / 1.3 > remesh.MAX_FACES
    kept = remesh.added_level(v, f, edge, mode, plain / 1.3)
    assert kept is not None and len(kept[1]) == plain
    assert remesh.added_level(v, f, edge, mode, plain / 1.2) is None


def test_the_added_level_is_counted_in_the_panels_solved():
    """``counted`` (the panels a mirrored solve keeps) judges the ratio, not the faces."""
    pytest.importorskip("pymeshlab")
    from stripcoef.hull import remesh

    v, f, area = _box(11)
    mode = remesh.MODES[0]
    edge = remesh.edge_for_panels(area, 800)
    plain = len(remesh.remesh_isotropic(v, f, edge, feature_angle=mode)[1])
    half = remesh.added_level(v, f, edge, mode, plain / 1.8, lambda lv: len(lv[1]) // 2)
    assert half is not None
    assert len(half[1]) // 2 >= remesh.MIN_FACE_RATIO * plain / 1.8


@pytest.mark.slow
def test_a_seeded_cad_frame_gets_a_finest_pair_of_celiks_ratio():
    """Frame 25 of the CAD draw 1795948662 (19-mm plates, four tubes; benchmarks.cad_shapes,
    estimated as a user has it): its no-flip family ends at 3,192 panels, about twice its
    1,600-panel target, and the remesh at the doubled target (4,584 panels, r = 1.20) was its
    fourth level; extrapolated, heave came out 5.8 % below the stored Capytaine reference while
    the finest level was within 2 % (benchmarks/data/fresh32f_trace.md).  Now the fourth level
    refines the third by r >= 1.3 and heave is within 5 % of that reference
    (reference_tables/bem/cad_shapes_1795948662.csv; benchmarks/data/frame32g_trace.md: +0.4 %).
    About 5 s of CPU."""
    pytest.importorskip("pymeshlab")
    from benchmarks.cad_shapes import stored_references
    from benchmarks.fresh32f_trace import RHO, model_ladder
    from stripcoef.hull import remesh
    from validation import ROOT

    model, info, _ = model_ladder(1795948662, 25)
    counts = info["panels"]
    assert len(counts) == 4
    assert counts[-1] >= remesh.MIN_FACE_RATIO * counts[-2], counts
    ref = stored_references(ROOT / "reference_tables" / "bem"
                            / "cad_shapes_1795948662.csv")[25]["ref"]
    heave = float(model.added_mass[2, 2]) * RHO / model.density
    assert heave == pytest.approx(ref[2, 2], rel=0.05)
