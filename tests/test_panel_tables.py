"""2D panel method against the DNV-RP-C205 Table A-1 rectangle rows (published tables).

The rows and their tolerances are the shared reference table
reference_tables/dnv_rp_c205/table_a1_added_mass_2d.csv.
"""

import numpy as np
import pytest

from validation.reference import load_table
from stripcoef.sections.panel import added_mass_contours

RHO = 1000.0
PREFIX = "rectangle.a_over_b_"
ROWS = [r for r in load_table("dnv_rp_c205", "table_a1_added_mass_2d")
        if r["name"].startswith(PREFIX) and "inf" not in r["name"]]

#: Rows where the converged panel method (512-1024 panels, monotone convergence) differs from
#: the printed value by more than the printed precision (half a unit in the last digit).
PRINTED_MISMATCH = {
    "rectangle.a_over_b_5.C_A": "converged 1.217 vs printed 1.21 (table 0.6 % low)",
    "rectangle.a_over_b_0.1.C_A": "converged 2.222 vs printed 2.23 (table 0.4 % high)",
}
#: Rows outside even the row's own tolerance.
ROW_MISMATCH = {
    "rectangle.a_over_b_10.beta": (
        "printed 0.125 is the zero-thickness plate value rho pi a^4/8; a 10:1 rectangle converges "
        "to 0.1436, the same as its printed mirror a/b = 0.1 (0.147): the table breaks its own "
        "a/b <-> b/a symmetry here"),
}


def _value(row, panels=512):
    ab = float(row["name"][len(PREFIX):].rsplit(".", 1)[0])
    a, b = 1.0, 1.0 / ab                       # 2a normal to the motion (heave), 2b along it
    m = added_mass_contours([np.array([[-a, -b], [a, -b], [a, b], [-a, b]])], rho=RHO,
                            panels=panels)
    if row["name"].endswith(".C_A"):
        return m[1, 1] / (RHO * np.pi * a * a)
    return m[2, 2] / (RHO * np.pi * max(a, b) ** 4)          # beta on the larger half-side


def _params(mismatch, names=None):
    out = []
    for row in ROWS:
        if names and not row["name"].endswith(names):
            continue
        marks = [pytest.mark.xfail(strict=True, reason=mismatch[row["name"]])] \
            if row["name"] in mismatch else []
        out.append(pytest.param(row, marks=marks, id=row["name"]))
    return out


@pytest.mark.parametrize("row", _params(ROW_MISMATCH))
def test_rectangle_rows_within_their_tolerance(row):
    tol = row["atol"] + row["rtol"] * abs(row["value"])
    assert abs(_value(row) - row["value"]) <= tol


@pytest.mark.parametrize("row", _params(PRINTED_MISMATCH, ".C_A"))
def test_rectangle_translation_within_printed_precision(row):
    assert abs(_value(row) - row["value"]) <= 0.005


def test_square_converged_value():
    """Square: C_A = 1.5132 (m = 4.754 rho a^2, Newman 1977 table of 2D added masses)."""
    row = {"name": PREFIX + "1.C_A"}
    assert _value(row, 1024) == pytest.approx(4.754 / np.pi, abs=5e-4)
