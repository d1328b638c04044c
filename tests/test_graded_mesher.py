"""The general graded reference mesher (benchmarks.graded_mesher, issue 32) and its stored
levels (reference_tables/bem/graded_meshes.csv)."""

from __future__ import annotations

import csv

import numpy as np
import pytest
import trimesh

from benchmarks import graded_mesher as GM
from validation.graded_bodies import MESHES, bluff_sources, read


def _box(x=0.4, y=0.3, z=0.2):
    return trimesh.creation.box([x, y, z])


def test_the_sharp_edges_of_a_box_are_its_twelve_edges_and_none_of_its_diagonals():
    """A box's triangulation has 18 interior edges: its 12 edges (90 deg, convex) and the 6
    face diagonals (0 deg); the sharp ones are the 12, of total length 4 (x + y + z)."""
    e = GM.sharp_edges(_box())
    assert len(e) == 12
    assert np.linalg.norm(e[:, 1] - e[:, 0], axis=1).sum() == pytest.approx(4 * 0.9, rel=1e-12)
    # the union's concave edge (an L-shaped block) is sharp but not convex
    ell = trimesh.boolean.union([_box(0.4, 0.3, 0.2),
                                 trimesh.creation.box([0.1, 0.3, 0.2],
                                                      transform=trimesh.transformations.
                                                      translation_matrix([0.15, 0, 0.2]))],
                                engine="manifold")
    convex = GM.sharp_edges(ell)
    every = GM.sharp_edges(ell, convex_only=False)
    assert len(every) > len(convex)
    gone = np.linalg.norm(every[:, 1] - every[:, 0], axis=1).sum() - np.linalg.norm(
        convex[:, 1] - convex[:, 0], axis=1).sum()
    assert gone == pytest.approx(0.3, rel=1e-6)     # the one concave edge, 0.3 m (float32)


def test_the_size_grows_linearly_from_the_edge_panel_to_the_largest():
    h, h0 = GM.size_function(0.04)
    assert h0 == pytest.approx(0.04 / GM.RATIO)
    assert h(0.0) == pytest.approx(h0)
    assert h(0.02) == pytest.approx(h0 + GM.GROWTH * 0.02)
    assert h(10.0) == pytest.approx(0.04)


def test_edge_points_are_no_further_apart_than_asked():
    pts = GM.edge_points(np.array([[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]]), 0.3)
    assert len(pts) == 5
    assert np.max(np.diff(np.sort(pts[:, 0]))) <= 0.3


@pytest.mark.slow
def test_a_box_remeshed_is_the_box_graded_towards_its_edges_and_mirrors_to_it():
    """gmsh's triangles of a box lie on it (area and volume to 1e-6: the STL gmsh reads holds float32), outward, and are graded:
    the panels touching an edge are smaller than those at the faces' centres; the y >= 0 half
    has its cut on y = 0 and mirrors to the same body."""
    pytest.importorskip("gmsh")
    box = _box()
    H = 0.08
    v, f = GM.graded_mesh(box, H)
    c = GM.check(v, f, box, False)
    assert abs(c["area"]) < 1e-6 and abs(c["volume"]) < 1e-6 and c["quality"] > 0.2
    p = v[f]
    size = np.sqrt(sum(np.sum((p[:, (k + 1) % 3] - p[:, k]) ** 2, axis=1) for k in range(3)) / 3)
    half = 0.5 * np.array([0.4, 0.3, 0.2])
    near = np.min(half - np.abs(p.mean(axis=1)), axis=1)      # distance to the box's edges
    far = np.sort(half - np.abs(p.mean(axis=1)), axis=1)[:, 1]
    edge, centre = size[far < 0.2 * H], size[far > 1.5 * H]
    assert near.max() < 1e-6                                   # every panel on a face
    assert np.median(edge) < 0.6 * np.median(centre)
    hv, hf = GM.graded_mesh(box, H, mirror=True)
    assert hv[:, 1].min() == 0.0
    c = GM.check(hv, hf, box, True)
    assert abs(c["area"]) < 1e-6 and abs(c["volume"]) < 1e-6


@pytest.mark.skipif(not MESHES.exists(), reason="no stored graded meshes")
def test_the_stored_levels_refine_keep_the_mirror_and_are_the_bluff_sets_references():
    """graded_meshes.csv: its command and Capytaine's version on the first line, four levels
    or more per shape whose faces and H refine, the couplings the xOz mirror plane forbids
    zero, and each shape's reference is the one the bluff benchmark takes."""
    with open(MESHES, newline="") as fh:
        first = fh.readline()
        rows = list(csv.DictReader(fh))
    assert first.startswith("# python -m benchmarks.graded_mesher") and "Capytaine" in first
    forbidden = {(0, 1), (0, 3), (0, 5), (1, 2), (1, 4), (2, 3), (2, 5), (3, 4), (4, 5)}
    for name, (_, faces, mats) in read(MESHES).items():
        assert len(faces) >= 4 and faces == sorted(set(faces))
        hs = [float(r["m"]) for r in rows if r["shape"] == name and r["i"] == r["j"] == "0"]
        assert hs == sorted(hs, reverse=True)
        for a in mats:
            for i, j in forbidden:
                assert abs(a[i, j]) <= 1e-9 * np.sqrt(a[i, i] * a[j, j])
        assert bluff_sources()[name][2].endswith("graded_meshes.csv")


def test_a_remesh_that_is_not_the_body_is_refused_in_one_line():
    """A level whose triangles are wound inconsistently, or whose volume is off by more than
    MAX_VOLUME_CHANGE, raises a one-line error naming it; a good one passes."""
    box = _box()
    v, f = np.asarray(box.vertices, float), np.asarray(box.faces)
    good = GM.check(v, f, box, False)
    assert good["consistent"] and abs(good["volume"]) < 1e-12
    assert GM.accepted(good, "box") is good
    bad = f.copy()
    bad[0] = bad[0][::-1]
    with pytest.raises(RuntimeError, match=r"^box at H = 1 m: .*not consistently wound"):
        GM.accepted(GM.check(v, bad, box, False), "box at H = 1 m")
    with pytest.raises(RuntimeError, match=r"volume differs by \+10\.0 %"):
        GM.accepted(dict(good, volume=0.10), "box")


PUBLIC_LEVELS = MESHES.parents[1] / "public_meshes" / "graded_levels.csv"


@pytest.mark.skipif(not PUBLIC_LEVELS.exists(), reason="no stored graded public levels")
def test_the_public_meshes_graded_levels_refine_and_give_a_reference_with_a_band():
    """graded_levels.csv: the command and Capytaine's version first; every mesh of it is one of
    the public benchmark's, with four levels or more that refine, and a reference (Eça &
    Hoekstra) positive definite with a finite positive diagonal band."""
    from benchmarks.public_meshes import MESHES as PUBLIC
    from validation.graded_bodies import references

    with open(PUBLIC_LEVELS) as fh:
        first = fh.readline()
    assert first.startswith("# python -m benchmarks.graded_mesher") and "Capytaine" in first
    names = {m.name for m in PUBLIC}
    got = read(PUBLIC_LEVELS)
    assert got and set(got) <= names
    for name, (ref, band, _, faces) in references(PUBLIC_LEVELS).items():
        assert len(faces) >= 4 and faces == sorted(set(faces)), name
        assert np.all(np.linalg.eigvalsh(ref) > 0.0), name
        assert np.all(np.isfinite(band)) and np.all(np.diag(band) > 0.0), name
