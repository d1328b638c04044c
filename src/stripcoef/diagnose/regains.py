r"""The thrusters' gains fitted again beside a water current the diagnosis found (issue 33;
option :attr:`~stripcoef.diagnose.settings.DiagnoseSettings.gains_beside_current`).

A whole-log diagnosis fits the per-thruster gains (:mod:`.gains`) first, on the prior's
window residual, before any effect is selected. A water current acts in every DOF through
the relative velocity :math:`\nu_r = \nu - [R^T V_c; 0]` (Fossen 2011, eq. 10.1), a force
that turns with the heading; the gains' joint fit has no such regressor, so when the log
holds a current the gains take the part of its force that their contrasts can imitate: the
omitted-variable bias of a least-squares fit, :math:`E[\hat a] = a + (G^T G)^{-1} G^T F_c`
for the omitted force :math:`F_c` (Greene 2012, Econometric Analysis, 7th ed., sec. 4.3.2;
Seber & Lee 2003, Linear Regression Analysis, sec. 9.2). The current the DOFs then find is
judged beside gains that already hold part of it (the issue-33 real-style current log,
seed 9: the gained prior simulates the validation part better than the prior in every DOF,
the current added to it worse in five of six, and the held-out part worse than the prior in
every DOF: ``benchmarks/data/real33_trace.md``).

With the option, once the DOFs' shared current :math:`\hat V_c`
(:func:`stripcoef.diagnose.current.share_current`) is known the gains are fitted again on
the window residual of the prior *with that current* (its window forces subtracted, as a
calibrated model's effects are, :func:`stripcoef.effects.laws.effect_window_forces`): one
backfitting cycle of an additive model, each part refitted on the residual of the others
(Hastie & Tibshirani 1990, Generalized Additive Models, sec. 4.4; Breiman & Friedman 1985).
They are validated as before (:func:`stripcoef.diagnose.gains.validated`) against the prior
with the current, and the DOFs are diagnosed again on the prior with the new gains, where
the current is selected, shared and validated like any effect: nothing of the first pass
is written but the gains' values.

**Mode** ``"joint"``. Held at the DOFs' value, the current was itself found beside the
biased gains, and its error stays in the refitted gains. In this mode the current's two
components are parameters of the gains' joint fit, free (no prior) and common to every DOF,
their columns the derivatives of the current's window force at the DOFs' value
(:func:`current_columns`; one Gauss-Newton step of the joint least squares, Seber & Wild
1989, sec. 2.1). They are profiled out of the gains' information with the calibration
(the Schur complement, :func:`stripcoef.diagnose.gains._information`), so the gains'
likelihood-ratio test and the combinations the log determines are those *beside a free
current*: a combination the current's columns span is not identified apart from it
(Rothenberg 1971, Econometrica 39, 577-591, Theorem 1, the rule of
:func:`stripcoef.diagnose.crossscale.refitted_z`) and stays at the prior. And the gains so
fitted are the current's fitted partner (as a DOF's effects are its calibration's,
:func:`stripcoef.diagnose.validate.partners`): they were validated with the current in the
model, so when the second pass's validation removes the current from every DOF (or no DOF
selects it) they are not written without it, and the first pass (its gains, fitted
without a current, and its steps, validated as before) is the diagnosis
(:func:`current_kept`).

Depends on: diagnose.gains, diagnose.settings, effects, model.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from stripcoef.diagnose.gains import fit_thruster_gains, validated
from stripcoef.effects.laws import model_window_data

#: The effect whose force the gains' first fit omitted.
CURRENT = "current"
#: :attr:`~stripcoef.diagnose.settings.DiagnoseSettings.gains_beside_current`'s mode that
#: fits the current free beside the gains (:func:`current_columns`); ``True`` holds it at the
#: value the DOFs found.
JOINT = "joint"


def found_current(per: dict) -> dict | None:
    """The parameters (``current_north``, ``current_east`` [m/s]) of the current a
    diagnosis's DOFs selected (:class:`~stripcoef.diagnose.result.DofResult` per DOF, after
    :func:`~stripcoef.diagnose.current.share_current`: one value in every DOF), or None."""
    for r in per.values():
        for s in r.steps:
            if s.effect == CURRENT:
                p = s.final_parameters or s.parameters
                return {"current_north": float(p["current_north"]),
                        "current_east": float(p["current_east"])}
    return None


def with_found_current(prior, per: dict):
    """``prior`` with the current of :func:`found_current` as an effect of all six DOFs
    (``dof: all``), or None when no DOF selected one."""
    vc = found_current(per)
    if vc is None:
        return None
    return prior.with_effects({"name": CURRENT, "dof": "all", "parameters": vc})


#: Step of the central differences of the current's window force [m/s]: a thousandth of a
#: typical 0.1 m/s pool current; the force is smooth in V_c (quadratic drag and Munk terms
#: of the relative velocity), so the step's truncation error is of order its square.
CURRENT_STEP = 1e-4


def current_columns(data, vc: dict, dofs) -> dict:
    r"""DOF index -> (windows, 2): the derivative of the current's window force
    :math:`\partial \bar F_i / \partial (V_N, V_E)` at ``vc`` [N or N m per m/s]
    (:meth:`~stripcoef.effects.hydrodynamic.Current.window_force`, central differences of
    :data:`CURRENT_STEP`): the current's columns in the gains' joint fit, linearised about
    the value the DOFs found (Gauss-Newton, one step: Seber & Wild 1989, sec. 2.1)."""
    from stripcoef.effects.laws import get_effect

    eff = get_effect(CURRENT)
    keys = ("current_north", "current_east")
    out = {}
    for i in dofs:
        cols = []
        for k in keys:
            up, down = dict(vc), dict(vc)
            up[k] += CURRENT_STEP
            down[k] -= CURRENT_STEP
            cols.append((eff.window_force(data, up, i) - eff.window_force(data, down, i))
                        / (2.0 * CURRENT_STEP))
        out[i] = np.column_stack(cols)
    return out


def current_kept(per: dict, exclude) -> bool:
    """Whether some DOF of ``per`` (:class:`~stripcoef.diagnose.result.DofResult` per DOF)
    selected the current and the validation kept it (not in ``exclude``,
    :func:`~stripcoef.diagnose.validate.validate_changes`' removed changes)."""
    return any(s.effect == CURRENT and not s.not_determined
               and ("effect", d, CURRENT) not in exclude
               for d, r in per.items() for s in r.steps)


def withdrawn(gains, first):
    """The first pass's gains record (``first``, a
    :class:`~stripcoef.diagnose.gains.ThrusterGains` or None) with why the gains fitted
    beside the current (``gains``) were withdrawn (module docstring, mode ``"joint"``)."""
    why = ("; the gains fitted beside the current (" + ", ".join(
        f"{g:.4g}" for g in gains.gains) + ") withdrawn with it: the validation removed "
        "the current they were fitted beside (their fitted partner) or no DOF selected it")
    return None if first is None else replace(first, reason=first.reason + why)


def refit_gains(water, prior, data0, train_log, val_log, dofs, excited, settings, budget):
    """``(gains, model, data)``: the thrusters' gains fitted again on the window residual of
    ``water`` (the prior with the current found) over ``dofs``, validated against ``water``
    (:func:`~stripcoef.diagnose.gains.validated`); ``model`` the prior with them when kept
    (else ``prior``) and ``data`` its window data (``data0``, the prior's, when not kept).
    The gains' record says what they were fitted beside. ``gains`` None when the fit is not
    possible (as :func:`~stripcoef.diagnose.gains.fit_thruster_gains`)."""
    data_c = model_window_data(train_log, water, window=settings.window)
    vc = water.effects[-1]["parameters"]
    shared = None
    if settings.gains_beside_current == JOINT:
        shared = (("current_north", "current_east"), current_columns(data_c, vc, dofs))
    gains = fit_thruster_gains(data_c, dofs, settings, excited=excited, budget=budget,
                               shared=shared)
    if gains is None:
        return None, prior, data0
    gains = validated(gains, val_log, water, dofs, settings.gains_logged_dofs(dofs))
    gains = replace(gains, reason=gains.reason + "; fitted beside the current the DOFs found "
                    f"(north {vc['current_north']:.4g}, east {vc['current_east']:.4g} m/s), "
                    "the DOFs diagnosed again on them")
    if not gains.applied:
        return gains, prior, data0
    model = gains.model(prior)
    return gains, model, model_window_data(train_log, model, window=settings.window)
