"""The panel method's grid convergence study (issue 32): observed order and Roache's GCI on
seeded exact sequences, and the levels the panel method reports."""

import numpy as np
import pytest

from stripcoef.hull.convergence import (SAFETY_THREE_GRIDS, SAFETY_TWO_GRIDS,
                                        grid_convergence_index, observed_order, richardson)


def _sequence(p, counts, f0=2.0, c=3.0):
    h = np.asarray(counts, float) ** -0.5
    return [np.array([f0 + c * hk ** p]) for hk in h]


@pytest.mark.parametrize("p", [0.8, 1.0, 1.5, 2.0])
@pytest.mark.parametrize("counts", [(400, 800, 1600), (430, 770, 1710)])
def test_observed_order_is_exact_on_a_power_law(p, counts):
    f3, f2, f1 = _sequence(p, counts)
    h = np.asarray(counts, float) ** -0.5
    got = observed_order(f1, f2, f3, h[1] / h[2], h[0] / h[1])
    assert got[0] == pytest.approx(p, rel=1e-6)


def test_gci_three_levels_in_the_asymptotic_range_take_safety_1_25_and_the_formal_order():
    counts = (400, 800, 1600)
    levels = _sequence(2.0, counts)
    gci, order, safety = grid_convergence_index(levels, counts)
    assert order[0] == pytest.approx(2.0)
    assert safety[0] == SAFETY_THREE_GRIDS
    # with the exact order the band is 1.25 times the fine level's true error
    assert gci[0] == pytest.approx(1.25 * abs(levels[-1][0] - 2.0), rel=1e-6)


@pytest.mark.parametrize("p", [0.8, 1.0, 1.5])
def test_gci_outside_the_asymptotic_range_takes_safety_3_and_the_observed_order(p):
    # Oberkampf & Roy 2010, sec. 8.6.3.2: |p - p_f| > 0.1 p_f -> F_s = 3, p = observed
    counts = (400, 800, 1600)
    levels = _sequence(p, counts)
    gci, order, safety = grid_convergence_index(levels, counts)
    assert order[0] == pytest.approx(p, rel=1e-6)
    assert safety[0] == SAFETY_TWO_GRIDS
    assert gci[0] == pytest.approx(3.0 * abs(levels[-1][0] - 2.0), rel=1e-6)


def test_gci_order_within_ten_percent_counts_as_asymptotic():
    counts = (400, 800, 1600)
    _, order, safety = grid_convergence_index(_sequence(1.85, counts), counts)
    assert safety[0] == SAFETY_THREE_GRIDS and order[0] == 2.0
    _, order, safety = grid_convergence_index(_sequence(0.3, counts), counts)
    assert safety[0] == SAFETY_TWO_GRIDS and order[0] == pytest.approx(0.5)


def test_gci_order_capped_at_the_formal_order():
    counts = (400, 800, 1600)
    gci, order, safety = grid_convergence_index(_sequence(3.0, counts), counts)
    assert order[0] == pytest.approx(2.0)
    assert safety[0] == SAFETY_TWO_GRIDS


def test_gci_oscillating_or_two_levels_fall_back_to_safety_three():
    counts = (400, 800, 1600)
    lv = [np.array([1.0]), np.array([1.2]), np.array([1.1])]
    gci, order, safety = grid_convergence_index(lv, counts)
    assert safety[0] == SAFETY_TWO_GRIDS and order[0] == 2.0
    gci2, _, s2 = grid_convergence_index(lv[1:], counts[1:])
    assert s2[0] == SAFETY_TWO_GRIDS
    assert gci2[0] == pytest.approx(3.0 * 0.1 / (2.0 - 1.0))


def test_richardson_is_exact_for_1_over_n():
    a1, a2 = 5.0 + 7.0 / 800, 5.0 + 7.0 / 1600
    assert richardson(a1, a2, 800, 1600) == pytest.approx(5.0, rel=1e-12)


def test_panel_added_mass_reports_levels_error_and_convergence():
    trimesh = pytest.importorskip("trimesh")
    from stripcoef.hull.panels import panel_added_mass

    sphere = trimesh.creation.icosphere(subdivisions=3, radius=0.5)
    a, info = panel_added_mass(sphere, rho=1000.0, panels=400, family="input")
    # Lamb: half the displaced mass, of the polyhedron's volume (the panels see the polyhedron;
    # a near-sphere's added mass goes with its volume to first order)
    exact = 0.5 * 1000.0 * sphere.volume
    assert len(info["panels"]) >= 2 and info["panels"][-1] > info["panels"][0]
    assert info["error"].shape == (6, 6) and np.all(info["error"] >= 0)
    for i in range(3):
        assert abs(a[i, i] - exact) <= 0.01 * exact
    assert info["converged"] in (True, False)
    # every level's matrix, coarse to fine: the reported value is the Richardson value of the
    # two finest (1/N), symmetrised
    levels = info["levels"]
    assert len(levels) == len(info["panels"]) and all(m.shape == (6, 6) for m in levels)
    n = info["panels"]
    again = richardson(levels[-2], levels[-1], n[-2], n[-1])
    np.testing.assert_allclose(a, 0.5 * (again + again.T), rtol=1e-12, atol=1e-12 * abs(a).max())


def test_remesh_keeps_a_box_and_reaches_the_panels():
    pytest.importorskip("pymeshlab")
    trimesh = pytest.importorskip("trimesh")
    from stripcoef.hull import remesh
    from stripcoef.hull.bisection import enclosed_volume

    box = trimesh.creation.box([0.5, 0.4, 0.3])
    v, f = np.asarray(box.vertices), np.asarray(box.faces)
    out = remesh.remesh_family(v, f, [remesh.edge_for_panels(box.area, n) for n in (200, 400,
                                                                                    800)])
    assert out is not None
    levels, angle = out
    for (rv, rf), n in zip(levels, (200, 400, 800)):
        assert 0.7 * n <= len(rf) <= 1.4 * n
        assert enclosed_volume(rv, rf) == pytest.approx(0.06, rel=1e-6)
