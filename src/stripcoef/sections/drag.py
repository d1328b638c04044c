r"""2D cross-flow drag coefficients of sections, and the axial friction lines.

The drag force per unit length of a section in cross-flow V is
:math:`f = \tfrac12 \rho\, C_D\, h\, |V| V` with h the section's height across the
flow (the cross-flow principle, Hoerner 1965, ch. 3).
"""

from __future__ import annotations

import numpy as np

from stripcoef.data import load_table

#: Subcritical plateau of the circle curve, used to scale other rounded shapes.
CIRCLE_CD_SUBCRITICAL = 1.2


def circle_cd(reynolds):
    r"""Drag coefficient of a smooth circular cylinder in steady cross-flow, :math:`C_D(Re_D)`.

    Interpolated in log10(Re) in the DNV-RP-C205 curve (data/cylinder_drag_dnv.csv,
    1.02e4 <= Re_D <= 4.94e6); outside, clamped with an ExtrapolationWarning.

    Parameters
    ----------
    reynolds : float or array
        Re_D = V D / nu on the diameter [-]

    Returns
    -------
    float or array
        C_D [-]

    References
    ----------
    DNV-RP-C205 (2025-04), fig. 6-6 / sec. 6.7, digitised by M. Seidl
    (cybergalactic/MSS HYDRO/cylinderDrag.m).
    """
    return load_table("cylinder_drag_dnv").interp(reynolds, "Cd", log_x=True, what="Re_D")


def cylinder_length_factor(length_over_diameter, reynolds):
    r"""Finite-length reduction :math:`\kappa(L/D, Re)`, :math:`C_{D,eff} = \kappa C_{D,2D}`.

    Subcritical column for Re < 2e5, supercritical column otherwise
    (data/cylinder_length_factor.csv; L/D in 2..100, clamped with a warning outside).
    ``length_over_diameter`` L/D [-], ``reynolds`` Re_D [-]; returns kappa [-].

    References
    ----------
    DNV-RP-C205 (2025-04), table 6-3 (via cybergalactic/MSS HYDRO/cylinderDrag.m);
    Hoerner (1965), fig. 3-16.
    """
    t = load_table("cylinder_length_factor")
    ld = np.asarray(length_over_diameter, dtype=float)
    sub = t.interp(ld, "kappa_subcritical", log_x=True, what="L/D")
    sup = t.interp(ld, "kappa_supercritical", log_x=True, what="L/D")
    return np.where(np.asarray(reynolds) < 2e5, sub, sup)


def rectangle_cd(depth_over_height, reynolds=1e5):
    r"""Drag of a sharp-edged rectangular cylinder vs d/h (length along flow / height across).

    Reynolds-independent for Re >= 1e4 (separation fixed at the corners) and tabulated for
    0 <= d/h <= 6 (White, Fluid Mechanics, table 7.2, after Delany & Sorensen 1953, NACA
    TN 3038; data/rectangle_drag.csv, marked assumed: recalled, not re-checked).  A longer
    section (a plate edge-on, such as a fin in flow along its chord) is beyond the table; it is
    modelled instead of extrapolated as pressure drag decaying like h/d plus skin friction on
    both faces over the excess length:

    .. math:: C_D = 0.9\,\frac{6}{d/h} + 2\,C_f(Re_d)\,(d/h - 6),\qquad d/h > 6

    continuous at d/h = 6 (Hoerner 1965, ch. 2 and 3), with :math:`Re_d = Re\,(d/h)` and
    :func:`friction_coefficient`.

    Parameters
    ----------
    depth_over_height : float or array
        d/h [-]
    reynolds : float or array
        Reynolds number on the height across the flow (only used beyond the table) [-]
    """
    r = np.asarray(depth_over_height, dtype=float)
    t = load_table("rectangle_drag")
    out = t.interp(np.minimum(r, 6.0), "Cd", what="d/h")
    long = r > 6.0
    if np.any(long):
        re_d = np.broadcast_to(np.asarray(reynolds, dtype=float), r.shape)[long] * r[long]
        cf = np.array([friction_coefficient(v)[0] for v in np.atleast_1d(re_d)])
        out = np.array(out, dtype=float, copy=True)
        out[long] = 0.9 * 6.0 / r[long] + 2.0 * cf * (r[long] - 6.0)
    return out


def ellipse_cd(depth_over_height, reynolds):
    r"""Drag of an elliptic cylinder vs d/h, with the circle's Reynolds dependence.

    .. math:: C_D = C_{D,table}(d/h)\; C_{D,circle}(Re) / 1.2

    ``depth_over_height`` d/h [-], ``reynolds`` Re on the height [-]; returns C_D [-].
    The factor :math:`C_{D,circle}(Re)/1.2` (circle curve over its subcritical plateau) is an
    [assumption]: rounded sections share the circle's drag crisis.

    References
    ----------
    White, Fluid Mechanics, table 7.2 (elliptical cylinder, laminar column);
    data/ellipse_drag.csv (assumed values, see its header).
    """
    base = load_table("ellipse_drag").interp(depth_over_height, "Cd", what="d/h")
    return base * circle_cd(reynolds) / CIRCLE_CD_SUBCRITICAL


def flat_plate_cd():
    r"""Normal flat plate in 2D cross-flow, :math:`C_D = 2.0` [-] (on the plate's width).

    References
    ----------
    Hoerner, Fluid-Dynamic Drag (1965), ch. 3, fig. 3-11 (2D plate ~1.98-2.0).
    """
    return 2.0


def plate_cd(aspect_ratio):
    r"""Drag of a thin rectangular plate normal to the flow vs its aspect ratio (on its area).

    .. math:: F = \tfrac12\rho\, C_D(AR)\, b h\, |V| V,\qquad
              C_D = C_{D,table}(\min(AR, 1/AR)^{-1})

    interpolated linearly in h/b = 1/AR (short side over long side) in
    data/plate_drag_aspect_ratio.csv: 1.18 for a square plate, 1.2 up to AR = 5, 1.3 at 10,
    1.5 at 20 and the 2D value 2.0 as AR -> infinity (the table's h/b = 0 row), so the curve is
    bounded at both ends and never extrapolated.  Low-aspect-ratio plates shed vortices round
    their tips and have much less drag than the 2D plate (:func:`flat_plate_cd`).

    Parameters
    ----------
    aspect_ratio : float or array
        Span over chord b/h of the plate, any positive value (a plate of AR and of 1/AR is
        the same plate) [-]

    Returns
    -------
    float or array
        C_D [-]

    References
    ----------
    Hoerner, Fluid-Dynamic Drag (1965), ch. 3 (rectangular plates normal to the flow); White,
    Fluid Mechanics, Table 7.3 (data/plate_drag_aspect_ratio.csv, marked assumed: recalled).
    """
    ar = np.asarray(aspect_ratio, dtype=float)
    inv = np.minimum(ar, 1.0 / ar)
    return load_table("plate_drag_aspect_ratio").interp(inv, "Cd", what="h/b")


def fin_crossflow_factor(span, chord):
    r"""Finite-span factor of a fin's 2D plate drag in flow normal to the fin [-].

    .. math:: \kappa_{fin} = \frac{C_D(AR_e)}{C_{D,2D}},\qquad AR_e = \frac{2 s}{c}

    with :func:`plate_cd` and the 2D plate :func:`flat_plate_cd`; the effective aspect ratio
    doubles the geometric one, the hull the fin stands on acting as a reflection plane
    (Whicker & Fehlner 1958, DTMB report 933; Prestero 2001, sec. 3.6: AR_e = 2.21 for the
    REMUS fins) [assumption: a fin attached to a body].  ``span`` s (root to tip) and
    ``chord`` c [m].  References: Hoerner (1965), ch. 3 and 7; Whicker & Fehlner (1958).
    """
    return plate_cd(2.0 * np.asarray(span, float) / np.asarray(chord, float)) / flat_plate_cd()


# -- axial friction lines ---------------------------------------------------

def blasius_cf(reynolds):
    r"""Laminar flat-plate friction (Blasius): :math:`C_f = 1.328/\sqrt{Re_L}`.

    ``reynolds`` Re_L = U L / nu [-]; returns the mean (whole-plate) C_f [-].

    References
    ----------
    Schlichting & Gersten, Boundary-Layer Theory (8th ed.), eq. 6.59.

    Examples
    --------
    >>> round(float(blasius_cf(1e4)), 6)        # 1.328 / 100
    0.01328
    """
    return 1.328 / np.sqrt(np.asarray(reynolds, dtype=float))


def ittc57_cf(reynolds):
    r"""ITTC-1957 model-ship correlation line: :math:`C_f = 0.075/(\log_{10} Re_L - 2)^2`.

    ``reynolds`` Re_L = U L / nu [-]; returns C_f [-].

    References
    ----------
    ITTC (1957), Proc. 8th ITTC; ITTC 7.5-02-02-02.

    Examples
    --------
    >>> round(float(ittc57_cf(1e7)), 6)         # 0.075 / (7 - 2)^2
    0.003
    """
    return 0.075 / (np.log10(np.asarray(reynolds, dtype=float)) - 2.0) ** 2


#: Critical Reynolds number of laminar-turbulent transition on a flat plate [-].
RE_CRITICAL = 5e5


def friction_coefficient(reynolds, *, regime: str = "auto"):
    r"""Skin-friction coefficient with a laminar leading part.

    .. math::
        C_f = \begin{cases} 1.328/\sqrt{Re} & Re < Re_{cr} \\
        C_{f,ITTC}(Re) - \frac{Re_{cr}}{Re}\left[C_{f,ITTC}(Re_{cr}) - C_{f,Bl}(Re_{cr})\right]
        & Re \ge Re_{cr}\end{cases}

    The second line is Prandtl's correction for a laminar run up to Re_cr = 5e5 on a
    turbulent plate (Schlichting & Gersten, sec. 18.2.5, eq. 18.99 with its constant
    A = Re_cr (C_f,t - C_f,l)); it is continuous at Re_cr and tends to ITTC-57.

    Parameters
    ----------
    reynolds : float
        Re_L on the body length [-]
    regime : str
        ``auto`` (rule above), ``laminar`` (Blasius) or ``turbulent`` (ITTC-57)

    Returns
    -------
    (float, str)
        C_f [-] and the regime name: laminar, transitional or turbulent

    Examples
    --------
    Continuous at the transition, Re_cr = 5e5:

    >>> laminar, _ = friction_coefficient(5e5, regime="laminar")
    >>> cf, name = friction_coefficient(5e5)
    >>> round(cf / laminar, 9), name
    (1.0, 'transitional')
    """
    re = float(reynolds)
    if regime == "laminar":
        return float(blasius_cf(re)), "laminar"
    if regime == "turbulent":
        return float(ittc57_cf(re)), "turbulent"
    if re < RE_CRITICAL:
        return float(blasius_cf(re)), "laminar"
    a = RE_CRITICAL * (ittc57_cf(RE_CRITICAL) - blasius_cf(RE_CRITICAL))
    cf = float(ittc57_cf(re) - a / re)
    name = "turbulent" if re > 1e7 else "transitional"
    return cf, name


def hoerner_form_factor(diameter_over_length):
    r"""Form factor of a streamlined body of revolution on its wetted area.

    .. math:: C_{D,wet} = C_f\,[1 + 1.5 (d/l)^{3/2} + 7 (d/l)^3]

    References
    ----------
    Hoerner, Fluid-Dynamic Drag (1965), ch. 6, eq. 6-27 (tagged "from memory" in
    shared/reference/formulas.md sec. 5.4; values L/D = 4: 1.297, 6: 1.135, 10: 1.054).
    A fit to streamlined bodies: a closed hull uses it only from L/D 3 up
    (:data:`FORM_FACTOR_LD`, :func:`closed_body_axial_cd`); shorter bodies, and any body with a
    flat end (:func:`blunt_cylinder_axial_cd`), get measured whole-body drag instead.

    Examples
    --------
    The formula at L/D = 4, 6, 10 (at L/D = 6 it gives 1.13447, quoted as 1.135):

    >>> [round(float(hoerner_form_factor(1.0 / ld)), 3) for ld in (4.0, 6.0, 10.0)]
    [1.297, 1.134, 1.054]
    """
    r = np.asarray(diameter_over_length, dtype=float)
    return 1.0 + 1.5 * r**1.5 + 7.0 * r**3


#: The blunt-body curve's last L/D [-]: a longer flat-ended body adds only skin friction, which
#: the hull's friction line carries (Hoerner 1965, ch. 3: end-on cylinders up to L/d ~ 8)
BLUNT_LD_MAX = 8.0


def blunt_cylinder_axial_cd(length_over_diameter, aspect_ratio=1.0):
    r"""Whole-body drag of a flat-ended body in flow along its axis, on its frontal area.

    .. math:: F = \tfrac12 \rho\, C_D\, A_{frontal}\, u|u|,\qquad
              C_D = C_{D,cyl}\!\left(\min(L/D, 8)\right)\,
              \frac{C_{D,plate}(AR)}{C_{D,plate}(1)}

    :math:`C_{D,cyl}` is the measured curve of flat-ended circular cylinders end-on, from the
    disc (L/D = 0: 1.17) through 1.15 at L/D = 0.5, 0.90 at 1, 0.85 at 2, 0.87 at 4 to 0.99 at 8
    (data/blunt_body_axial_drag.csv), linear in L/D; a longer body keeps the value at 8 and
    adds only skin friction, which the hull friction line carries (Hoerner 1965, ch. 3).  The
    second factor carries the frontal section's aspect ratio AR (its width over its height,
    either way round) as it acts on a thin plate normal to the flow (:func:`plate_cd`: 1.18
    square, 1.2 at AR 5, 1.3 at 10, 2.0 as AR -> infinity), so a thin plate (L/D -> 0) gets its
    measured drag: 1.17 x 1.2 / 1.18 = 1.19 at AR 5 [assumption: the aspect ratio scales a
    blunt body's end-on drag as it scales a plate's; 1 for a round or square section, so the
    cylinder and cube curves are unchanged].

    Parameters
    ----------
    length_over_diameter : float or array
        L/D of the body along the flow, D the diameter of the frontal area's equal circle [-]
    aspect_ratio : float or array
        width over height of the frontal section (or its inverse) [-]

    Returns
    -------
    float or array
        C_D on the frontal area [-]

    References
    ----------
    Hoerner, Fluid-Dynamic Drag (1965), ch. 3 (discs, cylinders end-on, plates normal to the
    flow), as tabulated in White, Fluid Mechanics, Table 7.3 (recalled: data files' headers).
    """
    ld = np.minimum(np.asarray(length_over_diameter, dtype=float), BLUNT_LD_MAX)
    base = load_table("blunt_body_axial_drag").interp(ld, "Cd", what="L/D")
    return base * plate_cd(aspect_ratio) / plate_cd(1.0)


#: Reynolds numbers on the diameter [-] between which a smooth rounded body goes through its
#: drag crisis (laminar to turbulent separation): the sphere's C_D starts to fall at about 2e5
#: and reaches its supercritical minimum by about 4e5-5e5 (Achenbach 1972, J. Fluid Mech. 54,
#: fig. 3; Hoerner 1965, ch. 3, fig. 3-25)
RE_CRISIS = (2e5, 5e5)


def ellipsoid_axial_cd(length_over_diameter, reynolds):
    r"""Whole-body drag of a prolate ellipsoid (spheroid) nose-on, on its frontal area.

    .. math:: F = \tfrac12\rho\,C_D(L/d, Re_d)\,\frac{\pi d^2}{4}\,u|u|

    with :math:`C_D` interpolated linearly in L/d in data/ellipsoid_axial_drag.csv (L/d 0.75 to
    8: sphere 0.47, 2:1 0.27 subcritical; 0.2 and 0.13 supercritical), in its subcritical column
    for :math:`Re_d \le 2\times10^5`, its supercritical one for :math:`Re_d \ge 5\times10^5`
    and, between, linearly in log10(Re_d) from one to the other (the drag crisis,
    :data:`RE_CRISIS`) [assumption: every fineness ratio has the sphere's crisis range].
    Outside the table's L/d the end value is used, with an ExtrapolationWarning.

    Parameters
    ----------
    length_over_diameter : float or array
        L/d [-]
    reynolds : float or array
        Re_d = U d / nu on the diameter [-]

    Returns
    -------
    float or array
        C_D on the frontal area pi d^2/4 [-]

    References
    ----------
    Hoerner, Fluid-Dynamic Drag (1965), ch. 3 and 6, as tabulated in White, Fluid Mechanics,
    Table 7.3 (ellipsoids, laminar and turbulent columns; recalled: the data file's header);
    Achenbach (1972), J. Fluid Mech. 54, 565-575 (the sphere's critical range).
    """
    t = load_table("ellipsoid_axial_drag")
    sub = t.interp(length_over_diameter, "Cd_subcritical", what="L/d")
    sup = t.interp(length_over_diameter, "Cd_supercritical", what="L/d")
    lo, hi = np.log10(RE_CRISIS[0]), np.log10(RE_CRISIS[1])
    w = np.clip((np.log10(np.asarray(reynolds, dtype=float)) - lo) / (hi - lo), 0.0, 1.0)
    out = (1.0 - w) * sub + w * sup
    return float(out) if np.ndim(out) == 0 else out


#: L/D [-] range of the streamlined-body form factor (:func:`hoerner_form_factor`): below
#: FORM_FACTOR_LD[0] a closed body's axial drag is the measured whole-body drag of ellipsoids
#: (:func:`ellipsoid_axial_cd`); from FORM_FACTOR_LD[1] up it is friction times the form
#: factor; between, a log-linear bridge (:func:`closed_body_axial_cd`). Hoerner's fit rests on
#: streamlined bodies of fineness ratio about 3 and more (ch. 6, fig. 6-22 [recalled]); at
#: L/D 2 and 1 it gives a tenth and a sixth of the measured drag of a 2:1 ellipsoid and a
#: sphere (reference_tables/body_drag_3d)
FORM_FACTOR_LD = (2.0, 3.0)


def closed_body_axial_cd(length_over_diameter, reynolds_diameter, friction, wetted_over_frontal):
    r"""Axial whole-body drag of a closed body without flat ends, on its frontal area.

    .. math::
        C_D = \begin{cases} C_{D,ell}(L/D, Re_D) & L/D \le 2 \\
        C_f\,FF(D/L)\,S_{wet}/A_f & L/D \ge 3 \\
        C_{D,ell}^{\,1-w}\,\left(C_f\,FF\,S_{wet}/A_f\right)^{w},\ w = L/D - 2 & \text{between}
        \end{cases}

    :math:`C_{D,ell}`: :func:`ellipsoid_axial_cd` (measured short bodies: the flow separates);
    :math:`FF`: :func:`hoerner_form_factor` (streamlined bodies, attached flow), only inside the
    range :data:`FORM_FACTOR_LD` of its source; the bridge between L/D 2 and 3 is geometric in
    w [assumption: no measured body covers the change of regime; the model warns there].

    Parameters
    ----------
    length_over_diameter : float or array
        L/D, D the diameter of the largest section's equal circle [-]
    reynolds_diameter : float or array
        Re_D = U D / nu [-]
    friction : float or array
        C_f of the hull at Re_L [-] (:func:`friction_coefficient`)
    wetted_over_frontal : float or array
        S_wet / A_frontal [-]

    Returns
    -------
    float or array
        C_D on the frontal area [-]

    References
    ----------
    Hoerner, Fluid-Dynamic Drag (1965), ch. 3 and ch. 6, eq. 6-27; White, Fluid Mechanics,
    Table 7.3.
    """
    ld = np.asarray(length_over_diameter, dtype=float)
    lo, hi = FORM_FACTOR_LD
    streamlined = np.asarray(friction) * hoerner_form_factor(1.0 / ld) * \
        np.asarray(wetted_over_frontal)
    with np.errstate(invalid="ignore"):
        short = ellipsoid_axial_cd(np.minimum(ld, hi), reynolds_diameter)
    w = np.clip((ld - lo) / (hi - lo), 0.0, 1.0)
    out = np.where(w <= 0.0, short, np.where(w >= 1.0, streamlined,
                                              short ** (1.0 - w) * streamlined ** w))
    return float(out) if out.ndim == 0 else out


#: L/h of a part (its length along x over its largest extent across the flow) up to which
#: its cross-flow drag is the whole-body drag of a short body (:func:`short_body_crossflow_cd`),
#: and from which it is the strips' (cross-flow principle with the length factor, whose table
#: starts at L/D = 2: :func:`cylinder_length_factor`); linear in L/h between [assumption: at
#: L/h <= 1 the body is no longer than it is high across the flow, and the flow passes its ends
#: as much as its sides; no measured body covers the change of regime]
SHORT_CROSSFLOW_LH = (1.0, 2.0)


def short_body_crossflow_weight(length_over_height):
    r"""Share w of the whole-body drag in a part's cross-flow drag [-].

    .. math:: w = \mathrm{clip}\left(\frac{(L/h)_2 - L/h}{(L/h)_2 - (L/h)_1}, 0, 1\right)

    with :math:`(L/h)_{1,2}` = :data:`SHORT_CROSSFLOW_LH`: 1 for a part no longer than it is
    high across the flow, 0 from the length factor's first L/D (DNV-RP-C205 table 6-3) on.
    ``length_over_height`` L/h [-].
    """
    lo, hi = SHORT_CROSSFLOW_LH
    return np.clip((hi - np.asarray(length_over_height, dtype=float)) / (hi - lo), 0.0, 1.0)


def short_body_crossflow_cd(depth_over_diameter, flat, aspect_ratio, reynolds):
    r"""Whole-body drag of a short body in flow across its x axis, on its projected area.

    The body is seen as the flow sees it: a body of length :math:`\ell` along the flow (its
    depth) and projected area :math:`A` normal to it, :math:`D = \sqrt{4A/\pi}`; its class by
    the face that meets the flow, as for the axial drag of a short hull
    (:func:`blunt_cylinder_axial_cd`, :func:`ellipsoid_axial_cd`):

    .. math:: C_D = \begin{cases} C_{D,blunt}(\ell/D, AR) & \text{a flat face normal to the
              flow} \\ C_{D,ell}(\ell/D, Re_D) & \text{otherwise (closed: the flow
              separates from a rounded contour, an edge or a ridge)}\end{cases}

    so a sphere has the same drag in every direction, and a cube the same on each face
    [assumption: the measured whole-body drag of bodies of revolution about the flow holds for
    a short body of the same class seen along that flow; the sphere and the cube hold it
    exactly by symmetry].

    Parameters
    ----------
    depth_over_diameter : float
        :math:`\ell/D` [-]
    flat : bool
        a flat face normal to the flow meets it
    aspect_ratio : float
        width over height of the projected area (or its inverse) [-] (flat faces only)
    reynolds : float
        :math:`Re_D = U D/\nu` [-] (closed bodies only)

    Returns
    -------
    float
        C_D on the projected area A [-]

    References
    ----------
    Hoerner, Fluid-Dynamic Drag (1965), ch. 3 (bluff bodies: discs, cylinders end-on, plates,
    spheres and ellipsoids), as tabulated in White, Fluid Mechanics, Table 7.3.
    """
    if flat:
        return float(blunt_cylinder_axial_cd(depth_over_diameter, aspect_ratio))
    return float(ellipsoid_axial_cd(depth_over_diameter, reynolds))


def closed_body_depth_range():
    """(lowest, highest) L/d [-] of the measured closed bodies (data/ellipsoid_axial_drag.csv):
    a closed short body thinner along the flow than the lowest (an oblate body face-on, a
    cylinder across longer than about 1.4 diameters) has no measured whole-body drag here."""
    x = load_table("ellipsoid_axial_drag").column("L_over_d")
    return float(np.min(x)), float(np.max(x))


def ellipse_perimeter(b, h):
    r"""Ramanujan's approximation of an ellipse's perimeter [m] (exact for circles).

    .. math:: P \approx \pi(b + h)\left(1 + \frac{3\lambda}{10 + \sqrt{4 - 3\lambda}}\right),
              \quad \lambda = \left(\frac{b-h}{b+h}\right)^2

    Half-axes b, h [m]. Ramanujan (1914), Quart. J. Math. 45, the second approximation.
    """
    hh = ((b - h) / (b + h)) ** 2
    return np.pi * (b + h) * (1.0 + 3.0 * hh / (10.0 + np.sqrt(4.0 - 3.0 * hh)))
