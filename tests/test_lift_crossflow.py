"""The body's non-linear (viscous cross-flow) term at drift against its published forms
(issue 34): Allen & Perkins 1951 (NACA Report 1048) over the whole hull, as the strips' D_Q
holds it, against USAF DATCOM sec. 4.2.1.2's placement behind the separation station and
Allen & Perkins's subcritical c_dc = 1.2, on Roddy's (1990) Appendix B drift curves
(validation.lift.crossflow_variants)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from validation.lift import FT, hull_crossflow_integrals, val


@pytest.mark.slow
def test_hull_crossflow_is_allen_perkins_over_the_whole_hull():
    """The bare hull's quadratic cross-flow force at drift is 1/2 rho U^2 eta c_dc sin^2 beta
    times the whole planform (each strip at its station), eta c_dc = C_D(Re_D) kappa of the
    DNV circle on the supercritical branch (Re_D 1.49e6): 0.487 x 0.816; its moment about
    Roddy's point is the planform's (centroid 0.02 m aft of it)."""
    from validation.lift import drift_force_parts
    h = hull_crossflow_integrals("datcom")
    lbp = FT * val("t1.L_BP")
    s2 = math.sin(math.radians(12.0)) ** 2
    y, n = drift_force_parts(3, 12.0, "datcom")["crossflow"]
    assert y == pytest.approx(h["model"] * h["whole"][0] * s2 / lbp ** 2, rel=0.02)
    assert n == pytest.approx(h["model"] * h["whole"][1] * s2 / lbp ** 3, abs=5e-6)
    assert abs(n) < 0.01 * 0.00220          # < 1 % of Roddy's N'(12 deg), 0.00220
    assert h["model"] == pytest.approx(0.487 * 0.816, rel=0.01)
    assert h["subcritical"] == pytest.approx(1.2 * 0.667, rel=0.01)
    assert abs(h["whole"][1] / h["whole"][0]) < 0.03          # centroid [m] from the point


@pytest.mark.slow
def test_crossflow_behind_the_station_is_a_small_share():
    """DATCOM's placement (behind x_0) keeps 8.4 % of the planform under Hopkins's station
    (0.823 l) and 2.4 % under Stratford's (0.902 l), and its moment is stabilising."""
    for method, x0, share in (("datcom", 0.823, 0.084), ("stratford", 0.902, 0.024)):
        h = hull_crossflow_integrals(method)
        assert h["x0_fraction"] == pytest.approx(x0, abs=0.002)
        assert h["aft"][0] / h["whole"][0] == pytest.approx(share, abs=0.003)
        assert h["aft"][1] < 0.0


@pytest.mark.slow
def test_no_crossflow_placement_removes_the_stratford_moment_excess():
    """The drift points within 20 % (of 40) per placement, as docs/validation.md states them,
    and the finding: Stratford's N'(beta) at 12-18 deg stays 1.27-1.51 times the measured under
    every placement and c_dc, so its excess is not the viscous term's."""
    from validation.lift import crossflow_variant_checks, crossflow_variants
    assert crossflow_variant_checks() == {
        ("datcom", "model"): (21, 40), ("datcom", "subcritical"): (16, 40),
        ("datcom", "aft"): (23, 40), ("datcom", "aft_subcritical"): (23, 40),
        ("stratford", "model"): (20, 40), ("stratford", "subcritical"): (6, 40),
        ("stratford", "aft"): (11, 40), ("stratford", "aft_subcritical"): (13, 40)}
    ratios = np.array([c["model"] / c["measured"] for c in crossflow_variants()
                       if c["method"] == "stratford" and c["q"] == "N" and c["beta"] >= 12.0])
    assert ratios.size == 4 * 3 * 4
    assert np.all((ratios > 1.25) & (ratios < 1.55)), ratios
