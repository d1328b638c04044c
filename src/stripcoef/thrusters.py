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

A propeller also turns the vehicle the other way round its shaft: its reaction torque is
proportional to the thrust when both follow the same :math:`n|n|` law,
:math:`Q = K_Q \rho n^2 D^5 = (K_Q D / K_T)\,T`, so each thruster carries a signed
``torque_ratio`` :math:`k_Q = Q/T` [m] and its moment is :math:`k_Q T d` about its axis d
(Prestero 2001, sec. 3.8: K_prop = -0.543 N m at X_prop = 3.86 N, k_Q = -0.141 m for
REMUS; open-water K_T, K_Q of Carlton, Marine Propellers and Propulsion, ch. 6).
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
    torque_ratio : float
        Propeller reaction torque per newton of thrust, k_Q = Q/T [m], signed: the moment
        on the vehicle is ``k_Q T d`` (module docstring; 0 = no torque)
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
    torque_ratio: float = 0.0

    def thrust(self, n):
        r"""Thrust for command ``n`` [N]: :math:`T = \eta_\pm C_{t,\pm} n|n|`, saturated at the limits.

        ``n`` [command units]; zero for ``|n| <= deadband``; clipped to
        ``[-max_backward, max_forward]`` [N]. Wang & Clark (2006), eq. 6 (see module docstring).
        """
        if np.ndim(n) == 0:     # one command (the simulation's right-hand side): floats,
            x = float(n)        # the same operations as the array path below
            t = (self.ct_forward * self.eta_forward if x >= 0.0
                 else self.ct_backward * self.eta_backward) * x * abs(x)
            if self.deadband > 0.0 and abs(x) <= self.deadband:
                t = 0.0
            return min(max(t, -self.max_backward), self.max_forward)     # a NaN stays NaN
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
        r"""Generalized force per newton of thrust about a point: :math:`[d;\ (p - o) \times d + k_Q d]`.

        ``reference_point`` o [m] in FRD body axes; returns [-] (force rows) and [m]
        (moment rows). Moment of a point force, :math:`M = r \times F`; the
        :math:`\tau` of Wang & Clark 2006, eq. 1; plus the propeller torque
        :math:`k_Q T d` (module docstring, Prestero 2001, sec. 3.8).
        """
        d = np.asarray(self.direction, dtype=float)
        r = np.asarray(self.position, dtype=float) - np.asarray(reference_point, dtype=float)
        return np.concatenate([d, skew(r) @ d + float(self.torque_ratio) * d])

    def to_dict(self) -> dict:
        """Plain data (JSON/YAML); no limit (``inf``) is ``None``, the one encoding of
        non-finite values (docs/conventions.md), read back by :meth:`limit_from_data`."""
        def limit(v):
            return float(v) if np.isfinite(v) else None

        return {
            "name": self.name,
            "position": [float(x) for x in self.position],
            "direction": [float(x) for x in self.direction],
            "ct_forward": self.ct_forward, "ct_backward": self.ct_backward,
            "max_forward": limit(self.max_forward), "max_backward": limit(self.max_backward),
            "eta_forward": self.eta_forward, "eta_backward": self.eta_backward,
            "deadband": self.deadband,
            **({"torque_ratio": self.torque_ratio} if self.torque_ratio else {}),
        }

    @staticmethod
    def limit_from_data(value) -> float:
        """A thrust limit read from data [N]: ``None`` (or absent) means no limit, ``inf``."""
        return float("inf") if value is None else float(value)


def allocation_matrix(thrusters, reference_point=(0.0, 0.0, 0.0)) -> np.ndarray:
    r"""6 x n_thrusters matrix B with tau = B @ thrusts (about ``reference_point``).

    .. math:: B_{:,i} = [d_i;\ (p_i - o) \times d_i]

    ``reference_point`` o [m]; B [-] in force rows, [m] in moment rows; tau [N, N m],
    thrusts [N]. The :math:`\tau` of Wang & Clark 2006, eq. 1 (see :meth:`Thruster.wrench_column`).
    """
    if not thrusters:
        return np.zeros((6, 0))
    return np.column_stack([t.wrench_column(reference_point) for t in thrusters])


def check_command_columns(commanded, thrusters, *, file: str | None = None) -> None:
    """Command columns ``n_<name>`` of an inputs log against the model's thrusters.

    ``commanded``: the thruster names that have a column. Each must be a thruster of the
    model (a renamed column is an error), and when any thruster is commanded every one must
    be: a missing column would run that thruster switched off without a word (issue 36).
    A thruster that is off has a column of zeros.
    """
    from stripcoef.errors import InputError

    names = [t.name for t in thrusters]
    commanded = list(commanded)
    for name in commanded:
        if name not in names:
            raise InputError("unknown thruster", file=file, key="n_" + name,
                             expected="one of " + ", ".join("n_" + n for n in names))
    missing = [n for n in names if n not in commanded]
    if commanded and missing:
        raise InputError(f"no command column for thruster {missing[0]!r}", file=file,
                         key="n_" + missing[0],
                         expected="a column for every thruster when any is commanded ("
                                  + ", ".join("n_" + n for n in names)
                                  + "; zeros for a thruster that is off)")
