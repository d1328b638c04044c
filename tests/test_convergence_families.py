"""Eça & Hoekstra's least squares with one error constant per grid family (the base install's
ladder of two nested pairs) on known truths: exact two-family power laws."""

from __future__ import annotations

import numpy as np
import pytest

from benchmarks.ladder_families import eca_hoekstra_families, ladder_least_squares_error
from stripcoef.hull.convergence import EH_SAFETY_GOOD, EH_SAFETY_POOR, eca_hoekstra

COUNTS = (400, 800, 1600, 3200)          # N_1 < 2N_1 < 4N_1 < 8N_1: pairs (1, 3) and (2, 4)
FAMILIES = (0, 1, 0, 1)


def two_pairs(p, c_a, c_b, limit=2.0):
    """phi(N) = limit + c N^(-p/2), c = c_a on the first pair, c_b on the second."""
    n = np.asarray(COUNTS, float)
    return limit + np.where(np.arange(4) % 2 == 0, c_a, c_b) * n ** (-p / 2)


@pytest.mark.parametrize("p", [1.0, 4.0 / 3.0, 2.0])
@pytest.mark.parametrize("c_b", [1.0, 0.3, -0.5])
def test_exact_two_pair_law_gives_the_limit_and_1_25_times_the_error(p, c_b):
    """Zero residual: sigma 0 < the data range, the observed order p in [0.5, 2.1), so U is
    F_s = 1.25 times the finest level's exact error (Eça & Hoekstra 2014 eq. 20)."""
    phi = two_pairs(p, 1.0, c_b)
    r = eca_hoekstra_families(COUNTS, phi, FAMILIES, p)
    assert r.extrapolated == pytest.approx(2.0, abs=1e-12)
    assert r.safety == EH_SAFETY_GOOD
    assert r.order == pytest.approx(p, rel=0.02)
    assert r.uncertainty == pytest.approx(EH_SAFETY_GOOD * abs(phi[-1] - 2.0), rel=1e-8)


def test_one_constant_fit_reads_two_constants_as_scatter():
    """The same data through the one-constant fit: a band several times wider."""
    phi = two_pairs(2.0, 1.0, 0.3)
    one = eca_hoekstra(COUNTS, phi).uncertainty
    two = eca_hoekstra_families(COUNTS, phi, FAMILIES, 2.0).uncertainty
    assert one > 5.0 * two


def test_an_order_out_of_range_takes_safety_3():
    phi = two_pairs(3.0, 1.0, 0.5)                 # observed 3: above 2.1
    r = eca_hoekstra_families(COUNTS, phi, FAMILIES, 2.0)
    assert r.safety == EH_SAFETY_POOR
    assert r.uncertainty >= abs(phi[-1] - 2.0)


def test_too_few_levels_and_equal_counts_are_refused():
    with pytest.raises(ValueError, match="at least 4 levels"):
        eca_hoekstra_families(COUNTS[:3], two_pairs(2.0, 1.0, 1.0)[:3], (0, 1, 0), 2.0)
    with pytest.raises(ValueError, match="equal cell counts"):
        eca_hoekstra_families((400, 400, 1600, 3200), two_pairs(2.0, 1.0, 1.0), FAMILIES, 2.0)


def test_ladder_band_of_a_matrix_is_symmetric_and_covers_exact_laws():
    true = np.diag([10.0, 20.0, 30.0, 1.0, 2.0, 3.0]) + 0.5 * (np.eye(6, k=1) + np.eye(6, k=-1))
    c = np.full((6, 6), 40.0)
    levels = [true + c * (1.0 if k % 2 == 0 else 0.4) * n ** -1.0
              for k, n in enumerate(COUNTS)]
    from stripcoef.hull.panel_error import ladder_extrapolation

    a, _ = ladder_extrapolation(levels, COUNTS, 2.0)
    np.testing.assert_allclose(a, true, atol=1e-12)
    band = ladder_least_squares_error(levels, COUNTS, a, 2.0)
    np.testing.assert_allclose(band, band.T)
    assert np.all(band >= np.abs(levels[-1] - true) - 1e-12)
    with pytest.raises(ValueError, match="four levels"):
        ladder_least_squares_error(levels[:3], COUNTS[:3], a, 2.0)
