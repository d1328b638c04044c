"""The frames' graded references on their mirror plane (benchmarks.frame_references, issue 32)
and their stored levels (reference_tables/bem/graded_frames.csv)."""

from __future__ import annotations

import csv

import numpy as np
import pytest
import trimesh

from benchmarks import frame_references as FR
from benchmarks import graded_mesher as GM
from validation import ROOT
from validation.graded_bodies import read

FRAMES = ROOT / "reference_tables" / "bem" / "graded_frames.csv"
#: the couplings the xOz mirror plane forbids (a body symmetric in y: sway, roll and yaw do
#: not couple with surge, heave and pitch)
FORBIDDEN = {(0, 1), (0, 3), (0, 5), (1, 2), (1, 4), (2, 3), (2, 5), (3, 4), (4, 5)}


def test_the_asymmetry_of_a_box_about_a_plane_off_its_centre_is_the_volume_not_shared():
    """A box 1 x 0.3 x 0.2 m from x = 0 to 1 mirrored in x = 0.4 spans x = -0.2 .. 0.8: it
    shares 0.8 of its volume, so 2 (1 - 0.8) = 0.4 is not shared; about its centre, none (to manifold3d's float32 precision)."""
    box = trimesh.creation.box([1.0, 0.3, 0.2])
    box.apply_translation([0.5, 0.0, 0.0])
    assert FR.asymmetry(box, 0, 0.4) == pytest.approx(0.4, rel=1e-6)   # manifold3d: float32
    assert abs(FR.asymmetry(box, 0, 0.5)) < 1e-6
    assert set(FR.mirror_planes(box)) == {0, 1, 2}


def test_the_vehicle_files_surface_has_the_xoz_mirror_plane_only():
    """geometry/bluerov2_heavy.stl: symmetric in y = 0 to manifold3d's precision (the volume
    not shared below 1e-6), fore-aft and top-bottom not (the thrusters at x = +0.1355 and
    -0.1475 m, the tubes above the frame's middle)."""
    body = FR.vehicle_surface()
    planes = FR.mirror_planes(body)
    assert set(planes) == {1}
    assert abs(planes[1][0]) < 1e-9
    c = np.asarray(body.center_mass, float)
    assert FR.asymmetry(body, 0, float(c[0])) > 0.1
    assert FR.asymmetry(body, 2, float(c[2])) > 0.1


def test_the_memory_rule_refuses_a_level_over_eight_gigabytes():
    """24 N^2 bytes + 0.5 GB (S and K complex128, K's LU blocks): a 15,000-face level fits 8 GB,
    the vehicle file's 18,210-face level (measured 8.05 GB) does not."""
    assert GM.predicted_gb(15000) < FR.MAX_GB < GM.predicted_gb(18210)


@pytest.mark.slow
def test_the_symmetric_solve_equals_the_full_solve_of_the_same_panels():
    """A box with a block on top at one end (mirror-symmetric in y only), its graded y >= 0
    half solved by Capytaine on the xOz plane and as one mesh (the same panels merged): every
    term within 2e-4 of sqrt(A_ii A_jj) (the full solve's own asymmetry: its couplings that the
    plane forbids come out at about 1e-4), those couplings exactly zero in the symmetric
    solve, which is also cheaper."""
    pytest.importorskip("capytaine")
    pytest.importorskip("gmsh")
    body = trimesh.boolean.union(
        [trimesh.creation.box([0.4, 0.3, 0.2]),
         trimesh.creation.box([0.1, 0.1, 0.1], transform=trimesh.transformations.
                              translation_matrix([0.15, 0.0, 0.12]))], engine="manifold")
    assert set(FR.mirror_planes(body)) == {1}
    v, f = GM.graded_mesh(body, 0.1, mirror=True)
    half, _ = FR.solve_half(v, f)
    whole, _ = FR.solve_half(v, f, full=True)
    d = np.sqrt(np.diag(whole))
    scale = np.outer(d, d)
    assert np.max(np.abs(half - whole) / scale) < 2e-4
    for i, j in FORBIDDEN:
        assert abs(half[i, j]) <= 1e-12 * scale[i, j]
        assert abs(whole[i, j]) < 2e-4 * scale[i, j]


@pytest.mark.skipif(not FRAMES.exists(), reason="no stored graded frame levels")
def test_the_stored_frame_levels_refine_keep_the_mirror_and_give_a_reference():
    """graded_frames.csv: its command and Capytaine's version first, four levels or more whose
    faces and H refine, the forbidden couplings zero, and a reference (Eça & Hoekstra) with a
    positive definite matrix and a finite band, compared with the stored model rows."""
    with open(FRAMES, newline="") as fh:
        first = fh.readline()
        rows = list(csv.DictReader(fh))
    assert first.startswith("# python -m benchmarks.frame_references") and "Capytaine" in first
    for name, (_, faces, mats) in read(FRAMES).items():
        assert len(faces) >= 4 and faces == sorted(set(faces)), name
        hs = [float(r["m"]) for r in rows if r["shape"] == name and r["i"] == r["j"] == "0"]
        assert hs == sorted(hs, reverse=True)
        for a in mats:
            for i, j in FORBIDDEN:
                assert abs(a[i, j]) <= 1e-9 * np.sqrt(a[i, i] * a[j, j])
    out = FR.compare(FRAMES)
    diag = [r for r in out if r["i"] == r["j"]]
    assert len(diag) == 12                                   # two installs, six terms
    assert all(r["graded"] > 0 and np.isfinite(r["band"]) for r in diag)
