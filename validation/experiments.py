r"""Virtual experiments: data with a known truth, generated as the papers describe their trials.

These feed the reproductions (tests and docs/validation.md).  Every value not printed in a
paper is an assumption, stated in the docstring and in :data:`ASSUMPTIONS`.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy.integrate import solve_ivp

from stripcoef.fluid import G, RHO_SEAWATER
from stripcoef.logfile import Log
from stripcoef.identify.onestep import simulate_state

#: Lead density [kg/m^3] (pure lead, CRC Handbook).
RHO_LEAD = 11340.0

# --- ROMEO heave (Caccia, Indiveri 1998, sec. 4.2.4) --------------------------------------------
#: The chapter's eta-model estimates (eq. 4.17) used as the truth.
ROMEO_TRUTH = {"k_w": 50.0, "k_ww": 424.0, "eta": 0.57}
#: Assumed: each experiment adds one 0.25 kg diver's lead; experiment 3 is neutral
#: (footnote 3 of the chapter: buoyant in 1-2, neutral in 3, heavy in 4-5).
ROMEO_LEAD_MASS = 0.25
#: Assumed commanded heave forces [N], 6 levels each way (the chapter: 4 to 7 per direction).
ROMEO_FORCES = (10.0, 20.0, 30.0, 40.0, 50.0, 60.0)
#: Assumed noise: steady velocity from the SG-filtered depth, averaged [m/s];
#: applied force from the identified thruster model, relative [-].
ROMEO_NOISE_W = 0.003
ROMEO_NOISE_F = 0.02
#: Assumed: mean |command| of the horizontal thrusters holding the heading, nearly the same at
#: every heave speed (the chapter's explanation of the eta-md collinearity) [command units].
ROMEO_N_H = 600.0
ROMEO_N_H_SPREAD = 15.0


def romeo_weights(n: int = 5, *, lead_mass: float = ROMEO_LEAD_MASS) -> np.ndarray:
    r"""Net weight W (down positive) of the five ROMEO experiments [N].

    .. math:: W_i = (i - 3)\, m_{lead}\, g\, (1 - \rho_w/\rho_{lead})

    (the lead's weight less its buoyancy, Archimedes). m_lead [kg], g [m/s^2], densities
    [kg/m^3]. [assumption] one 0.25 kg lead per experiment, neutral in experiment 3
    (Indiveri 1998, sec. 4.2.4 and its footnote 3; see :data:`ROMEO_LEAD_MASS`).
    """
    step = lead_mass * G * (1.0 - RHO_SEAWATER / RHO_LEAD)
    return (np.arange(1, n + 1) - 3) * step


def steady_heave_velocity(force, *, k_w, k_ww, weight, eta):
    r"""Steady heave velocity solving :math:`\eta F + W = k_w w + k_{w|w|} w|w|` [m/s].

    (Indiveri 1998, eq. 4.16 solved for w; eta applies to upward F < 0.)
    """
    f = np.asarray(force, dtype=float)
    rhs = np.where(f < 0, eta * f, f) + weight
    s = np.sign(rhs)
    a = np.abs(rhs)
    return s * (-k_w + np.sqrt(k_w ** 2 + 4 * k_ww * a)) / (2 * k_ww)


def romeo_experiment(index: int, seed: int, *, forces=ROMEO_FORCES, truth=ROMEO_TRUTH,
                     noise_w: float = ROMEO_NOISE_W, noise_f: float = ROMEO_NOISE_F):
    """Steady-state points of ROMEO heave experiment ``index`` (1..5) with seeded noise.

    Truth: the eta model (no momentum drag), k_w, k_ww, eta from :data:`ROMEO_TRUTH`, the net
    weight from :func:`romeo_weights`; commanded forces +-:data:`ROMEO_FORCES`.

    Returns
    -------
    SteadyPoints, true net weight [N]
    """
    from stripcoef.identify.steady import SteadyPoints
    rng = np.random.default_rng(seed)
    weight = romeo_weights()[index - 1]
    f = np.concatenate([np.asarray(forces), -np.asarray(forces)])
    w = steady_heave_velocity(f, k_w=truth["k_w"], k_ww=truth["k_ww"], weight=weight,
                              eta=truth["eta"])
    w = w + rng.normal(0.0, noise_w, w.size)
    f_meas = f * (1.0 + rng.normal(0.0, noise_f, f.size))
    n_h = ROMEO_N_H + rng.normal(0.0, ROMEO_N_H_SPREAD, f.size)
    return SteadyPoints("heave", w, f_meas, n_h=n_h,
                        source=f"ROMEO virtual experiment {index}"), weight


# --- ROV II free-decay pendulum (Eng et al., Eng et al. 2009) --------------------------------------
#: Table II average (scaled model, surge) used as the truth.
ROV2_TRUTH = {"m_a": 0.5800, "K_L": 1.5515, "K_Q": 9.5439}
#: Assumed (the paper does not print them): scaled-model mass and buoyancy, pendulum length
#: as measured in air (0.39 m), release angle 45 deg, 30 frames/s, camera angle noise.
ROV2_MASS = 1.6            # [kg]
ROV2_BUOYANCY = 9.0        # [N]  (displaced volume 0.9 L in fresh water)
ROV2_LENGTH = 0.3904       # [m]  (from the in-air alpha = -25.128, Eng et al. 2009 sec. IV.A)
ROV2_THETA0 = np.radians(45.0)
ROV2_FPS = 30.0
ROV2_DURATION = 12.0       # [s]
ROV2_NOISE = 0.03          # [rad] marker-tracking noise on the angle


def pendulum_rhs(alpha, beta, gamma, restoring="sin"):
    r""":math:`\ddot\theta = \alpha f(\theta) - \beta\dot\theta - \gamma|\dot\theta|\dot\theta`
    with f = sin (Eng et al. 2009, eq. 4) or f = identity (torsion, eq. 12) as a first-order system.

    alpha [1/s^2], beta [1/s], gamma [1/rad]; the returned rhs(t, [theta, omega]) gives
    [omega, theta_ddot] in [rad/s, rad/s^2].
    """
    f = np.sin if restoring == "sin" else (lambda x: x)

    def rhs(_t, s):
        th, om = s
        return [om, alpha * f(th) - beta * om - gamma * abs(om) * om]
    return rhs


def simulate_pendulum(alpha, beta, gamma, theta0, t, *, omega0=0.0, restoring="sin"):
    r"""Angle [rad] of eq. 4 (or 12) at times ``t`` from rest at ``theta0`` (RK45, rtol 1e-10;
    an integrator independent of the estimator's).

    .. math:: \ddot\theta = \alpha f(\theta) - \beta\dot\theta - \gamma|\dot\theta|\dot\theta

    (Eng et al. 2009, eqs. 4 and 12; :func:`pendulum_rhs`). alpha [1/s^2], beta [1/s], gamma
    [1/rad], ``theta0`` [rad], ``omega0`` [rad/s], ``t`` [s].
    """
    sol = solve_ivp(pendulum_rhs(alpha, beta, gamma, restoring), (t[0], t[-1]),
                    [theta0, omega0], t_eval=t, rtol=1e-10, atol=1e-12, method="RK45")
    return sol.y[0]


@lru_cache(maxsize=16)
def _noise_free_pendulum(alpha, beta, gamma, theta0, duration, fps, restoring):
    """Frame times [s] and noise-free angle [rad] of :func:`simulate_pendulum` from rest at
    ``theta0``, sampled at ``fps`` for ``duration`` [s]: the same for every seed of a virtual
    experiment, so computed once per truth (read-only arrays; only the noise is seeded)."""
    t = np.arange(0.0, duration, 1.0 / fps)
    th = simulate_pendulum(alpha, beta, gamma, theta0, t, restoring=restoring)
    t.flags.writeable = th.flags.writeable = False
    return t, th


def rov2_pendulum_log(seed: int, *, truth=ROV2_TRUTH, mass=ROV2_MASS, buoyancy=ROV2_BUOYANCY,
                      length=ROV2_LENGTH, noise=ROV2_NOISE, duration=ROV2_DURATION,
                      fps=ROV2_FPS, g=G) -> Log:
    """A free-decay pendulum log (``t``, ``theta_pendulum``) of the ROV II scaled model."""
    m = mass + truth["m_a"]
    alpha = (buoyancy - mass * g) / (m * length)
    beta = truth["K_L"] / m
    gamma = truth["K_Q"] * length / m
    t, th = _noise_free_pendulum(alpha, beta, gamma, ROV2_THETA0, duration, fps, "sin")
    rng = np.random.default_rng(seed)
    return Log({"t": t, "theta_pendulum": th + rng.normal(0.0, noise, t.size)},
               source=f"ROV II virtual pendulum (seed {seed})")


# --- VideoRay yaw on a pivot (Wang & Clark, Wang & Clark 2006, sec. III.C) -----------------------------
#: Truth in SNAME signs from the paper's alpha, gamma and I_zz (Table I); N_rr = -beta/gamma.
VIDEORAY_IZZ = 0.02532                       # [kg m^2] Table I
VIDEORAY_TRUTH = {"alpha": -0.6199, "beta": -1.1219, "gamma": 26.95, "delta": 0.0316}
#: Assumed: torque amplitudes [N m] of the oscillating input, period 1.5 s (the paper's
#: n = 50..150 with period 1.5 s), 30 frames/s video, yaw-rate noise [rad/s].
VIDEORAY_AMPLITUDES = (0.02, 0.04, 0.06)
VIDEORAY_PERIOD = 1.5
VIDEORAY_FPS = 30.0
VIDEORAY_NOISE = 0.01


def videoray_yaw_log(seed: int, *, truth=VIDEORAY_TRUTH, cycles: int = 8,
                     noise: float = VIDEORAY_NOISE, fps: float = VIDEORAY_FPS) -> Log:
    r"""Yaw-rate log (``t``, ``r``, ``N``) of Wang & Clark 2006's pivot test from eq. 8 with seeded noise.

    Input: sinusoidal torque :math:`N(t) = A_j \sin(2\pi t / T)`, ``cycles`` periods per
    amplitude :math:`A_j`.
    """
    t, out, torque = _noise_free_yaw(tuple(truth[k] for k in ("alpha", "beta", "gamma", "delta")),
                                     cycles, fps)
    rng = np.random.default_rng(seed)
    return Log({"t": t, "r": out + rng.normal(0.0, noise, t.size), "N": torque},
               source=f"VideoRay virtual pivot test (seed {seed})")


@lru_cache(maxsize=16)
def _noise_free_yaw(truth: tuple, cycles: int, fps: float):
    """Frame times [s], noise-free yaw rate [rad/s] and torque [N m] of
    :func:`videoray_yaw_log` for ``truth`` = (alpha, beta, gamma, delta): the same for every
    seed, so simulated once per truth (read-only arrays; only the noise is seeded)."""
    a, b, c, d = truth
    seg = cycles * VIDEORAY_PERIOD
    amps = np.asarray(VIDEORAY_AMPLITUDES)

    def torque(tt):
        j = np.minimum((np.asarray(tt) // seg).astype(int), amps.size - 1)
        return amps[j] * np.sin(2 * np.pi * np.asarray(tt) / VIDEORAY_PERIOD)

    t = np.arange(0.0, seg * amps.size, 1.0 / fps)
    # truth: the identified equation itself (onestep.simulate_state, classical RK4) on a grid
    # 20 times finer than the frames, so the linearly interpolated torque is near exact
    sub = 20
    tf = np.arange(t.size * sub) * (1.0 / fps / sub)
    fine = simulate_state(tf, torque(tf), 0.0, {"alpha": a, "beta": b, "gamma": c, "delta": d},
                          "LQB", substeps=2)
    out, applied = fine[::sub], torque(t)
    for column in (t, out, applied):
        column.flags.writeable = False
    return t, out, applied


# --- ROV II torsion pendulum in yaw (Eng et al. 2009, eq. 12) ---------------------------------------
#: Truth: Tables III/IV full-scale yaw values divided by lambda^5 (lambda = 1/0.3) - the
#: scaled-model values the paper does not print.
ROV2_YAW_TRUTH = {"I_a": 3.60 * 0.3 ** 5, "K_L": 1.18 * 0.3 ** 5, "K_Q": 7.51 * 0.3 ** 5}
#: Assumed: model inertia about the spring axis [kg m^2], spring stiffness [N m/rad],
#: release angle [rad] (peak rate ~0.5 rad/s, Table IV's yaw range), angle noise [rad].
ROV2_YAW_INERTIA = 0.012
ROV2_YAW_STIFFNESS = 0.05
ROV2_YAW_THETA0 = 0.35
ROV2_YAW_NOISE = 0.005
ROV2_YAW_DURATION = 30.0


def rov2_torsion_log(seed: int, *, truth=ROV2_YAW_TRUTH, inertia=ROV2_YAW_INERTIA,
                     stiffness=ROV2_YAW_STIFFNESS, noise=ROV2_YAW_NOISE,
                     duration=ROV2_YAW_DURATION, fps=ROV2_FPS) -> Log:
    """A torsion-pendulum decay log (``t``, ``theta_pendulum``) of the ROV II scaled model."""
    total = inertia + truth["I_a"]
    t, th = _noise_free_pendulum(-stiffness / total, truth["K_L"] / total, truth["K_Q"] / total,
                                 ROV2_YAW_THETA0, duration, fps, "linear")
    rng = np.random.default_rng(seed)
    return Log({"t": t, "theta_pendulum": th + rng.normal(0.0, noise, t.size)},
               source=f"ROV II virtual torsion pendulum (seed {seed})")


# --- ROMEO heave as a time series from the 6-DOF simulation ----------------------------------
#: Assumed ROMEO-like rigid body (the chapter does not print it): mass [kg], inertia about the
#: CG [kg m^2], added mass diagonal [kg, kg m^2], other DOFs' damping; four vertical thrusters
#: at the frame corners with unit bench coefficient (command = thrust in N per thruster at
#: |n| = 1) and efficiency ROMEO_TRUTH["eta"] when pushing up.
ROMEO_MASS = 450.0
ROMEO_INERTIA = (60.0, 90.0, 80.0)
ROMEO_ADDED = (200.0, 300.0, 400.0, 40.0, 60.0, 50.0)
ROMEO_DAMPING = (80.0, 120.0, None, 60.0, 60.0, 40.0)          # linear; heave from the truth
ROMEO_QDAMPING = (200.0, 300.0, None, 80.0, 80.0, 60.0)        # quadratic
ROMEO_DEPTH_NOISE = 0.01                                        # [m] depth sensor


def romeo_hydromodel(net_weight: float, *, truth=ROMEO_TRUTH):
    """A ROMEO-like HydroModel whose heave obeys the eta model with ``truth`` [SI].

    Net weight W = m g - rho g V [N] (down positive); CB 0.1 m above the CG.
    """
    from stripcoef.model import HydroModel, rigid_body_mass_matrix
    from stripcoef.thrusters import Thruster
    d_l = np.diag([truth["k_w"] if v is None else v for v in ROMEO_DAMPING])
    d_q = np.diag([truth["k_ww"] if v is None else v for v in ROMEO_QDAMPING])
    volume = (ROMEO_MASS * G - net_weight) / (RHO_SEAWATER * G)
    thr = [Thruster(f"v{k}", np.array([x, y, -0.4]), np.array([0.0, 0.0, 1.0]),
                    ct_forward=1.0, ct_backward=1.0, eta_forward=1.0,
                    eta_backward=truth["eta"])
           for k, (x, y) in enumerate(((0.5, 0.4), (0.5, -0.4), (-0.5, 0.4), (-0.5, -0.4)))]
    return HydroModel(name="ROMEO (virtual)", reference_point=np.zeros(3),
                      rigid_body_mass=rigid_body_mass_matrix(ROMEO_MASS, np.zeros(3),
                                                             np.diag(ROMEO_INERTIA)),
                      added_mass=np.diag(ROMEO_ADDED), linear_damping=d_l,
                      quadratic_damping=d_q, mass=ROMEO_MASS, volume=volume,
                      center_of_gravity=np.zeros(3), center_of_buoyancy=np.array([0, 0, -0.1]),
                      density=RHO_SEAWATER, thrusters=thr)


def romeo_heave_log(index: int, seed: int, *, forces=ROMEO_FORCES, segment: float = 90.0,
                    rate: float = 10.0, noise: float = ROMEO_DEPTH_NOISE):
    """Heave trial ``index`` simulated with :func:`stripcoef.simulate.simulate`.

    Constant total commanded force per segment (+F down, -F up, alternating, the chapter's
    Fig. 4.8), four thrusters sharing it; each thruster's real thrust differs from the bench
    map by a random ROMEO_NOISE_F per segment.  The log keeps ``t``, the noisy depth ``z``
    and the commands ``n_v0..n_v3`` - as a real trial, no velocity and no applied force (they
    come from the depth and the bench thruster map).

    Returns
    -------
    Log, HydroModel (for the thruster map), true net weight [N]
    """
    from stripcoef.simulate import simulate
    weight = romeo_weights()[index - 1]
    model = romeo_hydromodel(weight)
    levels = np.ravel([[f, -f] for f in forces])
    t = np.arange(0.0, segment * levels.size, 1.0 / rate)
    total = levels[np.minimum((t // segment).astype(int), levels.size - 1)]
    per = total / 4.0
    n = np.sign(per) * np.sqrt(np.abs(per))               # T = n|n| per thruster (ct = 1)
    rng = np.random.default_rng(seed)
    # the real thrust differs from the bench map by ROMEO_NOISE_F per segment and thruster
    seg = np.minimum((t // segment).astype(int), levels.size - 1)
    actual = {}
    for th in model.thrusters:
        err = 1.0 + rng.normal(0.0, ROMEO_NOISE_F, levels.size)
        actual[th.name] = n * np.sqrt(err[seg])
    log = simulate(model, t, commands=actual)
    cols = {"t": t, "z": log["z"] + rng.normal(0.0, noise, t.size)}
    cols.update({f"n_{th.name}": n for th in model.thrusters})
    return Log(cols, source=f"ROMEO simulated trial {index}"), model, weight
