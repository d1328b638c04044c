"""benchmarks.cad_shapes' stored runs (issue 32): a ``--references`` re-run keeps the
references' own uncertainty and solve time, and what a file does not hold is unknown, never 0."""

import csv

import numpy as np
import pytest

from benchmarks import cad_shapes as CS
from validation import ROOT, read_stored_run

REFS = ROOT / "reference_tables" / "bem" / "cad_shapes_1375923287.csv"
STORED = ROOT / "reference_tables" / "bem" / "cad_shapes.csv"
#: the reference's columns a re-run must give back as the stored run wrote them
REF_COLUMNS = ("bem", "bem_faces", "t_bem_s", "bem_richardson_step_rel", "bem_gci_rel")


def _write_run(path, rows):
    """``rows`` written as a stored run of benchmarks.cad_shapes (a command line, the header)."""
    with open(path, "w", newline="") as fh:
        fh.write("# a command\n")
        w = csv.DictWriter(fh, fieldnames=CS.HEADER)
        w.writeheader()
        w.writerows(rows)
    return path


def _rerun_rows(refs_path):
    """The CSV rows a ``--references refs_path`` re-run writes, the model taken from the
    stored rows themselves (its value and estimated error): the reference side of
    :func:`benchmarks.cad_shapes.run_one` and :func:`~benchmarks.cad_shapes.csv_rows`."""
    _, rows = read_stored_run(refs_path)
    refs = CS.stored_references(refs_path)
    out = []
    for k, x in refs.items():
        terms = [r for r in rows if r["shape"] == str(k)]
        ours, est = np.zeros((6, 6)), np.zeros((6, 6))
        d = np.sqrt(np.abs(np.diag(x["ref"])))
        for t in terms:
            i, j = int(t["i"]), int(t["j"])
            ours[i, j] = ours[j, i] = float(t["model"])
            est[i, j] = est[j, i] = float(t["estimated_error_rel"]) * d[i] * d[j]
        head = terms[0]
        r = dict(k=k, family=head["family"], what=head["what"], how=head["how"],
                 panels=head["panels"], bem_faces=x["counts"], mirrors=head["mirrors"],
                 unconverged=head["warned"] == "1", t_model=1.0, c_model=1.0,
                 t_bem=x["t_bem"],
                 rows=CS.compare_terms(ours, est, x["ref"], x["gci"], x["step"]))
        out += [dict(zip(CS.HEADER, map(str, row))) for row in CS.csv_rows(r)]
    return rows, out


def test_a_references_rerun_keeps_the_references_uncertainty_and_time():
    """Every shape of the stored references' run: the re-run's reference columns (the value,
    its grid convergence index, its Richardson step, the solves' time) are the file's, and
    the root-sum-square coverage is known on every term."""
    stored, again = _rerun_rows(REFS)
    stored = [r for r in stored if not r["what"].startswith("FAILED")]
    assert len(again) == len(stored) > 600
    for a, b in zip(stored, again):
        assert (a["shape"], a["i"], a["j"]) == (b["shape"], b["i"], b["j"])
        for c in REF_COLUMNS:
            assert float(a[c].split("/")[0]) == pytest.approx(float(b[c].split("/")[0]),
                                                               rel=2e-3, abs=1e-6), (c, a, b)
        assert b["covered_with_bem_gci"] in ("0", "1")
    diag = [float(b["bem_gci_rel"]) for b in again if b["i"] == b["j"]]
    assert min(diag) > 0 and max(float(b["t_bem_s"]) for b in again) > 10.0


def test_a_lost_band_reads_back_as_unknown_never_zero(tmp_path):
    """A file whose reference band and time are empty or the all-zero cells of an earlier
    re-run: the bands and time read back as NaN and are written as empty cells; the
    root-sum-square coverage is then unknown (empty), not counted."""
    _, rows = read_stored_run(REFS)
    rows = [r for r in rows if r["shape"] in ("0", "1")]
    for r in rows:
        if r["shape"] == "0":
            r.update(bem_gci_rel="0", bem_richardson_step_rel="0", t_bem_s="0.000")
        else:
            r.update(bem_gci_rel="", bem_richardson_step_rel="", t_bem_s="")
    path = _write_run(tmp_path / "lost.csv", rows)
    refs = CS.stored_references(path)
    for x in refs.values():
        assert np.isnan(x["t_bem"]) and np.isnan(x["gci"]).all() and np.isnan(x["step"]).all()
    _, again = _rerun_rows(path)
    assert all(b[c] == "" for b in again for c in ("t_bem_s", "bem_gci_rel",
                                                   "bem_richardson_step_rel",
                                                   "covered_with_bem_gci"))
    assert CS.vv_count([{"covered_vv": None}, {"covered_vv": True}]) == (
        "1 of 1 (100 %); 1 terms' reference band unknown")


def test_the_stored_rerun_holds_its_references_uncertainty():
    """The model rows of docs/validation.md's section (cad_shapes.csv, a --references re-run)
    carry the references' band, step and solve time of cad_shapes_1375923287.csv."""
    _, rows = read_stored_run(STORED)
    _, refs = read_stored_run(REFS)
    by = {(r["shape"], r["i"], r["j"]): r for r in refs}
    for r in rows:
        if r["what"].startswith("FAILED"):
            continue
        s = by[(r["shape"], r["i"], r["j"])]
        for c in REF_COLUMNS:
            assert float(r[c].split("/")[0]) == pytest.approx(float(s[c].split("/")[0]),
                                                               rel=2e-3, abs=1e-6), (c, r, s)


def test_the_section_says_unknown_where_the_file_has_no_reference_band(tmp_path, monkeypatch):
    """docs/validation.md's CAD-shape section on a re-run without the references' band and
    time: it says unknown; it never prints a 0 s solve or a 0.0 % reference band."""
    import validation.cad_shapes as V

    _, rows = read_stored_run(STORED)
    for r in rows:
        r.update(bem_gci_rel="", bem_richardson_step_rel="", t_bem_s="",
                 covered_with_bem_gci="")
    path = _write_run(tmp_path / "cad.csv", rows)
    monkeypatch.setattr(V, "DATA", path)
    monkeypatch.setattr(V, "fine_section", lambda: "")
    monkeypatch.setattr(V, "graded_section", lambda: "")
    text = V.section()
    assert "reference solves (all levels, the references' own run) unknown" in text
    assert "0.00 s" not in text and "the reference's 0.0 %" not in text
    assert "Richardson step (finest BEM level to the extrapolation) is unknown" in text
    assert "covers an unknown number of terms" in text


@pytest.mark.slow
def test_the_rerun_command_writes_the_stored_references_band(tmp_path):
    """``python -m benchmarks.cad_shapes --references`` end to end on the stored seed's first
    shape: its reference columns are the stored file's and its first line names both runs."""
    out = tmp_path / "rerun.csv"
    assert CS.main(["--seed", "1375923287", "--count", "1", "--references", str(REFS),
                    "--csv", str(out)]) == 0
    command, again = read_stored_run(out)
    _, stored = read_stored_run(REFS)
    stored = [r for r in stored if r["shape"] == "0"]
    assert "--references" in command and command.startswith("benchmarks/cad_shapes.py --seed")
    assert len(again) == len(stored) == 21
    for a, b in zip(stored, again):
        for c in REF_COLUMNS:
            assert a[c] == b[c], (c, a[c], b[c])
