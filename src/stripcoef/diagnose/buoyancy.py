r"""A buoyancy change found in heave as one change of the buoyancy B, acting in every DOF
through the restoring force (issue 33; option ``buoyancy_carry``, off by default).

The library's buoyancy offset (:class:`~stripcoef.effects.hydrodynamic.BuoyancyOffset`) is a
constant force in the DOF it is found in: in heave, :math:`F_3 = b` [N], the weight-buoyancy
error W - B projected on the body z axis "for small roll and pitch" (Indiveri 1998,
eq. 4.15). A real vehicle's weight is weighed, its displaced volume is not (trim, foam,
flooded volumes), so what the heave balance finds is a change of B, and a change of B acts
in every DOF through the restoring force of Fossen 2011, eq. 4.6 (z down):

.. math::
    \Delta g(\eta) = -\Delta B\,\big[-\sin\theta,\ \cos\theta\sin\phi,\ \cos\theta\cos\phi,\
    (r_b \times k)\big], \qquad k = [-\sin\theta,\ \cos\theta\sin\phi,\ \cos\theta\cos\phi]

(:func:`stripcoef.model.restoring_from_down`; :math:`r_b` the prior's centre of buoyancy,
the offset has none of its own): surge feels :math:`-\Delta B\sin\theta` as the vehicle
pitches, sway :math:`\Delta B\cos\theta\sin\phi` as it rolls, roll and pitch the moment of
:math:`\Delta B` about the centre of buoyancy. Kept as a constant in heave alone, the change
is a force in surge that no candidate there holds, and a drag or tether law takes it
(issue 33: ``benchmarks/data/named33f_trace.md`` (c), a BlueROV2 linear drag;
``benchmarks/data/fresh33f_compare.md`` sec. 3.7, a VideoRay clean log naming a surge
tether that the truth's buoyancy in the prior removes).

With the option:

- **written as B**: the heave offset's step is written as the change of B,
  :math:`\Delta B = -b` (:class:`BuoyancyChange`, a native effect: the model's ``volume``
  moves by :math:`\Delta B / (\rho g)`), so the written model's heave force is
  :math:`-\Delta B\cos\theta\cos\phi = b\cos\theta\cos\phi`, the fitted constant to
  :math:`1 - \cos\theta\cos\phi` of it (0.9 % at the 7.6 deg RMS pitch of the BlueROV2 log
  of the trace), and the same change acts in every other DOF of the written model and its
  validation's free simulations;
- **carried**: in a whole-log diagnosis heave is diagnosed first, and the other DOFs are
  diagnosed on the prior with B + Delta B (:func:`carried`: their window residuals take the
  change's restoring force as a known force, Fossen 2011 eq. 4.6), so surge and sway need no
  effect of their own for it. A one-DOF diagnosis of another DOF does not fit heave, so it
  carries nothing.

No constant is added: :math:`\Delta B` is the heave step's own fitted value.

Depends on: effects (hydrodynamic).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from stripcoef.effects.hydrodynamic import BuoyancyOffset

#: The DOF whose buoyancy offset is the change of B (heave, index 2)
HEAVE = 2
#: The library's name of the offset (:class:`~stripcoef.effects.hydrodynamic.BuoyancyOffset`)
OFFSET = BuoyancyOffset.name


class BuoyancyChange(BuoyancyOffset):
    r"""The heave buoyancy offset (:class:`~stripcoef.effects.hydrodynamic.BuoyancyOffset`,
    the same fit: :math:`F_3 = b` [N], positive down) written as one change of the buoyancy,
    :math:`\Delta B = -b` [N] (module docstring; Fossen 2011, eq. 4.6): the model's displaced
    volume changes by :math:`\Delta B / (\rho g)` [m^3] and its restoring force carries the
    change into every DOF. Native (nothing in the model's ``effects``; the provenance records
    ``b``). Used only with the option ``buoyancy_carry``, so not in the registry."""

    native = True

    def apply(self, model, dof, params, std=None):
        """The model with its volume changed by :math:`-b / (\\rho g)` [m^3] for heave's
        ``b`` [N] (a new model); in another DOF the offset's own entry
        (:meth:`BuoyancyOffset.apply`)."""
        if dof != HEAVE:
            return super().apply(model, dof, params, std)
        return with_buoyancy_change(model, -float(params["b"]))


#: The one instance of :class:`BuoyancyChange` (effects are immutable specs)
BUOYANCY_CHANGE = BuoyancyChange()


def with_buoyancy_change(model, delta_b: float):
    """``model`` with its buoyancy B = rho g V changed by ``delta_b`` [N] (a new model; the
    volume moves by ``delta_b / (rho g)`` [m^3], the centre of buoyancy stays)."""
    return replace(model, volume=float(model.volume)
                   + float(delta_b) / (float(model.density) * float(model.gravity)))


def heave_change(result) -> float | None:
    """:math:`\\Delta B = -b` [N] of heave's selected buoyancy offset in ``result`` (its
    :class:`~stripcoef.diagnose.result.DofResult`); None without one."""
    for s in result.steps:
        if s.effect == OFFSET and not s.not_determined:
            b = (s.final_parameters or s.parameters).get("b")
            return None if b is None else -float(b)
    return None


def written_as_change(fit):
    """Heave's :class:`~stripcoef.diagnose.result.DofFit` with its buoyancy offset's term
    written as :data:`BUOYANCY_CHANGE` (the same columns and values; a new fit), or ``fit``
    unchanged without one."""
    cfg = fit.config
    if not any(eff.name == OFFSET and not isinstance(eff, BuoyancyChange)
               for eff, _ in cfg.terms):
        return fit
    terms = [(BUOYANCY_CHANGE, h) if eff.name == OFFSET else (eff, h) for eff, h in cfg.terms]
    return replace(fit, config=cfg.with_terms(terms))


def carried(data, delta_b: float):
    r"""The window data ``data`` of the other DOFs with the buoyancy change ``delta_b`` [N] in
    the prior (a new :class:`~stripcoef.effects.windows.WindowData`): its model's B moves by
    ``delta_b`` (:func:`with_buoyancy_change`) and each DOF's window residual by the window
    mean of the change's restoring force, :math:`e' = e + \overline{g'(\eta) - g(\eta)}`
    (the residual :math:`e = M\dot\nu + \overline{C\nu + D\nu + g(\eta)} - \bar\tau`,
    :func:`stripcoef.effects.windows.prior_residual`); heave's column stays, its change being
    the fitted offset itself."""
    model = data.model
    changed = with_buoyancy_change(model, delta_b)
    eta = data.eta.T
    dg = (changed.restoring(eta) - model.restoring(eta)).T          # (n, 6) [N, N m]
    e0 = np.array(data.e0, float) + data.mean(dg)
    e0[:, HEAVE] = data.e0[:, HEAVE]
    return replace(data, model=changed, e0=e0)


def order(dofs) -> list:
    """The diagnosed DOFs with heave first (its buoyancy change is carried to the others)."""
    return sorted(dofs, key=lambda i: i != HEAVE)
