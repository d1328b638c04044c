"""benchmarks.divergent_pair: Stern et al.'s convergence ratio on unequal refinement ratios."""

import numpy as np
import pytest

from benchmarks.divergent_pair import divergence_ratio, divergent_value


@pytest.mark.parametrize("order", [1.0, 4.0 / 3.0, 2.0])
def test_ratio_is_one_on_an_exact_power_law(order):
    counts = [834, 1478, 3084]                   # unequal ratios, as the remesher's levels
    values = [3.0 + 0.7 * n ** (-0.5 * order) for n in counts]
    assert divergence_ratio(counts, values, order) == pytest.approx(1.0, rel=1e-9)


def test_ratio_reads_the_three_finest_levels():
    counts = [500, 1478, 3084, 4008]
    values = [9.0, 4.0 + 0.5 * 1478 ** -0.5, 4.0 + 0.5 * 3084 ** -0.5, 4.0 + 0.5 * 4008 ** -0.5]
    assert divergence_ratio(counts, values, 1.0) == pytest.approx(1.0, rel=1e-12)


def test_divergent_terms_take_the_finest_level_and_no_other():
    counts = (1478, 3084, 4008)
    h = np.asarray(counts, float) ** -0.5
    base = np.diag([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
    levels = []
    for k in range(3):
        m = base * (1.0 + 0.1 * h[k] ** 2)       # every term converging faster than h ...
        m[2, 2] = 3.0 + [0.0, -0.01, -0.05][k]   # ... but heave's last change 4x the one before
        levels.append(m)
    value = base * 0.99
    out, mask = divergent_value({"levels": levels, "panels": counts, "formal_order": 1.0}, value)
    assert mask[2, 2] and mask.sum() == 1
    assert out[2, 2] == pytest.approx(2.95)
    np.testing.assert_allclose(np.delete(np.diag(out), 2), np.delete(np.diag(value), 2))
