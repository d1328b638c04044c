r"""Is an undeclared effect of an independent-simulator log detectable at all? The oracle test
of issue 33's detection benchmark (``benchmarks.diagnose_independent``).

A log can hold an effect too small to be told from what the rest of the model leaves in the
residual; counting it as the diagnosis's miss then measures the draw, not the method. The
oracle asks the diagnosis's own question with the truth known:

- the model is the truth's own numbers (:func:`truth_model`: its added mass, drag, buoyancy
  and thrust map, drawn x U(0.75, 1.25) around the prior's by ``validation.independent``),
  without the undeclared effect, so that the only thing missing from the window residual
  is the effect and the sensor noise (and the calibration's band priors are those the
  diagnosis uses, about the truth);
- the effect's library law is fitted, its coefficient free, with its nuisance columns free
  in the reference and with it (the test of :func:`stripcoef.diagnose.select._judge`), and
  its likelihood ratio counted on the effective number of windows
  (:func:`stripcoef.diagnose.evidence.step_test`; Bretherton et al. 1999, eq. 31);
- it is *detectable* when that test rejects at the level of the first step of Holm's
  procedure over the DOF's applicable candidates, :math:`\alpha / m`
  (:func:`stripcoef.diagnose.evidence.family_level`; Holm 1979), the evidence gate a
  one-DOF diagnosis applies. No threshold of the diagnosis is changed by it.

Beside it, on the prior the diagnosis is given, the truth's force (the effect at its true
strength, fixed) against the same reference: how much of the residual the prior leaves the
true force explains (``prior_p``), and the ratio of the part of the true force the
reference's columns cannot take up to the reference's residual noise (``prior_snr``,
``truth_snr``) [-].

Only the effects that the independent simulator adds as a separate force
(:data:`FORCE_EFFECTS`) have a truth model without them; the others change the truth's own
coefficients (a linear drag, an added mass, a thrust map) and are not tested here.

Depends on: stripcoef (the diagnosis's fit, selection and evidence), validation.independent.
"""

from __future__ import annotations

import copy

import numpy as np

from stripcoef.conventions import parse_dof
from stripcoef.diagnose.evidence import family_level, step_test
from stripcoef.diagnose.fit import _Config, _evaluate, _Nuisance
from stripcoef.diagnose.heldout import split
from stripcoef.diagnose.select import _dof_calibration, _Fixed, _judge, select_dofs
from stripcoef.diagnose.cross import moving_dofs
from stripcoef.diagnose.settings import DEFAULT_WINDOW, VALIDATION_FRACTION, DiagnoseSettings
from stripcoef.effects.laws import EFFECTS, get_effect
from stripcoef.effects.windows import window_data
from stripcoef.model import HydroModel
from validation.independent import GRAVITY, STRENGTHS

#: The undeclared effects ``validation.independent`` applies as a force of their own (the
#: truth's coefficients untouched), so that the truth's model without them exists.
FORCE_EFFECTS = ("tether_drag", "momentum_drag")


def truth_model(prior: HydroModel, truth) -> HydroModel:
    """The truth of ``validation.independent`` (a :class:`~validation.independent.Truth`) as
    a model: the prior's geometry with the truth's added mass, linear and quadratic damping,
    buoyancy (its displaced volume) and thrust map (each branch's coefficient, efficiency
    folded in, and dead band), without the undeclared effect."""
    d = copy.deepcopy(prior.to_dict())
    d["added_mass"] = np.asarray(truth.m_a, float).tolist()
    d["linear_damping"] = np.asarray(truth.d_l, float).tolist()
    d["quadratic_damping"] = np.asarray(truth.d_q, float).tolist()
    d["volume"] = float(truth.buoyancy) / (float(d["density"]) * GRAVITY)
    for t, p in zip(truth.thrusters, d["thrusters"]):
        p["ct_forward"], p["ct_backward"] = float(t["ct_forward"]), float(t["ct_backward"])
        p["eta_forward"] = p["eta_backward"] = 1.0
        p["deadband"] = float(t["deadband"])
    return HydroModel.from_dict(d)


def _test(data, dof: int, effect: str, strength: float, settings) -> dict:
    """The effect's test on window data ``data`` (module docstring): the free fit judged
    (:func:`~stripcoef.diagnose.select._judge`), the fixed true force's likelihood ratio,
    and the share of the true force beyond the reference's columns over its noise."""
    excited = select_dofs(data)[0]
    cal, _ = _dof_calibration(data, dof, settings, excited, moving_dofs(data))
    cfg = _Config(data, dof, cal, [], settings=settings)
    eff = get_effect(effect)
    ref = _evaluate(cfg.with_terms([(_Nuisance(eff), None)])
                    if eff.nuisance(data, dof) is not None else cfg)
    trial = cfg.with_terms([(eff, None)])
    free = _evaluate(trial)
    judged = _judge(eff, trial, free, ref, data, dof, list(cal.names), cal.sd, settings)
    fixed_term = _Fixed(eff, None, [float(strength)])
    fixed = _evaluate(cfg.with_terms([(fixed_term, None)]))
    force = fixed_term.design(data, dof)[0]
    h = ref["full"]["H"]
    beyond = force - h @ np.linalg.lstsq(h, force, rcond=None)[0] if h.shape[1] else force
    m = sum(bool(get_effect(n).applicable(data, dof)[0]) for n in EFFECTS)
    level = family_level(1) / max(m, 1)
    return {"estimate": float(eff.magnitude(judged["parameters"])),
            "std": float(next(iter(judged["std"].values()), np.nan)), "z": float(judged["z"]),
            "held_out_gain": float(judged["held_out_gain"]),
            "statistic": float(judged["evidence"]["statistic"]),
            "p_value": float(judged["evidence"]["p_value"]), "level": float(level),
            "candidates": int(m), "significant": bool(judged["significant"]),
            "fixed_p_value": float(step_test(ref, fixed, 1)["p_value"]),
            "snr": float(np.sqrt(np.mean(beyond ** 2)) / ref["full"]["sigma"]),
            "force_rms": float(np.sqrt(np.mean(force ** 2))),
            "noise": float(ref["full"]["sigma"])}


def oracle(log, prior: HydroModel, truth, *, settings=None) -> dict | None:
    """The oracle test of ``log``'s effect (module docstring), None for an effect outside
    :data:`FORCE_EFFECTS`: ``detectable`` (the test on the truth's model passes the evidence
    gate), ``truth`` (that test: ``estimate``, its ``std``, ``z``, ``held_out_gain``, ``statistic``,
    ``p_value``, ``level``, ``snr``, ...) and ``prior`` (the same on the prior, with
    ``fixed_p_value``: the true force fixed), on the part of the log a diagnosis fits
    (its first ``1 - VALIDATION_FRACTION``) in windows of ``DEFAULT_WINDOW``."""
    if truth.effect not in FORCE_EFFECTS:
        return None
    settings = DiagnoseSettings() if settings is None else settings
    dof = parse_dof(STRENGTHS[truth.effect][0])
    train, _ = split(log, VALIDATION_FRACTION, key="validation")
    out = {}
    for name, model in (("truth", truth_model(prior, truth)), ("prior", prior)):
        data = window_data(train, model, window=DEFAULT_WINDOW)
        out[name] = _test(data, dof, truth.effect, truth.strength, settings)
    out["detectable"] = bool(out["truth"]["p_value"] <= out["truth"]["level"])
    return out
