"""benchmarks.cad_seed_best on a stored fresh seed: its counts against the stored references
are the ones the CAD benchmark's own summary prints for that CSV (a known truth of the
stored run), and the edge-graded references replace exactly the terms they hold."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from benchmarks.cad_seed_best import best, model_rows, tally

ROOT = Path(__file__).resolve().parents[1]
BEM = ROOT / "reference_tables" / "bem"
MODEL = BEM / "cad_shapes_1795919297.csv"


def test_counts_against_the_stored_references_are_the_benchmarks():
    """The stored model rows' run (re-run with --references, stop 55) printed 232 of 240
    diagonal terms, 104 of 105 couplings within 5 %, 329 of 345 terms covered
    (reference_tables/bem/README.md, seed 1795919297)."""
    rows = model_rows(MODEL)
    assert len(rows) == 40
    text = tally(rows, *best(rows))
    assert "within 5 %: 232/240" in text
    assert "scale: 104/105" in text
    assert "covers the error: 329/345" in text


def test_graded_references_replace_only_their_terms():
    rows = model_rows(MODEL)
    stored, _ = best(rows)
    refs, source = best(rows, BEM / "cad_plates_graded_1795919297.csv",
                        BEM / "graded_coarse_1795919297.csv")
    assert {k for k, _, _ in source} == {3, 11, 14, 19, 23, 30}
    for k in rows:
        if k not in (3, 11, 14, 19, 23, 30):
            np.testing.assert_array_equal(refs[k], stored[k])
    # a plate's couplings keep the stored (3,000-face) values; its diagonal is graded
    off = ~np.eye(6, dtype=bool)
    np.testing.assert_array_equal(refs[19][off], stored[19][off])
    assert not np.allclose(np.diag(refs[19]), np.diag(stored[19]), rtol=0.01)


def test_finer_levels_replace_their_shapes_terms_and_yield_to_the_graded():
    """Seed 1795948662: cad_levels_fresh32f.csv holds four Capytaine levels of its shapes 8,
    21 and 25 (and of 1795939009's frame 8, another seed's rows); graded_cad_1795948662.csv
    an edge-graded reference of shape 21.  Shapes 8 and 25 take Eça & Hoekstra over their
    levels, 21 the edge-graded one, every other shape its stored (or graded plate) value."""
    from validation.cad_draws import read_frame_levels
    from validation.cad_shapes import fine_reference

    model = BEM / "cad_shapes_1795948662.csv"
    levels = BEM / "cad_levels_fresh32f.csv"
    rows = model_rows(model)
    stored, _ = best(rows)
    refs, source = best(rows, coarse=[BEM / "graded_cad_1795948662.csv"], levels=[levels],
                        seed=1795948662)
    assert {k for k, _, _ in source} == {8, 21, 25}
    assert source[(21, 3, 3)].startswith("graded polyhedron")
    assert source[(25, 2, 2)].startswith("Capytaine 2370-10842 faces")
    n, mats = read_frame_levels(levels, 1795948662)[25]
    expected, _, _ = fine_reference(n, mats)
    np.testing.assert_allclose(refs[25], 0.5 * (expected + expected.T), rtol=1e-12)
    for k in rows:
        if k not in (8, 21, 25):
            np.testing.assert_array_equal(refs[k], stored[k])
    assert set(read_frame_levels(levels, 1795939009)) == {8}


def test_finer_levels_need_the_seed():
    import pytest

    rows = model_rows(MODEL)
    with pytest.raises(ValueError, match="seed"):
        best(rows, levels=[BEM / "cad_frames_levels_frame32d.csv"])
