r"""A 6-DOF simulator written independently of ``stripcoef.simulate``, for the diagnosis benchmark.

Issue 33 asks for logs that stripcoef's own simulation did not make: a diagnosis tuned on logs
of its own simulator can pass by sharing that simulator's simplifications. This module shares
no code with ``stripcoef.simulate``, ``stripcoef.model`` (its C(nu), g(eta), J(eta)) or
``stripcoef.thrusters``: it reads a vehicle's *numbers* only (the matrices, the points and the
thruster data of ``HydroModel.to_dict()``) and integrates them with its own equations:

- rigid body and added mass in Fossen's form (Fossen 2011, eqs. 3.46, 6.43 and 7.190),
  :math:`M\dot\nu = \tau - C_{RB}(\nu)\nu - C_A(\nu_r)\nu_r - D(\nu_r)\nu_r - g(q)
  + M_A\dot\nu_c`, with :math:`C(\nu)` built from the blocks of the mass matrix, the relative
  velocity :math:`\nu_r = \nu - [R^T v_c; 0]` of a constant NED current;
- attitude as a unit quaternion, :math:`\dot q = \tfrac12 q \otimes [0, \omega]`
  (Fossen 2011, eq. 2.82), renormalised every step; position :math:`\dot p = R(q) v`;
- restoring forces from the weight at the CG and the buoyancy at the CB, rotated into the body
  by :math:`R(q)^T` (Fossen 2011, sec. 4.1);
- thrusters: command -> pure delay (a buffer) -> dead band -> :math:`T = \eta C_t n|n|`
  (forward and backward branches) -> limits -> first-order lag of the thrust
  (:math:`\dot T = (T_{cmd} - T)/\tau`), applied at each thruster's position along its axis;
- undeclared effects: tether drag :math:`-c_t L u_r|u_r|` (L the paid-out length), thrust
  asymmetry, momentum drag :math:`-\alpha\,n_h\,w_r` (:math:`n_h` the mean |command| of the
  thrusters that do not push in heave, Indiveri 1998; :func:`momentum_drag`), buoyancy offset,
  current, linear
  drag, dead band, added-mass error, thruster lag, actuation delay, thrust effectiveness, and
  one effect no library describes: Coulomb (dry) friction :math:`-F_c \tanh(u_r/0.02)`;
- a fixed-step classical Runge-Kutta integrator (RK4, 10 ms), the delay and lag states
  stepped with it;
- a pilot (:class:`Pilot`) of steps, doublets, chirps and holds of depth, heading, roll and
  pitch (on the *measured* state), flown for persistent excitation: the net buoyancy trimmed
  out, the demands symmetric about the trim and scaled to the authority left, so that every
  driven DOF moves both ways and the thrusters rarely saturate (:func:`excitation` measures
  it); the wrench turned into thruster commands by the pseudo-inverse allocation and the
  vehicle file's thrust map;
- seeded sensor noise (:data:`NOISE`, the same levels as ``validation.synthetic``, a stated
  assumption) at 10 Hz.

The truth is the prior with every coefficient family scaled by an independent factor drawn
from U(0.75, 1.25) (:func:`perturbed_truth`) plus the effect at a random strength
(:data:`STRENGTHS`).
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

import numpy as np

from stripcoef.logfile import Log

#: Sensor noise standard deviations (assumed: a DVL, a MEMS gyro, an AHRS, a USBL/pressure
#: fix) [m/s, rad/s, rad, m].
NOISE = {"u": 0.01, "v": 0.01, "w": 0.01, "p": 0.003, "q": 0.003, "r": 0.003,
         "phi": 0.005, "theta": 0.005, "psi": 0.005, "x": 0.02, "y": 0.02, "z": 0.02}
GRAVITY = 9.81
#: Strength ranges of the undeclared effects (uniform draws), the DOF they act in, and the
#: quantity compared with the diagnosis's ``magnitude`` (the library effect's own).
STRENGTHS = {
    "tether_drag": ("surge", (0.08, 0.3)),          # c_t [N s^2/m^3]
    "thrust_asymmetry": ("surge", (0.5, 0.75)),     # eta_backward / eta_forward [-], of the prior's map
    # s = alpha n_h,full / d_w [-]: the momentum drag's linear coefficient at the non-acting
    # thrusters' full command, a share of the hull's heave drag (momentum_drag_alpha); the
    # truth's strength is alpha [N s/m per command unit]
    "momentum_drag": ("heave", (0.5, 1.0)),
    "buoyancy_offset": ("heave", (0.3, 0.8)),       # B - B_prior [N] (lighter than the prior)
    "current": ("surge", (0.1, 0.25)),              # |v_c| [m/s]
    "linear_drag": ("surge", (1.5, 4.0)),           # X_u [N s/m]
    "deadband": ("surge", (0.15, 0.3)),             # dead band [share of full command]
    "added_mass_error": ("surge", (2.0, 3.0)),      # true X_udot / prior X_udot [-]
    "thruster_lag": ("surge", (0.3, 0.8)),          # time constant [s]
    "actuation_delay": ("surge", (0.2, 0.5)),       # delay [s]
    "thrust_effectiveness": ("surge", (0.55, 0.8)),  # delivered / mapped thrust [-]
}
#: Outside the library: dry friction of a cable guide or a rubbing tether, F_c [N].
OUTSIDE = {"coulomb_friction": ("surge", (0.3, 0.6))}


def _skew(a):
    x, y, z = a.tolist() if isinstance(a, np.ndarray) else a    # floats: the same values,
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])  # without numpy scalars


def _cross(a, b):
    """a x b of two 3-vectors: numpy.cross's products and differences in its order (the
    same floats) without its per-call overhead (the right-hand side calls it three times a
    stage: 18 of 40 s of a 120 s log's profile)."""
    a0, a1, a2 = a.tolist() if isinstance(a, np.ndarray) else a   # floats: the same
    b0, b1, b2 = b.tolist() if isinstance(b, np.ndarray) else b   # IEEE products
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


def _coriolis(m, nu):
    """C(nu) of a symmetric 6x6 inertia (Fossen 2011, eqs. 3.46 and 6.43): the blocks of
    [[0, -S(M11 v + M12 w)], [-S(M11 v + M12 w), -S(M21 v + M22 w)]]."""
    v, w = nu[:3], nu[3:]
    a = m[:3, :3] @ v + m[:3, 3:] @ w
    b = m[3:, :3] @ v + m[3:, 3:] @ w
    c = np.zeros((6, 6))
    c[:3, 3:] = c[3:, :3] = -_skew(a)
    c[3:, 3:] = -_skew(b)
    return c


def _rotation(q):
    """Body-to-NED rotation of a unit quaternion q = [eta, e1, e2, e3] (Fossen 2011, eq. 2.72)."""
    n, e = q[0], q[1:]
    s = _skew(e)
    return np.eye(3) + 2.0 * n * s + 2.0 * s @ s


def _euler(q):
    """zyx Euler angles of a unit quaternion [rad] (Fossen 2011, eq. 2.86)."""
    n, e1, e2, e3 = q
    phi = np.arctan2(2 * (e3 * e2 + n * e1), 1 - 2 * (e1 ** 2 + e2 ** 2))
    theta = -np.arcsin(np.clip(2 * (e1 * e3 - n * e2), -1.0, 1.0))
    psi = np.arctan2(2 * (e1 * e2 + n * e3), 1 - 2 * (e2 ** 2 + e3 ** 2))
    return phi, theta, psi


@dataclass
class Truth:
    """The simulated vehicle: matrices about its reference point (FRD), weight, buoyancy, and
    thrusters, plus the undeclared effect (name, strength, extras)."""

    m_rb: np.ndarray
    m_a: np.ndarray
    d_l: np.ndarray
    d_q: np.ndarray
    weight: float
    buoyancy: float
    r_g: np.ndarray
    r_b: np.ndarray
    thrusters: list
    effect: str | None = None
    strength: float | None = None
    current: np.ndarray = field(default_factory=lambda: np.zeros(3))
    lag: float = 0.0
    delay: float = 0.0


def perturbed_truth(model: dict, rng, *, spread: float = 0.25) -> Truth:
    """The prior's numbers (``HydroModel.to_dict()``) with every coefficient family scaled by its
    own factor from U(1 - spread, 1 + spread): each diagonal of M_A, D_L, D_Q (couplings scaled
    as sqrt(f_i f_j), keeping the matrices symmetric), the weight, the buoyancy and each
    thruster's coefficient."""
    def congruent(mat):
        f = np.sqrt(rng.uniform(1 - spread, 1 + spread, 6))
        return np.asarray(mat, float) * np.outer(f, f)

    ref = np.asarray(model["reference_point"], float)
    m_rb = np.asarray(model["rigid_body_mass"], float)
    mass = float(model["mass"])
    thr = []
    for t in model["thrusters"]:
        f = rng.uniform(1 - spread, 1 + spread)
        thr.append({"name": t["name"], "position": np.asarray(t["position"], float) - ref,
                    "direction": np.asarray(t["direction"], float) /
                    np.linalg.norm(t["direction"]),
                    "ct_forward": f * float(t.get("ct_forward", 1.0)) *
                    float(t.get("eta_forward", 1.0)),
                    "ct_backward": f * float(t.get("ct_backward", 1.0)) *
                    float(t.get("eta_backward", 1.0)),
                    "max_forward": _limit(t.get("max_forward")),
                    "max_backward": _limit(t.get("max_backward")), "deadband": 0.0})
    weight = mass * GRAVITY
    # near neutral, as the prior: the buoyancy keeps the prior's B/W within +-2 %
    ratio = float(model["density"]) * float(model["volume"]) / mass
    return Truth(m_rb=m_rb, m_a=congruent(model["added_mass"]),
                 d_l=congruent(model["linear_damping"]), d_q=congruent(model["quadratic_damping"]),
                 weight=weight, buoyancy=weight * ratio * rng.uniform(0.98, 1.02),
                 r_g=np.asarray(model["center_of_gravity"], float) - ref,
                 r_b=np.asarray(model["center_of_buoyancy"], float) - ref, thrusters=thr)


def _limit(v):
    return float("inf") if v is None else float(v)


def with_effect(truth: Truth, name: str | None, rng, prior: dict) -> Truth:
    """``truth`` carrying the undeclared effect ``name`` at a random strength (STRENGTHS)."""
    if name is None:
        return truth
    _, (lo, hi) = {**STRENGTHS, **OUTSIDE}[name]
    s = float(rng.uniform(lo, hi))
    truth.effect, truth.strength = name, s
    if name == "thrust_asymmetry":
        # relative to the prior's own branches, the quantity the library's ratio is (the
        # priors are not symmetric: the VideoRay's backward branch is 0.39 of its forward
        # one, so ct_backward = s ct_forward was a backward thrust 1.3-1.9x the prior's)
        for t in truth.thrusters:
            t["ct_backward"] = s * t["ct_backward"]
    elif name == "buoyancy_offset":
        # the offset from the prior's own buoyancy, the quantity the library's b is (the
        # prior need not be neutral: the VideoRay file's B - W is +0.30 N, so B = W + s
        # with s = 0.3 N was no offset at all); as added_mass_error and linear_drag, the
        # perturbed value is replaced
        truth.buoyancy = float(prior["density"]) * float(prior["volume"]) * GRAVITY + s
    elif name == "current":
        ang = rng.uniform(0, 2 * np.pi)
        truth.current = s * np.array([np.cos(ang), np.sin(ang), 0.0])
    elif name == "linear_drag":
        truth.d_l = truth.d_l.copy()
        truth.d_l[0, 0] = s
    elif name == "deadband":
        full = max(_full_command(t) for t in truth.thrusters)
        truth.strength = s * full
        for t in truth.thrusters:
            t["deadband"] = s * full
    elif name == "added_mass_error":
        truth.m_a = truth.m_a.copy()
        truth.m_a[0, 0] = s * float(prior["added_mass"][0][0])
        truth.strength = truth.m_a[0, 0] - float(prior["added_mass"][0][0])
    elif name == "momentum_drag":
        truth.strength = momentum_drag_alpha(truth, s)
    elif name == "thruster_lag":
        truth.lag = s
    elif name == "actuation_delay":
        truth.delay = s
    elif name == "thrust_effectiveness":
        for t in truth.thrusters:
            t["ct_forward"] *= s
            t["ct_backward"] *= s
    return truth


#: The DOF of the momentum drag (STRENGTHS) as a body axis index (a translation).
_AXIS = {"surge": 0, "sway": 1, "heave": 2}


def idle_thrusters(truth: Truth, axis: int) -> list[int]:
    """Indices of the thrusters whose force has no component along body axis ``axis`` (0-2):
    for heave, the horizontal thrusters, the "four horizontal thrusters" of Indiveri (1998)."""
    return [k for k, t in enumerate(truth.thrusters) if abs(t["direction"][axis]) <= 1e-9]


def momentum_drag(alpha: float, n_cmd, idle: list[int], w_r: float) -> float:
    r"""Momentum drag in the DOF [N] (Indiveri 1998, ch. 4, sec. 4.2.4, the eta-md heave model:
    :math:`\eta F = k_w w + k_{w|w|} w|w| - W + \alpha n_h w`, i.e.

    .. math:: F_{md} = -\alpha\, n_h\, w_r,\qquad n_h = \frac{1}{|H|}\sum_{k\in H} |n_k|

    with :math:`H` the thrusters that do not act in the DOF (the paper's "mean propeller
    revolution rate modulus of the four horizontal thrusters" for heave), :math:`n_k` their
    commands [command units], :math:`\alpha` [N s/m per command unit] and :math:`w_r` the
    velocity through the water in the DOF [m/s]. Zero when those thrusters are idle, or when
    there are none."""
    if not idle:
        return 0.0
    n_h = float(np.mean(np.abs(np.asarray(n_cmd, float)[idle])))
    return -alpha * n_h * w_r


def momentum_drag_alpha(truth: Truth, share: float) -> float:
    r"""alpha [N s/m per command unit] of a momentum drag whose linear coefficient at the idle
    thrusters' full command is ``share`` of the hull's heave drag [-]:
    :math:`\alpha = s\, d_w / \bar n_{full}`, :math:`\bar n_{full}` the mean full command of
    the thrusters not acting in the DOF (:func:`_full_command`) and :math:`d_w = F_{max}/w_{max}
    = D_L + D_Q w_{max}` [N s/m] the hull's drag linearised at the speed where it balances the
    full thrust in the DOF (:math:`D_L w + D_Q w^2 = F_{max}`, the truth's drag, Fossen 2011
    eq. 6.59; :math:`F_{max}` the sum of the thrusters' forward limits along the axis). The
    same share is the same physical size on any vehicle, whatever its command units (a
    VideoRay's are ~220, a BlueROV2's 1)."""
    axis = _AXIS[STRENGTHS["momentum_drag"][0]]
    idle = idle_thrusters(truth, axis)
    if not idle:
        return 0.0
    f_max = sum(abs(t["direction"][axis]) * (t["max_forward"] if np.isfinite(t["max_forward"])
                                             else t["ct_forward"]) for t in truth.thrusters)
    dl, dq = float(truth.d_l[axis, axis]), float(truth.d_q[axis, axis])
    w_max = (2.0 * f_max / (dl + np.sqrt(dl * dl + 4.0 * dq * f_max)) if dq > 0.0
             else f_max / dl)
    n_full = float(np.mean([_full_command(truth.thrusters[k]) for k in idle]))
    return share * (dl + dq * w_max) / n_full


def _full_command(t) -> float:
    """The command that gives the thruster's forward limit (1 when unlimited) [command]."""
    lim = t["max_forward"]
    return float(np.sqrt(lim / t["ct_forward"])) if np.isfinite(lim) else 1.0


def _thrust(t, n):
    """Thrust of command n [N]: dead band, both branches, limits (Wang & Clark 2006, eq. 6)."""
    if abs(n) <= t["deadband"]:
        return 0.0
    ct = t["ct_forward"] if n >= 0 else t["ct_backward"]
    return float(min(max(ct * n * abs(n), -t["max_backward"]), t["max_forward"]))


class Simulator:
    """Fixed-step RK4 of the state [p (3), q (4), nu (6), T (k thrusts)] (module docstring)."""

    def __init__(self, truth: Truth, dt: float = 0.01):
        self.truth, self.dt = truth, dt
        t = truth
        self.m = t.m_rb + t.m_a
        self.b = np.array([np.concatenate([th["direction"], np.cross(th["position"],
                                                                     th["direction"])])
                           for th in t.thrusters]).T
        self.k = len(t.thrusters)
        self.md_axis = _AXIS[STRENGTHS["momentum_drag"][0]]
        self.md_idle = idle_thrusters(t, self.md_axis)
        self.down_weight = np.array([0.0, 0.0, t.weight])
        self.up_buoyancy = np.array([0.0, 0.0, -t.buoyancy])

    def _restoring(self, r):
        """g(q): the force is -g [N, N m] (weight down at the CG, buoyancy up at the CB)."""
        t = self.truth
        fw = r.T @ self.down_weight
        fb = r.T @ self.up_buoyancy
        return -np.concatenate([fw + fb, _cross(t.r_g, fw) + _cross(t.r_b, fb)])

    def rhs(self, x, n_cmd, tether, target=None):
        """The state's rate; ``target`` the thrusts the commands ``n_cmd`` ask for (given by
        :meth:`step`, the same for its four stages), else computed here."""
        t = self.truth
        q = x[3:7] / np.linalg.norm(x[3:7])
        nu, thrust = x[7:13], x[13:13 + self.k]
        r = _rotation(q)
        vc = r.T @ t.current
        nu_r = nu - np.concatenate([vc, np.zeros(3)])
        nu_c_dot = np.concatenate([-_skew(nu[3:]) @ vc, np.zeros(3)])
        if target is None:
            target = self.target(n_cmd)
        if t.lag > 0.0:
            thrust_dot = (target - thrust) / t.lag
            applied = thrust
        else:
            thrust_dot = np.zeros(self.k)
            applied = target
        tau = self.b @ applied if self.k else np.zeros(6)
        if t.effect == "tether_drag":
            tau = tau + np.array([-t.strength * tether * nu_r[0] * abs(nu_r[0]), 0, 0, 0, 0, 0])
        elif t.effect == "momentum_drag":
            tau = tau.copy()
            tau[self.md_axis] += momentum_drag(t.strength, n_cmd, self.md_idle,
                                               nu_r[self.md_axis])
        elif t.effect == "coulomb_friction":
            tau = tau + np.array([-t.strength * np.tanh(nu_r[0] / 0.02), 0, 0, 0, 0, 0])
        damping = (t.d_l + t.d_q * np.abs(nu_r)) @ nu_r
        force = (tau - _coriolis(t.m_rb, nu) @ nu - _coriolis(t.m_a, nu_r) @ nu_r - damping
                 - self._restoring(r) + t.m_a @ nu_c_dot)
        nu_dot = np.linalg.solve(self.m, force)
        w = nu[3:]
        q_dot = 0.5 * np.array([-q[1:] @ w, *(q[0] * w + _cross(q[1:], w))])
        return np.concatenate([r @ nu[:3], q_dot, nu_dot, thrust_dot])

    def target(self, n_cmd) -> np.ndarray:
        """The thrusts [N] the commands ``n_cmd`` ask for (:func:`_thrust`)."""
        return np.array([_thrust(th, n) for th, n in zip(self.truth.thrusters, n_cmd)])

    def step(self, x, n_cmd, tether):
        h = self.dt
        target = self.target(n_cmd)
        k1 = self.rhs(x, n_cmd, tether, target)
        k2 = self.rhs(x + 0.5 * h * k1, n_cmd, tether, target)
        k3 = self.rhs(x + 0.5 * h * k2, n_cmd, tether, target)
        k4 = self.rhs(x + h * k3, n_cmd, tether, target)
        x = x + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        x[3:7] /= np.linalg.norm(x[3:7])
        return x


#: The pilot's closed loops, each designed as a second-order response of the vehicle file's
#: inertia :math:`M_{ii}` (rigid body plus added mass): (natural frequency [rad/s], damping
#: ratio [-]); gains :math:`K_p = M_{ii}\omega^2`, :math:`K_d = 2\zeta\omega M_{ii}`. The
#: frequencies are far under the 10-Hz command rate (:math:`K_d T / M_{ii} =
#: 2\zeta\omega T \le 0.36`, the sampled loop's limit is 2; the earlier pilot's roll hold
#: had ~3). The attitude loop is as fast as the benchmark's largest actuation delay (0.5 s)
#: allows: measured on a BlueROV2-Heavy-like log (seed 906317, 60 s), mean |roll| 0.16, 0.11
#: and 0.07 rad at 1, 2 and 3 rad/s, but 0.27, 0.23 and 0.59 rad with a 0.5-s delay.
LOOPS = {"depth": (0.5, 0.9), "attitude": (2.0, 0.9), "heading": (0.5, 0.9)}
#: The yaw-rate stick's loop bandwidth [1/s] (a first-order rate response).
RATE_BANDWIDTH = 1.0
#: The depth hold's integral time [s] (a slow trim correction; the integral is frozen during
#: heave manoeuvres and bounded to a tenth of the heave authority).
INTEGRAL_TIME = 20.0
#: The share of each thruster's limit that the allocation plans with [-].
MARGIN = 0.9


def pilot_wrench(rng, t, dofs):
    """Open-loop wrench demands [N, N m] (unit scale) over time: random steps, a doublet and a
    chirp in each DOF of ``dofs``, with quiet spells; the PD holds are added in the loop.

    The sign of the manoeuvres alternates within each DOF (the first one's drawn with equal
    odds, then +, -, +, ... over the manoeuvres that are not quiet spells): the demands
    are symmetric about zero, hence about the pilot's trim (:class:`Pilot`), in every log,
    not only on average over logs. With independently drawn signs a short log can push a
    DOF one way only (e.g. 3 steps of one sign in 30 s happen with probability 1/4), and a
    model fitted on it is not identifiable for the other branch of a thruster, a drag's
    sign dependence or a thrust asymmetry: the input must excite both signs, the
    persistent-excitation condition of the input for the model class (Ljung 1999, System
    Identification, ch. 13, sec. 13.2 on informative experiments and 13.3 on input
    design: symmetric binary-like signals about the operating point). The random draws are
    the same in number and order as with independent signs (the sign of each manoeuvre is
    still drawn, only the first is used), so the amplitudes, durations and kinds of a seed
    and everything drawn after them (noise) are unchanged."""
    n = t.size
    out = np.zeros((n, 6))
    for d in dofs:
        k = 0
        first, m = 0.0, 0       # the DOF's first sign, and its manoeuvres so far
        while k < n:
            hold = int(rng.uniform(4.0, 12.0) / (t[1] - t[0]))
            kind = rng.choice(["step", "doublet", "chirp", "zero"], p=[0.45, 0.2, 0.2, 0.15])
            seg = slice(k, min(k + hold, n))
            tt = t[seg] - t[seg][0]
            size, drawn = rng.uniform(0.3, 1.0), float(rng.choice([-1, 1]))
            if kind != "zero":
                first = first or drawn
                m += 1
            amp = size * first * (-1.0) ** (m - 1)
            if kind == "step":
                out[seg, d] = amp
            elif kind == "doublet":
                out[seg, d] = amp * np.where(tt < tt[-1] / 2 if tt.size else 0, 1, -1)
            elif kind == "chirp":
                f0, f1 = 0.05, 0.5
                out[seg, d] = amp * np.sin(2 * np.pi * (f0 + (f1 - f0) * tt /
                                                        max(tt[-1], 1e-9) / 2) * tt)
            k += hold
    return out


def _feasible_share(base, extra, lo, hi) -> float:
    """The largest :math:`\\lambda \\in [0, 1]` with ``lo <= base + lambda extra <= hi`` for every
    thruster (``base`` inside the limits) [-]."""
    lam = 1.0
    for b, e, low, high in zip(base, extra, lo, hi):
        if e > 0.0:
            lam = min(lam, (high - b) / e)
        elif e < 0.0:
            lam = min(lam, (low - b) / e)
    return max(lam, 0.0)


class Pilot:
    r"""The pilot and autopilot of :func:`generate`: how a ROV pilot flies an identification
    run, written for persistent excitation.

    A log identifies a coefficient only if the inputs excite its DOF persistently, in both
    directions and over a range of frequencies (Ljung 1999, ch. 13, "persistence of
    excitation"; Åström & Eykhoff 1971): a velocity of one sign only makes a
    Coulomb term :math:`\mathrm{sign}(w)`, a constant (a buoyancy offset) and a linear drag
    :math:`w` nearly collinear. The earlier pilot (PD gains a share of the thrusters' whole
    reach per metre or radian, at 10 Hz) made :math:`K_d T / M_{ii}` about 3 in the
    BlueROV2-Heavy's roll (above the sampled loop's stability limit of 2): the level hold
    limit-cycled, the vertical thrusters ran at their limit 70 % of the time in alternate
    directions, and as their backward branch is 0.8 of the forward one the mean heave thrust
    pushed down: w > 0 in ~100 % of samples. So this pilot:

    - trims: the net buoyancy of the real vehicle (the truth's :math:`B - W`, as a pilot
      finds it by ballasting or hovering before the run) and the static moment of a CG not
      below the CB are cancelled by a feed-forward wrench :math:`\tau_{trim} = g(\eta)`
      (force at the measured roll and pitch, moment at level; Fossen 2011 eq. 4.6), and
      a slow integral of the depth error (:data:`INTEGRAL_TIME`) takes up what the trim
      misses, so that the heave demands are symmetric about the trim;
    - holds depth (between heave manoeuvres), heading (between yaw manoeuvres), roll and
      pitch (where the thrusters reach them) by PD loops designed from the vehicle file's
      inertia (:data:`LOOPS`), and flies the yaw stick as a rate loop with the vehicle
      file's drag as feed-forward (:data:`RATE_BANDWIDTH`);
    - allocates the wrench by the pseudo-inverse of the thruster configuration (Johansen &
      Fossen 2013) and turns thrust into commands by the vehicle file's thrust map, each
      branch its own (the pilot's software knows the file, not the truth);
    - keeps within authority: the trim and the holds come first; the manoeuvre (the
      demands of :func:`pilot_wrench` and the yaw-rate loop) is scaled by the largest share
      :math:`\lambda \in [0, 1]` that keeps every planned thrust within :data:`MARGIN` of its
      limit in its own branch (the direction-preserving scaling of a constrained allocation,
      Johansen & Fossen 2013), so that a demand never saturates a thruster and
      the thrusters keep authority for the holds; saturation remains only where the truth's
      thrusters are weaker than the file's (U(0.75, 1.25)).
    """

    def __init__(self, vehicle: dict, truth: Truth, b: np.ndarray):
        self.b = b
        self.b_pinv = np.linalg.pinv(b) if b.size else np.zeros((0, 6))
        thr = vehicle["thrusters"]
        self.ct_f = np.array([float(t.get("ct_forward", 1.0)) * float(t.get("eta_forward", 1.0))
                              for t in thr])
        self.ct_b = np.array([float(t.get("ct_backward", 1.0)) *
                              float(t.get("eta_backward", 1.0)) for t in thr])
        # thrust limits [N]; an unlimited thruster: its thrust at command 1
        self.lim_f = np.array([_limit(t.get("max_forward")) for t in thr])
        self.lim_f = np.where(np.isfinite(self.lim_f), self.lim_f, self.ct_f)
        self.lim_b = np.array([_limit(t.get("max_backward")) for t in thr])
        self.lim_b = np.where(np.isfinite(self.lim_b), self.lim_b, self.ct_b)
        # the command range [command units]: the file's commands of full thrust
        self.n_f = np.sqrt(self.lim_f / self.ct_f)
        self.n_b = np.sqrt(self.lim_b / self.ct_b)
        self.m = (np.asarray(vehicle["rigid_body_mass"], float)
                  + np.asarray(vehicle["added_mass"], float))
        self.inertia = np.diag(self.m).copy()
        self.d_l = np.diag(np.asarray(vehicle["linear_damping"], float))
        self.d_q = np.diag(np.asarray(vehicle["quadratic_damping"], float))
        self.reach = np.abs(b) @ self.lim_f if b.size else np.zeros(6)   # full wrench per DOF
        self.net = truth.weight - truth.buoyancy                          # W - B [N]
        self.moment = -(np.cross(truth.r_g, [0.0, 0.0, truth.weight])
                        + np.cross(truth.r_b, [0.0, 0.0, -truth.buoyancy]))  # [N m]

    def gains(self, loop: str, dof: int) -> tuple[float, float]:
        """(K_p, K_d) of a hold [N/m, N s/m or N m/rad, N m s/rad] (:data:`LOOPS`)."""
        omega, zeta = LOOPS[loop]
        m = self.inertia[dof]
        return m * omega ** 2, 2.0 * zeta * omega * m

    def coriolis(self, nu: np.ndarray) -> np.ndarray:
        r"""The feed-forward :math:`C(\nu)\nu` [N, N m] of the vehicle file's inertia
        :math:`M_{RB} + M_A` (:func:`_coriolis`, Fossen 2011 eq. 6.43) at the measured
        velocity: its roll and pitch moments (the Munk moment :math:`(Z_{\dot w} -
        X_{\dot u}) u w` above all) are cancelled by the level hold, a feedback linearisation
        (Fossen 2011, ch. 13) of what the vehicle file knows."""
        return _coriolis(self.m, nu) @ nu

    def trim(self, phi: float, theta: float) -> np.ndarray:
        r"""The trim wrench [N, N m]: :math:`\tau = g(\eta)` of the truth's weight and
        buoyancy, the force :math:`-(W - B) R^T e_z` at the measured roll and pitch
        (:math:`R^T e_z = [-\sin\theta, \cos\theta\sin\phi, \cos\theta\cos\phi]`, Fossen 2011
        eq. 2.18), the moment at level (the righting moment is the vehicle's own)."""
        down = np.array([-np.sin(theta), np.cos(theta) * np.sin(phi),
                         np.cos(theta) * np.cos(phi)])
        return np.concatenate([-self.net * down, self.moment])

    def allocate(self, hold: np.ndarray, manoeuvre: np.ndarray) -> tuple[np.ndarray, float]:
        """Commands [command units] for ``hold + lambda manoeuvre`` (class docstring), and
        lambda [-]."""
        lo, hi = -MARGIN * self.lim_b, MARGIN * self.lim_f
        base, extra = self.b_pinv @ hold, self.b_pinv @ manoeuvre
        over = np.max(np.where(base >= 0.0, base / hi, base / lo), initial=0.0)
        if over > 1.0:                      # the holds alone exceed: scaled, no manoeuvre
            base, lam = base / over, 0.0
        else:
            lam = _feasible_share(base, extra, lo, hi)
        thrust = base + lam * extra
        n = np.where(thrust >= 0.0, np.sqrt(np.abs(thrust) / self.ct_f),
                     -np.sqrt(np.abs(thrust) / self.ct_b))
        return np.clip(n, -self.n_b, self.n_f), lam


def generate(vehicle: dict, effect: str | None, seed: int, *, duration: float = 300.0,
             rate: float = 10.0, logged_noise: bool = True):
    """A noisy log of ``vehicle`` (``HydroModel.to_dict()`` of the prior) with ``effect``,
    flown by :class:`Pilot`.

    ``logged_noise=False`` writes the true states instead of the measured ones: the pilot
    still flies on the noisy measurements and every random draw is made (a zero-width
    normal draw consumes the generator as the noisy one does), so the truth, the commands
    and the trajectory are those of the noisy log; only the logged columns' sensor noise
    (:data:`NOISE`) is left out (an errors-in-variables check: Fuller 1987, sec. 1.1).

    Returns ``(log, truth)``: the :class:`~stripcoef.logfile.Log` (t, pose, velocities,
    ``n_<thruster>`` commands, ``tether_length``; ``meta["command_range"]``: each thruster's
    (lowest, highest) command) and the :class:`Truth` (its ``strength`` is the effect's
    magnitude in the library's terms, STRENGTHS)."""
    rng = np.random.default_rng(seed)
    truth = with_effect(perturbed_truth(vehicle, rng), effect, rng, vehicle)
    sim = Simulator(truth)
    t_out = np.arange(0.0, duration + 1e-9, 1.0 / rate)
    dt = 1.0 / rate
    sub = int(round(1.0 / (rate * sim.dt)))
    reach = np.abs(sim.b).sum(axis=1)                     # DOFs the thrusters move
    dofs = [d for d in range(6) if reach[d] > 1e-6 and d not in (3, 4)]
    demand = pilot_wrench(rng, t_out, dofs)
    pilot = Pilot(vehicle, truth, sim.b if sim.k else np.zeros((6, 0)))
    # demand -> wrench: a fifth of the thrusters' reach in translation; the yaw stick a rate
    # of up to 0.6 rad/s (a pilot's moderate inputs)
    scale = np.array([0.2] * 3 + [0.0] * 3) * pilot.reach
    tether = 2.0 + (t_out / t_out[-1]) * rng.uniform(10.0, 30.0)
    x = np.zeros(13 + sim.k)
    x[3] = 1.0
    delay = deque([np.zeros(sim.k)] * int(round(truth.delay / sim.dt)))  # pure delay buffer
    rows, cmds = [], []
    z_hold, psi_hold, z_int = 0.0, 0.0, 0.0
    kp_z, kd_z = pilot.gains("depth", 2)
    kp_psi, kd_psi = pilot.gains("heading", 5)
    for i, time in enumerate(t_out):
        phi, theta, psi = _euler(x[3:7])
        meas = {"z": x[2] + rng.normal(0, NOISE["z"]), "psi": psi + rng.normal(0, NOISE["psi"]),
                "w": x[9] + rng.normal(0, NOISE["w"]), "r": x[12] + rng.normal(0, NOISE["r"]),
                "phi": phi + rng.normal(0, NOISE["phi"]), "p": x[10] + rng.normal(0, NOISE["p"]),
                "theta": theta + rng.normal(0, NOISE["theta"]),
                "q": x[11] + rng.normal(0, NOISE["q"])}
        meas["u"] = x[7] + rng.normal(0, NOISE["u"])
        meas["v"] = x[8] + rng.normal(0, NOISE["v"])
        manoeuvre = demand[i] * scale
        hold = pilot.trim(meas["phi"], meas["theta"])
        if demand[i, 5] != 0.0:                          # the yaw stick asks for a rate
            r_cmd = 0.6 * demand[i, 5]
            manoeuvre[5] = ((pilot.d_l[5] + pilot.d_q[5] * abs(r_cmd)) * r_cmd
                            + pilot.inertia[5] * RATE_BANDWIDTH * (r_cmd - meas["r"]))
            psi_hold = meas["psi"]
        else:                                            # heading hold
            err = np.angle(np.exp(1j * (meas["psi"] - psi_hold)))
            hold[5] += -(kp_psi * err + kd_psi * meas["r"])
        if demand[i, 2] == 0.0:                          # depth, between heave manoeuvres
            err = meas["z"] - z_hold
            z_int = float(np.clip(z_int + err * dt, -0.1 * pilot.reach[2] / max(kp_z, 1e-12)
                                  * INTEGRAL_TIME, 0.1 * pilot.reach[2] / max(kp_z, 1e-12)
                                  * INTEGRAL_TIME))
            hold[2] += -(kp_z * (err + z_int / INTEGRAL_TIME) + kd_z * meas["w"])
        else:
            z_hold = meas["z"]
        nu = np.array([meas[c] for c in VELOCITIES])
        ff = pilot.coriolis(nu)
        for d, a, rt in ((3, "phi", "p"), (4, "theta", "q")):   # level, where reachable
            if pilot.reach[d] > 1e-9:
                kp, kd = pilot.gains("attitude", d)
                hold[d] += ff[d] - (kp * meas[a] + kd * meas[rt])
        n = pilot.allocate(hold, manoeuvre)[0] if sim.k else np.zeros(0)
        cmds.append(n)
        rows.append(np.concatenate([[time], x[:3], [phi, theta, psi], x[7:13]]))
        if i == len(t_out) - 1:
            break
        for _ in range(sub):
            delay.append(n)
            x = sim.step(x, delay.popleft(), tether[i])
    data = np.array(rows)
    cols = {"t": data[:, 0]}
    names = ["x", "y", "z", "phi", "theta", "psi", "u", "v", "w", "p", "q", "r"]
    for j, name in enumerate(names):
        cols[name] = data[:, 1 + j] + rng.normal(0.0, NOISE[name] if logged_noise else 0.0,
                                                 data.shape[0])
    cols["psi"] = np.unwrap(cols["psi"])
    for k, th in enumerate(truth.thrusters):
        cols[f"n_{th['name']}"] = np.array([c[k] for c in cmds])
    cols["tether_length"] = tether
    meta = {"command_range": [(-float(a), float(b)) for a, b in zip(pilot.n_b, pilot.n_f)]}
    return Log(cols, source=f"independent({effect or 'clean'}, seed {seed})", meta=meta), truth


#: Velocity columns of the six DOFs.
VELOCITIES = ("u", "v", "w", "p", "q", "r")


def excitation(log: Log, truth: Truth) -> dict:
    r"""How a log excites each DOF, the property :class:`Pilot` is written for: per velocity
    column, the shares of samples [-] above ``+3 sigma`` and below ``-3 sigma`` of its sensor
    noise (:data:`NOISE`; ``pos``, ``neg``); per thruster, the share of samples [-] at which it
    saturates (``saturated``): its thrust by the truth's map (:func:`_thrust`) at the truth's
    limit in its branch, or its command at the end of the log's command range
    (``meta["command_range"]``, when given); and ``driven``, the DOFs (velocity columns) the
    thrusters push in, roll and pitch left out (held level, not flown)."""
    out = {}
    for c in VELOCITIES:
        v = np.asarray(log[c], float)
        thr = 3.0 * NOISE[c]
        out[c] = {"pos": float(np.mean(v > thr)), "neg": float(np.mean(v < -thr))}
    rng_ = log.meta.get("command_range") if getattr(log, "meta", None) else None
    sat = {}
    for k, t in enumerate(truth.thrusters):
        n = np.asarray(log[f"n_{t['name']}"], float)
        thrust = np.array([_thrust({**t, "deadband": 0.0}, x) for x in n])
        at = (thrust >= (1 - 1e-6) * t["max_forward"]) | (thrust <= -(1 - 1e-6) *
                                                         t["max_backward"])
        if rng_:
            lo, hi = rng_[k]
            at |= (n <= (1 - 1e-6) * lo) | (n >= (1 - 1e-6) * hi)
        sat[t["name"]] = float(np.mean(at))
    out["saturated"] = sat
    b = np.array([np.concatenate([t["direction"], np.cross(t["position"], t["direction"])])
                  for t in truth.thrusters]).T
    out["driven"] = [VELOCITIES[d] for d in (0, 1, 2, 5) if np.abs(b[d]).sum() > 1e-6]
    return out
