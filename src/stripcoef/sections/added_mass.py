r"""2D added mass per unit length of sections in an infinite fluid.

Every function returns per-unit-length values about the section's centre:
``m22`` (sway, motion along y) [kg/m], ``m33`` (heave, along z) [kg/m] and
``m44`` (roll about x) [kg m^2/m].  Symmetric sections have no couplings about
their centre; off-centre parts are shifted by the assembly.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from stripcoef.data import load_table
from stripcoef.errors import InputError
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

    Examples
    --------
    >>> round(float(circle(1.0, rho=1000.0)), 2)      # rho pi a^2
    3141.59
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

    Examples
    --------
    >>> import numpy as np
    >>> [round(float(m) / (1000.0 * np.pi), 6) for m in ellipse(2.0, 1.0, rho=1000.0)]
    [1.0, 4.0, 1.125]
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

    Examples
    --------
    >>> import numpy as np
    >>> [round(float(m) / np.pi, 6) for m in flat_plate(2.0, rho=1.0)]    # pi a^2, pi a^4 / 8
    [4.0, 2.0]
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


def fin_edgewise(thickness, chord, *, rho=RHO):
    r"""2D added mass of a fin's own section moving along its chord, per unit span [kg/m].

    A flat fin of thickness t and chord c, cut normal to its span, is a c x t rectangle; moving
    along the chord (the vehicle surging) it is the rectangle of DNV-RP-C205 table A-1 with the
    side 2a = t normal to the motion and 2b = c along it,

    .. math:: m_{11}' = C_A(t/c)\,\rho\pi\,(t/2)^2

    (:func:`rectangle`'s translation along the long side, read with
    :func:`rectangle_coefficient`; its thin limit t/c < 0.1 keeps C_A(0.1) = 2.23).  It vanishes
    as t^2: a zero-thickness plate moving in its own plane displaces no water (Newman 1977,
    sec. 4.13).  Strips along the span make this the fin's surge added mass for a span long
    against the thickness (the flow round the blunt edges reaches about one chord from them).

    Parameters
    ----------
    thickness, chord : float
        t and c [m], > 0
    rho : float
        Fluid density [kg/m^3]

    Returns
    -------
    float
        m_11' [kg/m]

    References
    ----------
    DNV-RP-C205 (2010), table A-1 (rectangle); Newman (1977), sec. 4.13.
    """
    along_chord, _, _ = rectangle(0.5 * float(chord), 0.5 * float(thickness), rho=rho)
    return float(along_chord[0])


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


def circle_with_fins(radius, tip_radius, *, fins: int = 2, rho=RHO):
    r"""Circle of radius R with two (a pair) or four (a cruciform) thin fins reaching tip radius a.

    Translation normal to a pair of fins (fins along the motion, of zero thickness, do not
    disturb the flow, so the cruciform has the same value):

    .. math:: m_n = \rho\pi\left(a^2 - R^2 + \frac{R^4}{a^2}\right)

    Roll about the axis: the exact conformal-mapping value of :func:`finned_circle_roll`
    (the whole section, all ``fins`` together), which is :math:`\tfrac{\pi}{8}\rho a^4`
    for a bare pair (a plate of width 2a) and :math:`\tfrac{2}{\pi}\rho a^4` for a bare
    cruciform (R = 0), and a few per cent above these with a hull.

    Parameters
    ----------
    radius : float
        Hull radius R >= 0 [m]
    tip_radius : float
        Fin tip distance from the axis a >= R [m]
    fins : {2, 4}
        Two fins on a diameter, or four at right angles
    rho : float
        Fluid density [kg/m^3]

    Returns
    -------
    tuple
        m_normal [kg/m], m44 [kg m^2/m]

    References
    ----------
    m_n: Blevins, Formulas for Natural Frequency and Mode Shape (1979), table 14-2 (circle with
    two fins); Prestero (2001), MIT/WHOI thesis, sec. 3.4; Newman (1977), sec. 4.13 (Joukowski
    map :math:`z + R^2/z` of the finned circle onto a slit of half-length :math:`a + R^2/a`).
    m44: see :func:`finned_circle_roll`.

    Examples
    --------
    A bare pair of fins (R = 0) is a flat plate of width 2a: :math:`\rho\pi a^2` and
    :math:`\tfrac{\pi}{8}\rho a^4`:

    >>> [round(float(m), 4) for m in circle_with_fins(0.0, 1.0, rho=1.0)]
    [3.1416, 0.3927]
    """
    r = float(radius)
    a = float(tip_radius)
    return rho * np.pi * (a**2 - r**2 + r**4 / a**2), finned_circle_roll(r, a, fins=fins, rho=rho)


#: Points on the unit circle for the Fourier series of :func:`finned_circle_roll` (a power of 2;
#: the series' tail is O(1/N): relative error < 2e-4 at 2**16 for R/a <= 0.8, < 2e-5 for
#: R/a <= 0.42, measured against 2**20 points; about 20 ms a call)
ROLL_SERIES_POINTS = 2**16


def finned_circle_roll(radius, tip_radius, *, fins: int = 2, rho=RHO):
    r"""Exact 2D roll added mass of a circle (radius R) with 2 or 4 thin fins to tip radius a.

    A conformal map :math:`z(\sigma)` takes the exterior of the unit circle onto the fluid
    domain; on :math:`\sigma = e^{i\theta}` the rigid-rotation boundary condition fixes the
    stream function, :math:`\psi = \tfrac{\Omega}{2}|z|^2`, so with
    :math:`|z(e^{i\theta})|^2 = \sum_n c_n e^{in\theta}` the kinetic energy
    :math:`T = \tfrac{\rho}{2}\iint|\nabla\psi|^2` gives

    .. math:: m_{44} = \rho\pi \sum_{n \ge 1} n\, |c_n|^2

    (ellipse: :math:`c_2 = (a^2 - b^2)/4`, hence :math:`\rho\pi(a^2-b^2)^2/8`, Newman's
    table 4.2).  The maps: two fins, :math:`z + R^2/z = C\cos\theta` with
    :math:`C = a + R^2/a`; four fins, :math:`z^2 + R^4/z^2 = C\cos 2\theta` with
    :math:`C = a^2 + R^4/a^2` (Newman 1977, sec. 4.13, Joukowski map), so on the boundary

    .. math:: |z|^2 = R^2 \ \text{(hull, } |C\cos k\theta| \le 2R^k\text{)},\qquad
              |z|^{k} = \tfrac12\left(|Z| + \sqrt{Z^2 - 4R^{2k}}\right)\ \text{(fins)}

    with k = 1 (pair) or 2 (cruciform), :math:`Z = C\cos k\theta`.  Closed forms at R = 0:
    :math:`\tfrac{\pi}{8}\rho a^4` (pair: the plate) and :math:`\tfrac{2}{\pi}\rho a^4`
    (cruciform: :math:`|z|^2 = a^2|\cos 2\theta|`, whose series sums to
    :math:`\tfrac{16}{\pi}\sum k/(4k^2-1)^2 = 2/\pi`).  The series is summed by FFT on
    :data:`ROLL_SERIES_POINTS` points (its tail, from the square-root corners where the fins
    meet the hull, is below 2e-4 relative; see there).

    Parameters
    ----------
    radius : float
        Hull radius R >= 0 [m]
    tip_radius : float
        Fin tip distance from the axis a >= R [m]
    fins : {2, 4}
    rho : float
        Fluid density [kg/m^3]

    Returns
    -------
    float
        m44 about the axis [kg m^2/m]

    References
    ----------
    Newman, Marine Hydrodynamics (1977), sec. 4.13 (conformal mapping, added mass of 2D
    bodies, table 4.2); Blevins (1979), table 14-2 (the cruciform's 2/pi rho a^4); Prestero
    (2001), sec. 3.4 (uses 2/pi rho a^4 for the finned REMUS tail, K_pdot).  Checked against
    the 2D panel method (:mod:`stripcoef.sections.panel`) in tests/test_fin_sections.py.

    Examples
    --------
    A bare cruciform (R = 0) has :math:`\tfrac{2}{\pi}\rho a^4` (Blevins 1979):

    >>> round(finned_circle_roll(0.0, 1.0, fins=4, rho=1.0), 4)
    0.6366
    """
    if fins not in (2, 4):
        raise ValueError(f"fins must be 2 or 4, got {fins}")
    return rho * _unit_roll_series(float(radius), float(tip_radius), fins)


@lru_cache(maxsize=2)
def _cos_k_theta(k: int) -> np.ndarray:
    r""":math:`\cos k\theta` on the :data:`ROLL_SERIES_POINTS` angles
    :math:`\theta_j = 2\pi j/N` of :func:`_unit_roll_series` (read-only; the same for every
    radius and tip, so computed once per k)."""
    theta = 2.0 * np.pi * np.arange(ROLL_SERIES_POINTS) / ROLL_SERIES_POINTS
    out = np.cos(k * theta)
    out.flags.writeable = False
    return out


@lru_cache(maxsize=4096)
def _unit_roll_series(r: float, a: float, fins: int) -> float:
    """:func:`finned_circle_roll` for rho = 1 [m^4] (cached: the strips of one fin share it)."""
    k = 1 if fins == 2 else 2
    c = a**k + r**(2 * k) / a**k
    zz = np.abs(c * _cos_k_theta(k))
    on_fin = zz > 2.0 * r**k
    f = np.full(zz.size, r * r)
    f[on_fin] = (0.5 * (zz[on_fin] + np.sqrt(zz[on_fin]**2 - 4.0 * r**(2 * k)))) ** (2.0 / k)
    cn = np.fft.rfft(f) / zz.size
    n = np.arange(cn.size)
    return float(np.pi * np.sum(n[1:] * np.abs(cn[1:]) ** 2))


def plate_chordwise_factor(span, chord):
    r"""3D added mass of a thin rectangular plate moving normal to itself, over its strip-theory
    value with strips across the span (the strip sum along the chord).

    Strip theory along the chord c gives :math:`\rho\pi (w/2)^2 c` for a plate of span w; the 3D
    value is :math:`A = \lambda(a/b)\,\rho\frac{\pi}{4} a^2 b` with a = min(w, c), b = max(w, c)
    (DNV-RP-H103 table A-2), hence

    .. math:: \kappa = \frac{A}{\rho\pi (w/2)^2 c} =
              \begin{cases}\lambda(c/w)\,c/w, & w \ge c\\ \lambda(w/c), & w < c\end{cases}

    tending to 1 for a long strip (w << c) and to :math:`\lambda(0)\,c/w = c/w` for a wide plate
    (the strip sum along the chord then over-counts: the real flow is 2D across the chord).
    lambda is interpolated linearly in a/b over the table's whole range 0..1
    (src/stripcoef/data/plate_added_mass_dnv.csv).

    Parameters
    ----------
    span : float
        Plate width w normal to the strips' axis [m], > 0
    chord : float
        Plate length c along the strips' axis [m], > 0

    Returns
    -------
    float
        kappa [-]

    References
    ----------
    DNV-RP-H103 (2011), appendix A, table A-2 (rectangular plates); Brennen (1982), "A review of
    added mass and fluid inertial forces", NCEL CR 82.010, sec. 3 (3D plates).

    Examples
    --------
    >>> plate_chordwise_factor(1.0, 1.0)       # the square plate, as DNV-RP-H103 prints it
    0.579
    """
    w, c = float(span), float(chord)
    for key, v in (("span", w), ("chord", c)):
        if not (np.isfinite(v) and v > 0):
            raise InputError("plate dimension must be positive", key=key, value=v,
                             expected="a finite length > 0 [m]")
    t = load_table("plate_added_mass_dnv")
    lam = t.interp(min(w, c) / max(w, c), "lambda", what="a/b")
    return lam * c / w if w >= c else lam
