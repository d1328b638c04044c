r"""The steady-state balance shared by the limit solvers: what it includes, what it requires.

:func:`required_force` is the generalized force a steady motion needs (Fossen 2011,
eq. 7.190 at :math:`\dot\nu = 0`); :mod:`stripcoef.limits.solver` balances it with
thrusters, :mod:`stripcoef.limits.steering` with thrusters and control surfaces.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class LimitOptions:
    """What the steady-state balance includes.

    Attributes
    ----------
    munk : bool
        Keep the Munk moment (the moment part of C_A(nu) nu).  Ferreira et al. (2009) neglect it.
    coriolis : bool
        Keep C(nu) = C_RB + C_A at all.
    """

    munk: bool = True
    coriolis: bool = True


def required_force(model, nu, eta=None, *, options: LimitOptions = LimitOptions()) -> np.ndarray:
    r"""Generalized force the thrusters must give to hold ``nu`` steady.

    .. math:: \tau_{req} = C(\nu)\nu + D(\nu)\nu + g(\eta)

    Parameters
    ----------
    model : HydroModel
    nu : (6,) array
        Body velocity [m/s, rad/s]
    eta : (6,) array, optional
        Pose [m, rad] (only roll and pitch matter); level by default
    options : LimitOptions
        Munk moment / Coriolis terms on or off

    Returns
    -------
    (6,) array
        [N, N, N, N m, N m, N m]

    References
    ----------
    Fossen (2011), eq. 7.190 with nu_dot = 0; Ferreira et al. 2009, eq. 23.
    """
    nu = np.asarray(nu, dtype=float)
    eta = np.zeros(6) if eta is None else np.asarray(eta, dtype=float)
    # the lifting fins' Munk compensation (in D) counted with C_A's Munk moment only
    tau = (model.damping(nu, munk=options.coriolis and options.munk) @ nu
           + model.restoring(eta))
    if options.coriolis:
        tau = tau + model.coriolis(nu, munk=options.munk) @ nu
    return tau
