"""2D section formulas against their closed forms and published tables."""

import numpy as np
import pytest

from stripcoef.errors import ExtrapolationWarning
from stripcoef.sections import added_mass as am
from stripcoef.sections import drag

RHO = 1000.0


def test_circle_is_rho_pi_a2():
    assert am.circle(0.5, rho=RHO) == pytest.approx(RHO * np.pi * 0.25, rel=1e-15)


def test_ellipse_translation_and_rotation():
    m22, m33, m44 = am.ellipse(1.0, 0.4, rho=RHO)
    assert m22 == pytest.approx(RHO * np.pi * 0.16)          # normal half-axis is h
    assert m33 == pytest.approx(RHO * np.pi * 1.0)
    assert m44 == pytest.approx(RHO * np.pi * (1.0 - 0.16) ** 2 / 8)


def test_ellipse_reduces_to_circle_and_plate():
    m22, m33, m44 = am.ellipse(0.3, 0.3, rho=RHO)
    assert m22 == pytest.approx(am.circle(0.3, rho=RHO)) and m44 == 0.0
    mn, m44p = am.flat_plate(1.0, rho=RHO)
    _, m33, m44 = am.ellipse(1.0, 1e-9, rho=RHO)
    assert m33 == pytest.approx(mn) and m44 == pytest.approx(m44p, rel=1e-12)


# DNV-RP-C205 table A-1: C_A for a/b (2a normal to the motion)
DNV = [(0.1, 2.23), (0.2, 1.98), (0.5, 1.70), (1.0, 1.51), (2.0, 1.36), (5.0, 1.21), (10.0, 1.14)]


@pytest.mark.parametrize("ratio,ca", DNV)
def test_rectangle_reproduces_dnv_table(ratio, ca):
    a = 0.2
    b = a / ratio
    m22, m33, _ = am.rectangle(b, a, rho=RHO)   # sway: normal half-side is h = a
    assert m22[0] / (RHO * np.pi * a**2) == pytest.approx(ca, abs=1e-12)


def test_rectangle_square_symmetric_and_plate_limit():
    m22, m33, m44 = am.rectangle(0.5, 0.5, rho=RHO)
    assert m22 == pytest.approx(m33)
    assert m44[0] == pytest.approx(0.234 * RHO * np.pi * 0.5**4)
    # very thin rectangle: approaches the plate (C_A -> 1, beta -> 1/8)
    m22, m33, m44 = am.rectangle(1.0, 1e-4, rho=RHO)
    assert m33[0] / (RHO * np.pi) == pytest.approx(1.0, abs=2e-3)
    assert m44[0] == pytest.approx(RHO * np.pi / 8)


def test_circle_with_fins_limits():
    # fins of zero height: the circle
    m, _ = am.circle_with_fins(0.1, 0.1, rho=RHO)
    assert m == pytest.approx(am.circle(0.1, rho=RHO))
    # hull radius -> 0: a plate of half-width a
    m, _ = am.circle_with_fins(1e-6, 0.3, rho=RHO)
    assert m == pytest.approx(am.flat_plate(0.3, rho=RHO)[0], rel=1e-9)


def test_circle_drag_table_values_and_warning():
    assert drag.circle_cd(1.18e5) == pytest.approx(1.211)
    assert drag.circle_cd(5.25e5) == pytest.approx(0.408)
    with pytest.warns(ExtrapolationWarning, match="outside the table range"):
        assert drag.circle_cd(1e3) == pytest.approx(1.208)


def test_length_factor_regimes():
    assert drag.cylinder_length_factor(10, 1e5) == pytest.approx(0.68)
    assert drag.cylinder_length_factor(10, 3e5) == pytest.approx(0.82)


@pytest.mark.parametrize("re,blasius,ittc", [(1e5, 4.20e-3, 8.33e-3), (1e6, 1.33e-3, 4.69e-3),
                                            (1e7, 4.2e-4, 3.00e-3)])
def test_friction_lines(re, blasius, ittc):
    assert drag.blasius_cf(re) == pytest.approx(blasius, rel=3e-3)
    assert drag.ittc57_cf(re) == pytest.approx(ittc, rel=3e-3)


def test_friction_transition_is_continuous_and_bounded():
    below, reg1 = drag.friction_coefficient(drag.RE_CRITICAL * (1 - 1e-9))
    above, reg2 = drag.friction_coefficient(drag.RE_CRITICAL * (1 + 1e-9))
    assert (reg1, reg2) == ("laminar", "transitional")
    assert above == pytest.approx(below, rel=1e-6)
    for re in (1e6, 3e6, 1e7):
        cf, _ = drag.friction_coefficient(re)
        assert drag.blasius_cf(re) < cf < drag.ittc57_cf(re)


@pytest.mark.parametrize("ld,ff", [(4, 1.297), (6, 1.135), (10, 1.054)])
def test_hoerner_form_factor(ld, ff):
    assert drag.hoerner_form_factor(1 / ld) == pytest.approx(ff, abs=1e-3)
