r"""Hull-level (3D) formulas: Lamb's spheroid factors, axial added mass, end corrections.

Strip theory integrates 2D sections and so has no axial added mass and no end
effects.  For a prolate spheroid with semi-axes a > b and eccentricity
:math:`e = \sqrt{1 - b^2/a^2}`:

.. math::
    \alpha_0 &= \frac{2(1-e^2)}{e^3}\left(\tfrac12\ln\frac{1+e}{1-e} - e\right), \qquad
    \beta_0 = \frac{1}{e^2} - \frac{1-e^2}{2e^3}\ln\frac{1+e}{1-e} \\
    k_1 &= \frac{\alpha_0}{2-\alpha_0},\quad k_2 = \frac{\beta_0}{2-\beta_0},\quad
    k' = \frac{e^4(\beta_0-\alpha_0)}{(2-e^2)\,[2e^2-(2-e^2)(\beta_0-\alpha_0)]}

giving :math:`m_{11} = k_1 \rho V`, :math:`m_{22} = m_{33} = k_2\rho V`,
:math:`m_{55} = m_{66} = k' \rho V (a^2+b^2)/5` (Lamb, Hydrodynamics, 6th ed., sec. 373;
Imlay 1961, DTMB report 1528; Fossen 2011, sec. 6.3.3; MSS ``imlay61.m``).
"""

from __future__ import annotations

import numpy as np


def lamb_k_factors(length_over_diameter):
    r"""Lamb's inertia coefficients (k1, k2, k') of a prolate spheroid with L/D >= 1.

    Parameters
    ----------
    length_over_diameter : float or array
        a/b = L/D [-]; L/D = 1 (sphere) gives (0.5, 0.5, 0).

    Returns
    -------
    tuple of float or array
        k1 (axial), k2 (transverse), k' (rotation about a transverse axis) [-]

    References
    ----------
    Lamb (1932), Hydrodynamics, sec. 373; Imlay (1961), DTMB 1528, eqs. 22-27;
    Fossen (2011), eqs. 6.97-6.101.

    Examples
    --------
    >>> lamb_k_factors(1.0)                       # the sphere
    (0.5, 0.5, 0.0)
    >>> [round(k, 3) for k in lamb_k_factors(5.0)]
    [0.059, 0.894, 0.7]
    """
    ld = np.asarray(length_over_diameter, dtype=float)
    if np.any(ld < 1.0):
        raise ValueError("prolate spheroid needs L/D >= 1")
    sphere = ld < 1.0 + 1e-6
    e = np.sqrt(1.0 - 1.0 / np.where(sphere, 2.0, ld) ** 2)
    log = np.log((1.0 + e) / (1.0 - e))
    a0 = 2.0 * (1.0 - e**2) / e**3 * (0.5 * log - e)
    b0 = 1.0 / e**2 - (1.0 - e**2) / (2.0 * e**3) * log
    k1 = a0 / (2.0 - a0)
    k2 = b0 / (2.0 - b0)
    kp = e**4 * (b0 - a0) / ((2.0 - e**2) * (2.0 * e**2 - (2.0 - e**2) * (b0 - a0)))
    k1 = np.where(sphere, 0.5, k1)
    k2 = np.where(sphere, 0.5, k2)
    kp = np.where(sphere, 0.0, kp)
    if np.ndim(ld) == 0:
        return float(k1), float(k2), float(kp)
    return k1, k2, kp


def spheroid_added_mass(a, b, *, rho):
    r"""Exact diagonal added mass of a prolate spheroid (semi-axes a >= b) about its centre.

    .. math:: M_A = \mathrm{diag}(k_1 m, k_2 m, k_2 m, 0, k' I, k' I),\quad
              m = \tfrac43\pi\rho a b^2,\quad I = m(a^2+b^2)/5

    Returns
    -------
    ndarray (6,)
        [kg, kg, kg, kg m^2, kg m^2, kg m^2]

    References
    ----------
    Lamb (1932), sec. 373; Fossen (2011), eq. 6.96.

    Examples
    --------
    The sphere: half its displaced mass in every translation, nothing in rotation:

    >>> import numpy as np
    >>> m = 1000.0 * 4.0 / 3.0 * np.pi
    >>> [round(float(v) / m, 6) + 0.0 for v in spheroid_added_mass(1.0, 1.0, rho=1000.0)]
    [0.5, 0.5, 0.5, 0.0, 0.0, 0.0]
    """
    k1, k2, kp = lamb_k_factors(a / b)
    m = 4.0 / 3.0 * np.pi * rho * a * b**2
    inertia = m * (a**2 + b**2) / 5.0
    return np.array([k1 * m, k2 * m, k2 * m, 0.0, kp * inertia, kp * inertia])


def equivalent_spheroid(length, volume):
    r"""Semi-axes (a, b) of the spheroid with the body's length and volume.

    .. math:: a = L/2,\qquad b = \sqrt{3V/(4\pi a)}

    A body's L/D used for Lamb's factors is ``a/b`` (>= 1 enforced: a body shorter than
    its volume-equivalent diameter is treated as a sphere of that volume).

    ``length`` L [m], ``volume`` V [m^3]; returns (a, b) [m].

    References
    ----------
    [assumption] equal-length, equal-volume spheroid, after Newman (1977), sec. 7.4 and
    the MARES equivalent ellipsoid (Ferreira et al. 2009, sec. IV.C).

    Examples
    --------
    >>> import numpy as np
    >>> [round(float(v), 9) for v in equivalent_spheroid(2.0, np.pi / 3.0)]  # V of a = 1, b = 0.5
    [1.0, 0.5]
    """
    a = 0.5 * length
    b = np.sqrt(3.0 * volume / (4.0 * np.pi * a))
    if b > a:
        a = b = (3.0 * volume / (4.0 * np.pi)) ** (1.0 / 3.0)
    return a, b


def end_correction_factors(length, volume):
    r"""3D end-correction factors for strip-theory added mass, from the equivalent spheroid.

    Strip theory over a spheroid gives :math:`m_{22}^{2D} = \rho V` and
    :math:`m_{66}^{2D} = \rho\pi b^2 \cdot 4a^3/15`; the exact values are :math:`k_2\rho V`
    and :math:`k'\rho V(a^2+b^2)/5`, so

    .. math:: f_t = k_2, \qquad f_r = k'\,(1 + b^2/a^2)

    are exact for spheroids and applied to other bodies through their equal-length,
    equal-volume spheroid (the approach of Newman 1977, sec. 7.4, and the MARES paper's
    equivalent ellipsoid, Ferreira et al. 2009 sec. IV.C).  The correction is applied as the congruence
    :math:`S M S` with :math:`S = \mathrm{diag}(1, \sqrt{f_t}, \sqrt{f_t}, 1, \sqrt{f_r},
    \sqrt{f_r})`, which keeps M_A symmetric positive definite.

    ``length`` L [m], ``volume`` V [m^3].

    Returns
    -------
    tuple
        (f_t, f_r, k1, L/D of the equivalent spheroid), all [-]

    References
    ----------
    Lamb (1932), sec. 373 (k factors, see module docstring); Newman (1977), sec. 7.4.

    Examples
    --------
    >>> import numpy as np
    >>> [round(float(v), 4) for v in end_correction_factors(2.0, np.pi / 3.0)]   # L/D = 2
    [0.7042, 0.2993, 0.21, 2.0]
    """
    a, b = equivalent_spheroid(length, volume)
    k1, k2, kp = lamb_k_factors(a / b)
    return k2, kp * (1.0 + (b / a) ** 2), k1, a / b


def power_law_split(exponent):
    r"""Split a power-law drag :math:`F = F_{ref} (V/V_{ref})^n` into linear + quadratic parts.

    The least-squares fit of :math:`a\,V + b\,V|V|` to :math:`F(V)` over
    :math:`0 \le V \le V_{ref}` has, with :math:`s = V/V_{ref}`,

    .. math::
        \begin{bmatrix}1/3 & 1/4\\ 1/4 & 1/5\end{bmatrix}
        \begin{bmatrix}\hat a\\ \hat b\end{bmatrix} =
        \begin{bmatrix}1/(n+2)\\ 1/(n+3)\end{bmatrix},\qquad
        a = \hat a F_{ref}/V_{ref},\quad b = \hat b F_{ref}/V_{ref}^2

    so n = 2 (constant C_D) is purely quadratic and laminar friction (n = 1.5) gives
    (a, b) = (0.381, 0.635).  Exponents are clamped to 1 <= n <= 2: in the drag crisis of
    a circular cylinder (Re_D ~ 3e5-6e5) the local exponent leaves that range and the fit
    would give a negative (energy-injecting) linear or quadratic term.  This is how stripcoef models the analytical *linear* damping:
    the part of the Reynolds-dependent drag that a linear + quadratic fit over the operating
    range assigns to the linear term, as the papers' flume fits do (Wang & Clark 2006, eq. 7).

    Returns
    -------
    tuple of float or array
        (a_hat, b_hat) [-]

    Examples
    --------
    >>> [round(float(v), 3) for v in power_law_split(1.5)]    # laminar friction
    [0.381, 0.635]
    >>> [round(float(v), 6) + 0.0 for v in power_law_split(2.0)]  # constant C_D: quadratic
    [0.0, 1.0]
    """
    n = np.clip(np.asarray(exponent, dtype=float), 1.0, 2.0)
    a_hat = 240.0 * (1.0 / (5.0 * (n + 2.0)) - 1.0 / (4.0 * (n + 3.0)))
    b_hat = 240.0 * (1.0 / (3.0 * (n + 3.0)) - 1.0 / (4.0 * (n + 2.0)))
    return a_hat, b_hat


def ellipsoid_added_mass(a, b, c, *, rho):
    r"""Exact diagonal added mass of a triaxial ellipsoid (semi-axes a, b, c along x, y, z).

    With :math:`\Delta = \sqrt{(a^2+\lambda)(b^2+\lambda)(c^2+\lambda)}`,

    .. math::
        \alpha_0 = abc\int_0^\infty\frac{d\lambda}{(a^2+\lambda)\Delta}
                 = \tfrac23\,abc\,R_D(b^2, c^2, a^2)

    (Carlson's symmetric integral :math:`R_D`; :math:`\beta_0, \gamma_0` likewise with b, c),
    :math:`m = \rho V = \tfrac43\pi\rho abc`:

    .. math::
        m_{11} = \frac{\alpha_0}{2-\alpha_0} m,\qquad
        m_{44} = \frac{m}{5}\,\frac{(b^2-c^2)^2(\gamma_0-\beta_0)}
                 {2(b^2-c^2) + (b^2+c^2)(\beta_0-\gamma_0)}

    and cyclically (b, c, beta_0, gamma_0) -> (c, a, gamma_0, alpha_0) for m_22, m_55, ->
    (a, b, alpha_0, beta_0) for m_33, m_66.  A rotation about an axis of symmetry (two equal
    semi-axes across it) moves no water: 0.  Off-diagonal terms are zero about the centre.

    Parameters
    ----------
    a, b, c : float
        Semi-axes along body x, y, z [m]
    rho : float
        Fluid density [kg/m^3]

    Returns
    -------
    ndarray (6,)
        [kg, kg, kg, kg m^2, kg m^2, kg m^2]

    References
    ----------
    Lamb (1932), Hydrodynamics, sec. 114 and 373 (eqs. 7-8 of sec. 373); Korotkin (2009),
    *Added Masses of Ship Structures*, sec. 2.1.3; Carlson (1995), Numer. Algorithms 10, for
    :math:`R_D` (scipy.special.elliprd).

    Examples
    --------
    Two equal semi-axes give Lamb's spheroid (:func:`spheroid_added_mass`):

    >>> import numpy as np
    >>> bool(np.allclose(ellipsoid_added_mass(5.0, 1.0, 1.0, rho=1.0),
    ...                  spheroid_added_mass(5.0, 1.0, rho=1.0), rtol=1e-9))
    True
    """
    from scipy.special import elliprd

    a, b, c = float(a), float(b), float(c)
    if min(a, b, c) <= 0:
        raise ValueError("ellipsoid semi-axes must be positive")
    m = 4.0 / 3.0 * np.pi * rho * a * b * c
    s = a * b * c * 2.0 / 3.0
    al, be, ga = s * elliprd(b * b, c * c, a * a), s * elliprd(c * c, a * a, b * b), \
        s * elliprd(a * a, b * b, c * c)

    def rot(p, q, g_p, g_q):      # rotation about the third axis; p, q the two others
        d2 = p * p - q * q
        if abs(d2) <= 1e-12 * (p * p + q * q):
            return 0.0
        return m / 5.0 * d2 ** 2 * (g_q - g_p) / (2.0 * d2 + (p * p + q * q) * (g_p - g_q))

    return np.array([al / (2 - al) * m, be / (2 - be) * m, ga / (2 - ga) * m,
                     rot(b, c, be, ga), rot(c, a, ga, al), rot(a, b, al, be)])
