"""The panel value's pair where the finest pair refines by less than Celik et al.'s r = 1.3
(stripcoef.hull.panel_error.finest_pair_under_refined; issue 32, frame32d)."""

import numpy as np
import pytest

from stripcoef.hull.panel_error import finest_pair_under_refined, ladder_extrapolation
from stripcoef.hull.remesh import MIN_FACE_RATIO


@pytest.mark.parametrize("counts, expected", [
    ((944, 1682, 3010, 3830), True),       # frame 22 of seed 1795919297: last r = 1.13
    ((926, 1690, 3212, 6866), False),      # every pair r >= 1.3
    ((400, 800, 1600, 3200), False),       # uniform halving
    ((1600, 2000, 2500, 3000), False),     # the nested pairs under r = 1.3 too
    ((944, 1682, 3010), False),            # three levels: the two finest
])
def test_rule_reads_celik_ratio_in_panels(counts, expected):
    assert finest_pair_under_refined(counts) is expected


def test_boundary_is_the_ratio_itself():
    n = 1000.0
    assert not finest_pair_under_refined((n / 4, n / 2, n, MIN_FACE_RATIO * n))
    assert finest_pair_under_refined((n / 4, n / 2, n, 0.999 * MIN_FACE_RATIO * n))


@pytest.mark.parametrize("p", [1.0, 4.0 / 3.0, 2.0])
def test_nested_pairs_exact_on_a_power_law_with_noise_free_levels(p):
    """phi_i = phi_0 + alpha h_i^p, h ~ N^-1/2: the nested pairs' value is phi_0 exactly and
    its change zero, whatever the finest pair's ratio."""
    counts = (944, 1682, 3010, 3830)
    phi0, alpha = 7.0, 3.0
    mats = [np.full((6, 6), phi0 + alpha * n ** (-p / 2)) for n in counts]
    a, err = ladder_extrapolation(mats, counts, p)
    np.testing.assert_allclose(a, phi0, rtol=1e-12)
    np.testing.assert_allclose(err, np.abs(mats[-1] - phi0), rtol=1e-9, atol=1e-12)


def test_unknown_value_pair_is_one_line_error():
    import trimesh

    from stripcoef.errors import InputError
    from stripcoef.hull.panels import panel_added_mass

    with pytest.raises(InputError, match="value_pair"):
        panel_added_mass(trimesh.creation.box(), rho=1000.0, value_pair="coarsest")
