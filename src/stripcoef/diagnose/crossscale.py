r"""Whole-log: a thrust scale must be identified apart from the other DOFs' added masses, which
a closed loop's feed-forward puts into the command (issue 33).

A thrust effectiveness (:class:`~stripcoef.effects.thrust.ThrustEffectiveness`) in DOF i
fits :math:`\Delta F_i = (s_i - 1)\,\tau_i`: its column is the applied force itself. A pilot
or autopilot that holds an attitude by feedback linearisation adds the model's own Coriolis
and centripetal wrench to its command, :math:`\tau = C(\nu)\nu + K_p e + K_d \dot e`
(Fossen 2011, ch. 13; the independent simulator's level hold,
``validation.independent.Pilot.coriolis``, adds the vehicle file's). Where the hold is tight
the command is mostly that feed-forward, whose added-mass part is the Munk and cross-coupling
moment, e.g. :math:`(Z_{\dot w} - X_{\dot u})\,u w` in pitch (Fossen 2011, eq. 6.43): linear
in the other DOFs' added masses :math:`M_{jj}`. An error of those added masses (a real
vehicle differs from its file) then leaves a residual :math:`\sum_j \Delta M_{jj}
(C_A[E_{jj}](\nu)\nu)_i` that is nearly proportional to the command, and a scale
:math:`s_i - 1` of the command takes it: the input is correlated with the output through the
controller, so the log cannot tell the two apart (closed-loop identifiability; Ljung 1999,
sec. 13.4). Issue 33, the independent benchmark's seed 29112026 (BlueROV2-like): on
``added_mass_error`` 29113033 (the truth's surge added mass 2.5x the file's) the pitch
command correlates 0.99 with the file's :math:`C(\nu)\nu`, and a whole-log run named a
pitch scale of 1.64 (z 3.0) where the truth's thrusters give +0.026; on ``current``
29113030 a roll scale of 1.65 (z 3.1), the truth's +0.033.

The calibration of DOF i holds those added masses already (``M_<dof>``,
:func:`~stripcoef.diagnose.fit._calibration`), but within their bands: the band is how far
the prior expects the vehicle from its file, and a scale is free. The rule is the one a
translational thrust asymmetry meets beside a buoyancy change
(:meth:`~stripcoef.diagnose.thrusterparts.ThrusterParts.buoyancy_confounded`): a parameter is
locally identified only when the information matrix is non-singular (Rothenberg 1971,
Econometrica 39, 577-591, Theorem 1), i.e. by the part of its column that the other
columns do not span. The scale is refitted with the columns of the other DOFs' added masses
that its calibration holds free beside it (:class:`CrossMassFreeScale`; the same columns,
:func:`~stripcoef.effects.windows.coefficient_column`, released from their bands, as an
effect without a signature releases its own coefficient), and it must still be ``MIN_Z``
standard deviations from zero, the z gate of every step (the profiled scale's curvature,
:func:`~stripcoef.diagnose.fit._hyper_std`). No threshold is new. The DOF's own inertia and
drag stay in their bands: the force balance is homogeneous in them and the scale
(:class:`~stripcoef.effects.thrust.ThrustEffectiveness`), which the scale-or-added-mass
choice (:mod:`.scalechoice`) and the held-out error decide; only the columns a feed-forward
of the other DOFs' motion puts into the command are freed. Whole-log runs only (this module
serves :class:`~stripcoef.diagnose.thrusterparts.ThrusterParts`).

Depends on: diagnose.select, diagnose.settings, effects.
"""

from __future__ import annotations

import math

import numpy as np

from stripcoef.diagnose.select import _evaluate, _own_estimate
from stripcoef.diagnose.settings import MIN_Z
from stripcoef.effects.thrust import ThrustEffectiveness


class CrossMassFreeScale(ThrustEffectiveness):
    r""":class:`~stripcoef.effects.thrust.ThrustEffectiveness` with the columns of the other
    DOFs' added masses :attr:`nuisance_names` (``M_<dof>``, [kg or kg m^2], free: no band,
    no bound) as its nuisance: the identification test of :func:`cross_mass_confounded`
    (module docstring). Never written, not in the registry; made for a set of columns by
    :func:`cross_free_scale` (an effect is a frozen spec)."""


def cross_free_scale(names) -> CrossMassFreeScale:
    """A :class:`CrossMassFreeScale` whose nuisance columns are the added masses ``names``."""
    cls = type("CrossMassFreeScale", (CrossMassFreeScale,), {"nuisance_names": tuple(names)})
    return cls()


def cross_names(cfg) -> tuple:
    """The other DOFs' added masses (``M_<dof>``) that configuration ``cfg``'s calibration
    holds (those the log determines, :func:`~stripcoef.diagnose.fit._identifiability`)."""
    return tuple(n for n in (cfg.cal_names or ()) if n.startswith("M_"))



def refitted_z(cfg, term, *, index: int = 0) -> tuple[float, float] | None:
    """The step of configuration ``cfg`` refitted with its last term replaced by ``term``
    (an ``(effect, nuisance)`` pair: the effect with the columns it frees beside its own):
    the coefficient ``index`` of the effect's own estimate and its distance from zero in
    standard deviations [-] (``inf`` with a zero standard deviation); None when the refit
    is singular or estimates nothing.  The one refit behind the rules that refuse a step
    not identified apart from a confounder (Rothenberg 1971, Theorem 1:
    :func:`cross_mass_confounded`, the thrust asymmetry beside a buoyancy change, the bias
    beside the thrusters' gains)."""
    refit = cfg.with_terms(list(cfg.terms[:-1]) + [term])
    try:
        _, value, sd = _own_estimate(refit, _evaluate(refit))
    except (np.linalg.LinAlgError, ValueError):
        return None
    if not value.size:
        return None
    v, s = float(value[index]), float(sd[index])
    return v, (abs(v) / s if s > 0 else math.inf)

def cross_mass_confounded(trial: dict, dof: int, free: dict) -> str:
    """Why the thrust scale ``trial`` (:func:`~stripcoef.diagnose.select._judge`'s record)
    of DOF ``dof`` is not identified apart from the other DOFs' added masses (module
    docstring): refitted with their columns free beside it, the shortfall ``s - 1`` is under
    ``MIN_Z`` standard deviations from zero; '' when it is not, for another effect, or when
    the calibration holds no such added mass. ``free``: {names: :class:`CrossMassFreeScale`},
    kept by the caller (one instance per set of columns: the fits cache its columns)."""
    cfg = trial.get("_cfg")
    if trial["effect"] != ThrustEffectiveness.name or cfg is None:
        return ""
    names = cross_names(cfg)
    if not names:
        return ""
    eff = free.get(names) or free.setdefault(names, cross_free_scale(names))
    got = refitted_z(cfg, (eff, None), index=-1)
    if got is None or got[1] >= MIN_Z:
        return ""
    value, z = got
    return (f"not identified apart from the other DOFs' added masses ({', '.join(names)}): "
            f"with their columns free beside it the scale is {1.0 + value:.3g}, "
            f"{z:.1f} standard deviations from 1 (< {MIN_Z:g}); a command that carries "
            "their Coriolis force (a feed-forward) is scaled by their error")
