"""The least-squares grid uncertainty of Eça & Hoekstra (2014) (stripcoef.hull.convergence,
issue 32): exact power laws of known order, the paper's choice of fits and safety factors,
and the coverage of seeded noisy sequences."""

import numpy as np
import pytest

from stripcoef.hull.convergence import (EH_SAFETY_GOOD, EH_SAFETY_POOR, eca_hoekstra,
                                        eca_hoekstra_terms)

COUNTS = (1500, 3000, 6000, 12000)          # coarse to fine, h ~ N^-1/2 (a refinement ratio
                                            # of sqrt 2 per level, as the stored BEM levels)


def _levels(p, counts=COUNTS, f0=2.0, c=3.0):
    h = (counts[-1] / np.asarray(counts, float)) ** 0.5      # h_1 = 1 at the finest
    return f0 + c * h ** p, h


@pytest.mark.parametrize("p", [0.6, 1.0, 1.5, 2.0])
def test_exact_power_law_in_range_recovers_order_limit_and_the_gci_band(p):
    """0.5 <= p <= 2, no scatter: the free-order fit, the exact limit and order, F_s = 1.25
    and U = 1.25 |phi_1 - phi_0| (sec. 3: the procedure then reduces to the GCI)."""
    phi, _ = _levels(p)
    r = eca_hoekstra(COUNTS, phi)
    assert r.fit == "p" or (p == 2.0 and r.fit == "2")     # p a hair above 2: delta_2
    assert r.order == pytest.approx(p, rel=1e-5)
    assert r.extrapolated == pytest.approx(2.0, abs=1e-7)
    assert r.safety == EH_SAFETY_GOOD
    assert r.sigma == pytest.approx(0.0, abs=1e-8)
    assert r.uncertainty == pytest.approx(1.25 * 3.0, rel=1e-5)


def test_level_order_and_scale_do_not_matter():
    phi, _ = _levels(1.3)
    a = eca_hoekstra(COUNTS, phi)
    b = eca_hoekstra([10 * n for n in COUNTS[::-1]], phi[::-1])
    assert a.uncertainty == pytest.approx(b.uncertainty, rel=1e-9)
    assert a.extrapolated == pytest.approx(b.extrapolated, rel=1e-9)


def test_order_above_two_takes_the_fixed_order_fits_and_safety_3():
    """p > 2: the best of delta_1, delta_2 with and without weights (App. A), F_s = 3."""
    phi, _ = _levels(3.0)
    r = eca_hoekstra(COUNTS, phi)
    assert r.order == pytest.approx(3.0, rel=1e-4)
    assert r.fit in {"1", "2"}
    assert r.safety == EH_SAFETY_POOR
    assert abs(phi[-1] - 2.0) <= r.uncertainty          # still covers the exact error


def test_order_below_half_takes_the_three_alternatives_and_safety_3():
    phi, _ = _levels(0.3, c=0.5)
    r = eca_hoekstra(COUNTS, phi)
    assert r.order == pytest.approx(0.3, rel=1e-4)
    assert r.fit in {"1", "2", "12"}
    assert r.safety == EH_SAFETY_POOR


def test_an_extra_fixed_order_joins_the_alternatives():
    """A sequence exactly of order 0.4 (< 0.5): with 0.4 among the extra orders that fit has
    no scatter, is chosen, and extrapolates to the limit."""
    phi, _ = _levels(0.4)
    r = eca_hoekstra(COUNTS, phi, extra_orders=(0.4,))
    assert r.fit == "0.4"
    assert r.extrapolated == pytest.approx(2.0, abs=1e-9)
    assert r.uncertainty == pytest.approx(3.0 * abs(phi[-1] - 2.0), rel=1e-6)


def test_diverging_data_are_anomalous():
    """Levels moving away faster on refinement (p < 0): no free-order fit is kept
    (sec. 2.2), the alternatives and F_s = 3."""
    h = (COUNTS[-1] / np.asarray(COUNTS, float)) ** 0.5
    phi = 1.0 + 0.5 / h
    r = eca_hoekstra(COUNTS, phi)
    assert np.isnan(r.order)
    assert r.fit in {"1", "2", "12"}
    assert r.safety == EH_SAFETY_POOR


def test_scatter_beyond_the_data_range_inflates_the_band():
    """sigma >= Delta_phi: U = 3 (sigma/Delta_phi)(eps + sigma + |phi_1 - fit|) (eq. 21)."""
    counts = (750, 1500, 3000, 6000, 12000)
    phi = np.array([1.00, 1.10, 0.95, 1.08, 0.97])
    r = eca_hoekstra(counts, phi)
    assert r.data_range == pytest.approx(0.15 / 4)
    if r.sigma >= r.data_range:
        want = 3.0 * r.sigma / r.data_range * (r.error + r.sigma + r.residual)
    else:
        want = r.safety * r.error + r.sigma + r.residual
    assert r.uncertainty == pytest.approx(want, rel=1e-12)
    assert r.uncertainty > 0.05


def test_constant_levels_have_no_uncertainty_and_three_levels_are_refused():
    r = eca_hoekstra(COUNTS, [4.0] * 4)
    assert r.uncertainty == 0.0 and r.extrapolated == 4.0
    with pytest.raises(ValueError, match="at least 4"):
        eca_hoekstra(COUNTS[1:], [1.0, 2.0, 3.0])


def test_seeded_noisy_sequences_are_covered_about_as_the_paper_claims():
    """phi_0 + c h^p with p drawn in [0.8, 2] and scatter of 1 % of the finest level's error
    (seeded): U covers the finest level's true error in at least 90 % of the draws (the
    procedure aims at 95 %, eq. 18), and never by a band of more than 10x the error."""
    rng = np.random.default_rng(20141)
    counts = (750, 1500, 3000, 6000, 12000)
    h = (counts[-1] / np.asarray(counts, float)) ** 0.5
    covered, ratio = 0, []
    for _ in range(200):
        p = rng.uniform(0.8, 2.0)
        c = rng.choice([-1.0, 1.0]) * rng.uniform(0.5, 2.0)
        phi = 1.0 + c * h ** p + 0.01 * abs(c) * rng.normal(size=h.size)
        r = eca_hoekstra(counts, phi)
        err = abs(phi[-1] - 1.0)
        covered += err <= r.uncertainty
        ratio.append(r.uncertainty / err)
    assert covered >= 180
    assert np.median(ratio) < 10


def test_terms_of_a_matrix():
    rng = np.random.default_rng(3)
    limit, c = rng.normal(size=(6, 6)), rng.normal(size=(6, 6))
    mats = [limit + c * 1000.0 / n for n in COUNTS]             # order 2 in h
    ref, band, order, safety = eca_hoekstra_terms(COUNTS, mats)
    np.testing.assert_allclose(ref, limit, atol=1e-8)
    np.testing.assert_allclose(order, 2.0, rtol=1e-4)
    np.testing.assert_allclose(band, 1.25 * np.abs(mats[-1] - limit), rtol=1e-4, atol=1e-10)
    assert np.all(safety == EH_SAFETY_GOOD)


@pytest.mark.parametrize("p, covers", [(0.2, False), (0.3, False), (0.35, True), (0.45, True),
                                       (2.5, True), (4.0, True)])
def test_the_band_on_exact_power_laws_out_of_range(p, covers):
    """Out of [0.5, 2] the fixed orders 1, 2 and 1 & 2 take over: with F_s = 3 they cover an
    exact sequence's error from p of about 0.35 up, but not a slower one (p = 0.2, 0.3:
    delta_12 extrapolates too little), a limit of the procedure stated in the docstring."""
    phi, _ = _levels(p, c=0.7, f0=1.0)
    r = eca_hoekstra(COUNTS, phi)
    assert r.safety == EH_SAFETY_POOR
    assert bool(abs(phi[-1] - 1.0) <= r.uncertainty) == covers


def test_least_squares_band_is_eca_hoekstra_per_term_symmetric_and_covers_exact_laws():
    """The panel method's band over four levels or more (convergence.least_squares_band):
    each term's U is eca_hoekstra's of that term's sequence (upper triangle, mirrored), and
    on exact power laws of seeded orders in [0.6, 2] it covers the finest level's error
    with F_s = 1.25; a term constant over the levels (a coupling zero by symmetry) has none."""
    from stripcoef.hull.convergence import least_squares_band

    rng = np.random.default_rng(5)
    counts = (400, 800, 1600, 3200)
    orders = rng.uniform(0.6, 2.0, (3, 3))
    limits = rng.uniform(1.0, 5.0, (3, 3))
    h = (counts[-1] / np.asarray(counts, float)) ** 0.5
    mats = [limits + 0.3 * hk ** orders for hk in h]
    for m in mats:
        m[0, 2] = m[2, 0] = 0.0
    band, order, safety = least_squares_band(counts, mats)
    assert np.array_equal(band, band.T) and band[0, 2] == 0.0
    for i, j in ((0, 0), (0, 1), (1, 2), (2, 2)):
        r = eca_hoekstra(counts, [m[i, j] for m in mats])
        assert band[i, j] == pytest.approx(r.uncertainty, rel=1e-12)
        assert order[i, j] == pytest.approx(orders[i, j], rel=1e-4)
        assert safety[i, j] == EH_SAFETY_GOOD
        assert band[i, j] >= abs(mats[-1][i, j] - limits[i, j])
