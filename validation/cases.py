r"""The papers' cases of issue 7, reproduced with the diagnosis.

**VideoRay surge** (Wang & Clark, Wang & Clark 2006, sec. IV.A and Table I). The model predicted
0.51 m/s at n = 60 and the pool measured 0.47 m/s, which the authors attributed to the
tether they had not modelled. :func:`videoray_tether_gap` computes the tether drag that
closes the gap; :func:`videoray_pool_log` generates pool runs with that tether and
:func:`videoray_case` diagnoses them with and without a ``tether_length`` column.

**ROMEO heave** (Caccia et al., Indiveri 1998, sec. 4.2.4, eqs. 4.15-4.17). Five heave
experiments with different weights; the upward thrust is weakened by the propeller-hull
interaction (eta = 0.57). The standard model finds the vehicle buoyant in all five; the
diagnosis must find the direction-dependent efficiency from the residuals, and with it the
buoyancy bias disappears. :func:`romeo_case`.

Assumptions (not printed in the papers):

- VideoRay mass 3.6 kg; the model of :func:`validation.synthetic.rov_model`
  (Table I); tether: the VideoRay Pro III's neutrally buoyant tether, diameter 7.5 mm
  (:data:`VIDEORAY_TETHER_DIAMETER`), normal drag coefficient 1.2 (Hoerner 1965, ch. 3),
  tangential friction coefficient 0.015 (:data:`TETHER_CF`); in the generated pool log
  the tether is paid out from 3 to 15 m.
- ROMEO: mass 450 kg (:data:`validation.experiments.ROMEO_MASS`: the chapter prints no mass)
  and heave added mass 500 kg (an open frame of about 1.3 x 0.9 x 1 m);
  one diver's lead of 2 kg per experiment step (experiment 3 neutral, 1-2 buoyant, 4-5
  heavy, as the chapter's footnote says); applied heave forces of 10 to 60 N each way held
  20 s; heave velocity noise 5 mm/s; the prior is the chapter's standard-model estimate
  (k_w = 116 N s/m, k_w|w| = 403 N s^2/m^2, eq. 4.17) with eta = 1 and neutral buoyancy.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from stripcoef.fluid import G
from stripcoef.logfile import Log
from stripcoef.model import HydroModel, rigid_body_mass_matrix
from stripcoef.simulate import simulate
from stripcoef.diagnose.pipeline import diagnose, fit_effects
from stripcoef.effects.laws import get_effect
from validation.experiments import (RHO_LEAD, ROMEO_MASS, ROMEO_TRUTH,  # noqa: F401 (re-exported)
                                    romeo_weights)
from validation.synthetic import add_noise, rov_model

#: Wang & Clark 2006, sec. IV.A: predicted and measured surge speed at n = 60 [m/s]
VIDEORAY_PREDICTED = 0.51
VIDEORAY_MEASURED = 0.47
VIDEORAY_COMMAND = 60.0
#: assumed tether diameter [m] and drag coefficients (module docstring)
VIDEORAY_TETHER_DIAMETER = 0.0075
TETHER_CD = 1.2
TETHER_CF = 0.015
RHO_FRESH = 1000.0


def videoray_tether_gap(*, predicted: float = VIDEORAY_PREDICTED,
                        measured: float = VIDEORAY_MEASURED, model=None) -> dict:
    r"""Tether drag that turns the predicted steady surge speed into the measured one.

    The model's thrust at the command is the drag at the predicted speed,
    :math:`T = d_L u_p + d_Q u_p^2`; at the measured speed the same thrust balances the hull
    drag plus the tether:

    .. math::
        F_t = T - (d_L u_m + d_Q u_m^2), \qquad c_t L = F_t / u_m^2

    and, for the assumed tether, the length in full cross-flow
    :math:`L_n = c_t L / (\tfrac12\rho C_d d)` or trailing along the flow
    :math:`L_t = c_t L / (\tfrac12\rho C_f \pi d)`.

    Returns
    -------
    dict
        thrust [N], tether_force [N], c_t_L [N s^2/m^2], lengths [m], and the model's own
        steady speed at n = 60 with Table I's thrust coefficient [m/s].

    References
    ----------
    Wang & Clark (2006), eq. 7 and Table I (experimental X_u, X_u|u|); Hoerner (1965) ch. 3 (C_d of a
    cylinder in cross-flow; skin friction of a cylinder along the flow).
    """
    model = rov_model() if model is None else model
    d_l, d_q = float(model.linear_damping[0, 0]), float(model.quadratic_damping[0, 0])
    thrust = d_l * predicted + d_q * predicted ** 2
    force = thrust - (d_l * measured + d_q * measured ** 2)
    ctl = force / measured ** 2
    d = VIDEORAY_TETHER_DIAMETER
    t_table = 2 * model.thruster("port").thrust(VIDEORAY_COMMAND)
    u_table = (-d_l + np.sqrt(d_l ** 2 + 4 * d_q * t_table)) / (2 * d_q)
    return {"thrust": thrust, "tether_force": force, "c_t_L": ctl,
            "length_cross_flow": ctl / (0.5 * RHO_FRESH * TETHER_CD * d),
            "length_along_flow": ctl / (0.5 * RHO_FRESH * TETHER_CF * np.pi * d),
            "table_thrust": float(t_table), "table_speed": float(u_table)}


def videoray_pool_log(seed: int = 0, *, length=(3.0, 15.0), with_length: bool = True):
    """Pool surge runs of the VideoRay with a tether the model does not know.

    Runs at n = 30, 60, 90 (and back, n = -60) of 20 s, separated by 10 s stops; the tether
    drag coefficient per metre c_t is chosen so that at the middle of the paid-out range
    it closes the gap of :func:`videoray_tether_gap`; surge only (Wang & Clark 2006's decoupled
    model: the Munk moment is dropped). Returns (log, prior, c_t).
    """
    rng = np.random.default_rng(seed)
    prior = rov_model()
    gap = videoray_tether_gap()
    # thrust coefficient that makes the model predict 0.51 m/s at n = 60 (the paper's
    # simulation); keep Table I's forward/backward ratio
    scale = gap["thrust"] / gap["table_thrust"]
    prior = replace(prior, thrusters=[replace(th, ct_forward=th.ct_forward * scale,
                                              ct_backward=th.ct_backward * scale)
                                      if th.name in ("port", "starboard") else th
                                      for th in prior.thrusters])
    c_t = gap["c_t_L"] / (0.5 * (length[0] + length[1]))
    dt = 0.1
    levels = [30, 60, 90, 60, -60, 60, 30, 90, 60]
    n = []
    for lv in levels:
        n += [lv] * 200 + [0] * 100
    n = np.array(n, float)
    t = np.arange(n.size) * dt
    tether = length[0] + (length[1] - length[0]) * t / t[-1]

    # the undeclared effect is the library's own tether law, applied in surge
    tether_force = get_effect("tether_drag").force_law({"c_t": c_t}, 0)
    log = simulate(prior, t, commands={"port": n, "starboard": n}, extra_force=tether_force,
                   channels={"tether_length": tether}, munk=False, rtol=1e-7, atol=1e-9)
    cols = {k: v for k, v in log.columns.items() if k not in "XYZKMN"}
    if not with_length:
        cols.pop("tether_length")
    return add_noise(Log(cols, source=f"VideoRay pool runs (seed {seed})"), rng), prior, c_t


def videoray_case(seed: int = 0) -> dict:
    """Diagnose the pool runs with and without the ``tether_length`` column."""
    gap = videoray_tether_gap()
    out = {"gap": gap}
    log, prior, c_t = videoray_pool_log(seed, with_length=True)
    out["c_t_truth"] = c_t
    out["with_tether_length"] = diagnose(log, prior, dof="surge").to_dict()
    without = Log({k: v for k, v in log.columns.items() if k != "tether_length"},
                  source=log.source + " without tether_length")
    out["without_tether_length"] = diagnose(without, prior, dof="surge").to_dict()
    return out


# ---------------------------------------------------------------------------
# ROMEO
# ---------------------------------------------------------------------------

ROMEO_STANDARD = {"k_w": 116.0, "k_ww": 403.0}               # Indiveri 1998, eq. 4.17 (standard)
ROMEO_ADDED_MASS = 500.0
ROMEO_LEAD = 2.0


def romeo_model(*, k_w=ROMEO_STANDARD["k_w"], k_ww=ROMEO_STANDARD["k_ww"]) -> HydroModel:
    """The ROMEO heave prior: the chapter's standard model, neutrally buoyant (assumed
    mass and added mass, module docstring); forces are given in the log (no thrusters)."""
    rho = 1025.0
    mrb = rigid_body_mass_matrix(ROMEO_MASS, (0.0, 0.0, 0.1), np.diag([80.0, 100.0, 90.0]))
    ma = np.diag([300.0, 400.0, ROMEO_ADDED_MASS, 60.0, 70.0, 50.0])
    dl = np.diag([60.0, 70.0, k_w, 40.0, 40.0, 40.0])
    dq = np.diag([300.0, 350.0, k_ww, 60.0, 60.0, 50.0])
    return HydroModel(name="romeo-standard", reference_point=np.zeros(3), rigid_body_mass=mrb,
                      added_mass=ma, linear_damping=dl, quadratic_damping=dq,
                      mass=ROMEO_MASS, volume=ROMEO_MASS / rho,
                      center_of_gravity=np.array([0.0, 0.0, 0.1]),
                      center_of_buoyancy=np.zeros(3), density=rho, gravity=G)


def romeo_weight(index: int) -> float:
    """Net weight W - B of experiment ``index`` (1..5) [N], down positive: the law of
    :func:`validation.experiments.romeo_weights` with this case's lead mass
    ``ROMEO_LEAD`` [kg] ([assumption], Indiveri 1998 sec. 4.2.4, footnote 3)."""
    return float(romeo_weights(5, lead_mass=ROMEO_LEAD)[index - 1])


def romeo_log(index: int, seed: int = 0):
    """Heave experiment ``index`` (1..5): applied force steps +-10..60 N held 20 s each;
    upward force (F < 0) delivered with efficiency eta = 0.57. Returns (log, prior, W)."""
    rng = np.random.default_rng(1000 * index + seed)
    truth = romeo_model(k_w=ROMEO_TRUTH["k_w"], k_ww=ROMEO_TRUTH["k_ww"])
    weight = romeo_weight(index)
    truth = replace(truth, mass=ROMEO_MASS + weight / G)
    levels = rng.permutation([10.0, 20.0, 30.0, 40.0, 50.0, 60.0])
    f = []
    for lv in levels:
        f += [lv] * 200 + [-lv] * 200
    f = np.array(f)
    t = np.arange(f.size) * 0.1
    forces = np.zeros((t.size, 6))
    forces[:, 2] = f
    eta = ROMEO_TRUTH["eta"]

    def interaction(time, eta_pose, nu, inputs):
        fz = inputs["tau"][2]
        return np.array([0, 0, (eta - 1.0) * min(fz, 0.0), 0, 0, 0])

    log = simulate(truth, t, forces=forces, extra_force=interaction, rtol=1e-7, atol=1e-9)
    cols = {k: log[k] for k in ("t", "z", "phi", "theta", "psi", "u", "v", "w", "p", "q", "r",
                                "Z")}
    noise = {"w": 0.005, "u": 0.005, "v": 0.005, "z": 0.01, "p": 0.002, "q": 0.002,
             "r": 0.002, "phi": 0.003, "theta": 0.003, "psi": 0.003}
    return add_noise(Log(cols, source=f"ROMEO heave experiment {index}"), rng, noise), \
        romeo_model(), weight


def romeo_case(seed: int = 0) -> list:
    """For each of the five experiments: the standard model's buoyancy (calibration +
    buoyancy_offset, no efficiency), the diagnosis, and the buoyancy after the efficiency."""
    rows = []
    for i in range(1, 6):
        log, prior, weight = romeo_log(i, seed)
        standard = fit_effects(log, prior, "heave", ["buoyancy_offset"])
        with_eta = fit_effects(log, prior, "heave", ["thrust_asymmetry", "buoyancy_offset"])
        res = diagnose(log, prior, dof="heave").to_dict()
        rows.append({"experiment": i, "weight_truth": weight,
                     "standard_buoyancy": standard.parameters["buoyancy_offset"]["b"],
                     "standard_buoyancy_std": standard.std["buoyancy_offset"]["b"],
                     "eta_buoyancy": with_eta.parameters["buoyancy_offset"]["b"],
                     "eta_buoyancy_std": with_eta.std["buoyancy_offset"]["b"],
                     "eta": with_eta.parameters["thrust_asymmetry"],
                     "diagnosis": res})
    return rows


__all__ = ["videoray_tether_gap", "videoray_pool_log", "videoray_case", "romeo_model",
           "romeo_log", "romeo_case"]
