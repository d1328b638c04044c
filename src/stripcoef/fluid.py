r"""Water properties: density and kinematic viscosity.

Density of sea water at atmospheric pressure from the one-atmosphere
International Equation of State of Seawater (EOS-80), or from TEOS-10 (the ``seawater``
extra, gsw) when asked; dynamic viscosity from
Sharqawy, Lienhard & Zubair (2010), the correlation recommended by ITTC
7.5-02-01-03 (2011).  Both valid for 0-40 degC and salinity 0-42 g/kg
(EOS-80: practical salinity 0-42); outside, a warning.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from stripcoef.errors import ExtrapolationWarning, InputError

RHO_SEAWATER = 1025.0
"""Default sea-water density [kg/m^3] (Fossen 2011; ITTC nominal)."""
RHO_FRESHWATER = 1000.0
"""Nominal fresh-water density [kg/m^3]."""
NU_SEAWATER = 1.19e-6
"""Sea-water kinematic viscosity at 15 degC, S = 35 [m^2/s] (ITTC 7.5-02-01-03)."""
G = 9.81
"""Gravitational acceleration [m/s^2]."""
MAX_VEHICLE_SPEED = 100.0
"""Bound of any speed through the water in stripcoef's inputs [m/s]: faster than any
underwater vehicle (the supercavitating VA-111 torpedo reaches ~100 m/s); a larger value is in
other units or corrupt (reference speeds, log velocities)."""


def density_eos80(temperature, salinity):
    r"""Sea-water density at atmospheric pressure (EOS-80, one-atmosphere form).

    .. math::
        \rho_w &= 999.842594 + 6.793952\,10^{-2} t - 9.095290\,10^{-3} t^2
                  + 1.001685\,10^{-4} t^3 - 1.120083\,10^{-6} t^4 + 6.536332\,10^{-9} t^5 \\
        \rho &= \rho_w + S (0.824493 - 4.0899\,10^{-3} t + 7.6438\,10^{-5} t^2
                - 8.2467\,10^{-7} t^3 + 5.3875\,10^{-9} t^4) \\
             &\quad + S^{3/2}(-5.72466\,10^{-3} + 1.0227\,10^{-4} t - 1.6546\,10^{-6} t^2)
                + 4.8314\,10^{-4} S^2

    Parameters
    ----------
    temperature : float or array
        Water temperature t [degC]
    salinity : float or array
        Practical salinity S [PSU, ~g/kg]

    Returns
    -------
    float or array
        Density [kg/m^3]

    References
    ----------
    UNESCO (1981), Tenth report of the joint panel on oceanographic tables and
    standards, UNESCO Tech. Pap. Mar. Sci. 36; Millero & Poisson (1981), Deep-Sea
    Res. 28A, 625-629.  (15 degC, S = 35 gives 1025.97 kg/m^3.)

    Examples
    --------
    >>> round(density_eos80(15.0, 35.0), 2)      # standard sea water
    1025.97
    >>> round(density_eos80(4.0, 0.0), 3)        # fresh water near its density maximum
    999.975
    """
    t = np.asarray(temperature, dtype=float)
    s = np.asarray(salinity, dtype=float)
    rho_w = (999.842594 + 6.793952e-2 * t - 9.095290e-3 * t**2 + 1.001685e-4 * t**3
             - 1.120083e-6 * t**4 + 6.536332e-9 * t**5)
    a = 0.824493 - 4.0899e-3 * t + 7.6438e-5 * t**2 - 8.2467e-7 * t**3 + 5.3875e-9 * t**4
    b = -5.72466e-3 + 1.0227e-4 * t - 1.6546e-6 * t**2
    c = 4.8314e-4
    out = rho_w + a * s + b * s**1.5 + c * s**2
    return float(out) if out.ndim == 0 else out


def dynamic_viscosity_sharqawy(temperature, salinity):
    r"""Dynamic viscosity of sea water (Sharqawy et al. 2010, eqs. 22-23).

    .. math::
        \mu_w &= 4.2844\,10^{-5} + [0.157 (t + 64.993)^2 - 91.296]^{-1} \\
        \mu &= \mu_w (1 + A S + B S^2),\quad S\ \text{in kg/kg} \\
        A &= 1.541 + 1.998\,10^{-2} t - 9.52\,10^{-5} t^2,\quad
        B = 7.974 - 7.561\,10^{-2} t + 4.724\,10^{-4} t^2

    Parameters
    ----------
    temperature : float or array
        Temperature [degC]
    salinity : float or array
        Salinity [g/kg]

    Returns
    -------
    float or array
        Dynamic viscosity [Pa s]

    References
    ----------
    Sharqawy, Lienhard & Zubair (2010), Desalination and Water Treatment 16, 354-380;
    ITTC Recommended Procedure 7.5-02-01-03 (2011), "Fresh water and seawater properties".

    Examples
    --------
    >>> round(dynamic_viscosity_sharqawy(20.0, 0.0) * 1e3, 4)   # fresh water, 20 degC [mPa s]
    1.0018
    """
    t = np.asarray(temperature, dtype=float)
    s = np.asarray(salinity, dtype=float) / 1000.0
    mu_w = 4.2844e-5 + 1.0 / (0.157 * (t + 64.993) ** 2 - 91.296)
    a = 1.541 + 1.998e-2 * t - 9.52e-5 * t**2
    b = 7.974 - 7.561e-2 * t + 4.724e-4 * t**2
    out = mu_w * (1.0 + a * s + b * s**2)
    return float(out) if out.ndim == 0 else out


#: The equations of state a fluid can be computed with (``fluid.equation``).
EQUATIONS = ("eos80", "teos10")


def density_teos10(temperature, salinity):
    r"""Sea-water density at the surface from TEOS-10 (needs the ``seawater`` extra, gsw).

    .. math::
        S_R = \frac{35.16504}{35} S_P,\qquad
        \Theta = \Theta(S_R, t, p = 0),\qquad
        \rho = \rho(S_R, \Theta, p = 0)

    Reference-composition salinity :math:`S_R` [g/kg] stands for the absolute salinity where
    the location is not known (IOC et al. 2010, sec. 2.5); conservative temperature and the
    75-term density are gsw's ``CT_from_t`` and ``rho``.

    Parameters
    ----------
    temperature : float or array
        In-situ temperature t [degC]
    salinity : float or array
        Practical salinity S_P [PSU]

    Returns
    -------
    float or array
        Density [kg/m^3]

    References
    ----------
    IOC, SCOR & IAPSO (2010), The international thermodynamic equation of seawater - 2010
    (TEOS-10), Manuals and Guides 56, UNESCO, secs. 2.5 and 3.8; McDougall & Barker (2011),
    Getting started with TEOS-10 and the Gibbs Seawater (GSW) Oceanographic Toolbox.
    (15 degC, S_P = 35 gives 1025.97 kg/m^3, within 0.01 of EOS-80.)
    """
    try:
        import gsw
    except ImportError:
        raise InputError("TEOS-10 density needs the gsw package", key="equation",
                         value="teos10",
                         expected="pip install 'stripcoef[seawater]', or equation eos80") \
            from None
    sr = gsw.SR_from_SP(np.asarray(salinity, dtype=float))
    ct = gsw.CT_from_t(sr, np.asarray(temperature, dtype=float), 0.0)
    out = np.asarray(gsw.rho(sr, ct, 0.0), dtype=float)
    return float(out) if out.ndim == 0 else out


@dataclass(frozen=True)
class Fluid:
    """The water the vehicle moves in.

    Attributes
    ----------
    density : float
        rho [kg/m^3]
    kinematic_viscosity : float
        nu [m^2/s]
    source : str
        How the values were obtained (for reports).
    """

    density: float = RHO_SEAWATER
    kinematic_viscosity: float = NU_SEAWATER
    source: str = "default sea water (rho = 1025 kg/m^3, nu = 1.19e-6 m^2/s)"

    def __post_init__(self):
        # the one check of a fluid, however it was made (file, flags, temperature, API)
        for key, value in (("density", self.density),
                           ("kinematic_viscosity", self.kinematic_viscosity)):
            if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)) \
                    or not np.isfinite(value) or value <= 0:
                raise InputError(f"impossible water {key.replace('_', ' ')}", key=key,
                                 value=value, expected=f"a finite number > 0 ({self.source})")

    @classmethod
    def from_temperature_salinity(cls, temperature: float, salinity: float, *,
                                  equation: str = "eos80") -> "Fluid":
        """Fluid from water temperature [degC] and salinity [PSU] (EOS-80 + Sharqawy 2010).

        rho = rho_EOS80(t, S) [kg/m^3] (:func:`density_eos80`), or TEOS-10 with
        ``equation="teos10"`` (:func:`density_teos10`, needs gsw), mu = mu_Sharqawy(t, S)
        [Pa s] (:func:`dynamic_viscosity_sharqawy`), nu = mu / rho [m^2/s]; see those
        functions and the module docstring for the equations and their references.

        >>> water = Fluid.from_temperature_salinity(15.0, 35.0)
        >>> round(water.density, 2), round(water.kinematic_viscosity * 1e6, 3)   # [m^2/s] x 1e6
        (1025.97, 1.189)
        """
        if equation not in EQUATIONS:
            from stripcoef.errors import unknown_name
            raise unknown_name("equation of state", equation, EQUATIONS, key="equation")
        for name, value, lo, hi in (("temperature", temperature, 0.0, 40.0),
                                    ("salinity", salinity, 0.0, 42.0)):
            if not np.isfinite(value):
                raise InputError("not a finite number", key=name, value=value)
            if value < lo or value > hi:
                warnings.warn(f"{name} = {value} is outside the range {lo}-{hi} of the "
                              "EOS-80 / Sharqawy (2010) correlations", ExtrapolationWarning,
                              stacklevel=2)
        rho = (density_teos10 if equation == "teos10" else density_eos80)(temperature, salinity)
        mu = dynamic_viscosity_sharqawy(temperature, salinity)
        # outside their range the correlations are extrapolated (the warning above); where the
        # result is no longer liquid water (inside the range they give rho = 992-1034 kg/m^3 and
        # mu = 0.65-1.9e-3 Pa s; accepted: 950-1100 kg/m^3, 2e-4-5e-3 Pa s) it is an error
        if not (950.0 <= rho <= 1100.0 and 2e-4 <= mu <= 5e-3):
            key, value = (("salinity", salinity) if 0.0 <= temperature <= 40.0
                          else ("temperature", temperature))
            raise InputError("outside the validity of the EOS-80 / Sharqawy (2010) "
                             f"correlations: rho = {rho:.5g} kg/m^3, mu = {mu:.4g} Pa s",
                             key=key, value=value,
                             expected="0-40 degC and 0-42 PSU (water properties that exist)")
        name = "TEOS-10" if equation == "teos10" else "EOS-80"
        return cls(density=float(rho), kinematic_viscosity=float(mu / rho),
                   source=f"t = {temperature} degC, S = {salinity} PSU "
                          f"({name} density, Sharqawy 2010 viscosity)")

    def to_dict(self) -> dict:
        return {"density": self.density, "kinematic_viscosity": self.kinematic_viscosity,
                "source": self.source}
