"""The estimate rules of benchmarks.ladder_estimate_rules on exact power laws (known truths)."""

from __future__ import annotations

import numpy as np
import pytest

from benchmarks.ladder_estimate_rules import FS_KNOWN_ORDER, RULES, XS_FS1, rules

COUNTS = (400, 800, 1600, 3200)          # N_1 < 2N_1 < 4N_1 < 8N_1: two pairs, h halved
TRUE = np.diag([10.0, 20.0, 30.0, 1.0, 2.0, 3.0]) + 0.5 * (np.eye(6, k=1) + np.eye(6, k=-1))
C = np.full((6, 6), 40.0)


def exact(p: float):
    """Levels L(N) = A_0 + C N^(-p/2) [kg, kg m, kg m^2]: the error of order p in h ~ N^-1/2."""
    return [TRUE + C * n ** (-p / 2) for n in COUNTS]


@pytest.mark.parametrize("p", [1.0, 4.0 / 3.0, 2.0])
def test_every_rule_extrapolates_an_exact_power_law_of_the_formal_order(p):
    out = rules(exact(p), COUNTS, p)
    assert set(out) == set(RULES)
    for value, error, warned_on in out.values():
        np.testing.assert_allclose(value, TRUE, rtol=1e-10, atol=1e-10)
        assert np.all(error >= 0.0) and np.all(warned_on >= 0.0)


@pytest.mark.parametrize("p", [1.0, 2.0])
def test_step_change_and_gci_rules_on_an_exact_power_law(p):
    """The change between the pairs' extrapolations is zero, so the default and Richardson's
    reading are the step |A - L_4| = C N_4^(-p/2); Roache's index of the finer pair,
    F_s |L_4 - L_2|/(2^p - 1), is F_s times the step, moved to A by the step."""
    step = C * COUNTS[3] ** (-p / 2)
    out = rules(exact(p), COUNTS, p)
    np.testing.assert_allclose(out[RULES[0]][1], step, rtol=1e-8)
    np.testing.assert_allclose(out[RULES[1]][1], step, rtol=1e-8)
    np.testing.assert_allclose(out[RULES[2]][1], (1.0 + FS_KNOWN_ORDER) * step, rtol=1e-8)


@pytest.mark.parametrize("p", [1.0, 2.0])
def test_xing_stern_and_the_bounded_gci_on_an_exact_power_law(p):
    """The three finest levels of an exact law of the formal order: the observed order is p
    (P = 1), Richardson's error of the finest level is the step, so Xing & Stern's U is
    F_S1 = 1.6 times it and Roache's bounded index 1.25 times it, each moved to A by the
    step; the split rules show Eça & Hoekstra's band and warn on the default's estimate."""
    step = C * COUNTS[3] ** (-p / 2)
    out = rules(exact(p), COUNTS, p)
    np.testing.assert_allclose(out["Xing & Stern FS, three finest"][1],
                               (1.0 + XS_FS1) * step, rtol=1e-6)
    np.testing.assert_allclose(out["GCI F_s 1.25, p = min(observed, formal)"][1],
                               (1.0 + FS_KNOWN_ORDER) * step, rtol=1e-6)
    split = out["E&H U shown, warn step + change (default)"]
    np.testing.assert_allclose(split[1], out["Eça & Hoekstra"][1], rtol=1e-12)
    np.testing.assert_allclose(split[2], out[RULES[0]][1], rtol=1e-12)


def test_the_change_read_by_richardson_is_larger_than_the_change():
    """Levels of a lower order than the formal one: the pairs' extrapolations differ, and
    the change over r^p - 1 (r = sqrt 2, p = 2: divided by 1) is not below the default."""
    levels = exact(1.0)
    out = rules(levels, COUNTS, 2.0)
    assert np.all(out[RULES[1]][1] >= out[RULES[0]][1] - 1e-12)
    assert np.all(out[RULES[0]][1] > 0.0)
