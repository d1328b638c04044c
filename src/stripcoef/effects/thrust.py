r"""Thruster effects: an asymmetric thrust map, a dead band and a thrust effectiveness
(the force laws of :mod:`stripcoef.effects.laws`' registry; each class's docstring has its
equation, units and source).

Depends on: effects.base, effects.windows.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from stripcoef.effects.base import THRUST_BAND, Effect, _unit_vec

#: Least share of the thrust (RMS over the windows) each direction must carry for a thrust
#: asymmetry to be fitted [-]: the asymmetry is the ratio of the backward and forward
#: branches, and a branch that carries under a tenth of the thrust is not measured by the log
#: (a stated threshold, not a fitted one).
MIN_BRANCH_SHARE = 0.1


class ThrustAsymmetry(Effect):
    r"""Thrust efficiency that depends on the direction of thrust.

    .. math:: \Delta F_i = k_+ (F^+_i + F^-_i) + k_a F^-_i,\qquad
              \eta_+ = 1 + k_+,\ \eta_- = 1 + k_+ + k_a

    where :math:`F^\pm_i = \sum_k B_{ik}\max(\pm T_k, 0)(\pm 1)` is the part of the prior's
    thruster force in DOF i from thrusters pushing forward (+) or backward (-) (or, for a log
    of forces, the positive and negative parts of the applied force). The asymmetry
    :math:`\eta_-/\eta_+` is the signature: inertia and drag terms cannot produce a force
    that scales differently with the sign of the thrust. A symmetric error k_+ scales the
    force balance like the prior's own M, D_L and D_Q together, so it is fitted in the
    reference as well and only k_a is tested. [-]

    Source: Caccia et al. (Indiveri 1998, eq. 4.16, the eta model: propeller-hull interaction of
    the upward thrust, eta = 0.57); Wang & Clark (Wang & Clark 2006, Table I: forward and backward
    thrust coefficients).
    """

    name = "thrust_asymmetry"
    summary = "direction-dependent thruster efficiency (propeller-hull interaction)"
    source = "Indiveri 1998 eq. 4.16; Wang & Clark 2006 Table I"
    parameters = {"eta_forward": "-", "eta_backward": "-"}

    def _parts(self, data, dof):
        if data.thrust is not None:
            fk = data.thruster_force(dof)
            pos = np.where(data.thrust >= 0, fk, 0.0).sum(axis=1)
            neg = np.where(data.thrust < 0, fk, 0.0).sum(axis=1)
        else:
            f = data.tau[:, dof]
            pos, neg = np.maximum(f, 0.0), np.minimum(f, 0.0)
        return pos, neg

    def applicable(self, data, dof):
        pos, neg = self._parts(data, dof)
        if np.abs(pos).max() == 0 or np.abs(neg).max() == 0:
            return False, "the thrust in this DOF never changes direction"
        # each direction must carry a share of the thrust: an asymmetry is the ratio of the
        # two branches, not measurable from a branch that is almost never used (issue 33:
        # a pitch asymmetry claimed on a command that is never positive)
        rms = {"forward": float(np.sqrt(np.mean(pos ** 2))),
               "backward": float(np.sqrt(np.mean(neg ** 2)))}
        for name, value in rms.items():
            share = value / sum(rms.values())
            if share < MIN_BRANCH_SHARE:
                return False, (f"the {name} thrust in this DOF is {100 * share:.1f} % of the "
                               f"thrust (RMS; at least {100 * MIN_BRANCH_SHARE:.0f} % needed "
                               "to measure an asymmetry)")
        return True, ""

    def signature(self, data, dof):
        return "force that depends on the sign of the thrust"

    nuisance_names = ("thrust_scale",)

    def nuisance(self, data, dof):
        # a symmetric thrust error scales the whole force balance like the prior's M, D_L,
        # D_Q together: fit it in the reference too, judge only the asymmetry
        pos, neg = self._parts(data, dof)
        return data.mean_held(pos + neg)[:, None]

    def nuisance_sd(self, data, dof):
        # the bench-measured thrust coefficients (Wang & Clark 2006 Table I, least squares on a
        # load cell) are taken as known to THRUST_BAND: without this anchor a free thrust
        # scale and the calibrated inertia and drag could all shrink together to zero
        return np.array([THRUST_BAND])

    def lower_bounds(self, data, dof, hyper=None):
        # thrust scale > -0.9: the thrusters deliver at least 10 % of their map
        return np.array([-0.9, -np.inf])

    def own_design(self, data, dof, hyper=None):
        pos, neg = self._parts(data, dof)
        return None, data.mean_held(neg)[:, None]

    def to_parameters(self, theta, hyper, nuisance=None):
        k = float(nuisance[0]) if nuisance is not None and len(nuisance) else 0.0
        return {"eta_forward": 1.0 + k, "eta_backward": 1.0 + k + float(theta[0])}

    def std_of(self, theta, cov, hyper_std, full_cov=None):
        if full_cov is None:
            return super().std_of(theta, cov, hyper_std)
        v0, v1, c = full_cov[0, 0], full_cov[1, 1], full_cov[0, 1]
        return {"eta_forward": float(math.sqrt(max(v0, 0.0))),
                "eta_backward": float(math.sqrt(max(v0 + v1 + 2 * c, 0.0)))}

    def magnitude(self, params):
        return params["eta_backward"] / params["eta_forward"]

    admits = "0.1 < eta_forward < 3 and 0.1 < eta_backward < 3"

    def plausible(self, params):
        return 0.1 < params["eta_forward"] < 3.0 and 0.1 < params["eta_backward"] < 3.0

    input_driven = True
    held = True

    def force_law(self, params, dof):
        """Simulation force law: Delta F_i = (eta_+ - 1) F+_i + (eta_- - 1) F-_i, eta [-], F+-_i [N or N m];
        returns f(time, eta, nu, inputs) -> (6,) [N, N m]. Equation and source: class docstring."""
        kp, kn = params["eta_forward"] - 1.0, params["eta_backward"] - 1.0
        e = _unit_vec(dof)

        def f(time, eta, nu, inputs):
            model = inputs["model"]
            thrust = inputs.get("thrust") or {}
            if model.thrusters and thrust:
                b = inputs["allocation"][dof]
                tk = np.array([thrust[th.name] for th in model.thrusters])
                pos = float(np.sum(np.where(tk >= 0, b * tk, 0.0)))
                neg = float(np.sum(np.where(tk < 0, b * tk, 0.0)))
            else:
                fi = float(inputs["tau"][dof])
                pos, neg = max(fi, 0.0), min(fi, 0.0)
            return (kp * pos + kn * neg) * e
        return f

    def batch_force_law(self, params, dof, history):
        r""":meth:`force_law` for many segments of one log at once (the free simulations of
        :mod:`stripcoef.diagnose.freesim`), the same numbers: ``history`` holds the log's
        ``tau`` (n, 6) [N, N m], ``thrust`` (n, k) [N] (the model's thrusters in order, or
        None) and ``allocation`` (6, k); returns g(times, rows (S,), last) -> (S, 6)
        [N, N m] at the samples ``rows``."""
        kp, kn = params["eta_forward"] - 1.0, params["eta_backward"] - 1.0
        e = _unit_vec(dof)
        thrust, tau = history.get("thrust"), history["tau"]
        b = history["allocation"][dof]

        def g(times, rows, last):
            if thrust is not None:
                tk = thrust[rows]
                pos = np.sum(np.where(tk >= 0, b * tk, 0.0), axis=1)
                neg = np.sum(np.where(tk < 0, b * tk, 0.0), axis=1)
            else:
                fi = tau[rows, dof]
                pos, neg = np.maximum(fi, 0.0), np.minimum(fi, 0.0)
            return (kp * pos + kn * neg)[:, None] * e
        return g



class Deadband(Effect):
    r"""A thruster dead zone around zero command.

    .. math:: T_k(n) = 0 \ \text{for}\ |n| \le \delta, \qquad
              \Delta F_i = -\sum_k B_{ik} T_k(n_k)\,[\,|n_k| \le \delta\,]

    with :math:`\delta` [command units] found by a one-dimensional search. The signature:
    no response to small commands, full response to large ones.

    Source: Yoerger, Cooke & Slotine (1990), IEEE JOE 15 (thruster dynamics, the dead zone of
    brushless thrusters); Wang & Clark 2006 eq. 6 (the thrust map it modifies).
    """

    name = "deadband"
    summary = "thruster dead zone around zero command"
    source = "Yoerger et al. (1990); Wang & Clark 2006 eq. 6"
    parameters = {"deadband": "command units"}
    hyper = ("deadband",)
    native = True

    def applicable(self, data, dof):
        if data.commands is None:
            return False, "needs thruster commands n_<name>"
        act = data.acting(dof)
        if not act:
            return False, "no thruster acts in this DOF"
        small = np.abs(data.commands[:, act])
        if not np.any((small > 0) & (small < np.percentile(small[small > 0], 50)
                                     if np.any(small > 0) else False)):
            return False, "no small non-zero commands"
        return True, ""

    def signature(self, data, dof):
        return "no response to small commands"

    def candidates(self, data, dof):
        act = data.acting(dof)
        levels = np.unique(np.abs(data.commands[:, act]))
        levels = levels[levels > 0]
        top = np.percentile(levels, 60) if levels.size else 0.0
        levels = levels[levels <= top]
        mids = 0.5 * (levels[1:] + levels[:-1])
        cands = np.unique(np.concatenate([levels, mids]))
        if cands.size > 60:
            cands = np.quantile(cands, np.linspace(0, 1, 60))
        return cands

    def offset(self, data, dof, delta):
        # the acting thrusters' forces and command magnitudes: the same for every threshold
        # the search tries, so taken once per window data
        fk, size = data.cached(("deadband_parts", dof), lambda: (
            data.thruster_force(dof)[:, data.acting(dof)],
            np.abs(data.commands[:, data.acting(dof)])))
        return -data.mean_held(np.where(size <= delta, fk, 0.0).sum(axis=1))

    def own_design(self, data, dof, hyper=None):
        delta = 0.0 if hyper is None else float(np.atleast_1d(hyper)[0])
        return self.offset(data, dof, delta), np.zeros((data.n_windows, 0))

    def to_parameters(self, theta, hyper, nuisance=None):
        return {"deadband": float(np.atleast_1d(hyper)[0])}

    admits = "deadband > 0"

    def plausible(self, params):
        return params["deadband"] > 0.0

    def force_law(self, params, dof):
        """Simulation force law: Delta F_i = -sum_k B_ik T_k [|n_k| <= delta], T_k [N], delta [command units];
        returns f(time, eta, nu, inputs) -> (6,) [N, N m]. Equation and source: class docstring."""
        delta = params["deadband"]
        e = _unit_vec(dof)

        def f(time, eta, nu, inputs):
            model = inputs["model"]
            b = inputs["allocation"][dof]
            cmds = inputs.get("commands") or {}
            thrust = inputs.get("thrust") or {}
            s = sum(b[k] * thrust.get(th.name, 0.0) for k, th in enumerate(model.thrusters)
                    if abs(cmds.get(th.name, 0.0)) <= delta and abs(b[k]) > 1e-9)
            return -s * e
        return f

    def apply(self, model, dof, params, std=None):
        """The model whose thrusters acting in ``dof`` have the dead band (a new model)."""
        b = model.allocation()[dof]
        return replace(model, thrusters=[
            replace(th, deadband=max(th.deadband, params["deadband"]))
            if abs(b[k]) > 1e-9 else th for k, th in enumerate(model.thrusters)])



class ThrustEffectiveness(Effect):
    r"""Commanded wrench that reaches the water only in part: a thrust scale per axis.

    .. math:: \Delta F_i = (s_i - 1)\,\tau_i

    with :math:`\tau_i` the applied generalized force the prior predicts from the commands
    (or the logged wrench) [N or N m] and :math:`s_i` [-] the fraction that acts: thruster
    wake and hull interaction, ventilation, a wrong thrust map or a controller whose
    commanded wrench is saturated downstream. The regressor is the applied force itself;
    it is separated from the prior's inertia and drag only by their bands (the force
    balance :math:`M\dot\nu + D\nu = s\tau` is homogeneous), so it is kept only when it
    improves the held-out free simulation (:mod:`stripcoef.diagnose.heldout`).

    The scale is a profiled nonlinear parameter (``hyper``: the shortfall :math:`k = s - 1`,
    0 without the effect) and the fit that holds it measures its residual in the units of
    the commanded force, :math:`(s\tau - M\dot\nu - \dots)/s` (:meth:`residual_scale`;
    :class:`stripcoef.diagnose.fit._Config`): the log determines the inertia, the drag and
    every other force only as their ratio to the thrust map (the balance divided by s), so
    the residual of a scaled balance, and the velocity noise in it (:math:`(M + \mu) n`),
    shrink with s. Measured in the delivered force, a fit lowers s to shrink its own
    residual (issue 33: 0.535 for a true 0.688, BlueROV2-like log of the independent
    simulator, seed 5242) and beats an added-mass change by the factor s on residual size
    alone (seed 5243: held-out errors 0.50 against 0.90, ratio 0.56, the fitted s 0.57);
    in the commanded force the same logs give 0.70 and, for the added mass, a scale of
    0.93 for a true 0.93.

    Source: Fossen (2011) sec. 6.7 (thrust deduction and propeller-hull interaction,
    :math:`T_{eff} = (1 - t_d) T`); Indiveri 1998 eq. 4.16 (the eta model, eta = 0.57 upward);
    issue 16 (real logs at 0.3-0.5 of the commanded wrench).
    """

    name = "thrust_effectiveness"
    summary = "only a fraction of the commanded thrust/wrench acts (scale per axis)"
    source = "Fossen (2011) sec. 6.7; Indiveri 1998 eq. 4.16"
    parameters = {"scale": "-"}
    hyper = ("shortfall",)
    input_driven = True
    held = True
    #: its regressor scales the prior's whole force balance (see the diagnosis's bands test)
    scales_prior = True
    #: plausible range of the scale [-]: at least 5 % and at most twice the prior's map
    BOUNDS = (0.05, 2.0)
    #: search points of the shortfall k = s - 1 over BOUNDS (spacing 0.05; the profile
    #: then refines between the best point's neighbours, fit.grid_minimum)
    GRID_POINTS = 40

    def applicable(self, data, dof):
        if not np.any(data.tau[:, dof] != 0):
            return False, "no applied force in this DOF"
        return True, ""

    def signature(self, data, dof):
        # none: the regressor is the applied force, which the prior's inertia and drag
        # scaled together reproduce; the effect is separated from them only by their bands
        # and must win on held-out error like any other candidate without a signature
        return ""

    def grid(self, data, dof):
        """Search points of the shortfall k = s - 1 [-] (:attr:`BOUNDS`)."""
        return np.linspace(self.BOUNDS[0] - 1.0, self.BOUNDS[1] - 1.0, self.GRID_POINTS)

    def hyper_start(self, data, dof):
        return np.array([0.0])

    def own_design(self, data, dof, hyper=None):
        k = 0.0 if hyper is None else float(np.atleast_1d(hyper)[0])
        return k * data.mean_held(data.tau[:, dof]), np.zeros((data.n_windows, 0))

    def residual_scale(self, hyper) -> float:
        """The factor s [-] that turns the fit's residual, in the delivered force, into the
        commanded force's units (class docstring): the residual is divided by it."""
        return 1.0 + float(np.atleast_1d(hyper)[0])

    def to_parameters(self, theta, hyper, nuisance=None):
        return {"scale": 1.0 + (0.0 if hyper is None else float(np.atleast_1d(hyper)[0]))}

    def at_bound(self, params) -> str:
        """``"lower"``/``"upper"`` when the scale sits at a bound of :attr:`BOUNDS` (within
        1e-4, the bounded search's tolerance), else ''."""
        for bound, side in zip(self.BOUNDS, ("lower", "upper")):
            if abs(params["scale"] - bound) <= 1e-4 * max(1.0, bound):
                return side
        return ""

    def magnitude(self, params):
        return params["scale"]

    def window_force(self, data, params, dof):
        return (params["scale"] - 1.0) * data.mean_held(data.tau[:, dof])

    admits = f"{BOUNDS[0]:g} <= scale <= {BOUNDS[1]:g}"
    all_dofs = True

    def plausible(self, params):
        return self.BOUNDS[0] <= params["scale"] <= self.BOUNDS[1]

    def force_law(self, params, dof):
        """Simulation force law: Delta F = (s - 1) tau in DOF ``dof`` (all six for None),
        s [-], tau [N, N m]; returns f(time, eta, nu, inputs) -> (6,) [N, N m]."""
        k = params["scale"] - 1.0
        e = np.ones(6) if dof is None else _unit_vec(dof)
        return lambda time, eta, nu, inputs: k * np.asarray(inputs["tau"], float) * e

    def batch_force_law(self, params, dof, history):
        r""":meth:`force_law` for many segments of one log at once (as
        :meth:`ThrustAsymmetry.batch_force_law`): g(times, rows (S,), last) -> (S, 6)
        [N, N m], :math:`(s - 1)\tau` at the samples ``rows``."""
        k = params["scale"] - 1.0
        e = np.ones(6) if dof is None else _unit_vec(dof)
        tau = history["tau"]
        return lambda times, rows, last: k * tau[rows] * e




class ThrusterGain(Effect):
    r"""Thrusters that differ from each other: one thrust gain per thruster.

    .. math:: \tau = T(\alpha)\,K\,u,\qquad K = \mathrm{diag}(g_1, \dots, g_N),\qquad
              \Delta F_i = \sum_k B_{ik}\,T_k\,(g_k - 1)

    with :math:`T(\alpha)` the thruster configuration (allocation) matrix B [-, m],
    :math:`K u` the thrusts, :math:`T_k` [N] thruster k's thrust from the prior's map
    (both branches) and :math:`g_k` [-] its gain: the share of its bench map it delivers
    on the vehicle (Fossen 2011, sec. 11.2.1, eq. 11.14: :math:`\tau = T(\alpha) K u`, the
    force coefficient matrix K diagonal, one entry per actuator). Real thrusters of one
    model differ from each other by a few per cent to 10-15 % (wear, fouling, a bent
    blade, motor and ESC spread, the mount's inflow), which no symmetric per-DOF scale
    (:class:`ThrustEffectiveness`) describes: the spread leaks the commands of one DOF
    into the others (issue 33).

    The gains are a property of the whole vehicle, not of one DOF: they are fitted jointly
    over every diagnosed DOF of a whole-log diagnosis (:mod:`stripcoef.diagnose.gains`),
    never by the per-DOF selection (:meth:`applicable`), with a Gaussian prior of standard
    deviation :data:`~stripcoef.effects.base.THRUST_BAND` about 1 (the bench uncertainty
    of the thrust maps), and only as *contrasts*, :math:`\sum_k (g_k - 1) = 0`: a common
    gain of all thrusters is the thrust effectiveness of each DOF (one rule per concept).
    The fitted gains are folded into each thruster's efficiency ``eta_forward`` and
    ``eta_backward`` (:meth:`apply`; native: the written model's thrust maps carry them).
    The thrust limits [N] are unchanged.

    Parameters: ``gain_<thruster name>`` [-], one per thruster (:attr:`parameters` names
    the family).

    Source: Fossen (2011), Handbook of Marine Craft Hydrodynamics and Motion Control,
    sec. 11.2.1 (eq. 11.14); Wang & Clark 2006 Table I (bench-measured thrust maps).
    """

    name = "thruster_gain"
    summary = "thrusters differ from each other: one thrust gain per thruster"
    source = "Fossen (2011) sec. 11.2.1, eq. 11.14"
    parameters = {"gain": "-"}
    native = True
    input_driven = True
    held = True
    all_dofs = True

    def applicable(self, data, dof):
        return False, ("a property of every thruster at once: fitted jointly over the DOFs "
                       "of a whole-log diagnosis (stripcoef.diagnose.gains)")

    def signature(self, data, dof):
        return "commands of other DOFs leaking through thrusters of unequal gains"

    @staticmethod
    def gains(model, params: dict) -> np.ndarray:
        """The gains of ``model``'s thrusters from ``params`` (``gain_<name>``; 1 where
        absent) [-]."""
        return np.array([float(params.get(f"gain_{th.name}", 1.0)) for th in model.thrusters])

    def own_design(self, data, dof, hyper=None):
        """Columns: window means of :math:`B_{ik} T_k`, one per thruster [N or N m]."""
        if data.thrust is None:
            return None, np.zeros((data.n_windows, 0))
        return None, data.mean_held(data.thruster_force(dof))

    def to_parameters(self, theta, hyper, nuisance=None):
        raise NotImplementedError("thruster_gain names its parameters by thruster: "
                                  "stripcoef.diagnose.gains.ThrusterGains.parameters")

    def magnitude(self, params):
        """The largest relative deviation of a gain from 1 [-]."""
        return max((abs(v - 1.0) for v in params.values()), default=0.0)

    admits = "0.1 < gain < 3 for every thruster"

    def plausible(self, params):
        return all(0.1 < v < 3.0 for v in params.values())

    def force_law(self, params, dof):
        """Simulation force law: Delta F_i = sum_k B_ik T_k (g_k - 1), g_k [-], T_k [N];
        returns f(time, eta, nu, inputs) -> (6,) [N, N m] (all six with ``dof`` None).
        Equation and source: class docstring."""
        e = np.ones(6) if dof is None else _unit_vec(dof)

        def f(time, eta, nu, inputs):
            model = inputs["model"]
            thrust = inputs.get("thrust") or {}
            if not (model.thrusters and thrust):
                return np.zeros(6)
            g = self.gains(model, params) - 1.0
            tk = np.array([thrust[th.name] for th in model.thrusters])
            return (inputs["allocation"] @ (g * tk)) * e
        return f

    def apply(self, model, dof, params, std=None):
        """The model whose thrusters' efficiencies carry their gains (a new model)."""
        g = self.gains(model, params)
        return replace(model, thrusters=[
            replace(th, eta_forward=th.eta_forward * float(gk),
                    eta_backward=th.eta_backward * float(gk))
            for th, gk in zip(model.thrusters, g)])
