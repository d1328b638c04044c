r"""2D added mass per unit length of sections in an infinite fluid.

Every function returns per-unit-length values about the section's centre:
``m22`` (sway, motion along y) [kg/m], ``m33`` (heave, along z) [kg/m] and
``m44`` (roll about x) [kg m^2/m].  Symmetric sections have no couplings about
their centre; off-centre parts are shifted by the assembly.
"""

from __future__ import annotations

import numpy as np

from stripcoef.data import load_table
from stripcoef.fluid import RHO_SEAWATER as RHO   # the default density of every function


def circle(radius, *, rho=RHO):
    r"""Added mass per unit length of a circle translating in any direction.

    .. math:: m_{22} = m_{33} = \rho \pi a^2, \qquad m_{44} = 0

    Parameters
    ----------
    radius : float or array
        Circle radius a [m]
    rho : float
        Fluid density [kg/m^3]

    Returns
    -------
    float or array
        Added mass per unit length [kg/m]

    References
    ----------
    Newman, Marine Hydrodynamics (1977), sec. 4.13, table 4.2; DNV-RP-C205 table A-1.
    """
    return rho * np.pi * np.asarray(radius, dtype=float) ** 2


def ellipse(half_breadth, half_height, *, rho=RHO):
    r"""Added mass of an ellipse with half-axes b (along y) and h (along z).

    .. math::
        m_{22} = \rho\pi h^2,\qquad m_{33} = \rho\pi b^2,\qquad
        m_{44} = \frac{\rho\pi}{8}(b^2 - h^2)^2

    (translation: the half-axis normal to the motion squared; rotation about the centre).

    Parameters
    ----------
    half_breadth, half_height : float or array
        b and h [m]
    rho : float
        Fluid density [kg/m^3]

    Returns
    -------
    tuple of arrays
        m22 [kg/m], m33 [kg/m], m44 [kg m^2/m]

    References
    ----------
    Newman (1977), sec. 4.13, table 4.2 (ellipse); DNV-RP-C205 table A-1.
    """
    b = np.asarray(half_breadth, dtype=float)
    h = np.asarray(half_height, dtype=float)
    return rho * np.pi * h**2, rho * np.pi * b**2, rho * np.pi * (b**2 - h**2) ** 2 / 8.0


def flat_plate(half_width, *, rho=RHO):
    r"""Flat plate of width 2a moving normal to itself, and rotating about its centre.

    .. math:: m_n = \rho \pi a^2, \qquad m_{44} = \rho \pi a^4 / 8

    (the limit of :func:`ellipse` with a vanishing half-axis).

    Parameters
    ----------
    half_width : float or array
        a [m]

    Returns
    -------
    tuple
        m_normal [kg/m], m44 [kg m^2/m]

    References
    ----------
    Newman (1977), table 4.2; DNV-RP-C205 table A-1 (plate: C_A = 1).
    """
    a = np.asarray(half_width, dtype=float)
    return rho * np.pi * a**2, rho * np.pi * a**4 / 8.0


def rectangle_coefficient(a_over_b):
    r"""DNV added-mass coefficient :math:`C_A(a/b)` of a rectangle 2a (normal to motion) x 2b.

    Tabulated for 0.1 <= a/b <= 10 (src/stripcoef/data/rectangle_added_mass_dnv.csv,
    DNV-RP-C205 table A-1).  Beyond the table two documented limits apply instead of
    extrapolation:

    - a/b > 10 (a plate moving normal to itself): :math:`C_A = 1 + 1.4\,b/a`, tending to the
      exact flat-plate value 1 (Newman 1977, table 4.2) and equal to the table at a/b = 10;
    - a/b < 0.1 (a thin plate moving edgewise): :math:`C_A = C_A(0.1) = 2.23`.  The added mass
      :math:`C_A\rho\pi a^2` then vanishes with the thickness 2a, as the exact thin-ellipse
      value :math:`\rho\pi a^2` does; the table's end value is kept (the true coefficient
      grows only logarithmically with b/a).

    ``a_over_b`` [-]; returns C_A [-] (added mass per unit length
    :math:`C_A\rho\pi a^2` [kg/m]).
    """
    t = load_table("rectangle_added_mass_dnv")
    ratio = np.asarray(a_over_b, dtype=float)
    thin = ratio > 10.0
    out = np.empty_like(ratio)
    inside = ~thin
    if np.any(inside):
        out[inside] = t.interp(np.maximum(ratio[inside], 0.1), "C_A", log_x=True, what="a/b")
    if np.any(thin):
        out[thin] = 1.0 + 1.4 / ratio[thin]
    return out


def rectangle(half_breadth, half_height, *, rho=RHO):
    r"""Added mass of a 2b x 2h rectangle (DNV table).

    .. math::
        m_{22} = C_A(h/b)\,\rho\pi h^2,\qquad m_{33} = C_A(b/h)\,\rho\pi b^2,\qquad
        m_{44} = \beta(a_{max}/a_{min})\,\rho\pi a_{max}^4

    with C_A and beta from DNV-RP-C205 table A-1 (data/rectangle_added_mass_dnv.csv;
    beta is read on its a/b >= 1 branch with the larger half-side, which reproduces the
    flat-plate limit beta -> 1/8).

    Parameters
    ----------
    half_breadth, half_height : array
        b (along y), h (along z) [m]

    Returns
    -------
    tuple of arrays
        m22 [kg/m], m33 [kg/m], m44 [kg m^2/m]

    References
    ----------
    DNV-RP-C205 (2010), table A-1; Newman (1977), table 4.2 (square: C_A = 1.51).
    """
    b = np.atleast_1d(np.asarray(half_breadth, dtype=float))
    h = np.atleast_1d(np.asarray(half_height, dtype=float))
    m22 = rectangle_coefficient(h / b) * rho * np.pi * h**2
    m33 = rectangle_coefficient(b / h) * rho * np.pi * b**2
    amax, amin = np.maximum(b, h), np.minimum(b, h)
    t = load_table("rectangle_added_mass_dnv")
    ratio = amax / amin
    beta = np.where(ratio > 10.0, 0.125,
                    t.interp(np.minimum(ratio, 10.0), "beta", log_x=True, what="a/b"))
    m44 = beta * rho * np.pi * amax**4
    return m22, m33, m44


def circle_with_fins(radius, tip_radius, *, rho=RHO):
    r"""Circle of radius R with two symmetric fins reaching tip radius a (motion normal to fins).

    .. math::
        m_n = \rho\pi\left(a^2 - R^2 + \frac{R^4}{a^2}\right), \qquad
        m_{44} = \frac{2}{\pi}\rho a^4

    Along the fins the section behaves as the circle (:math:`\rho\pi R^2`).

    Parameters
    ----------
    radius : float or array
        Hull radius R [m]
    tip_radius : float or array
        Fin tip distance from the axis a >= R [m]

    Returns
    -------
    tuple
        m_normal [kg/m], m44 [kg m^2/m]

    References
    ----------
    Blevins, Formulas for Natural Frequency and Mode Shape (1979), table 14-2;
    Prestero (2001), MIT/WHOI thesis, sec. 3.4 (eqs. 3.20, 3.27), as re-implemented in
    ArizaWilmerUTAS/Semiempirical-coefficients-for-underwater-vehicles.
    The roll term is tagged "from memory" in shared/reference/formulas.md.
    """
    r = np.asarray(radius, dtype=float)
    a = np.asarray(tip_radius, dtype=float)
    return rho * np.pi * (a**2 - r**2 + r**4 / a**2), 2.0 / np.pi * rho * a**4
