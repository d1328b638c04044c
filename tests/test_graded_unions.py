"""Edge-graded references of the bluff set's unions of prisms (benchmarks.graded_unions,
benchmarks.graded_references unions, issue 32): the panels cover the body the stored references
and the panel method see, outward; the reader returns what the stored CSVs hold, and every
stored shape has a band.  No Capytaine here: the stored levels are read."""

import csv

import numpy as np
import pytest
import shapely

from benchmarks import graded_unions as GU
from benchmarks.bluff_shapes import PRISM_PARTS, SHAPES
from validation.graded_bodies import (BLUFF_FILES, UNIONS, bluff_references, bluff_sources,
                                      read, references)

NAMES = tuple(PRISM_PARTS)


def _inside(prisms, pts):
    out = np.zeros(len(pts), bool)
    for a, b, poly in prisms:
        out |= (pts[:, 0] > a) & (pts[:, 0] < b) & shapely.contains_xy(poly, pts[:, 1], pts[:, 2])
    return out


@pytest.mark.parametrize("name", NAMES)
def test_the_graded_panels_are_the_union_mirrored_with_outward_normals(name):
    """The half (quarter) mirrored has the area and volume of the trimesh union that
    ``bem_bluff.csv`` and the panel method take (to its float32 vertices, 1e-7), and each
    panel's normal points out of the body (a point 1 um outside is in no part, 1 um inside in
    one)."""
    prisms, quarter = GU.shape_prisms(name)
    assert quarter == (name in ("box_skid", "twin_hull"))
    v, f = GU.graded_part(prisms, 13, quarter)
    assert v[:, 1].min() >= 0.0 and (not quarter or v[:, 0].min() >= 0.0)
    whole_v, whole_f = GU.whole(v, f, quarter)
    area, volume = GU.area_volume(whole_v, whole_f)
    union = SHAPES[name][0](None)
    assert area == pytest.approx(union.area, rel=2e-7)
    assert volume == pytest.approx(union.volume, rel=2e-7)
    p = whole_v[whole_f]
    n = np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1])
    n /= np.linalg.norm(n, axis=1)[:, None]
    c = p.mean(axis=1)
    assert not _inside(prisms, c + 1e-6 * n).any()
    assert _inside(prisms, c - 1e-6 * n).all()


def test_each_piece_refines_with_the_level():
    """Every graded piece's panel count grows as m (ceil(m sqrt(l / S))), not held at its
    floor: the levels are similar meshes."""
    assert [GU._count(m, 0.03, 0.4, 2) for m in (8, 16, 32)] == [3, 5, 9]
    assert [GU._count(m, 0.4, 0.4, 2) for m in (8, 16, 32)] == [8, 16, 32]
    assert GU._count_smooth(8, 0.02, 0.4) == 1 and GU._count_smooth(32, 0.02, 0.4) == 4


def _csv_rows(path):
    with open(path, newline="") as fh:
        first = fh.readline()
        return first, list(csv.DictReader(fh))


@pytest.fixture(scope="module")
def every():
    return bluff_references()


@pytest.mark.parametrize("path", [p for p in BLUFF_FILES if p.exists()],
                         ids=lambda p: p.name)
def test_the_graded_reader_returns_what_the_csv_holds_and_every_shape_has_a_band(path, every):
    """``read`` gives every stored row's value at its level and term (both triangles), the
    faces of each level, coarse to fine; every shape of the file has the four levels Eça &
    Hoekstra need, so ``references`` and ``bluff_references`` give it a reference with a
    finite, non-negative band on every term and a strictly positive one on the diagonal."""
    from stripcoef.hull.convergence import EH_MIN_LEVELS

    first, rows = _csv_rows(path)
    assert first.startswith(("# python -m benchmarks.graded_references",
                             "# python -m benchmarks.graded_mesher")) and "Capytaine" in first
    got = read(path)
    shapes = {r["shape"] for r in rows}
    assert {str(k) for k in got} == shapes
    for r in rows:
        key = int(r["shape"]) if r["shape"].isdigit() else r["shape"]
        what, faces, mats = got[key]
        lev, i, j = int(r["level"]), int(r["i"]), int(r["j"])
        assert what == r["what"] and faces[lev] == int(r["faces"])
        assert mats[lev][i, j] == mats[lev][j, i] == float(r["added_mass"])
    refs = references(path)
    for key, (_, faces, _) in got.items():
        assert len(faces) >= EH_MIN_LEVELS and faces == sorted(faces), key
        ref, band, order, n = refs[key]
        assert n == faces
        assert np.all(np.isfinite(band)) and np.all(band >= 0.0), key
        assert np.all(np.diag(band) > 0.0), key
        assert np.all(np.diag(ref) > 0.0) and np.all(np.linalg.eigvalsh(ref) > 0.0), key
        np.testing.assert_array_equal(every[key][0], ref)
        np.testing.assert_array_equal(every[key][1], band)


@pytest.mark.skipif(not UNIONS.exists(), reason="no stored graded unions")
def test_the_stored_unions_are_the_meshers_and_the_benchmarks_reference():
    """Each stored union's coarsest level has the faces the mesher gives at its m (the file
    is what ``benchmarks.graded_unions`` builds), its mirror-forbidden couplings are zero,
    and ``benchmarks.bluff_shapes.reference_matrix`` / ``reference_source`` take it."""
    from benchmarks.bluff_shapes import reference_matrix, reference_source

    _, rows = _csv_rows(UNIONS)
    srcs = bluff_sources()
    for name, (_, faces, mats) in read(UNIONS).items():
        m = next(int(r["m"]) for r in rows if r["shape"] == name and r["level"] == "0")
        prisms, quarter = GU.shape_prisms(name)
        assert faces[0] == (4 if quarter else 2) * len(GU.graded_part(prisms, m, quarter)[1])
        for a in mats:                    # mirror in y: no sway/roll/yaw with surge/heave/pitch
            assert np.all(np.abs(a[np.ix_([0, 2, 4], [1, 3, 5])]) < 1e-12 * np.abs(a).max())
        np.testing.assert_array_equal(reference_matrix(name), srcs[name][0])
        assert "graded_unions.csv" in reference_source(name)
