r"""Steady flight of a vehicle steered by rudders and elevators: trim, turning circle, dive.

A torpedo AUV has one propeller and control surfaces: no thruster gives heave, sway or
yaw, so the balance of :mod:`stripcoef.limits.solver` (thrusters only) cannot hold it.  Its
steady states are found instead from the equations of motion at :math:`\dot\nu = 0`
(Fossen 2011, eq. 7.190) with the control-surface force (Prestero 2001, sec. 3.7):

.. math::
    B\,T + u|u|\,B_\delta\,\delta = C(\nu)\nu + D(\nu)\nu + g(\eta)

where :math:`D(\nu)` holds the lift terms :math:`u L` (:meth:`HydroModel.damping`).  Three
manoeuvres, each three rows solved for three unknowns (:func:`scipy.optimize.fsolve`),
the surge thrust :math:`X_T` shared over the thrusters in proportion to their surge
component (least-norm allocation of the X row):

* **level trim** (vertical plane, rows X, Z, M): unknowns :math:`X_T`, pitch :math:`\theta`,
  elevator :math:`\delta_s`, with :math:`w = u\tan\theta` so that the path is level
  (:math:`\dot z = -u\sin\theta + w\cos\theta = 0`, Fossen 2011, eq. 2.18).  A buoyant
  vehicle (B > W) flies nose-down with its elevator pushing it down; this is the trim it
  needs, reported, never refused.  Below some speed the elevator cannot hold the net
  buoyancy within its limit: the smallest level-flight speed.
* **dive / climb** (rows X, Z, M): at a pitch :math:`\theta`, unknowns :math:`X_T`, w,
  :math:`\delta_s`; depth rate :math:`\dot z = -u\sin\theta + w\cos\theta`.  The
  steepest dive is the pitch whose elevator reaches its limit (a full elevator may pitch
  the vehicle over: the hydrostatic moment cannot hold it, no straight steady dive exists).
* **turn** (horizontal plane, rows X, Y, N): the rudder at :math:`\delta_r`, unknowns
  :math:`X_T`, v, r; radius :math:`R = \sqrt{u^2+v^2}/|r|` and drift angle
  :math:`\beta = -\operatorname{atan2}(v, u)` (Ferreira et al. 2009, eq. 59, for the
  circle).  Heave and pitch of the turn are left out (the vertical plane is trimmed
  separately), and so is the heel.

The roll moment of the propeller torque is carried by a heel angle
:math:`\phi = \arcsin(K / (z_g W - z_b B))` (Fossen 2011, eq. 4.6, linearised).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq, fsolve

from stripcoef.errors import UnreachableError
from stripcoef.limits.balance import LimitOptions, required_force

#: Speeds of the turning-circle and dive tables, as fractions of the top speed [-].
SPEED_FRACTIONS = (0.25, 0.4, 0.55, 0.7, 0.85, 1.0)


@dataclass
class Flight:
    """One steady flight condition.

    Attributes
    ----------
    u : float
        Surge speed [m/s]
    nu : (6,) array
        Body velocity [m/s, rad/s]
    pitch, roll : float
        Attitude [rad]
    deflections : dict
        Control surface name -> deflection [rad]
    thrust : dict
        Thruster name -> thrust [N]
    load : float
        Largest thruster load |T|/T_max [-] (> 1: beyond the thrust limit)
    radius : float or None
        Turning radius [m] (turns only)
    yaw_rate : float
        r [rad/s]
    drift_angle : float
        -atan2(v, u) [rad]
    depth_rate : float
        dz/dt [m/s], positive down
    """

    u: float
    nu: np.ndarray
    pitch: float
    roll: float
    deflections: dict
    thrust: dict
    load: float
    radius: float | None = None
    yaw_rate: float = 0.0
    drift_angle: float = 0.0
    depth_rate: float = 0.0

    def to_dict(self) -> dict:
        return {"u": float(self.u), "nu": [float(x) for x in self.nu],
                "pitch": float(self.pitch), "roll": float(self.roll),
                "deflections": {k: float(v) for k, v in self.deflections.items()},
                "thrust": {k: float(v) for k, v in self.thrust.items()},
                "load": float(self.load),
                "radius": None if self.radius is None else float(self.radius),
                "yaw_rate": float(self.yaw_rate), "drift_angle": float(self.drift_angle),
                "depth_rate": float(self.depth_rate)}


@dataclass
class SteeringLimits:
    """Limits of a rudder/elevator-steered vehicle (JSON: :meth:`to_dict`)."""

    surge_speed_max: float
    level_speed_min: float | None
    trim: list[Flight]
    turning: list[Flight]
    dive: list[Flight]
    climb: list[Flight]
    notes: list[str] = field(default_factory=list)

    def to_dict(self) -> dict:
        return {"surge_speed_max": float(self.surge_speed_max),
                "level_speed_min": (None if self.level_speed_min is None
                                    else float(self.level_speed_min)),
                "trim": [f.to_dict() for f in self.trim],
                "turning": [f.to_dict() for f in self.turning],
                "dive": [f.to_dict() for f in self.dive],
                "climb": [f.to_dict() for f in self.climb],
                "notes": list(self.notes)}


class _Plant:
    """The model's pieces the steady equations need (computed once)."""

    def __init__(self, model, options):
        self.model = model
        self.options = options
        self.required = lambda nu, eta: required_force(model, nu, eta, options=options)
        self.B = model.allocation()
        self.bd = model.control_matrix
        self.names = [t.name for t in model.thrusters]
        sx = self.B[0]
        if not np.any(sx > 0.0):
            raise UnreachableError("no thruster pushes the vehicle forward")
        self.share = sx / float(sx @ sx)            # least-norm T for X_T = 1 N
        self.fmax = np.array([t.max_forward for t in model.thrusters], float)
        self.bmax = np.array([t.max_backward for t in model.thrusters], float)
        self.stiffness = model.weight * model.r_g[2] - model.buoyancy * model.r_b[2]

    def kind(self, kind: str) -> np.ndarray:
        """Unit deflection vector moving every surface of ``kind`` together."""
        return np.array([1.0 if s.kind == kind else 0.0 for s in self.model.control_surfaces])

    def limit(self, kind: str) -> float:
        lims = [s.max_deflection for s in self.model.control_surfaces if s.kind == kind]
        if not lims:
            raise UnreachableError(f"the vehicle has no {kind}")
        return float(min(lims))

    def thrust(self, x_t: float) -> np.ndarray:
        return self.share * x_t

    def load(self, thrust) -> float:
        with np.errstate(divide="ignore", invalid="ignore"):
            ld = np.where(thrust >= 0.0, thrust / self.fmax, -thrust / self.bmax)
        return float(np.nan_to_num(ld, nan=0.0, posinf=np.inf).max(initial=0.0))

    def balance(self, nu, eta, x_t, delta) -> np.ndarray:
        """B T + u|u| B_d delta - tau_req(nu, eta) [N, N m] (module docstring)."""
        u = nu[0]
        return (self.B @ self.thrust(x_t) + u * abs(u) * (self.bd @ delta)
                - self.required(nu, eta))

    def heel(self, nu, eta, x_t, delta) -> float:
        """Heel angle carrying the roll moment (module docstring) [rad]."""
        k = float(self.balance(nu, eta, x_t, delta)[3])
        if abs(k) < 1e-12:
            return 0.0
        if self.stiffness <= 0.0 or abs(k) >= self.stiffness:
            raise UnreachableError(f"roll moment {k:.4g} N m cannot be trimmed (z_g W - z_b B = "
                                   f"{self.stiffness:.4g} N m)")
        return math.asin(k / self.stiffness)

    def flight(self, u, nu, eta, x_t, delta, **extra) -> Flight:
        t = self.thrust(x_t)
        return Flight(u=u, nu=np.asarray(nu, float), pitch=float(eta[4]),
                      roll=self.heel(nu, eta, x_t, delta),
                      deflections={s.name: float(d) for s, d in
                                   zip(self.model.control_surfaces, delta)},
                      thrust={n: float(v) for n, v in zip(self.names, t)}, load=self.load(t),
                      **extra)


def _solve(f, x0, what: str, steps: int = 1):
    """Root of ``f(x, s)`` at s = 1 by continuation from s = 0 in ``steps`` steps
    (:func:`scipy.optimize.fsolve` at each; the previous root starts the next)."""
    x = np.asarray(x0, dtype=float)
    for s in np.linspace(0.0 if steps > 1 else 1.0, 1.0, steps + 1 if steps > 1 else 1):
        x, info, ier, msg = fsolve(lambda y, s=s: f(y, s), x, full_output=True, xtol=1e-12)
        res = np.abs(info["fvec"]).max()
        if ier != 1 and res > 1e-8 * (1.0 + np.abs(x).max()):
            raise UnreachableError(f"{what}: no steady state found ({msg.strip()})")
    return x


def level_trim(model, u: float, *, options=None, _plant=None) -> Flight:
    r"""Level flight at surge speed ``u`` [m/s]: thrust, pitch and elevator that balance X, Z, M.

    .. math:: w = u\tan\theta,\quad [B T + u^2 B_\delta \delta_s - \tau_{req}(\nu, \eta)]_{X,Z,M} = 0

    (module docstring; Fossen 2011, eqs. 4.6, 7.190; Prestero 2001, sec. 3.7). The elevator
    may come out beyond its limit: the vehicle cannot hold depth at that speed
    (:func:`level_speed_min`).
    """
    p = _plant or _Plant(model, _options(options))
    e = p.kind("elevator")

    def parts(x):
        x_t, theta, ds = x
        nu = np.array([u, 0.0, u * math.tan(theta), 0.0, 0.0, 0.0])
        eta = np.array([0.0, 0.0, 0.0, 0.0, theta, 0.0])
        return nu, eta, x_t, ds * e

    def f(x, s):
        return p.balance(*parts(x))[[0, 2, 4]]

    x0 = [float(p.required(np.array([u, 0, 0, 0, 0, 0.0]), np.zeros(6))[0]), 0.0, 0.0]
    x = _solve(f, x0, f"level flight at u = {u:.4g} m/s")
    return p.flight(u, *parts(x))


def free_flight(model, u: float, *, options=None, _plant=None) -> Flight:
    r"""Steady straight flight at surge speed ``u`` [m/s] of a vehicle without elevators.

    Unknowns thrust, pitch :math:`\theta` and heave w (rows X, Z, M), control surfaces at
    zero: the attitude its weight, buoyancy, lift and fins settle on; the path is not level
    and the depth rate :math:`\dot z = -u\sin\theta + w\cos\theta` [m/s] says how fast it
    rises or sinks (Fossen 2011, eqs. 2.18, 4.6, 7.190; module docstring).
    """
    p = _plant or _Plant(model, _options(options))
    zero = np.zeros(len(model.control_surfaces))

    def parts(x):
        x_t, theta, w = x
        return (np.array([u, 0.0, w, 0.0, 0.0, 0.0]),
                np.array([0.0, 0.0, 0.0, 0.0, theta, 0.0]), x_t, zero)

    def f(x, s):
        return p.balance(*parts(x))[[0, 2, 4]]

    x0 = [float(p.required(np.array([u, 0, 0, 0, 0, 0.0]), np.zeros(6))[0]), 0.0, 0.0]
    x = _solve(f, x0, f"free flight at u = {u:.4g} m/s")
    nu, eta, x_t, d = parts(x)
    return p.flight(u, nu, eta, x_t, d, depth_rate=-u * math.sin(eta[4])
                    + nu[2] * math.cos(eta[4]))


#: Steepest pitch searched for the dive and climb [rad] (assumption: AUV autopilots limit
#: pitch to well below this; beyond it the small-angle hydrostatic trim is poor).
PITCH_CAP = math.radians(60.0)


def dive(model, u: float, pitch: float, *, options=None, _plant=None) -> Flight:
    r"""Steady straight dive or climb at surge speed ``u`` [m/s] and pitch ``pitch`` [rad].

    Unknowns thrust, heave w and elevator :math:`\delta_s` (rows X, Z, M); the depth rate is
    :math:`\dot z = -u\sin\theta + w\cos\theta` [m/s] (Fossen 2011, eq. 2.18; module
    docstring). The elevator may come out beyond its limit (the pitch cannot be held).
    """
    p = _plant or _Plant(model, _options(options))
    e = p.kind("elevator")
    eta = np.array([0.0, 0.0, 0.0, 0.0, pitch, 0.0])

    def parts(x):
        x_t, w, ds = x
        return np.array([u, 0.0, w, 0.0, 0.0, 0.0]), eta, x_t, ds * e

    def f(x, s):
        return p.balance(*parts(x))[[0, 2, 4]]

    x0 = [float(p.required(np.array([u, 0, 0, 0, 0, 0.0]), np.zeros(6))[0]), 0.0, 0.0]
    x = _solve(f, x0, f"dive at u = {u:.4g} m/s, pitch {math.degrees(pitch):.3g} deg")
    nu, eta, x_t, d = parts(x)
    rate = -u * math.sin(pitch) + nu[2] * math.cos(pitch)
    return p.flight(u, nu, eta, x_t, d, depth_rate=rate)


def steepest_dive(model, u: float, sign: float, *, options=None, _plant=None) -> Flight:
    """The steepest steady dive (``sign`` = -1, nose down) or climb (+1) at ``u`` [m/s]
    whose elevator and thrusters stay within their limits, up to :data:`PITCH_CAP` (Brent on
    |delta_s(theta)| = delta_max; :func:`dive`)."""
    p = _plant or _Plant(model, _options(options))
    lim = p.limit("elevator")

    def excess(theta):
        # the larger of the elevator's and the thrusters' excess over their limits [-]
        try:
            f = dive(model, u, theta, _plant=p)
        except UnreachableError:
            return 1.0
        return max(max(abs(d) for d in f.deflections.values()) / lim, f.load) - 1.0

    grid = sign * np.linspace(0.0, PITCH_CAP, 13)        # 5 deg steps, then Brent
    prev = grid[0]
    if excess(prev) > 0.0:
        raise UnreachableError(f"u = {u:.4g} m/s: the elevators or the thrusters cannot "
                               "hold even level pitch within their limits")
    for theta in grid[1:]:
        if excess(theta) > 0.0:
            lo, hi = sorted((prev, theta))
            root = brentq(excess, lo, hi, xtol=1e-8)
            return dive(model, u, root, _plant=p)
        prev = theta
    return dive(model, u, grid[-1], _plant=p)


def rudder_turn(model, u: float, delta: float, *, options=None, _plant=None) -> Flight:
    r"""Steady turn at surge speed ``u`` [m/s] with every rudder at ``delta`` [rad].

    Unknowns thrust, sway v and yaw rate r (rows X, Y, N; module docstring);
    :math:`R = \sqrt{u^2+v^2}/|r|`, drift angle :math:`-\operatorname{atan2}(v, u)`
    (Ferreira et al. 2009, eq. 59). A positive rudder gives +Y at the tail and turns the
    vehicle to port (r < 0; Prestero 2001's convention).
    """
    p = _plant or _Plant(model, _options(options))
    dvec = delta * p.kind("rudder")

    def parts(x, s=1.0):
        x_t, v, r = x
        return np.array([u, v, 0.0, 0.0, 0.0, r]), np.zeros(6), x_t, s * dvec

    def f(x, s):
        return p.balance(*parts(x, s))[[0, 1, 5]]

    x0 = [float(p.required(np.array([u, 0, 0, 0, 0, 0.0]), np.zeros(6))[0]), 0.0, 0.0]
    x = _solve(f, x0, f"turn at u = {u:.4g} m/s, rudder {math.degrees(delta):.3g} deg",
               steps=8)
    nu, eta, x_t, d = parts(x)
    radius = math.hypot(u, nu[1]) / abs(nu[5]) if nu[5] != 0.0 else math.inf
    return p.flight(u, nu, eta, x_t, d, radius=radius, yaw_rate=float(nu[5]),
                    drift_angle=-math.atan2(nu[1], u))


def _options(options):
    return options if options is not None else LimitOptions()


def level_speed_min(model, u_max: float, *, options=None, _plant=None) -> float | None:
    """Smallest speed of level flight with the elevators within their limit [m/s].

    The root of :math:`|\\delta_s(u)| = \\delta_{max}` below ``u_max`` (Brent); 0 for a
    neutral vehicle; None when even ``u_max`` is not enough (module docstring).
    """
    p = _plant or _Plant(model, _options(options))
    lim = p.limit("elevator")

    def excess(u):
        t = level_trim(model, u, _plant=p)
        return max(abs(d) for d in t.deflections.values()) - lim

    if excess(u_max) > 0.0:
        return None
    lo = 1e-3 * u_max
    try:
        if excess(lo) <= 0.0:
            return 0.0
    except UnreachableError:
        pass
    return brentq(lambda u: _safe(excess, u), lo, u_max, xtol=1e-6 * u_max)


def _safe(func, u):
    try:
        return func(u)
    except UnreachableError:
        return 1.0


def steering_limits(model, *, options=None, turn_speed: float | None = None) -> SteeringLimits:
    """Top speed in level flight, smallest level speed, trims, turning circle, dive and climb.

    The top speed is the root of load(u) = 1 of the level trim (:func:`level_trim`); the
    tables are at :data:`SPEED_FRACTIONS` of it (and at ``turn_speed``) with the
    rudders/elevators at their limits (module docstring).
    """
    p = _Plant(model, _options(options))
    notes = []
    have_rudder = any(s.kind == "rudder" for s in model.control_surfaces)
    have_elevator = any(s.kind == "elevator" for s in model.control_surfaces)
    trim_of = level_trim if have_elevator else free_flight

    def load(u):
        return trim_of(model, u, _plant=p).load - 1.0

    # bracket the top speed: stepping up from 0.1 m/s by 25 % to the first speed the
    # thrusters can hold (slow level flight may need a steep, costly trim, or no trim
    # exists), then on to the first they cannot
    lo, u = None, 0.1
    while True:
        try:
            val = load(u)
        except UnreachableError:
            val = None
        if val is not None and val < 0.0:
            lo = u
        elif val is not None and lo is not None:
            break
        u *= 1.25
        if u > 1e3:
            raise UnreachableError("level flight: no speed from 0.1 to 1000 m/s the thrusters "
                                   "can hold" if lo is None else "level flight: no top speed "
                                   "below 1000 m/s")
    u_max = brentq(load, lo, u, xtol=1e-9)
    u_min = level_speed_min(model, u_max, _plant=p) if have_elevator else None
    if not have_elevator:
        notes.append("no elevator: the trim table is the free flight the vehicle settles on "
                     "(pitch and depth rate from its weight, buoyancy and lift)")
    elif u_min is None:
        notes.append("the elevators cannot hold the net buoyancy in level flight at any "
                     "speed up to the top speed")
    elif u_min > 0.0:
        notes.append(f"below u = {u_min:.3f} m/s the elevators cannot hold the net "
                     f"buoyancy (W - B = {model.weight - model.buoyancy:.4g} N) within "
                     f"their limit: the vehicle cannot hold depth")
    speeds = sorted(set([f * u_max for f in SPEED_FRACTIONS]
                        + ([float(turn_speed)] if turn_speed else [])))
    trim, turning, dives, climbs = [], [], [], []
    for u in speeds:
        if not have_elevator:
            trim.append(free_flight(model, u, _plant=p))
        if have_elevator:
            trim.append(level_trim(model, u, _plant=p))
            for sign, out in ((-1.0, dives), (1.0, climbs)):
                try:
                    out.append(steepest_dive(model, u, sign, _plant=p))
                except UnreachableError as exc:
                    notes.append(f"{'dive' if sign < 0 else 'climb'}: {exc}")
        if have_rudder:
            try:
                turning.append(rudder_turn(model, u, p.limit("rudder"), _plant=p))
            except UnreachableError as exc:   # e.g. a heel the restoring moment cannot hold
                notes.append(f"turn at full rudder, u = {u:.3f} m/s: {exc}")
    if not have_rudder:
        notes.append("no rudder: no turning circle")
    if not have_elevator:
        notes.append("no elevator: no dive or climb")
    for f in turning + dives + climbs:
        if f.load > 1.0 + 1e-6:
            notes.append(f"at u = {f.u:.3f} m/s the manoeuvre needs {f.load:.2f} times the "
                         "thrust limit (not sustainable)")
    return SteeringLimits(surge_speed_max=u_max, level_speed_min=u_min, trim=trim,
                          turning=turning, dive=dives, climb=climbs, notes=notes)
