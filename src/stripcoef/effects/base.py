r"""The base of the effects library: :class:`Effect`, the interface every effect
implements (its physics, parameters, regressors over log windows and force law), see
:mod:`stripcoef.effects.laws`.

Depends on: effects.windows, conventions, errors.
"""

from __future__ import annotations

import math
from dataclasses import FrozenInstanceError

import numpy as np

from stripcoef.conventions import DOF
from stripcoef.effects.windows import (WindowData, coefficient_column)

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

    def nuisance_lower(self, data, dof) -> np.ndarray:
        r"""Lower bounds of the nuisance parameters: a released prior coefficient (``M``,
        ``D_L``, ``D_Q``) keeps its total at or above zero, the physical bound the
        calibration's own columns have (no negative drag or added mass), so the release is
        a bounded least-squares fit (Stark & Parker 1995, BVLS) instead of a free one whose
        impossible value then rejects the effect (issue 33: a current of 0.095 m/s, truth
        0.108, 49 % held-out gain, rejected for a released D_L of -0.86 N s/m that the log
        cannot determine); -inf for any other nuisance parameter [units of each]."""
        nuis = self.nuisance(data, dof)
        if nuis is None:
            return np.zeros(0)
        m = data.model
        prior = {"M": m.added_mass, "D_L": m.linear_damping, "D_Q": m.quadratic_damping}
        return np.array([-abs(float(prior[n][dof, dof])) if n in prior else -np.inf
                         for n in self.nuisance_names[:nuis.shape[1]]])

    def nuisance_sd(self, data, dof) -> np.ndarray:
        """Prior standard deviations of the nuisance parameters (inf = free)."""
        nuis = self.nuisance(data, dof)
        return np.full(0 if nuis is None else nuis.shape[1], np.inf)

    def prior_sd(self, data, dof, hyper=None, *, ncols=None) -> np.ndarray:
        """Prior standard deviations of all columns of :meth:`design` (inf = free);
        ``ncols``: their number, when the caller has the design already."""
        if ncols is None:
            ncols = self.design(data, dof, hyper)[1].shape[1]
        sd = self.nuisance_sd(data, dof)
        return np.concatenate([sd, np.full(ncols - sd.size, np.inf)])

    def lower_bounds(self, data, dof, hyper=None, *, ncols=None) -> np.ndarray:
        """Lower bounds of all columns of :meth:`design`: :meth:`nuisance_lower` for the
        nuisance columns, none (-inf) for the effect's own (an effect with bounds of its own
        overrides this and keeps the nuisance bounds first); ``ncols`` as in
        :meth:`prior_sd`."""
        if ncols is None:
            ncols = self.design(data, dof, hyper)[1].shape[1]
        low = self.nuisance_lower(data, dof)
        return np.concatenate([low, np.full(ncols - low.size, -np.inf)])

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

    #: The parameter values :meth:`plausible` admits, in words (a model file's error says it)
    admits = "finite parameters"
    #: The force law acts in all six DOFs at once (a model file's ``dof: all``)
    all_dofs = False

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
        input (:attr:`input_driven`) or by the trapezoidal rule. A held effect with a law for
        many samples at once (``batch_force_law``, the same numbers) evaluates it at all
        samples in one call."""
        names = [th.name for th in data.model.thrusters]
        if self.held and hasattr(self, "batch_force_law") and len(set(names)) == len(names):
            law = self.batch_force_law(params, dof, {
                "t": data.t, "tau": data.tau, "allocation": data.alloc,
                "thrust": data.thrust if names else None})
            f = np.array(law(None, np.arange(data.t.size), None)[:, dof], float)
            return data.mean_held(f) if self.input_driven else data.mean(f)
        law = self.force_law(params, dof)
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
    #: the force law depends on nothing but the inputs of the sample being held (not on the
    #: time within the interval, nor on the state): constant between two samples, so a
    #: free simulation evaluates it once per sample (stripcoef.diagnose.freesim)
    held = False

    def implausible(self, params: dict, data=None, dof=None) -> str:
        """Why the parameters are physically impossible for this log ('' if they are not)."""
        return "" if self.plausible(params) else "implausible parameters"


def _unit_vec(dof):
    e = np.zeros(6)
    e[dof] = 1.0
    return e

