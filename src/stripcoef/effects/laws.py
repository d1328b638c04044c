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

The effects live by family: :mod:`.base` (the :class:`Effect` interface),
:mod:`.hydrodynamic`, :mod:`.thrust`, :mod:`.timing`; this module holds the registry and
what reads a model's effects.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from stripcoef.conventions import DOF, parse_dof
from stripcoef.errors import InputError, unknown_name
from stripcoef.effects.base import Effect
from stripcoef.effects.hydrodynamic import (AddedMassError, BuoyancyOffset, Current, LinearDrag,
                                           MomentumDrag, TetherDrag)
from stripcoef.effects.thrust import (Deadband, ThrustAsymmetry, ThrustEffectiveness,
                                     ThrusterGain)
from stripcoef.effects.timing import ActuationDelay, ThrusterLag
# the window data effects are fitted to, re-exported for the callers of this module
from stripcoef.effects.windows import (WindowData, coefficient_column,  # noqa: F401
                                       coriolis_times_velocity, damping_times_velocity,
                                       window_data)

#: The registry: name -> the effect (one frozen instance per effect).
EFFECTS = {e.name: e for e in (TetherDrag(), ThrustAsymmetry(), MomentumDrag(),
                               BuoyancyOffset(), Current(), LinearDrag(), Deadband(),
                               AddedMassError(), ThrustEffectiveness(), ThrusterLag(),
                               ActuationDelay(), ThrusterGain())}


def get_effect(name: str) -> Effect:
    try:
        return EFFECTS[name]
    except KeyError:
        raise unknown_name("effect", name, EFFECTS, key="effect") from None


def _dof_index(raw) -> int:
    """An effect entry's DOF: an index 0-5 (a model file may give one) or a DOF name."""
    if isinstance(raw, int) and not isinstance(raw, bool) and 0 <= raw < 6:
        return raw
    return parse_dof(raw)


def check_effect_entries(entries, *, file: str | None = None) -> None:
    """A model file's ``effects`` checked against the registry, like a vehicle file's keys.

    Each entry (``{name, dof, parameters}``, their types already checked by
    :func:`stripcoef.modelfile.check_model_parts`) must name an effect of :data:`EFFECTS`,
    a degree of freedom the effect acts in (:attr:`Effect.dofs`; ``all`` only for an effect
    whose force law acts in all six, :attr:`Effect.all_dofs`), and exactly the effect's
    parameters (:attr:`Effect.parameters`) with values its law admits
    (:meth:`Effect.plausible`, said in words by :attr:`Effect.admits`). Each error names the
    file, the key path (``effects[0].parameters.c_t``), the value and what was expected.
    """
    for k, entry in enumerate(entries):
        path = f"effects[{k}]"
        name = entry.get("name")
        if name not in EFFECTS:
            raise unknown_name("effect", name, EFFECTS, file=file, key=f"{path}.name")
        eff = EFFECTS[name]
        raw = entry.get("dof", "surge")
        acts = ", ".join(DOF[i] for i in eff.dofs) + (" or all" if eff.all_dofs else "")
        if str(raw).strip().lower() == "all":
            if not eff.all_dofs:
                raise InputError(f"effect {name} does not act in all degrees of freedom",
                                 file=file, key=f"{path}.dof", value=raw,
                                 expected="one of " + acts)
        elif _dof_index(raw) not in eff.dofs:
            raise InputError(f"effect {name} does not act in this degree of freedom",
                             file=file, key=f"{path}.dof", value=raw, expected="one of " + acts)
        params = entry.get("parameters") or {}
        expected = "parameters " + ", ".join(f"{p} [{u}]" for p, u in eff.parameters.items())
        for p in params:
            if p not in eff.parameters:
                raise InputError(f"unknown parameter of effect {name}", file=file,
                                 key=f"{path}.parameters.{p}", value=p, expected=expected)
        missing = [p for p in eff.parameters if p not in params]
        if missing:
            raise InputError(f"parameter of effect {name} missing", file=file,
                             key=f"{path}.parameters.{missing[0]}", expected=expected)
        values = {p: float(params[p]) for p in eff.parameters}
        if not eff.plausible(values):
            raise InputError(f"parameters of effect {name} out of range", file=file,
                             key=f"{path}.parameters", value=values, expected=eff.admits)


def effect_forces(model) -> list:
    """Force laws of a model's effects (``HydroModel.effects``) for the simulation.

    Native effects (linear drag, dead band, added mass) are already folded into the model's
    matrices and thrusters by :meth:`Effect.apply` and are skipped here.
    """
    return [law for _, law in effect_force_terms(model)]


def effect_force_terms(model) -> list:
    """(effect, force law) of each of a model's effects that is not native
    (:func:`effect_forces`, with the effect, e.g. to ask whether it is :attr:`Effect.held`)."""
    return [(eff, eff.force_law(params, dof)) for eff, dof, params in effect_entries(model)]


def effect_entries(model) -> list:
    """(effect, dof or None for "all", parameters) of each of a model's effects that is not
    native, in the model's order (:func:`effect_force_terms` makes their force laws)."""
    out = []
    for k, entry in enumerate(model.effects):
        if not isinstance(entry, Mapping) or "name" not in entry:
            raise InputError("effect entry without a name", key=f"effects[{k}]",
                             value=entry, expected="{name, dof, parameters}")
        eff = get_effect(entry["name"])
        if eff.native:
            continue
        dof, params = _entry(eff, entry, k)
        out.append((eff, dof, params))
    return out


def _entry(eff, entry, k):
    """(dof or None for "all", parameters) of a model's effect entry number ``k``."""
    raw = entry.get("dof", "surge")
    dof = None if str(raw).lower() == "all" else _dof_index(raw)
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


def model_window_data(log, model, *, window: float) -> WindowData:
    """The window data of ``model`` on ``log`` (:func:`stripcoef.effects.windows.window_data`)
    with the forces of the model's effects taken out of its residual
    (:func:`effect_window_forces`): a calibrated model's effects are part of its prediction."""
    data = window_data(log, model, window=window)
    if model.effects:
        data.e0 = data.e0 - effect_window_forces(data, model)
    return data

__all__ = ["EFFECTS", "Effect", "check_effect_entries", "effect_forces", "effect_window_forces",
           "get_effect", "model_window_data"]
