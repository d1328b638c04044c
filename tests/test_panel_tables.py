"""2D panel method against the DNV-RP-C205 rectangle table (published tables)."""

import csv
from pathlib import Path

import numpy as np
import pytest

from stripcoef.sections.panel import added_mass_contours

TABLE = Path(__file__).resolve().parents[1] / "reference_tables" / "dnv_rp_c205" / "table_a1_rectangle.csv"
ROWS = [r for r in csv.DictReader(line for line in TABLE.open() if not line.startswith("#"))]
#: Printed precision of the table (3 significant digits).
TOL = 0.005
#: Rows where the converged panel method (1024 panels, monotone convergence) differs from the
#: printed value by more than its rounding.
KNOWN_MISMATCH = {
    5.0: "converged panel value 1.217 vs printed 1.21 (table after Wendel 1950 is 0.6 % low)",
    0.1: "converged panel value 2.222 vs printed 2.23 (table is 0.4 % high)",
}


def _ca(a_over_b, panels):
    a = 1.0
    b = a / a_over_b
    rect = np.array([[-a, -b], [a, -b], [a, b], [-a, b]])
    return added_mass_contours([rect], rho=1000.0, panels=panels)[1, 1] / (1000.0 * np.pi * a * a)


def _params():
    out = []
    for row in ROWS:
        ab, ca = float(row["a_over_b"]), float(row["C_A"])
        marks = []
        if ab in KNOWN_MISMATCH:
            marks = [pytest.mark.xfail(strict=True, reason=KNOWN_MISMATCH[ab])]
        out.append(pytest.param(ab, ca, marks=marks, id=f"a/b={ab:g}"))
    return out


@pytest.mark.parametrize("a_over_b,ca", _params())
def test_rectangle_table(a_over_b, ca):
    assert abs(_ca(a_over_b, 512) - ca) <= TOL


def test_square_converged_value():
    """Square: C_A = 1.5132 (m = 4.754 rho a^2, Newman 1977 table of 2D added masses)."""
    assert _ca(1.0, 1024) == pytest.approx(4.754 / np.pi, abs=5e-4)
