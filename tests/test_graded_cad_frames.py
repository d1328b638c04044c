"""The CAD frames' edge-graded references (benchmarks.graded_cad_frames, issue 32): the
frame's exact union, the cosine law, the panels' area and volume, and the stored levels."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from benchmarks import graded_cad_frames as GF
from benchmarks.plate_graded import cosine_nodes
from validation import ROOT

BEM = ROOT / "reference_tables" / "bem"


def test_the_cosine_law_is_the_spacing_of_the_cosine_nodes():
    """On an edge of 0.4 m with n = ceil(pi l / 2H) cosine nodes, each panel but the two at
    the ends lies within 15 % of h(d) at its centre's distance d from the nearer end (the
    law is the nodes' continuous spacing), the middle one is H within 1 %, and the end panel
    is the law's least value H^2 / l within 5 %."""
    length, H = 0.4, 0.03
    x = cosine_nodes(length, GF._panels(length, H))
    w = np.diff(x)
    d = np.minimum(0.5 * (x[1:] + x[:-1]), length - 0.5 * (x[1:] + x[:-1]))
    h = GF.cosine_size(H, length)(d)
    assert np.all(np.abs(w[1:-1] / h[1:-1] - 1.0) < 0.15)
    assert w.max() == pytest.approx(H, rel=0.01)
    assert w[0] == pytest.approx(H * H / length, rel=0.05)


def test_the_rim_edge_panel_is_the_faces_edge_panel():
    """A 20 mm rim with the faces' edge panel h0 = 2 mm: n_t = ceil(pi/2 sqrt(t/h0)) = 5,
    raised to the six of RIM_MIN; at h0 = 0.2 mm n_t = 16 and the cosine nodes' end panel
    t pi^2 / 4 n_t^2 is within 15 % of h0."""
    assert GF._rim_panels(0.02, 0.002) == GF.RIM_MIN == 6
    n = GF._rim_panels(0.02, 0.0002)
    assert n == 16
    assert np.diff(cosine_nodes(0.02, n))[0] == pytest.approx(0.0002, rel=0.15)


def _frame(seed=1795971315, k=6):
    what, parts, body = GF.frames(seed, 40, [k])[k]
    return what, parts, body


def test_the_frame_is_two_plates_and_the_tubes_union_between_them():
    """Frame 6 of seed 1795971315 (0.45 x 0.48 x 0.37 m, 30 mm plates, 2 tubes): plates
    0.45 long and 0.37 high between y = 0.2268 and 0.2567 m, two separate 16-gons; the
    exact union's volume (plates and the prisms between their inner faces) is the parts'
    manifold union's within 1e-6."""
    _, parts, body = _frame()
    g = GF.frame_geometry(parts)
    assert g["l"] == pytest.approx(0.4476, abs=1e-3)
    assert g["y_out"] - g["y_in"] == pytest.approx(0.030, abs=1e-3)
    assert len(g["tubes"]) == 2
    assert all(len(t.exterior.coords) == 17 for t in g["tubes"])
    vol = 2 * g["l"] * g["h"] * (g["y_out"] - g["y_in"]) + sum(
        t.area for t in g["tubes"]) * 2 * g["y_in"]
    assert vol == pytest.approx(body.volume, rel=1e-6)


def test_overlapping_tubes_are_one_polygon():
    """Frame 11 of seed 1795971315: its two tubes overlap, so their union is one polygon
    (more than 16 corners), and the union's volume is still the manifold union's."""
    _, parts, body = _frame(k=11)
    g = GF.frame_geometry(parts)
    assert len(g["tubes"]) == 1 and len(g["tubes"][0].exterior.coords) > 17
    vol = 2 * g["l"] * g["h"] * (g["y_out"] - g["y_in"]) + g["tubes"][0].area * 2 * g["y_in"]
    assert vol == pytest.approx(body.volume, rel=1e-6)


def test_a_part_that_is_no_frame_is_refused():
    """A plate and a box that are not mirror images in y = 0: a one-line error."""
    import trimesh

    parts = [trimesh.creation.box([0.3, 0.02, 0.2], transform=trimesh.transformations
                                  .translation_matrix([0, 0.1, 0])),
             trimesh.creation.box([0.3, 0.02, 0.2], transform=trimesh.transformations
                                  .translation_matrix([0, -0.12, 0]))]
    with pytest.raises(ValueError, match="not a frame"):
        GF.frame_geometry(parts)


def test_the_panels_are_the_faceted_body_with_outward_normals():
    """Frame 6's y >= 0 half at H = 0.06 m, mirrored: the body's area and volume within 1e-6
    of the manifold union's (the panels tile every face, the inner face's holes included), the
    volume positive (normals outward), more panels at a smaller H, every panel on y >= 0."""
    pytest.importorskip("gmsh")
    _, parts, body = _frame()
    g = GF.frame_geometry(parts)
    counts = []
    for H in (0.06, 0.05):
        v, f = GF.half_frame(g, H)
        c = GF.check(v, f, body)
        assert abs(c["area"]) < 1e-6 and abs(c["volume"]) < 1e-6
        assert v[:, 1].min() >= 0.0
        counts.append(c["faces"])
    assert counts[1] > counts[0]


def test_the_lone_plate_is_the_box():
    """The plate check's lone plate (0.3 x 0.4 x 0.01 m, thickness along y) at H = 0.06: the
    box's area and volume within 1e-9."""
    pytest.importorskip("gmsh")
    import trimesh

    v, f = GF.half_plate(GF.plate_geometry(0.3, 0.4, 0.01), 0.06)
    c = GF.check(v, f, trimesh.creation.box([0.3, 0.01, 0.4]))
    assert abs(c["area"]) < 1e-9 and abs(c["volume"]) < 1e-9


@pytest.mark.parametrize("seed", [1795971315, 1795948662, 1795919297, 1795939009, 1795960449,
                                  1795981340])
def test_the_stored_levels_refine_and_respect_the_mirror_plane(seed):
    """Each stored file (reference_tables/bem/graded_cad_frames_SEED.csv): per frame four or
    more levels, faces rising; the couplings the xOz plane forbids zero to rounding (below
    1e-12 of sqrt(A_ii A_jj): the half solve); every diagonal term positive."""
    from validation.graded_bodies import read

    path = BEM / f"graded_cad_frames_{seed}.csv"
    if not path.exists():
        pytest.skip(f"{path.name} not stored")
    forbidden = {(0, 1), (0, 3), (0, 5), (1, 2), (1, 4), (2, 3), (2, 5), (3, 4), (4, 5)}
    for k, (what, n, mats) in read(path).items():
        assert "frame" in what
        assert len(n) >= 4 and all(b > a for a, b in zip(n, n[1:]))
        for m in mats:
            assert np.all(np.diag(m) > 0)
            d = np.sqrt(np.diag(m))
            assert all(abs(m[i, j]) < 1e-12 * d[i] * d[j] for i, j in forbidden)
    with open(path) as fh:
        assert fh.readline().startswith("# python -m benchmarks.graded_cad_frames")
        assert next(csv.reader(fh)) == GF.HEADER
