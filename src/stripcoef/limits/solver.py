r"""Steady-state manoeuvre limits: how fast a vehicle can go, dive, turn, and on which circle.

At steady state (:math:`\dot\nu = 0`) the equations of motion (Fossen 2011, eq. 7.190;
Wang & Clark 2006 eq. 1; Ferreira et al. 2009 eq. 23) reduce to a balance between the generalized force the
vehicle *needs* and the force its thrusters *give*:

.. math::
    \tau_{req}(\nu, \eta) = C(\nu)\nu + D(\nu)\nu + g(\eta) = B\,T,
    \qquad -T_{max,-,i} \le T_i \le T_{max,+,i}

with :math:`B` the allocation matrix (:meth:`HydroModel.allocation`, one column
:math:`[d_i;\ r_i \times d_i]` per thruster) and :math:`T` the thrusts [N].  For a given
velocity the allocation is a bounded linear feasibility problem; it is solved as the
linear programme

.. math::
    s^*(\nu) = \min_{T, s}\ s \quad \text{s.t.}\quad B_S T = \tau_{S},\
    -s\,T_{max,-,i} \le T_i \le s\,T_{max,+,i}

(:func:`scipy.optimize.linprog`, HiGHS), whose value :math:`s^*` is the utilisation of the
most loaded thruster.  A manoeuvre of speed :math:`x` is reachable while
:math:`s^*(\nu(x)) \le 1`; the maximum speed is the root of :math:`s^*(\nu(x)) = 1`
(:func:`scipy.optimize.brentq` after bracketing).  At that root the most loaded thruster
is the one that saturates first.

Which rows must balance.  Translations and yaw have no hydrostatic stiffness, so their
rows are always enforced.  Roll and pitch are enforced only when the thrusters control
them independently of the other rows (a rank test on :math:`B`); otherwise the vehicle
trims: the residual moment is carried by the restoring moment
:math:`(z_g W - z_b B)\sin\phi` (Fossen 2011, eq. 4.6, linearised), and the trim angle is
reported.  A required row the thrusters cannot give (its component outside the range
of :math:`B_S`) makes the manoeuvre unreachable (:class:`UnreachableError`).

The steady turn (Ferreira et al. 2009, sec. V.D, eqs. 58-64): body velocity
:math:`\nu = [u, v, 0, 0, 0, r]` on a circle of radius :math:`R` with
:math:`r = \sqrt{u^2 + v^2}/R` (eq. 59).  The sway speed :math:`v` follows from the
sway row with no net sway thrust (eq. 60): :math:`\tau_{req,Y}(u, v, r) = 0`; the surge
and yaw rows are the paper's common- and differential-mode equations (61-64) and are
solved here, for any thruster layout, by the allocation above.

The Munk moment (Ferreira et al. 2009, sec. V.D) is the part of :math:`C_A(\nu)\nu` that turns
linear momentum into moments (:meth:`HydroModel.coriolis` with ``munk=False`` drops
it); ``coriolis=False`` drops :math:`C(\nu)` entirely.

References
----------
Fossen, Handbook of Marine Craft Hydrodynamics and Motion Control (2011), eqs. 4.6,
6.43, 7.190; Ferreira et al. 2009 (MARES), sec. V, eqs. 51-64 (equations lost in the extraction,
reconstructed from Fossen's model, see docs/limits.md); Wang & Clark 2006 (VideoRay), eq. 1.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq, linprog

from stripcoef.conventions import DOF, FORCES
from stripcoef.errors import InputError, ModelWarning, UnreachableError
from stripcoef.limits.balance import LimitOptions, required_force
from stripcoef.physical import check_physical

#: Rows that have no hydrostatic stiffness and must always balance.
_ALWAYS = (0, 1, 2, 5)
#: Rows that may be carried by a hydrostatic trim angle.
_TRIMMABLE = (3, 4)
#: Largest speed searched before declaring a limit unbounded [m/s or rad/s].
_SPEED_CAP = 1.0e3


# ---------------------------------------------------------------------------
# options and results
# ---------------------------------------------------------------------------
@dataclass
class Manoeuvre:
    """One steady manoeuvre at its limit.

    Attributes
    ----------
    speed : float
        The limit [m/s or rad/s]
    nu : (6,) array
        Body velocity at the limit [m/s, rad/s]
    thrust : dict
        Thruster name -> force [N]
    saturated : str
        Thruster at its limit (the first to saturate)
    trim : dict
        Hydrostatic trim angle of each uncontrolled rotation ("roll", "pitch") [rad]
    """

    speed: float
    nu: np.ndarray
    thrust: dict
    saturated: str
    trim: dict = field(default_factory=dict)
    at_limit: list = field(default_factory=list)


@dataclass
class TurnPoint:
    """The fastest steady turn on a circle of one radius.

    Attributes
    ----------
    radius : float [m]
    u_max : float
        Largest surge speed on the circle [m/s]
    v : float
        Sway speed at u_max [m/s]
    yaw_rate : float
        r = sqrt(u^2 + v^2) / R [rad/s]
    drift_angle : float
        Angle from the circle's tangent to the body x axis, psi - chi = -atan2(v, u)
        [rad]; positive when the nose points into the circle (starboard turn)
    thrust : dict
        Thruster name -> force [N]
    saturated : str
        Thruster at its limit
    trim : dict
        Hydrostatic trim angles of uncontrolled rotations [rad]
    """

    radius: float
    u_max: float
    v: float
    yaw_rate: float
    drift_angle: float
    thrust: dict
    saturated: str
    trim: dict = field(default_factory=dict)
    at_limit: list = field(default_factory=list)

    def to_dict(self) -> dict:
        return {"radius": float(self.radius), "u_max": float(self.u_max), "v": float(self.v),
                "yaw_rate": float(self.yaw_rate), "drift_angle": float(self.drift_angle),
                "thrust": {k: float(x) for k, x in self.thrust.items()},
                "saturated": self.saturated, "at_limit": list(self.at_limit),
                "trim": {k: float(x) for k, x in self.trim.items()}}


@dataclass
class LimitsResult:
    """Every limit of one vehicle (the JSON contract is :meth:`to_dict`)."""

    name: str
    surge: Manoeuvre
    heave: Manoeuvre | None
    yaw: Manoeuvre | None
    sway: Manoeuvre | None
    turning: list[TurnPoint]
    min_turning_radius: float | None
    min_turning_speed: float
    options: LimitOptions
    notes: list[str] = field(default_factory=list)
    thrust_limits: dict = field(default_factory=dict)
    steering: object = None     # SteeringLimits of a rudder/elevator-steered vehicle

    @property
    def surge_speed_max(self) -> float:
        return self.surge.speed

    @property
    def heave_speed_max(self) -> float | None:
        return None if self.heave is None else self.heave.speed

    @property
    def yaw_rate_max(self) -> float | None:
        return None if self.yaw is None else self.yaw.speed

    @property
    def sway_speed_max(self) -> float | None:
        return None if self.sway is None else self.sway.speed

    def to_dict(self) -> dict:
        """JSON contract: speeds [m/s], yaw rate [rad/s], radii [m], angles [rad], forces [N]."""
        def man(m):
            if m is None:
                return None
            return {"speed": float(m.speed), "nu": [float(x) for x in m.nu],
                    "thrust": {k: float(x) for k, x in m.thrust.items()},
                    "saturated": m.saturated, "at_limit": list(m.at_limit),
                    "trim": {k: float(x) for k, x in m.trim.items()}}

        return {
            "name": self.name,
            "surge_speed_max": float(self.surge_speed_max),
            "heave_speed_max": None if self.heave is None else float(self.heave.speed),
            "yaw_rate_max": None if self.yaw is None else float(self.yaw.speed),
            "sway_speed_max": None if self.sway is None else float(self.sway.speed),
            "min_turning_radius": (None if self.min_turning_radius is None
                                   else float(self.min_turning_radius)),
            "min_turning_radius_speed": float(self.min_turning_speed),
            "turning": [t.to_dict() for t in self.turning],
            "manoeuvres": {"surge": man(self.surge), "heave": man(self.heave),
                           "yaw": man(self.yaw), "sway": man(self.sway)},
            "options": {"munk": self.options.munk, "coriolis": self.options.coriolis},
            "notes": list(self.notes),
            "steering": None if self.steering is None else self.steering.to_dict(),
        }


# ---------------------------------------------------------------------------
# input checks
# ---------------------------------------------------------------------------
def check_model(model, *, file: str | None = None) -> None:
    """Raise :class:`InputError` if ``model`` cannot give limits.

    Needs at least one thruster, finite non-negative thrust limits with at least one
    direction positive per thruster, and drag matrices that dissipate energy:
    non-negative diagonals of D_L and D_Q and a positive semi-definite symmetric part of
    D_L (:math:`\\nu^T D_L \\nu \\ge 0`, Fossen 2011, sec. 6.4).
    """
    if not model.thrusters:
        raise InputError("vehicle has no thrusters", file=file, key="thrusters",
                         expected="at least one thruster with thrust limits")
    for i, t in enumerate(model.thrusters):
        for attr in ("max_forward", "max_backward"):
            val = float(getattr(t, attr))
            if not math.isfinite(val) or val < 0.0:
                raise InputError(f"thruster {t.name!r} has no usable thrust limit", file=file,
                                 key=f"thrusters[{i}].{attr}", value=val,
                                 expected="a finite thrust >= 0 [N]")
        if t.max_forward <= 0.0 and t.max_backward <= 0.0:
            raise InputError(f"thruster {t.name!r} gives no thrust", file=file,
                             key=f"thrusters[{i}].max_forward",
                             value=float(t.max_forward),
                             expected="a maximum thrust > 0 [N] in at least one direction")
        if np.linalg.norm(np.asarray(t.direction, float)) == 0.0:
            raise InputError(f"thruster {t.name!r} has no direction", file=file,
                             key=f"thrusters[{i}].direction", value=list(t.direction),
                             expected="a non-zero vector")
    check_physical(model, file=file)   # finite, positive-definite mass, dissipative drag


# ---------------------------------------------------------------------------
# the steady-state balance
# ---------------------------------------------------------------------------
class _Allocator:
    """Bounded allocation tau_S = B_S T on the rows the thrusters must balance."""

    def __init__(self, model):
        self.model = model
        self.names = [t.name for t in model.thrusters]
        self.B = model.allocation()
        self.fmax = np.array([float(t.max_forward) for t in model.thrusters])
        self.bmax = np.array([float(t.max_backward) for t in model.thrusters])
        rows = list(_ALWAYS)
        self.trimmed = []
        for i in _TRIMMABLE:
            if self._rank(rows + [i]) > self._rank(rows):
                rows.append(i)
            else:
                self.trimmed.append(i)
        self.rows = sorted(rows)
        bs = self.B[self.rows]
        u, sv, _ = np.linalg.svd(bs, full_matrices=False)
        k = int(np.sum(sv > 1e-10 * max(sv[0], 1e-300))) if sv.size else 0
        self.basis = u[:, :k]                       # orthonormal basis of range(B_S)
        self.A = self.basis.T @ bs                  # full row rank k x n
        self.square = np.linalg.inv(self.A) if k == bs.shape[1] and k > 0 else None
        self.scale = float(np.max(np.abs(self.B) @ np.maximum(self.fmax, self.bmax)))
        m = model
        self.stiffness = m.weight * m.r_g[2] - m.buoyancy * m.r_b[2]   # z_g W - z_b B [N m]
        n = len(self.names)
        eye = np.eye(n)
        self.A_ub = np.vstack([np.hstack([eye, -self.fmax[:, None]]),
                               np.hstack([-eye, -self.bmax[:, None]])])
        self.b_ub = np.zeros(2 * n)
        self.c = np.zeros(n + 1)
        self.c[-1] = 1.0
        self.bounds = [(None, None)] * n + [(0.0, None)]

    def _rank(self, rows):
        return int(np.linalg.matrix_rank(self.B[rows], tol=1e-10 * max(1.0, np.abs(self.B).max())))

    def controls(self, row: int) -> bool:
        """True if the thrusters can give a force in ``row`` (range of B_S)."""
        if row not in self.rows:
            return False
        e = np.zeros(len(self.rows))
        e[self.rows.index(row)] = 1.0
        return float(np.linalg.norm(self.basis.T @ e)) > 1e-8

    def outside(self, tau) -> np.ndarray:
        """Part of the required rows that no thrust combination gives."""
        ts = tau[self.rows]
        return ts - self.basis @ (self.basis.T @ ts)

    def utilisation(self, tau):
        """(s*, T) of the min-max allocation; s* = inf when the rows cannot balance.

        s* = min s s.t. B_S T = tau_S, -s T_max,- <= T <= s T_max,+ (module docstring);
        ``tau`` [N, N m]; returns s* [-] and T [N].
        """
        out = self.outside(tau)
        tol = 1e-7 * (self.scale + float(np.abs(tau).max()))
        if np.abs(out).max(initial=0.0) > tol:
            return math.inf, None
        b = self.basis.T @ tau[self.rows]
        if self.square is not None:
            # as many independent rows as thrusters: the allocation is unique, T = A^-1 b
            thrust = self.square @ b
            return float(self.loads(thrust).max(initial=0.0)), thrust
        a_eq = np.hstack([self.A, np.zeros((self.A.shape[0], 1))])
        res = linprog(self.c, A_ub=self.A_ub, b_ub=self.b_ub, A_eq=a_eq, b_eq=b,
                      bounds=self.bounds, method="highs")
        if res.status != 0:
            return math.inf, None
        return float(res.x[-1]), np.asarray(res.x[:-1])

    def explain_outside(self, tau, what: str) -> str:
        out = self.outside(tau)
        i = int(np.argmax(np.abs(out)))
        row = self.rows[i]
        unit = "N" if row < 3 else "N m"
        return (f"{what}: no thruster combination gives the {DOF[row]} force "
                f"{FORCES[row]} = {tau[row]:.4g} {unit} it needs")

    def trim(self, tau, thrust) -> dict:
        """Hydrostatic trim angle of each uncontrolled rotation [rad] (linearised eq. 4.6).

        angle = asin(M_resid / (z_g W - z_b B)), residual moment M_resid = B_i T - tau_i [N m],
        stiffness [N m] (roll/pitch rows of g(eta), Fossen 2011, eq. 4.6, the other
        rotation at zero); ``tau`` [N, N m], ``thrust`` [N].
        """
        out = {}
        for i in self.trimmed:
            resid = float(self.B[i] @ thrust - tau[i])
            if abs(resid) <= 1e-9 * (self.scale + 1.0):
                out[DOF[i]] = 0.0
                continue
            if self.stiffness <= 0.0:
                raise UnreachableError(
                    f"{DOF[i]} moment {-resid:.4g} N m cannot be trimmed: the vehicle is not "
                    f"hydrostatically stable (z_g W - z_b B = {self.stiffness:.4g} N m) and no "
                    f"thruster controls {DOF[i]}")
            ratio = resid / self.stiffness
            if abs(ratio) >= 1.0:
                raise UnreachableError(
                    f"{DOF[i]} moment {-resid:.4g} N m exceeds the largest restoring moment "
                    f"{self.stiffness:.4g} N m and no thruster controls {DOF[i]}")
            out[DOF[i]] = math.asin(ratio)
        return out

    def thrust_dict(self, thrust) -> dict:
        return {n: float(x) for n, x in zip(self.names, thrust)}

    def loads(self, thrust) -> np.ndarray:
        """|T_i| / limit_i in the direction of T_i [-]."""
        with np.errstate(divide="ignore", invalid="ignore"):
            load = np.where(thrust >= 0.0, thrust / self.fmax, -thrust / self.bmax)
        return np.nan_to_num(load, nan=0.0, posinf=np.inf)

    def at_limit(self, thrust) -> list[str]:
        """Names of every thruster loaded within 1e-6 of the most loaded (ties: all)."""
        load = self.loads(thrust)
        top = float(load.max())
        return [n for n, x in zip(self.names, load) if x >= top - 1e-6 * max(top, 1.0)]

    def most_loaded(self, thrust) -> str:
        """The first (in the vehicle's order) of :meth:`at_limit`."""
        return self.at_limit(thrust)[0]


def _max_speed(evaluate, what: str, *, hint: float | None = None):
    """Largest x >= 0 with s*(x) <= 1, by bracketing then Brent's method.

    ``evaluate(x)`` returns ``(s, payload)``.  Raises UnreachableError when even
    x = 0 is not reachable or when no finite limit exists below the search cap.
    """
    s0, _ = evaluate(0.0)
    if not math.isfinite(s0):
        raise UnreachableError(f"{what}: the thrusters cannot hold the vehicle still "
                               "(a force at rest, e.g. net buoyancy, that no thruster gives)")
    if not s0 <= 1.0:
        raise UnreachableError(f"{what}: not reachable even at zero speed (thruster "
                               f"utilisation {s0:.3g} > 1 holding the vehicle still)")
    lo = 0.0
    hi = hint if hint and hint > 0.0 else 0.1
    while True:
        s, _ = evaluate(hi)
        if s > 1.0:
            break
        lo = hi
        hi *= 2.0
        if hi > _SPEED_CAP:
            raise UnreachableError(f"{what}: no finite limit below {_SPEED_CAP:g} "
                                   "(no drag in this direction?)")

    def f(x):
        s, _ = evaluate(x)
        return (s if math.isfinite(s) else 1.0e6) - 1.0

    x = brentq(f, lo, hi, xtol=1e-10 + 1e-9 * hi, rtol=1e-12, maxiter=200)
    return x


def _single_dof(model, alloc, dof: int, what: str, options: LimitOptions) -> Manoeuvre:
    """Limit of one velocity component; the others are zero except a free sway drift
    when no thruster gives sway (e.g. a sway force from Y_r while yawing on the spot)."""
    free = dof != 1 and not alloc.controls(1)

    def nu_of(x):
        nu = np.zeros(6)
        nu[dof] = x
        if free and x != 0.0:
            def with_v(v):
                n = nu.copy()
                n[1] = v
                return n
            nu[1] = _free_sway(model, with_v, options, speed=abs(x) if dof < 3 else abs(x) * 0.1,
                               what=what)
        return nu

    def evaluate(x):
        tau = required_force(model, nu_of(x), options=options)
        return alloc.utilisation(tau)

    tau1 = required_force(model, nu_of(1e-3), options=options)
    if not math.isfinite(alloc.utilisation(tau1)[0]):
        raise UnreachableError(alloc.explain_outside(tau1, what))
    x = _max_speed(evaluate, what)
    nu = nu_of(x)
    tau = required_force(model, nu, options=options)
    s, thrust = alloc.utilisation(tau)
    return Manoeuvre(speed=x, nu=nu, thrust=alloc.thrust_dict(thrust),
                     saturated=alloc.most_loaded(thrust), trim=alloc.trim(tau, thrust),
                     at_limit=alloc.at_limit(thrust))


# ---------------------------------------------------------------------------
# public API
# ---------------------------------------------------------------------------
def surge_limit(model, *, options: LimitOptions = LimitOptions()) -> Manoeuvre:
    r"""Largest forward speed, straight and level (Ferreira et al. 2009, eqs. 51-53).

    .. math:: -(X_u + X_{u|u|}|u|)\,u = \textstyle\sum_i T_i d_{x,i}, \quad \nu = [u,0,0,0,0,0]

    (SNAME signs: :math:`X_u = -D_{L,11} \le 0`, so the left side is the positive drag)

    together with every other row of :math:`\tau_{req} = B T` (the single-DOF closed form
    :math:`u = (-D_L + \sqrt{D_L^2 + 4 D_Q T})/(2 D_Q)` when nothing couples).

    Returns
    -------
    Manoeuvre
        speed [m/s], thrusts [N], saturated thruster
    """
    check_model(model)
    return _single_dof(model, _Allocator(model), 0, "surge", options)


def heave_limit(model, *, options: LimitOptions = LimitOptions()) -> Manoeuvre:
    r"""Largest dive (downward, +w) speed at zero pitch (Ferreira et al. 2009, eqs. 54-55).

    .. math:: -(Z_w + Z_{w|w|}|w|)\,w - (W - B) = \textstyle\sum_i T_i d_{z,i}

    (FRD: z down, so a heavy vehicle, W > B, is helped by its weight when diving; SNAME
    signs, :math:`Z_w = -D_{L,33} \le 0`; W, B [N], thrusts [N]; :math:`g_z = -(W-B)`,
    Fossen 2011, eq. 4.6).

    Returns
    -------
    Manoeuvre
        speed w [m/s], thrusts [N], saturated thruster
    """
    check_model(model)
    return _single_dof(model, _Allocator(model), 2, "heave", options)


def yaw_limit(model, *, options: LimitOptions = LimitOptions()) -> Manoeuvre:
    r"""Largest yaw rate turning on the spot (Ferreira et al. 2009, eqs. 56-57).

    .. math:: -(N_r + N_{r|r|}|r|)\,r = \textstyle\sum_i T_i (r_i \times d_i)_z

    (SNAME signs, :math:`N_r = -D_{L,66} \le 0`; lever arms r_i [m], thrusts [N]).

    Returns
    -------
    Manoeuvre
        speed = yaw rate r [rad/s], thrusts [N], saturated thruster
    """
    check_model(model)
    return _single_dof(model, _Allocator(model), 5, "yaw", options)


def sway_limit(model, *, options: LimitOptions = LimitOptions()) -> Manoeuvre | None:
    r"""Largest sway speed, or None when no thruster gives a sway force.

    .. math:: -(Y_v + Y_{v|v|}|v|)\,v = \textstyle\sum_i T_i d_{y,i}

    (SNAME signs, :math:`Y_v = -D_{L,22} \le 0`), with every other row of
    :math:`\tau_{req} = B T` (module docstring; Fossen 2011, eq. 7.190 at steady state).

    Returns
    -------
    Manoeuvre or None
        speed v [m/s], thrusts [N], saturated thruster
    """
    check_model(model)
    alloc = _Allocator(model)
    if not alloc.controls(1):
        return None
    return _single_dof(model, alloc, 1, "sway", options)


def _free_sway(model, nu_of_v, options: LimitOptions, *, speed: float, what: str) -> float:
    """Sway speed v with no net sway thrust: tau_req,Y(nu(v)) = 0 (Ferreira et al. 2009, eq. 60).

    ``nu_of_v(v)`` builds the body velocity; ``speed`` sets the search scale [m/s].
    The root nearest v = 0 is taken (bracketed outwards on both sides, then Brent).
    """
    def g(v):
        return required_force(model, nu_of_v(v), options=options)[1]

    g0 = g(0.0)
    ref = abs(g(speed)) if speed > 0.0 else 0.0
    if g0 == 0.0 or abs(g0) <= 1e-13 * ref:
        return 0.0
    a = max(0.02 * speed, 1e-9)
    top = max(200.0 * speed, 10.0)
    while a <= top:
        for side in (-1.0, 1.0):
            if g(side * a) * g0 <= 0.0:
                lo, hi = sorted((0.0, side * a))
                return brentq(g, lo, hi, xtol=1e-15 + 1e-12 * max(speed, abs(a)), rtol=1e-13)
        a *= 2.0
    raise UnreachableError(f"{what}: no sway speed balances the sway force "
                           f"({g0:.4g} N at v = 0) and no thruster gives sway")


def _sway_balance(model, u: float, radius: float, options: LimitOptions) -> float:
    """Sway speed v with tau_req,Y(u, v, r = sqrt(u^2+v^2)/R) = 0 (Ferreira et al. 2009, eq. 60).

    ``u`` [m/s], ``radius`` R [m]; returns v [m/s]; r from Ferreira et al. 2009, eq. 59.
    """
    if u == 0.0:
        return 0.0
    return _free_sway(model, lambda v: [u, v, 0.0, 0.0, 0.0, math.hypot(u, v) / radius],
                      options, speed=abs(u),
                      what=f"turn of radius {radius:g} m at u = {u:.4g} m/s")


def steady_turn(model, radius: float, u: float, *, options: LimitOptions = LimitOptions(),
                _alloc=None) -> TurnPoint:
    r"""Thrusts for a steady starboard turn of radius R at surge speed u (Ferreira et al. 2009, sec. V.D).

    .. math::
        \nu = [u, v, 0, 0, 0, r], \quad r = \sqrt{u^2+v^2}/R, \quad
        \tau_{req,Y}(\nu) = 0, \quad \tau_{req}(\nu) = B T

    Raises UnreachableError if the thrusters cannot hold it (u above u_max(R)).
    """
    alloc = _alloc or _Allocator(model)
    if not (radius > 0.0 and math.isfinite(radius)):
        raise InputError("turning radius must be positive", key="radius", value=radius,
                         expected="a finite radius > 0 [m]")
    v = _sway_balance(model, u, radius, options)
    r = math.hypot(u, v) / radius
    tau = required_force(model, [u, v, 0.0, 0.0, 0.0, r], options=options)
    s, thrust = alloc.utilisation(tau)
    if thrust is None:
        raise UnreachableError(alloc.explain_outside(tau, f"turn of radius {radius:g} m"))
    if s > 1.0 + 1e-7:
        try:
            rmin = f"; the smallest circle at this speed is R = " \
                   f"{min_turning_radius(model, u, options=options):.4g} m"
        except UnreachableError:
            rmin = "; no steady turn is possible at this speed"
        raise UnreachableError(
            f"turn of radius {radius:g} m at u = {u:.4g} m/s needs {s:.3g} times the thrust "
            f"limit of thruster {alloc.most_loaded(thrust)!r}{rmin}")
    return TurnPoint(radius=radius, u_max=u, v=v, yaw_rate=r,
                     drift_angle=-math.atan2(v, u) if u or v else 0.0,
                     thrust=alloc.thrust_dict(thrust), saturated=alloc.most_loaded(thrust),
                     trim=alloc.trim(tau, thrust), at_limit=alloc.at_limit(thrust))


def turn_limit(model, radius: float, *, options: LimitOptions = LimitOptions(),
               _alloc=None, _hint: float | None = None) -> TurnPoint:
    """The fastest steady starboard turn on a circle of ``radius`` [m] (Ferreira et al. 2009, Figs. 6-8).

    u_max(R) is the root of s*(u) = 1 where s* is the min-max thruster utilisation of
    the turn at surge speed u with v from the sway balance (see :func:`steady_turn`).
    """
    alloc = _alloc or _Allocator(model)
    if not (radius > 0.0 and math.isfinite(radius)):
        raise InputError("turning radius must be positive", key="radius", value=radius,
                         expected="a finite radius > 0 [m]")
    if not alloc.controls(5):
        raise UnreachableError("turn: no thruster gives a yaw moment")
    what = f"turn of radius {radius:g} m"

    def evaluate(u):
        v = _sway_balance(model, u, radius, options)
        r = math.hypot(u, v) / radius
        tau = required_force(model, [u, v, 0.0, 0.0, 0.0, r], options=options)
        s, thrust = alloc.utilisation(tau)
        if thrust is None and u > 0.0:
            raise UnreachableError(alloc.explain_outside(tau, what))
        return s, thrust

    u = _max_speed(evaluate, what, hint=_hint)
    point = steady_turn(model, radius, u, options=options, _alloc=alloc)
    point.radius = radius
    return point


def turning_curve(model, radii, *, options: LimitOptions = LimitOptions()) -> list[TurnPoint]:
    """u_max(R), v, drift angle, thrusts and saturated thruster for each radius [m].

    Per radius R [m], :func:`turn_limit`: u_max [m/s] is the root of s*(u) = 1 with
    nu = [u, v, 0, 0, 0, r], r = sqrt(u^2 + v^2)/R [rad/s] (Ferreira et al. 2009, eqs. 59-60) and drift
    angle beta = -atan2(v, u) [rad]; thrusts [N]. See module docstring (Ferreira et al. 2009, sec. V.D).
    """
    radii = check_radii(radii)
    check_model(model)
    alloc = _Allocator(model)
    out = []
    hint = None
    for radius in radii:
        p = turn_limit(model, float(radius), options=options, _alloc=alloc, _hint=hint)
        out.append(p)
        hint = 1.2 * p.u_max if p.u_max > 0 else None
    return out


def min_turning_radius(model, speed: float, *, options: LimitOptions = LimitOptions(),
                       r_hi: float = 1.0e4) -> float:
    r"""Smallest circle the vehicle can hold at surge speed ``speed`` [m/s].

    The root of :math:`u_{max}(R) = u` (u_max rises with R).  A thruster-steered vehicle
    turns on the spot (R -> 0) as u -> 0, so a minimum radius only exists at a stated
    speed.  Raises UnreachableError if even a straight line is too fast.

    Returns R_min [m]: the root of :math:`s^*(\nu(R)) = 1` with
    :math:`\nu = [u, v, 0, 0, 0, \sqrt{u^2+v^2}/R]` (Ferreira et al. 2009, eqs. 59-60; module docstring).
    """
    check_model(model)
    alloc = _Allocator(model)
    if not alloc.controls(5):
        raise UnreachableError("turn: no thruster gives a yaw moment")

    def f(radius):
        try:
            v = _sway_balance(model, speed, radius, options)
        except UnreachableError:
            return 1.0
        r = math.hypot(speed, v) / radius
        tau = required_force(model, [speed, v, 0.0, 0.0, 0.0, r], options=options)
        s, _ = alloc.utilisation(tau)
        return (s if math.isfinite(s) else 1e6) - 1.0

    hi = 1.0
    while f(hi) > 0.0:
        hi *= 2.0
        if hi > r_hi:
            raise UnreachableError(f"no steady turn at u = {speed:.4g} m/s on a circle "
                                   f"smaller than {r_hi:g} m (straight-line limit reached)")
    lo = hi / 2.0
    while f(lo) <= 0.0:
        hi = lo
        lo /= 2.0
        if lo < 1e-6:
            return 0.0
    return brentq(f, lo, hi, xtol=1e-9 * hi, rtol=1e-10)


#: Most turning radii solved in one run (each takes ~10 ms: 1000 take ~10 s).
MAX_RADII = 1000


def check_radii(radii) -> np.ndarray:
    """Radii must be positive, finite and strictly increasing [m], at most :data:`MAX_RADII`."""
    arr = np.atleast_1d(np.asarray(radii, dtype=float))
    if arr.ndim != 1 or arr.size == 0:
        raise InputError("no turning radii", key="radii", value=list(arr.ravel()),
                         expected="one or more radii > 0 [m]")
    if arr.size > MAX_RADII:
        raise InputError("too many turning radii", key="radii", value=int(arr.size),
                         expected=f"at most {MAX_RADII}")
    if not np.all(np.isfinite(arr)) or np.any(arr <= 0.0):
        bad = float(arr[~(np.isfinite(arr) & (arr > 0.0))][0])
        raise InputError("turning radius must be positive", key="radii", value=bad,
                         expected="radii > 0 [m]")
    if np.any(np.diff(arr) <= 0.0):
        raise InputError("turning radii are not increasing", key="radii",
                         value=[float(x) for x in arr[:6]],
                         expected="strictly increasing radii [m]")
    return arr


#: Turning radii solved when none are given: 40 from 0.5 m to 20 m [m].
DEFAULT_RADII = (0.5, 20.0, 40)


def solve_limits(model, *, radii=None, munk: bool = True, coriolis: bool = True,
                 turn_speed: float | None = None) -> LimitsResult:
    """Every manoeuvre limit of ``model`` (a :class:`~stripcoef.model.HydroModel`).

    Parameters
    ----------
    model : HydroModel
        With thrusters that have finite thrust limits
    radii : array, optional
        Turning radii [m], positive and increasing (default 0.5 to 20 m, 40 radii)
    munk, coriolis : bool
        Include the Munk moment / the Coriolis-centripetal terms
    turn_speed : float, optional
        Surge speed [m/s] at which the minimum turning radius is given (default: half the
        straight-line maximum)

    Raises
    ------
    InputError
        No thrusters, unusable thrust limits, non-positive drag, bad radii
    UnreachableError
        The thrusters cannot hold the vehicle in straight-line surge, or ``turn_speed``
        has no steady circle.  Any other manoeuvre they cannot do at all (no thruster
        gives heave or yaw, ...) is ``None`` in the result with the reason in ``notes``.
    """
    check_model(model)
    options = LimitOptions(munk=munk, coriolis=coriolis)
    if getattr(model, "control_surfaces", ()) or (
            np.any(getattr(model, "lift", 0.0)) and not _Allocator(model).controls(2)):
        # steered by control surfaces, or a finned body whose thrusters give no heave
        return _steered_limits(model, options, turn_speed)
    radii = check_radii(np.linspace(*DEFAULT_RADII[:2], DEFAULT_RADII[2]) if radii is None else radii)
    alloc = _Allocator(model)
    notes = []
    if alloc.trimmed:
        notes.append("not controlled by the thrusters, carried by a hydrostatic trim angle: "
                     + ", ".join(DOF[i] for i in alloc.trimmed))
    surge = _single_dof(model, alloc, 0, "surge", options)

    def attempt(func, *args, **kwargs):
        # a manoeuvre the thrusters cannot do at all is reported (null + note), not fatal
        try:
            return func(*args, **kwargs)
        except UnreachableError as exc:
            notes.append(f"unreachable: {exc}")
            return None

    heave = attempt(_single_dof, model, alloc, 2, "heave", options)
    yaw = attempt(_single_dof, model, alloc, 5, "yaw", options)
    sway = attempt(_single_dof, model, alloc, 1, "sway", options) if alloc.controls(1) else None
    turning = attempt(turning_curve, model, radii, options=options) or []
    speed = 0.5 * surge.speed if turn_speed is None else float(turn_speed)
    if turn_speed is not None:
        rmin = min_turning_radius(model, speed, options=options)    # asked for: errors are errors
    else:
        rmin = attempt(min_turning_radius, model, speed, options=options) if turning else None
    for key, m in (("surge", surge), ("heave", heave), ("yaw", yaw)):
        if m is None:
            continue
        big = {k: a for k, a in m.trim.items() if abs(a) > math.radians(15.0)}
        if big:
            warnings.warn(f"{key} limit needs a trim of "
                          + ", ".join(f"{k} {math.degrees(a):.1f} deg" for k, a in big.items())
                          + "; the linearised trim is inaccurate there", ModelWarning,
                          stacklevel=2)
    return LimitsResult(name=model.name, surge=surge, heave=heave, yaw=yaw, sway=sway,
                        turning=turning, min_turning_radius=rmin, min_turning_speed=speed,
                        options=options, notes=notes,
                        thrust_limits={t.name: (float(t.max_forward), float(t.max_backward))
                                       for t in model.thrusters})




def _steered_limits(model, options: LimitOptions, turn_speed) -> LimitsResult:
    """Limits of a vehicle with rudders/elevators (:mod:`stripcoef.limits.steering`): the top
    speed of trimmed level flight, the turning circle at full rudder, dive and climb.

    The surge manoeuvre is the level trim at the top speed (pitch and heel in ``trim``);
    ``min_turning_radius`` is the full-rudder circle at ``turn_speed`` (default half the top
    speed). Heave, yaw and sway on the spot are None: no thruster gives them.
    """
    from stripcoef.limits.steering import (free_flight, level_trim, rudder_turn,  # noqa: PLC0415
                                           steering_limits)

    steer = steering_limits(model, options=options, turn_speed=turn_speed)
    trim_of = level_trim if any(s.kind == "elevator" for s in model.control_surfaces) \
        else free_flight
    top = trim_of(model, steer.surge_speed_max, options=options)
    loads = {n: abs(t) / (lim[0] if t >= 0 else lim[1]) if (lim[0] if t >= 0 else lim[1]) else 0.0
             for (n, t), lim in zip(top.thrust.items(),
                                    ((th.max_forward, th.max_backward) for th in model.thrusters))}
    top_load = max(loads.values())
    at_limit = [n for n, x in loads.items() if x >= top_load - 1e-6 * max(top_load, 1.0)]
    surge = Manoeuvre(speed=steer.surge_speed_max, nu=top.nu, thrust=top.thrust,
                      saturated=at_limit[0], trim={"roll": top.roll, "pitch": top.pitch},
                      at_limit=at_limit)
    speed = 0.5 * steer.surge_speed_max if turn_speed is None else float(turn_speed)
    rmin = None
    if any(s.kind == "rudder" for s in model.control_surfaces):
        lim = min(s.max_deflection for s in model.control_surfaces if s.kind == "rudder")
        rmin = rudder_turn(model, speed, lim, options=options).radius
    notes = ["steered by control surfaces (or finned without heave thrust): heave, yaw and "
             "sway on the spot need thrusters this vehicle does not have; see steering (trim, "
             "turning circle, dive, climb)"]
    notes += steer.notes
    return LimitsResult(name=model.name, surge=surge, heave=None, yaw=None, sway=None,
                        turning=[], min_turning_radius=rmin, min_turning_speed=speed,
                        options=options, notes=notes,
                        thrust_limits={t.name: (float(t.max_forward), float(t.max_backward))
                                       for t in model.thrusters},
                        steering=steer)
