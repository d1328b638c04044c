r"""Separation of a body's turbulent boundary layer on its afterbody (Stratford's criterion).

The station where a streamlined body's axial boundary layer separates in the pressure recovery
over its afterbody, used as the station behind which its cross-flow lift stops being potential
(``body_lift: stratford``, :func:`stripcoef.assembly.lift._body_lift`): a separation station
from the body's own pressure distribution and boundary layer, where Hopkins's correlation
(:func:`stripcoef.hull.lift.separation_station`) places it from the body's shape alone on missile
bodies with boat-tails.

Stratford's criterion (Stratford 1959): a turbulent layer that has run an effective length x'
at the peak speed :math:`U_m` separates in the pressure rise behind it where

.. math:: C_p'\,\Big(x'\,\frac{dC_p'}{dx}\Big)^{1/2}\,\big(10^{-6} Re_{x'}\big)^{-1/10} = k,
          \qquad C_p' = 1 - (U_e/U_m)^2,\qquad Re_{x'} = U_m x'/\nu

with :math:`k` = 0.39 where :math:`d^2p/dx^2 > 0` and 0.35 where :math:`d^2p/dx^2 \le 0`, valid
for :math:`C_p' < 4/7`; for a layer turbulent from the station :math:`s_t` and accelerated up to
the peak :math:`s_m` the effective length is

.. math:: x' = \int_{s_t}^{s_m} (U_e/U_m)^3\,ds + (s - s_m).
"""

from __future__ import annotations

import math

import numpy as np

#: Stratford's constant k for a convex pressure recovery (d^2p/dx^2 > 0) and for a concave one
#: (d^2p/dx^2 <= 0) (Stratford 1959, J. Fluid Mech. 5, the turbulent separation criterion;
#: the same values in Kroo's Applied Aerodynamics notes, "Turbulent separation criteria", and
#: CFD-Wiki "Stratford's separation criterion") [-].
STRATFORD_CONVEX, STRATFORD_CONCAVE = 0.39, 0.35
#: Largest canonical pressure coefficient C_p' for which the criterion holds (the same
#: sources) [-].
STRATFORD_CP_LIMIT = 4.0 / 7.0
#: Stretch of the body (fractions of its length from the nose) searched for the peak speed that
#: starts the afterbody's pressure recovery (assumption: the afterbody's recovery starts behind
#: the middle of the body and ahead of the tail cap, where the last 3 % close the body) [-].
PEAK_SEARCH = (0.5, 0.97)


def stratford_separation(s, speed_ratio, *, speed: float, viscosity: float,
                         transition: float) -> dict:
    r"""Station of the afterbody where Stratford's criterion says the turbulent layer separates.

    .. math:: F(s) = C_p'\,\Big(x'\,\frac{dC_p'}{ds}\Big)^{1/2}\big(10^{-6}U_m x'/\nu\big)^{-1/10}
              \ \ge\ k

    searched from the peak surface speed :math:`U_m` (its largest value within
    :data:`PEAK_SEARCH` of the length; the aftmost station of a plateau, where the rise starts)
    aft (module docstring; :math:`dC_p'/ds \le 0` stretches
    skipped), with :math:`k` from the sign of :math:`d^2C_p'/ds^2`, which is that of
    :math:`d^2p/ds^2`.

    Parameters
    ----------
    s : (n,) array
        Stations from the nose, increasing [m] (standing for the arc length, as in
        :func:`stripcoef.hull.lift.turbulent_boundary_layer`)
    speed_ratio : (n,) array
        Surface speed U_e/U of the body in axial potential flow [-]
        (:func:`stripcoef.hull.lift.surface_speed_ratio`)
    speed : float
        U [m/s] > 0
    viscosity : float
        Kinematic viscosity [m^2/s] > 0
    transition : float
        s_t [m] from the nose, where the layer is taken turbulent

    Returns
    -------
    dict
        ``separation`` [m] from the nose (None when the criterion is not met ahead of the end
        of the search, or only where C_p' >= 4/7: no separation the criterion can state);
        ``peak`` s_m [m], ``peak_speed`` U_m/U [-], ``effective_length`` x' at the peak [m],
        ``cp`` C_p' and ``k`` at the separation (None without one); ``limit`` why there is
        none: ``"end"`` (the search reached :data:`PEAK_SEARCH`'s end) or ``"cp"`` (C_p'
        reached 4/7 first, outside the criterion's range), None with a separation

    References
    ----------
    Stratford, B. S. (1959), "The prediction of separation of the turbulent boundary layer",
    J. Fluid Mech. 5, 1-16 (the criterion, k = 0.39 and 0.35, C_p' < 4/7); Cebeci, T. &
    Bradshaw, P. (1977), *Momentum Transfer in Boundary Layers* (Stratford's criterion among
    the turbulent separation criteria); Kroo, I., *Applied Aerodynamics: A Digital Textbook*,
    "Turbulent separation criteria" (the effective length of a layer accelerated to the peak).
    """
    s = np.asarray(s, dtype=float)
    ue = np.asarray(speed_ratio, dtype=float)
    if speed <= 0.0 or viscosity <= 0.0:
        raise ValueError(f"stratford_separation needs speed and viscosity > 0, got {speed}, "
                         f"{viscosity}")
    length = float(s[-1] - s[0])
    lo, hi = (s[0] + f * length for f in PEAK_SEARCH)
    window = (s >= lo) & (s <= hi)
    masked = np.where(window, ue, -np.inf)
    im = len(s) - 1 - int(np.argmax(masked[::-1]))     # the last station of the peak speed
    um = float(ue[im])
    turbulent = (s >= transition) & (s <= s[im])
    x_peak = float(np.trapezoid((ue[turbulent] / um) ** 3, s[turbulent])) \
        if np.count_nonzero(turbulent) > 1 else max(float(s[im]) - transition, 0.0)
    cp = 1.0 - (ue / um) ** 2
    dcp = np.gradient(cp, s)
    d2cp = np.gradient(dcp, s)
    out = {"separation": None, "peak": float(s[im]), "peak_speed": um,
           "effective_length": x_peak, "cp": None, "k": None, "limit": "end"}
    for i in range(im + 1, len(s)):
        if s[i] > hi:
            break
        if cp[i] >= STRATFORD_CP_LIMIT:
            out["limit"] = "cp"
            break
        if cp[i] <= 0.0 or dcp[i] <= 0.0:
            continue
        xp = x_peak + float(s[i] - s[im])
        k = STRATFORD_CONVEX if d2cp[i] > 0.0 else STRATFORD_CONCAVE
        f = cp[i] * math.sqrt(xp * dcp[i]) * (1e-6 * speed * um * xp / viscosity) ** -0.1
        if f >= k:
            out.update(separation=float(s[i]), cp=float(cp[i]), k=k, limit=None)
            break
    return out
