r"""The effects library: forces a strip-theory model lacks, with their regressors.

Each effect is a small class with

- its physics (docstring: equation, units, source),
- ``parameters``: name -> unit,
- ``design(data, dof, hyper)`` -> ``(offset, columns)``: the missing generalized force in one
  DOF, window-averaged (see :class:`~stripcoef.effects.windows.WindowData`), is modelled as
  ``offset(hyper) + columns @ theta`` [N or N m]; ``hyper`` are the effect's nonlinear
  parameters (a current, a dead band), profiled by :mod:`stripcoef.diagnose.pipeline`,
- ``force_law(parameters, dof)`` -> ``f(time, eta, nu, inputs) -> (6,)``: the same force for
  :func:`stripcoef.simulate.simulate` (a calibrated model carries its effects in
  ``HydroModel.effects`` and the simulation applies them),
- ``mimics``: the prior coefficient whose regressor the effect reproduces when the log has
  no signature of it (then it is identifiable only as a coefficient far outside its band).

The registry :data:`EFFECTS` has one entry per effect name; :func:`get_effect` raises an
error listing the valid names.

What the effects are fitted to, the log's window data, is :mod:`stripcoef.effects.windows`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import FrozenInstanceError, replace

import numpy as np

from stripcoef.conventions import DOF, parse_dof
from stripcoef.errors import InputError, unknown_name
from stripcoef.effects.windows import (WindowData, coefficient_column, coriolis_times_velocity,
                                       damping_times_velocity, rotation_matrices)

TRANSLATIONAL = (0, 1, 2)
#: 1-sigma relative uncertainty of the thrust maps (bench-measured C_t) [-]
THRUST_BAND = 0.05


# ---------------------------------------------------------------------------
# vectorised model terms (same formulas as HydroModel; tested against it)
# ---------------------------------------------------------------------------


# ---------------------------------------------------------------------------
# the log, cut into windows
# ---------------------------------------------------------------------------


# ---------------------------------------------------------------------------
# effects
# ---------------------------------------------------------------------------

class Effect:
    """Base class: see the module docstring for the interface.

    An effect is a frozen spec: its name, parameters, physics and regressors are class
    attributes and methods, and an instance cannot be changed (the registry :data:`EFFECTS`
    shares one instance per effect with every caller).
    """

    def __setattr__(self, name, value):
        raise FrozenInstanceError(f"effect {self.name!r} is immutable (cannot set {name!r})")

    def __delattr__(self, name):
        raise FrozenInstanceError(f"effect {self.name!r} is immutable (cannot delete {name!r})")

    name = ""
    summary = ""
    source = ""
    parameters: dict = {}
    hyper: tuple = ()
    dofs = tuple(range(6))
    mimics = None
    native = False

    def applicable(self, data: WindowData, dof: int) -> tuple[bool, str]:
        if dof not in self.dofs:
            return False, f"acts only in {', '.join(DOF[i] for i in self.dofs)}"
        return True, ""

    def signature(self, data: WindowData, dof: int) -> str:
        """What in the data separates this effect from the prior's own terms ('' = none)."""
        return "" if self.mimics else "a regressor the prior's terms do not have"


    def hyper_start(self, data, dof):
        return None

    def to_parameters(self, theta, hyper, nuisance=None) -> dict:
        names = list(self.parameters)
        vals = list(np.atleast_1d(theta)) + list(np.atleast_1d(hyper) if hyper is not None
                                                 else [])
        return {n: float(v) for n, v in zip(names, vals)}

    #: indices of the linear parameters that carry the signature (tested for |theta|/sigma)
    z_columns = None

    #: names of the nuisance columns (prior coefficients ``M``, ``D_L``, ``D_Q`` released
    #: from their bands, or a parameter of the effect itself)
    nuisance_names: tuple = ()

    def nuisance(self, data, dof):
        """Columns fitted, free, in the reference as well as with the effect: the part of
        the effect the prior's own terms can mimic. The effect is judged on what it adds
        beyond them (its signature). None = no nuisance columns."""
        if not self.nuisance_names:
            return None
        return np.column_stack([coefficient_column(data, dof, n) for n in self.nuisance_names])

    def nuisance_sd(self, data, dof) -> np.ndarray:
        """Prior standard deviations of the nuisance parameters (inf = free)."""
        nuis = self.nuisance(data, dof)
        return np.full(0 if nuis is None else nuis.shape[1], np.inf)

    def prior_sd(self, data, dof, hyper=None) -> np.ndarray:
        """Prior standard deviations of all columns of :meth:`design` (inf = free)."""
        ncols = self.design(data, dof, hyper)[1].shape[1]
        sd = self.nuisance_sd(data, dof)
        return np.concatenate([sd, np.full(ncols - sd.size, np.inf)])

    def own_design(self, data, dof, hyper=None):
        """(offset, columns) of the effect's own parameters."""
        raise NotImplementedError

    def design(self, data, dof, hyper=None):
        """Nuisance columns first, then the effect's own columns."""
        off, cols = self.own_design(data, dof, hyper)
        nuis = self.nuisance(data, dof)
        return off, cols if nuis is None else np.hstack([nuis, cols])

    def std_of(self, theta, cov, hyper_std, full_cov=None) -> dict:
        """Standard deviations of :meth:`to_parameters` (``theta``, ``cov``: own part;
        ``full_cov``: with the nuisance parameters first)."""
        vals = list(np.sqrt(np.clip(np.diag(cov), 0, None))) + list(hyper_std)
        return {n: float(v) for n, v in zip(self.parameters, vals)}

    def magnitude(self, params: dict) -> float:
        """The one number the benchmark compares with the truth."""
        return float(next(iter(params.values())))

    def plausible(self, params: dict) -> bool:
        return all(math.isfinite(v) for v in params.values())

    def force_law(self, params: dict, dof: int):
        """Force law ``f(time, eta, nu, inputs) -> (6,)`` [N, N m] of the effect's equation
        (class docstring, with its units and source) in DOF ``dof``, for
        :func:`stripcoef.simulate.simulate`; ``params`` in the units of :attr:`parameters`."""
        raise NotImplementedError

    def window_force(self, data, params: dict, dof: int) -> np.ndarray:
        """Window mean of the effect's force in ``dof`` along the log [N or N m], (m,): the
        force law evaluated at every sample (the log's state and inputs), averaged as a held
        input (:attr:`input_driven`) or by the trapezoidal rule."""
        law = self.force_law(params, dof)
        names = [th.name for th in data.model.thrusters]
        f = np.zeros(data.t.size)
        for n in range(data.t.size):
            cmd = {} if data.commands is None else dict(zip(names, data.commands[n]))
            thr = {} if data.thrust is None else dict(zip(names, data.thrust[n]))
            inputs = {"commands": cmd, "thrust": thr, "tau": data.tau[n], "nu_c": np.zeros(6),
                      "nu_r": data.nu[n], "model": data.model, "allocation": data.alloc,
                      "columns": {k: v[n] for k, v in data.columns.items()},
                      "input_history": (data.t, data.tau)}
            f[n] = law(data.t[n], data.eta[n], data.nu[n], inputs)[dof]
        return data.mean_held(f) if self.input_driven else data.mean(f)

    def apply(self, model, dof: int, params: dict, std: dict | None = None):
        """The model with the effect added (a new model; ``model`` is immutable): as an
        entry of ``model.effects``."""
        return model.with_effects({
            "name": self.name, "dof": DOF[dof], "parameters": dict(params),
            "std": dict(std or {}), "units": dict(self.parameters)})

    #: the force depends only on the applied inputs (window-averaged exactly as a held input)
    input_driven = False

    def implausible(self, params: dict, data=None, dof=None) -> str:
        """Why the parameters are physically impossible for this log ('' if they are not)."""
        return "" if self.plausible(params) else "implausible parameters"


def _unit_vec(dof):
    e = np.zeros(6)
    e[dof] = 1.0
    return e


class TetherDrag(Effect):
    r"""Drag of a tether paid out behind the vehicle.

    .. math:: F_i = -c_t\, L(t)\, \nu_{r,i}|\nu_{r,i}|, \qquad c_t = \tfrac12 \rho C_d d_t

    with L the paid-out length [m] (log column ``tether_length``), d_t the tether diameter
    [m] and C_d its drag coefficient (about 1.2 in cross-flow, Hoerner 1965, ch. 3, fig. 21;
    much less along the cable). c_t [N s^2/m^3] is the drag per metre of tether per (m/s)^2.
    Without a ``tether_length`` column L = 1 and the effect is a quadratic drag increase,
    indistinguishable from a larger D_Q (it ``mimics`` that coefficient). With the column, a
    free D_Q change is fitted alongside (nuisance) and the tether is judged on the
    dependence on L alone.

    Source: Hoerner, Fluid-Dynamic Drag (1965) ch. 3 (cylinder cross-flow drag); Wang &
    Clark (Wang & Clark 2006, sec. IV.A): the unmodelled tether blamed for 0.47 vs 0.51 m/s.
    """

    name = "tether_drag"
    nuisance_names = ("D_Q",)
    summary = "tether drag, quadratic in speed, proportional to the paid-out length"
    source = "Hoerner (1965) ch. 3; Wang & Clark 2006 sec. IV.A"
    parameters = {"c_t": "N s^2/m^3"}
    dofs = TRANSLATIONAL

    def _length(self, data):
        return data.columns.get("tether_length")

    def signature(self, data, dof):
        length = self._length(data)
        if length is None or np.ptp(length) <= 1e-9 * max(1.0, float(np.max(np.abs(length)))):
            return ""
        return "dependence on tether_length"

    @property
    def mimics(self):  # decided per log in signature(); the prior term it can look like
        return "D_Q"

    def nuisance(self, data, dof):
        return super().nuisance(data, dof) if self.signature(data, dof) else None

    def own_design(self, data, dof, hyper=None):
        length = self._length(data)
        length = np.ones(data.t.size) if length is None else length
        v = data.nu[:, dof]
        return None, -data.mean(length * v * np.abs(v))[:, None]

    def plausible(self, params):
        return params["c_t"] > 0.0

    def force_law(self, params, dof):
        """Simulation force law: F_i = -c_t L nu_r,i |nu_r,i|, c_t [N s^2/m^3], L [m], nu_r [m/s];
        returns f(time, eta, nu, inputs) -> (6,) [N, N m]. Equation and source: class docstring."""
        c = params["c_t"]
        e = _unit_vec(dof)

        def f(time, eta, nu, inputs):
            length = inputs.get("columns", {}).get("tether_length", 1.0)
            v = inputs.get("nu_r", nu)[dof]
            return -c * length * v * abs(v) * e
        return f


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

    def plausible(self, params):
        return 0.1 < params["eta_forward"] < 3.0 and 0.1 < params["eta_backward"] < 3.0

    input_driven = True

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


class MomentumDrag(Effect):
    r"""Drag proportional to another thruster group's speed times the velocity.

    .. math:: F_i = -\alpha\, n_h(t)\, \nu_{r,i}

    with :math:`n_h` the mean modulus of the commands of the thrusters that do not act in
    DOF i [command units] and :math:`\alpha` [N s/m per command unit] (N m s/rad for a
    rotation). The signature: dependence on another channel (those thrusters' speed).

    Source: Caccia et al. (Indiveri 1998, the eta-md model, sec. 3.3.1 and the H_md regressor:
    F_md = -alpha n_h w).
    """

    name = "momentum_drag"
    nuisance_names = ("D_L",)
    summary = "drag proportional to other thrusters' speed times the velocity"
    source = "Indiveri 1998 eta-md model (sec. 3.3.1, eq. 4.17)"
    parameters = {"alpha": "N s/m per command unit"}

    def _nh(self, data, dof):
        if data.commands is None:
            return None
        others = [k for k in range(data.commands.shape[1]) if k not in data.acting(dof)]
        if not others:
            return None
        return np.mean(np.abs(data.commands[:, others]), axis=1)

    def applicable(self, data, dof):
        nh = self._nh(data, dof)
        if nh is None:
            return False, "needs commands of thrusters that do not act in this DOF"
        if np.ptp(nh) == 0 and nh.max() == 0:
            return False, "the other thrusters never run"
        return True, ""

    def signature(self, data, dof):
        nh = self._nh(data, dof)
        return "dependence on other thrusters' speed" if nh is not None and np.ptp(nh) > 0 \
            else ""

    @property
    def mimics(self):
        return "D_L"

    def nuisance(self, data, dof):
        return super().nuisance(data, dof) if self.signature(data, dof) else None

    def own_design(self, data, dof, hyper=None):
        nh = self._nh(data, dof)
        return None, -data.mean(nh * data.nu[:, dof])[:, None]

    def plausible(self, params):
        return params["alpha"] > 0.0

    def force_law(self, params, dof):
        """Simulation force law: F_i = -alpha n_h nu_r,i, alpha [N s/m per command unit], n_h [command units];
        returns f(time, eta, nu, inputs) -> (6,) [N, N m]. Equation and source: class docstring."""
        a = params["alpha"]
        e = _unit_vec(dof)

        def f(time, eta, nu, inputs):
            model = inputs["model"]
            b = inputs["allocation"][dof]
            cmds = inputs.get("commands") or {}
            others = [th.name for k, th in enumerate(model.thrusters) if abs(b[k]) <= 1e-9]
            nh = float(np.mean([abs(cmds.get(n, 0.0)) for n in others])) if others else 0.0
            return -a * nh * inputs.get("nu_r", nu)[dof] * e
        return f


class BuoyancyOffset(Effect):
    r"""A constant force or moment: wrong weight or buoyancy, a trim or bias.

    .. math:: F_i = b

    [N or N m]. For heave this is the weight-buoyancy error W - B projected on the body z
    axis (constant for small roll and pitch); for yaw the bias delta of Wang & Clark 2006's eq. 8.

    Source: Caccia et al. (Indiveri 1998, eq. 4.15: the buoyancy term W); Wang & Clark (Wang & Clark 2006,
    eq. 8: the bias delta); Fossen (2011) eq. 4.6.
    """

    name = "buoyancy_offset"
    summary = "constant force or moment (weight/buoyancy error, bias)"
    source = "Indiveri 1998 eq. 4.15; Wang & Clark 2006 eq. 8; Fossen (2011) eq. 4.6"
    parameters = {"b": "N or N m"}

    def signature(self, data, dof):
        return "a bias"

    input_driven = True

    def own_design(self, data, dof, hyper=None):
        return None, np.ones((data.n_windows, 1))

    def force_law(self, params, dof):
        """Simulation force law: F_i = b, b [N or N m];
        returns f(time, eta, nu, inputs) -> (6,) [N, N m]. Equation and source: class docstring."""
        e = params["b"] * _unit_vec(dof)
        return lambda time, eta, nu, inputs: e


class Current(Effect):
    r"""A constant water current, so drag and added-mass forces act on the relative velocity.

    .. math::
        \Delta F = -\big[D(\nu_r)\nu_r - D(\nu)\nu\big] - \big[C_A(\nu_r)\nu_r - C_A(\nu)\nu\big]
        + M_A\dot\nu_c,\qquad \nu_r = \nu - [R^T V_c;\ 0]

    with the horizontal current :math:`V_c = [V_N, V_E, 0]` [m/s] in NED, fitted by
    nonlinear least squares (variable projection). The signature: a force that rotates
    with the heading (turns) and is not symmetric in the sign of the speed.

    Source: Fossen (2011), eq. 10.1 and sec. 10.3 (relative velocity, irrotational current).
    """

    name = "current"
    nuisance_names = ("D_L", "D_Q")
    summary = "constant water current: drag on the relative velocity"
    source = "Fossen (2011) eq. 10.1, sec. 10.3"
    parameters = {"current_north": "m/s", "current_east": "m/s"}
    hyper = ("current_north", "current_east")
    dofs = (0, 1)

    def signature(self, data, dof):
        return ("a force that turns with the heading" if np.ptp(data.eta[:, 5]) > 0.5
                else "a force asymmetric in the sign of the speed")

    def _current_body(self, data, vc):
        """nu_c = [R^T V_c; 0] per sample (n, 6) [m/s]."""
        rot = rotation_matrices(data.eta)
        v = np.array([vc[0], vc[1], 0.0])
        nuc = np.zeros_like(data.nu)
        nuc[:, :3] = np.einsum("nji,j->ni", rot, v)  # R^T V_c
        return nuc

    def relative_velocity(self, data, vc):
        """nu_r = nu - [R^T V_c; 0] (n, 6) [m/s, rad/s]: the velocity the calibration's drag
        and added-mass terms act on once the current is in the model (Fossen 2011, eq. 10.1)."""
        return data.nu - self._current_body(data, vc)

    def design(self, data, dof, hyper=None):
        """Nuisance columns (released D_L, D_Q) at the relative velocity, then the offset."""
        off, cols = self.own_design(data, dof, hyper)
        nur = self.relative_velocity(data, (0.0, 0.0) if hyper is None else hyper)
        nuis = np.column_stack([coefficient_column(data, dof, n, nur)
                                for n in self.nuisance_names])
        return off, np.hstack([nuis, cols])

    def offset(self, data, dof, vc):
        model = data.model
        nuc = self._current_body(data, vc)
        nur = data.nu - nuc
        diff = (damping_times_velocity(model, nur) - damping_times_velocity(model, data.nu)
                + coriolis_times_velocity(model.added_mass, nur)
                - coriolis_times_velocity(model.added_mass, data.nu))
        return -data.mean(diff[:, dof]) + data.rate(nuc @ model.added_mass[dof])

    def own_design(self, data, dof, hyper=None):
        vc = (0.0, 0.0) if hyper is None else hyper
        return self.offset(data, dof, vc), np.zeros((data.n_windows, 0))

    def hyper_start(self, data, dof):
        return np.zeros(2)

    def to_parameters(self, theta, hyper, nuisance=None):
        return {"current_north": float(hyper[0]), "current_east": float(hyper[1])}

    def magnitude(self, params):
        return math.hypot(params["current_north"], params["current_east"])

    def plausible(self, params):
        return self.magnitude(params) < 5.0

    def max_magnitude(self, data) -> float:
        r"""Largest current the log can support [m/s]: the vehicle's 95th-percentile
        horizontal speed over ground, :math:`|V_c| \le P_{95}(\sqrt{u^2 + v^2})`. A vehicle
        driven around a basin against a current faster than itself would be swept away,
        and a constant current larger than the speeds the log explores is an extrapolation
        of the drag law, not a measurement (issue 16: 0.73 m/s accepted in a pool)."""
        return float(np.percentile(np.hypot(data.nu[:, 0], data.nu[:, 1]), 95))

    def implausible(self, params, data=None, dof=None):
        if not self.plausible(params):
            return "implausible parameters"
        if data is not None and self.magnitude(params) > self.max_magnitude(data):
            return (f"a current of {self.magnitude(params):.3g} m/s exceeds what the log "
                    f"supports ({self.max_magnitude(data):.3g} m/s, the 95th-percentile "
                    "horizontal speed)")
        return ""

    def force_law(self, params, dof):
        """Simulation force law: Delta F_i of the class docstring at nu_r = nu - [R^T V_c; 0], V_c [m/s] in NED, nu_c_dot = [-S(omega) R^T V_c; 0] [m/s^2];
        returns f(time, eta, nu, inputs) -> (6,) [N, N m]. Equation and source: class docstring."""
        v = np.array([params["current_north"], params["current_east"], 0.0])
        e = _unit_vec(dof)

        def f(time, eta, nu, inputs):
            from stripcoef.conventions import rotation_matrix, skew
            model = inputs["model"]
            rt = rotation_matrix(eta[3], eta[4], eta[5]).T
            nuc = np.concatenate([rt @ v, np.zeros(3)])
            nur = nu - nuc
            nuc_dot = np.concatenate([-skew(nu[3:]) @ (rt @ v), np.zeros(3)])
            diff = (model.damping(nur) @ nur - model.damping(nu) @ nu
                    + model.coriolis(nur, rigid_body=False) @ nur
                    - model.coriolis(nu, rigid_body=False) @ nu)
            return (-diff[dof] + (model.added_mass @ nuc_dot)[dof]) * e
        return f


class LinearDrag(Effect):
    r"""A linear damping term missing from a quadratic-only model.

    .. math:: F_i = -d_L\, \nu_{r,i}

    [N s/m or N m s/rad]. Dominant at low speed (Wang & Clark 2006, eq. 7; Indiveri 1998's yaw tables
    where the linear no-bias LNB model is the best at rates below 10 deg/s). When the prior
    already has this linear term the effect mimics its calibration.

    Source: Fossen (2011) eq. 6.59; Wang & Clark 2006 eq. 7; Indiveri 1998 sec. 4.2.5.
    """

    name = "linear_drag"
    summary = "linear damping missing from the model"
    source = "Fossen (2011) eq. 6.59; Wang & Clark 2006 eq. 7; Indiveri 1998 sec. 4.2.5"
    parameters = {"d_L": "N s/m or N m s/rad"}
    native = True

    def signature(self, data, dof):
        return "" if data.model.linear_damping[dof, dof] != 0 else \
            "linear damping where the prior has none"

    @property
    def mimics(self):
        return "D_L"

    def own_design(self, data, dof, hyper=None):
        return None, -data.mean(data.nu[:, dof])[:, None]

    def plausible(self, params):
        return params["d_L"] > 0.0

    def force_law(self, params, dof):
        """Simulation force law: F_i = -d_L nu_r,i, d_L [N s/m or N m s/rad];
        returns f(time, eta, nu, inputs) -> (6,) [N, N m]. Equation and source: class docstring."""
        d = params["d_L"]
        e = _unit_vec(dof)
        return lambda time, eta, nu, inputs: -d * inputs.get("nu_r", nu)[dof] * e

    def apply(self, model, dof, params, std=None):
        """The model with d_L added to D_L[dof, dof] (a new model)."""
        dl = np.array(model.linear_damping, dtype=float)
        dl[dof, dof] += params["d_L"]
        return replace(model, linear_damping=dl)


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
        act = data.acting(dof)
        fk = data.thruster_force(dof)[:, act]
        dead = np.abs(data.commands[:, act]) <= delta
        return -data.mean_held(np.where(dead, fk, 0.0).sum(axis=1))

    def own_design(self, data, dof, hyper=None):
        delta = 0.0 if hyper is None else float(np.atleast_1d(hyper)[0])
        return self.offset(data, dof, delta), np.zeros((data.n_windows, 0))

    def to_parameters(self, theta, hyper, nuisance=None):
        return {"deadband": float(np.atleast_1d(hyper)[0])}

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


class AddedMassError(Effect):
    r"""Wrong total inertia (added mass), visible in the transients.

    .. math:: F_i = -\delta m\, \dot\nu_i

    [kg or kg m^2]. The regressor is the prior's own inertia term, so the effect is the
    inertia released from its band: it is reported only when the data force the inertia
    far outside the band strip theory is known to have (Wang & Clark 2006, Table I: N_rdot 0.0321
    analytical vs 0.0118 experimental).

    Source: Fossen (2011) sec. 6.3 (added mass); Wang & Clark 2006 Table I.
    """

    name = "added_mass_error"
    inertia = True  # its column multiplies the acceleration (profiled, see diagnose._solve)
    summary = "wrong total inertia, visible in transients"
    source = "Fossen (2011) sec. 6.3; Wang & Clark 2006 Table I"
    parameters = {"delta_m": "kg or kg m^2"}
    mimics = "M"
    native = True

    def signature(self, data, dof):
        return ""

    def lower_bounds(self, data, dof, hyper=None):
        # no negative added mass (the released inertia stays >= the rigid-body one)
        return np.array([-abs(float(data.model.added_mass[dof, dof]))])

    def own_design(self, data, dof, hyper=None):
        return None, coefficient_column(data, dof, "M")[:, None]

    def plausible(self, params):
        return True

    def force_law(self, params, dof):
        """Simulation force law: none, the effect is native (F_i = -delta_m nu_dot_i [N], delta_m [kg], is folded into M_A by apply);
        returns f(time, eta, nu, inputs) -> (6,) [N, N m]. Equation and source: class docstring."""
        raise InputError("added_mass_error is applied to the added-mass matrix, not as a force",
                         key="effects", value=self.name, expected="a native model change")

    def apply(self, model, dof, params, std=None):
        """The model with delta_m added to M_A[dof, dof] (a new model)."""
        ma = np.array(model.added_mass, dtype=float)
        ma[dof, dof] += params["delta_m"]
        return replace(model, added_mass=ma)


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

    Source: Fossen (2011) sec. 6.7 (thrust deduction and propeller-hull interaction,
    :math:`T_{eff} = (1 - t_d) T`); Indiveri 1998 eq. 4.16 (the eta model, eta = 0.57 upward);
    issue 16 (real logs at 0.3-0.5 of the commanded wrench).
    """

    name = "thrust_effectiveness"
    summary = "only a fraction of the commanded thrust/wrench acts (scale per axis)"
    source = "Fossen (2011) sec. 6.7; Indiveri 1998 eq. 4.16"
    parameters = {"scale": "-"}
    input_driven = True
    #: its regressor scales the prior's whole force balance (see the diagnosis's bands test)
    scales_prior = True
    #: plausible range of the scale [-]: at least 5 % and at most twice the prior's map
    BOUNDS = (0.05, 2.0)

    def applicable(self, data, dof):
        if not np.any(data.tau[:, dof] != 0):
            return False, "no applied force in this DOF"
        return True, ""

    def signature(self, data, dof):
        # none: the regressor is the applied force, which the prior's inertia and drag
        # scaled together reproduce; the effect is separated from them only by their bands
        # and must win on held-out error like any other candidate without a signature
        return ""

    def own_design(self, data, dof, hyper=None):
        return None, data.mean_held(data.tau[:, dof])[:, None]

    def lower_bounds(self, data, dof, hyper=None):
        return np.array([self.BOUNDS[0] - 1.0])

    def upper_bounds(self, data, dof, hyper=None):
        return np.array([self.BOUNDS[1] - 1.0])

    def to_parameters(self, theta, hyper, nuisance=None):
        return {"scale": 1.0 + float(np.atleast_1d(theta)[0])}

    def magnitude(self, params):
        return params["scale"]

    def window_force(self, data, params, dof):
        return (params["scale"] - 1.0) * data.mean_held(data.tau[:, dof])

    def plausible(self, params):
        return self.BOUNDS[0] <= params["scale"] <= self.BOUNDS[1]

    def force_law(self, params, dof):
        """Simulation force law: Delta F = (s - 1) tau in DOF ``dof`` (all six for None),
        s [-], tau [N, N m]; returns f(time, eta, nu, inputs) -> (6,) [N, N m]."""
        k = params["scale"] - 1.0
        e = np.ones(6) if dof is None else _unit_vec(dof)
        return lambda time, eta, nu, inputs: k * np.asarray(inputs["tau"], float) * e


def _held_history(inputs):
    """(t, tau) of the whole run from the simulation's inputs (``input_history``)."""
    hist = inputs.get("input_history")
    if hist is None:
        raise InputError("this effect needs the input history of the simulation",
                         key="effects", expected="stripcoef.simulate.simulate")
    return hist


def lagged_held(t, u, time_constant):
    r"""First-order lag of a zero-order-hold input, exactly.

    .. math:: T\dot y = u - y,\quad y_{k+1} = u_k + (y_k - u_k)e^{-\Delta t_k/T},\quad
              \int_{t_k}^{t_{k+1}} y\,dt = u_k\Delta t_k + (y_k - u_k)\,T(1 - e^{-\Delta t_k/T})

    with :math:`y_0 = u_0` (in equilibrium at the start). ``t`` (n,) [s], ``u`` (n,) or
    (n, c), ``time_constant`` T [s]. Returns ``(y, integral)``: y at the samples and the
    exact integral of y over each interval (n - 1) [units of u times s].

    Source: Fossen (2011) sec. 9.3 (first-order actuator dynamics); Yoerger, Cooke &
    Slotine (1990), IEEE JOE 15 (thruster dynamics).
    """
    u = np.asarray(u, float)
    dt = np.diff(t)
    y = np.empty_like(u)
    y[0] = u[0]
    tc = max(float(time_constant), 1e-9)
    a = np.exp(-dt / tc)
    for k in range(dt.size):
        y[k + 1] = u[k] + (y[k] - u[k]) * a[k]
    w = tc * (1.0 - a)
    if u.ndim > 1:
        dt, w = dt[:, None], w[:, None]
    integral = u[:-1] * dt + (y[:-1] - u[:-1]) * w
    return y, integral


def delayed_integral(t, u, delay, s):
    r"""Integral of a held input delayed by ``delay`` up to the times ``s``.

    .. math:: \int_{t_0}^{s} u(\sigma - d)\,d\sigma = C(s - d) - C(t_0 - d),\quad
              C(x) = \int_{t_0}^{x} u,\ u(x < t_0) = u_0

    ``t`` (n,) [s], ``u`` (n,) zero-order hold, ``delay`` d [s] >= 0, ``s`` (m,) [s].
    """
    u = np.asarray(u, float)
    dt = np.diff(t)
    cum = np.concatenate([[0.0], np.cumsum(u[:-1] * dt)])

    def c(x):
        x = np.asarray(x, float)
        k = np.clip(np.searchsorted(t, x, side="right") - 1, 0, t.size - 1)
        return np.where(x < t[0], u[0] * (x - t[0]), cum[k] + u[k] * (x - t[k]))
    return c(np.asarray(s) - delay) - c(t[0] - delay)


def _resolvable(effect, value, data, samples):
    """'' if a time [s] is plausible and longer than ``samples`` sampling intervals of the
    log (a shorter lag or delay is not resolvable from it: it absorbs the quadrature error
    of the window integrals at input steps instead), else the reason."""
    if not effect.plausible({next(iter(effect.parameters)): value}):
        return "implausible parameters"
    if data is not None:
        dt = float(np.median(np.diff(data.t)))
        if value < samples * dt:
            return (f"{value:.3g} s is shorter than {samples:g} sampling interval(s) "
                    f"({samples * dt:.3g} s): not resolvable from this log")
    return ""


class _TimedInputEffect(Effect):
    """An effect of the inputs with one time parameter [s] (a lag, a delay), profiled by a
    one-dimensional search over :meth:`grid`: its design is the window mean of
    :meth:`offset`, the input as it acts minus the input as logged, and it has no linear
    coefficient.  Subclasses give ``hyper = (NAME,)``, ``GRID_MAX`` [s], ``GRID_LOG``
    (search points spaced geometrically, else evenly, from a tenth of the median sampling
    interval to ``GRID_MAX``), ``RESOLVE`` (how many sampling intervals make the parameter
    resolvable) and :meth:`offset`."""

    input_driven = True
    GRID_MAX = 1.0
    GRID_LOG = False
    RESOLVE = 1.0

    def grid(self, data, dof):
        dt = float(np.median(np.diff(data.t)))
        return (np.geomspace if self.GRID_LOG else np.linspace)(0.1 * dt, self.GRID_MAX, 12)

    def applicable(self, data, dof):
        if not np.any(data.tau[:, dof] != 0):
            return False, "no applied force in this DOF"
        return True, ""

    def hyper_start(self, data, dof):
        return np.array([0.0])

    def offset(self, data, dof, value):  # pragma: no cover - abstract
        raise NotImplementedError

    def own_design(self, data, dof, hyper=None):
        value = 0.0 if hyper is None else float(np.atleast_1d(hyper)[0])
        off = np.zeros(data.n_windows) if value <= 0 else self.offset(data, dof, value)
        return off, np.zeros((data.n_windows, 0))

    def to_parameters(self, theta, hyper, nuisance=None):
        return {self.hyper[0]: float(np.atleast_1d(hyper)[0])}

    def window_force(self, data, params, dof):
        return self.own_design(data, dof, [params[self.hyper[0]]])[0]

    def plausible(self, params):
        return 0.0 < params[self.hyper[0]] <= self.GRID_MAX

    def implausible(self, params, data=None, dof=None):
        return _resolvable(self, params[self.hyper[0]], data, self.RESOLVE)


class ThrusterLag(_TimedInputEffect):
    r"""Thruster dynamics: the thrust follows the command with a first-order lag.

    .. math:: T_l\,\dot{\tau}_{l} = \tau - \tau_{l},\qquad \Delta F_i = \tau_{l,i} - \tau_i

    with :math:`\tau` the applied force the prior predicts from the commands [N or N m],
    :math:`\tau_l` the force that acts and :math:`T_l` [s] the time constant, profiled by a
    one-dimensional search (one value for the vehicle's thrusters). The signature: a force
    that follows every step of the input and decays with the time constant; an inflated
    added mass (the confusion issue 16 measured in 6 of 6 logs) acts on the acceleration of
    the vehicle instead, whose time constant is M/D.

    Source: Yoerger, Cooke & Slotine (1990), IEEE JOE 15 (thruster dynamics); Fossen (2011)
    sec. 9.3 (first-order actuator model).
    """

    name = "thruster_lag"
    summary = "first-order lag of the thrust behind the command"
    source = "Yoerger et al. (1990); Fossen (2011) sec. 9.3"
    parameters = {"time_constant": "s"}
    hyper = ("time_constant",)
    #: search range of the time constant [s]: from a tenth of a sample to 2 s, geometric
    GRID_MAX = 2.0
    GRID_LOG = True
    RESOLVE = 0.5

    def signature(self, data, dof):
        return "a force that follows the steps of the input and decays"

    def offset(self, data, dof, tc):
        tau = data.tau[:, dof]
        _, integral = lagged_held(data.t, tau, tc)
        cum = np.concatenate([[0.0], np.cumsum(integral)])
        lagged = (cum[data.i1] - cum[data.i0]) / data.T
        return lagged - data.mean_held(tau)

    def force_law(self, params, dof):
        """Simulation force law: Delta F = tau_l - tau with T_l dtau_l/dt = tau - tau_l, exact
        for held inputs, T_l [s], tau [N, N m], in DOF ``dof`` (all six for None); returns
        f(time, eta, nu, inputs) -> (6,) [N, N m]."""
        tc = params["time_constant"]
        e = np.ones(6) if dof is None else _unit_vec(dof)
        state = {"k": 0, "y": None}

        def f(time, eta, nu, inputs):
            t, taus = _held_history(inputs)
            k = int(np.clip(np.searchsorted(t, time, side="right") - 1, 0, t.size - 1))
            if state["y"] is None or k < state["k"]:
                state["k"], state["y"] = 0, np.array(taus[0], float)
            while state["k"] < k:  # advance the lag state sample by sample (exact, held)
                j = state["k"]
                a = math.exp(-(t[j + 1] - t[j]) / tc)
                state["y"] = taus[j] + (state["y"] - taus[j]) * a
                state["k"] = j + 1
            u = np.asarray(inputs["tau"], float)
            y = u + (state["y"] - u) * math.exp(-max(time - t[k], 0.0) / tc)
            return (y - u) * e
        return f


class ActuationDelay(_TimedInputEffect):
    r"""A pure delay between the logged command and the force it produces.

    .. math:: \Delta F_i = \tau_i(t - d) - \tau_i(t)

    with d [s] profiled by a one-dimensional search: communication and driver latency, a
    command logged before it is sent. The signature: a force that precedes the response
    by a fixed time at every step of the input.

    Source: Fossen (2011) sec. 9.3 (actuator dynamics and time delays); Yoerger, Cooke &
    Slotine (1990), IEEE JOE 15.
    """

    name = "actuation_delay"
    summary = "pure time delay between command and thrust"
    source = "Fossen (2011) sec. 9.3; Yoerger et al. (1990)"
    parameters = {"delay": "s"}
    hyper = ("delay",)
    GRID_MAX = 1.0
    RESOLVE = 1.0

    def signature(self, data, dof):
        return "a force that precedes the response by a fixed time"

    def offset(self, data, dof, delay):
        tau = data.tau[:, dof]
        a = delayed_integral(data.t, tau, delay, data.t[data.i0])
        b = delayed_integral(data.t, tau, delay, data.t[data.i1])
        return (b - a) / data.T - data.mean_held(tau)

    def force_law(self, params, dof):
        """Simulation force law: Delta F = tau(t - d) - tau(t), d [s], tau [N, N m], in DOF
        ``dof`` (all six for None); returns f(time, eta, nu, inputs) -> (6,) [N, N m]."""
        d = params["delay"]
        e = np.ones(6) if dof is None else _unit_vec(dof)

        def f(time, eta, nu, inputs):
            t, taus = _held_history(inputs)
            k = int(np.clip(np.searchsorted(t, time - d, side="right") - 1, 0, t.size - 1))
            return (np.asarray(taus[k], float) - np.asarray(inputs["tau"], float)) * e
        return f


#: The registry: name -> the effect (one frozen instance per effect).
EFFECTS = {e.name: e for e in (TetherDrag(), ThrustAsymmetry(), MomentumDrag(),
                               BuoyancyOffset(), Current(), LinearDrag(), Deadband(),
                               AddedMassError(), ThrustEffectiveness(), ThrusterLag(),
                               ActuationDelay())}


def get_effect(name: str) -> Effect:
    try:
        return EFFECTS[name]
    except KeyError:
        raise unknown_name("effect", name, EFFECTS, key="effect") from None


def effect_forces(model) -> list:
    """Force laws of a model's effects (``HydroModel.effects``) for the simulation.

    Native effects (linear drag, dead band, added mass) are already folded into the model's
    matrices and thrusters by :meth:`Effect.apply` and are skipped here.
    """
    out = []
    for k, entry in enumerate(model.effects):
        if not isinstance(entry, Mapping) or "name" not in entry:
            raise InputError("effect entry without a name", key=f"effects[{k}]",
                             value=entry, expected="{name, dof, parameters}")
        eff = get_effect(entry["name"])
        if eff.native:
            continue
        dof, params = _entry(eff, entry, k)
        out.append(eff.force_law(params, dof))
    return out


def _entry(eff, entry, k):
    """(dof or None for "all", parameters) of a model's effect entry number ``k``."""
    raw = entry.get("dof", "surge")
    dof = None if str(raw).lower() == "all" else parse_dof(raw)
    params = entry.get("parameters", {})
    missing = [p for p in eff.parameters if p not in params]
    if missing:
        raise InputError("effect parameter missing", key=f"effects[{k}].parameters",
                         value=missing[0], expected="parameters " + ", ".join(eff.parameters))
    return dof, {p: float(params[p]) for p in eff.parameters}


def effect_window_forces(data: WindowData, model) -> np.ndarray:
    r"""Window means of the forces of a model's (non-native) effects along a log [N, N m],
    shape (m, 6): what a calibrated model already carries, subtracted from its window
    residual so that a diagnosis of that model does not find its effects again (issue 16).

    .. math:: \bar F_{e} = \frac{1}{T}\int_{t_0}^{t_1} \sum_{effects} F(t)\,dt
    """
    out = np.zeros((data.n_windows, 6))
    for k, entry in enumerate(model.effects):
        if not isinstance(entry, dict) or "name" not in entry:
            raise InputError("effect entry without a name", key=f"effects[{k}]",
                             value=entry, expected="{name, dof, parameters}")
        eff = get_effect(entry["name"])
        if eff.native:
            continue
        dof, params = _entry(eff, entry, k)
        for i in (range(6) if dof is None else [dof]):
            out[:, i] += eff.window_force(data, params, i)
    return out


__all__ = ["EFFECTS", "Effect", "effect_forces", "effect_window_forces", "get_effect"]
