r"""Thrusters: position, direction and the command-to-thrust map.

The thrust of one thruster at command ``n`` (propeller speed or the vehicle's
command signal) follows the bilinear model of Yoerger et al. (1990), as used by
Wang & Clark (Wang & Clark 2006, eq. 6) with separate forward and backward
coefficients (Wang & Clark 2006, Table I):

.. math::
    T(n) = \eta_\pm\, C_{t,\pm}\, n |n|, \qquad
    T \in [-T_{max,-},\ T_{max,+}]

with ``+`` for ``n >= 0``.  The efficiency ``eta`` per direction is the
propeller-hull interaction factor of Caccia et al. (Indiveri 1998, eq. 4.16).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from stripcoef.conventions import skew


@dataclass(frozen=True)
class Thruster:
    """One thruster.

    Attributes
    ----------
    name : str
        Identifier; log files carry its command in the column ``n_<name>``.
    position : (3,) array
        Point of application in FRD body axes [m]
    direction : (3,) array
        Unit vector of positive thrust in FRD body axes [-]
    ct_forward, ct_backward : float
        Thrust coefficients for ``n >= 0`` and ``n < 0`` [N per command^2]
    max_forward, max_backward : float
        Largest thrust magnitude in each direction [N] (``inf`` = unlimited)
    eta_forward, eta_backward : float
        Efficiency per direction [-] (1 = as measured on the bench)
    deadband : float
        Commands with ``|n| <= deadband`` give no thrust [command units]
    """

    name: str
    position: np.ndarray
    direction: np.ndarray
    ct_forward: float = 1.0
    ct_backward: float = 1.0
    max_forward: float = float("inf")
    max_backward: float = float("inf")
    eta_forward: float = 1.0
    eta_backward: float = 1.0
    deadband: float = 0.0
    source: dict = field(default_factory=dict, compare=False)

    def thrust(self, n):
        r"""Thrust for command ``n`` [N]: :math:`T = \eta_\pm C_{t,\pm} n|n|`, saturated at the limits.

        ``n`` [command units]; zero for ``|n| <= deadband``; clipped to
        ``[-max_backward, max_forward]`` [N]. Seed 000, eq. 6 (see module docstring).
        """
        n = np.asarray(n, dtype=float)
        fwd = n >= 0.0
        ct = np.where(fwd, self.ct_forward * self.eta_forward, self.ct_backward * self.eta_backward)
        t = ct * n * np.abs(n)
        if self.deadband > 0.0:
            t = np.where(np.abs(n) <= self.deadband, 0.0, t)
        t = np.clip(t, -self.max_backward, self.max_forward)
        return float(t) if t.ndim == 0 else t

    def command_for(self, thrust):
        r"""Inverse map: command giving ``thrust`` [N] (unsaturated).

        .. math:: n = \operatorname{sign}(T) \sqrt{|T| / (\eta_\pm C_{t,\pm})}

        Returns ``n`` [command units]; ignores the deadband and the limits.
        Inverse of Wang & Clark 2006, eq. 6 (see module docstring).
        """
        t = np.asarray(thrust, dtype=float)
        ct = np.where(t >= 0.0, self.ct_forward * self.eta_forward,
                      self.ct_backward * self.eta_backward)
        n = np.sign(t) * np.sqrt(np.abs(t) / ct)
        return float(n) if n.ndim == 0 else n

    def wrench_column(self, reference_point=(0.0, 0.0, 0.0)) -> np.ndarray:
        r"""Generalized force per newton of thrust about a point: :math:`[d;\ (p - o) \times d]`.

        ``reference_point`` o [m] in FRD body axes; returns [-] (force rows) and [m]
        (moment rows). Moment of a point force, :math:`M = r \times F`; the
        :math:`\tau` of Wang & Clark 2006, eq. 1.
        """
        d = np.asarray(self.direction, dtype=float)
        r = np.asarray(self.position, dtype=float) - np.asarray(reference_point, dtype=float)
        return np.concatenate([d, skew(r) @ d])

    def to_dict(self) -> dict:
        """The thruster as plain data; an unlimited thrust (``inf``) is left out, so that every
        number written is finite (``HydroModel.from_dict`` reads a missing limit as ``inf``)."""
        out = {
            "name": self.name,
            "position": [float(x) for x in self.position],
            "direction": [float(x) for x in self.direction],
            "ct_forward": self.ct_forward, "ct_backward": self.ct_backward,
            "max_forward": self.max_forward, "max_backward": self.max_backward,
            "eta_forward": self.eta_forward, "eta_backward": self.eta_backward,
            "deadband": self.deadband,
        }
        for key in ("max_forward", "max_backward"):
            if out[key] == float("inf"):
                del out[key]
        return out


def allocation_matrix(thrusters, reference_point=(0.0, 0.0, 0.0)) -> np.ndarray:
    r"""6 x n_thrusters matrix B with tau = B @ thrusts (about ``reference_point``).

    .. math:: B_{:,i} = [d_i;\ (p_i - o) \times d_i]

    ``reference_point`` o [m]; B [-] in force rows, [m] in moment rows; tau [N, N m],
    thrusts [N]. The :math:`\tau` of Wang & Clark 2006, eq. 1 (see :meth:`Thruster.wrench_column`).
    """
    if not thrusters:
        return np.zeros((6, 0))
    return np.column_stack([t.wrench_column(reference_point) for t in thrusters])
