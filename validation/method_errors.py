"""The measured errors of the method against the stored references
(reference_tables/method_errors/method_errors.csv, written by
``python -m scripts.make_method_uncertainty --measure``): read by the script that makes the
method-uncertainty table, by benchmarks/band_coverage.py and by the tests."""

from __future__ import annotations

import csv

from validation import ROOT

#: one row per compared term: strip value, reference value, error, the reference's source
ERRORS = ROOT / "reference_tables" / "method_errors" / "method_errors.csv"


def read_errors(path=ERRORS) -> list[dict]:
    """The rows of the errors file (a file written before the ``matrix`` column: added mass)."""
    with open(path) as fh:
        rows = list(csv.DictReader(ln for ln in fh if not ln.startswith("#")))
    for r in rows:
        r["matrix"] = r.get("matrix") or "added_mass"
        r["slenderness"] = r.get("slenderness") or ""
    return rows
