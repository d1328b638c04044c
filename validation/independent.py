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
- a pilot of steps, doublets, chirps and PD holds of depth and heading (on the *measured*
  state), turned into thruster commands by the pseudo-inverse allocation and the inverse thrust
  map;
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
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def _coriolis(m, nu):
    """C(nu) of a symmetric 6x6 inertia (Fossen 2011, eqs. 3.46 and 6.43): the blocks of
    [[0, -S(M11 v + M12 w)], [-S(M11 v + M12 w), -S(M21 v + M22 w)]]."""
    v, w = nu[:3], nu[3:]
    a = m[:3, :3] @ v + m[:3, 3:] @ w
    b = m[3:, :3] @ v + m[3:, 3:] @ w
    c = np.zeros((6, 6))
    c[:3, 3:] = -_skew(a)
    c[3:, :3] = -_skew(a)
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
    return float(np.clip(ct * n * abs(n), -t["max_backward"], t["max_forward"]))


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

    def _restoring(self, r):
        """g(q): the force is -g [N, N m] (weight down at the CG, buoyancy up at the CB)."""
        t = self.truth
        fw = r.T @ np.array([0.0, 0.0, t.weight])
        fb = r.T @ np.array([0.0, 0.0, -t.buoyancy])
        return -np.concatenate([fw + fb, np.cross(t.r_g, fw) + np.cross(t.r_b, fb)])

    def rhs(self, x, n_cmd, tether):
        t = self.truth
        q = x[3:7] / np.linalg.norm(x[3:7])
        nu, thrust = x[7:13], x[13:13 + self.k]
        r = _rotation(q)
        vc = r.T @ t.current
        nu_r = nu - np.concatenate([vc, np.zeros(3)])
        nu_c_dot = np.concatenate([-_skew(nu[3:]) @ vc, np.zeros(3)])
        target = np.array([_thrust(th, n) for th, n in zip(t.thrusters, n_cmd)])
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
        q_dot = 0.5 * np.array([-q[1:] @ w, *(q[0] * w + np.cross(q[1:], w))])
        return np.concatenate([r @ nu[:3], q_dot, nu_dot, thrust_dot])

    def step(self, x, n_cmd, tether):
        h = self.dt
        k1 = self.rhs(x, n_cmd, tether)
        k2 = self.rhs(x + 0.5 * h * k1, n_cmd, tether)
        k3 = self.rhs(x + 0.5 * h * k2, n_cmd, tether)
        k4 = self.rhs(x + h * k3, n_cmd, tether)
        x = x + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        x[3:7] /= np.linalg.norm(x[3:7])
        return x


def pilot_wrench(rng, t, dofs):
    """Open-loop wrench demands [N, N m] (unit scale) over time: random steps, a doublet and a
    chirp in each DOF of ``dofs``, with quiet spells; the PD holds are added in the loop."""
    n = t.size
    out = np.zeros((n, 6))
    for d in dofs:
        k = 0
        while k < n:
            hold = int(rng.uniform(4.0, 12.0) / (t[1] - t[0]))
            kind = rng.choice(["step", "doublet", "chirp", "zero"], p=[0.45, 0.2, 0.2, 0.15])
            seg = slice(k, min(k + hold, n))
            tt = t[seg] - t[seg][0]
            amp = rng.uniform(0.3, 1.0) * rng.choice([-1, 1])
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


def generate(vehicle: dict, effect: str | None, seed: int, *, duration: float = 300.0,
             rate: float = 10.0):
    """A noisy log of ``vehicle`` (``HydroModel.to_dict()`` of the prior) with ``effect``.

    Returns ``(log, truth)``: the :class:`~stripcoef.logfile.Log` (t, pose, velocities,
    ``n_<thruster>`` commands, ``tether_length``) and the :class:`Truth` (its ``strength`` is
    the effect's magnitude in the library's terms, STRENGTHS)."""
    rng = np.random.default_rng(seed)
    truth = with_effect(perturbed_truth(vehicle, rng), effect, rng, vehicle)
    sim = Simulator(truth)
    t_out = np.arange(0.0, duration + 1e-9, 1.0 / rate)
    sub = int(round(1.0 / (rate * sim.dt)))
    b_pinv = np.linalg.pinv(sim.b) if sim.k else np.zeros((0, 6))
    reach = np.abs(sim.b).sum(axis=1)                     # DOFs the thrusters move
    dofs = [d for d in range(6) if reach[d] > 1e-6 and d not in (3, 4)]
    demand = pilot_wrench(rng, t_out, dofs)
    full = np.array([_full_command(th) for th in truth.thrusters])
    fmax = np.array([th["max_forward"] if np.isfinite(th["max_forward"]) else th["ct_forward"]
                     for th in truth.thrusters])                   # full thrust [N]
    # demand -> wrench: a fifth of the thrusters' reach in translation; the yaw stick a rate
    # of up to 0.6 rad/s (a pilot's moderate inputs)
    reach_n = np.abs(sim.b) @ fmax if sim.k else np.zeros(6)      # full wrench per DOF
    scale = np.array([0.2] * 3 + [0.06] * 3) * reach_n
    tether = 2.0 + (t_out / t_out[-1]) * rng.uniform(10.0, 30.0)
    x = np.zeros(13 + sim.k)
    x[3] = 1.0
    delay = deque([np.zeros(sim.k)] * int(round(truth.delay / sim.dt)))  # pure delay buffer
    rows, cmds = [], []
    z_hold, psi_hold = 0.0, 0.0
    for i, time in enumerate(t_out):
        phi, theta, psi = _euler(x[3:7])
        meas = {"z": x[2] + rng.normal(0, NOISE["z"]), "psi": psi + rng.normal(0, NOISE["psi"]),
                "w": x[9] + rng.normal(0, NOISE["w"]), "r": x[12] + rng.normal(0, NOISE["r"]),
                "phi": phi + rng.normal(0, NOISE["phi"]), "p": x[10] + rng.normal(0, NOISE["p"]),
                "theta": theta + rng.normal(0, NOISE["theta"]),
                "q": x[11] + rng.normal(0, NOISE["q"])}
        wrench = demand[i] * scale
        if demand[i, 5] != 0.0:                          # the yaw stick asks for a rate
            wrench[5] = reach_n[5] * np.clip(0.5 * (0.6 * demand[i, 5] - meas["r"]), -0.5, 0.5)
        # PD holds on the measured state, gains a share of the full wrench per metre or radian
        if demand[i, 2] == 0.0:                          # depth, between heave manoeuvres
            wrench[2] += -reach_n[2] * (0.5 * (meas["z"] - z_hold) + 0.5 * meas["w"])
        else:
            z_hold = meas["z"]
        if demand[i, 5] == 0.0:                          # heading
            err = np.angle(np.exp(1j * (meas["psi"] - psi_hold)))
            wrench[5] += -reach_n[5] * (0.3 * err + 0.3 * meas["r"])
        else:
            psi_hold = meas["psi"]
        for d, a, rate in ((3, "phi", "p"), (4, "theta", "q")):   # level, where reachable
            wrench[d] += -reach_n[d] * (0.5 * meas[a] + 0.3 * meas[rate])
        thrust = b_pinv @ wrench if sim.k else np.zeros(0)
        ct = np.array([th["ct_forward"] for th in truth.thrusters])
        n = np.sign(thrust) * np.sqrt(np.abs(thrust) / ct)
        n = np.clip(n, -full, full)
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
        cols[name] = data[:, 1 + j] + rng.normal(0.0, NOISE[name], data.shape[0])
    cols["psi"] = np.unwrap(cols["psi"])
    for k, th in enumerate(truth.thrusters):
        cols[f"n_{th['name']}"] = np.array([c[k] for c in cmds])
    cols["tether_length"] = tether
    return Log(cols, source=f"independent({effect or 'clean'}, seed {seed})"), truth
