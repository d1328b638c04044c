r"""Whole-log: the thrusters' lag and delay compared over every DOF they drive (issue 33,
whole-log failure kind (2)).

A first-order thruster lag and a pure actuation delay both hold back the applied force; in
one DOF over a short log their window regressors are nearly collinear, and each DOF's
selection (:func:`~stripcoef.diagnose.select.diagnose_dof`, whose competing effects are
compared by :mod:`.compare`) may name either. Both are properties of the thrusters, one value
for all of them (:func:`~stripcoef.diagnose.calibrate.share_timing`), so a whole-log
diagnosis compares them as :mod:`.compare` does, in the comprehensive model that holds both
(Atkinson 1970; Davidson & MacKinnon 1981), but over every diagnosed DOF the thrusters drive
at once, a multiresponse model (Seber & Wild 1989, ch. 11):

- :math:`S_L`, :math:`S_D`, :math:`S_{LD}`: the joint cost
  (:func:`~stripcoef.diagnose.calibrate._joint_cost`: each DOF's whitened MAP residual, its
  own linear parameters profiled, at its selected fit's noise level) with the lag alone, the
  delay alone and both, each nonlinear parameter profiled jointly over the DOFs
  (:func:`~stripcoef.diagnose.fit.grid_minimum`; for both, the delay with the lag at its
  value alone, then the lag with that delay);
- "the lag is not needed": :math:`\Lambda_L = S_D - S_{LD}`, "the delay is not needed":
  :math:`\Lambda_D = S_L - S_{LD}`, each :math:`\chi^2_1` (Wilks 1938), Holm-adjusted
  (Holm 1979) at :data:`~stripcoef.diagnose.compare.ALPHA`;
- one needed and not the other: that one, in every DOF the thrusters drive, the other
  removed (the selection's pick replaced where it was the other); both: both; neither: the
  log cannot tell them apart and the selection's choice stays.

Every DOF's step records the comparison (``comparison``). The validation then keeps or
removes the shared timing as one change (:func:`stripcoef.diagnose.validate.partners`).

Depends on: effects, diagnose.fit, diagnose.compare, diagnose.calibrate.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from scipy.stats import chi2

from stripcoef.conventions import parse_dof
from stripcoef.diagnose.calibrate import _with_value, joint_profile
from stripcoef.diagnose.compare import ALPHA, holm
from stripcoef.diagnose.fit import refit
from stripcoef.effects.laws import get_effect

LAG, DELAY = "thruster_lag", "actuation_delay"


def _without(cfg, name):
    return cfg.with_terms([(e, h) for e, h in cfg.terms if e.name != name])


def compare_timing(per: dict, fits: dict) -> tuple[dict, dict, dict | None]:
    """``(per, fits, record)``: the thrusters' lag and delay of a whole-log diagnosis
    compared over the DOFs they drive (module docstring), the steps and fits of those DOFs
    made to hold the outcome; ``record`` None when no timing effect was selected or fewer
    than two DOFs are driven."""
    lag, delay = get_effect(LAG), get_effect(DELAY)
    have = {n: [d for d, f in fits.items() if any(e.name == n for e, _ in f.config.terms)]
            for n in (LAG, DELAY)}
    if not (have[LAG] or have[DELAY]):
        return per, fits, None
    targets = [d for d in fits if lag.applicable(fits[d].config.data, parse_dof(d))[0]
               and delay.applicable(fits[d].config.data, parse_dof(d))[0]]
    if len(targets) < 2:
        return per, fits, None
    base = {d: _without(_without(fits[d].config, LAG), DELAY) for d in targets}
    sigmas = {d: float(fits[d].evaluation["full"]["sigma"]) for d in targets}
    d0 = targets[0]
    t_l, s_l, sd_l = joint_profile(lag, base, sigmas, d0)
    t_d, s_d, sd_d = joint_profile(delay, base, sigmas, d0)
    # both: one parameter profiled with the other at its value alone, then the other with
    # it, in both orders (the cost is not separable); the lower of the two
    t_d2, _, sd_d2 = joint_profile(delay, {d: _with_value(c, lag, t_l) for d, c in base.items()},
                              sigmas, d0)
    t_l2, s_ld, sd_l2 = joint_profile(lag, {d: _with_value(c, delay, t_d2)
                                       for d, c in base.items()}, sigmas, d0)
    t_l3, _, sd_l3 = joint_profile(lag, {d: _with_value(c, delay, t_d) for d, c in base.items()},
                              sigmas, d0)
    t_d3, s_ld3, sd_d3 = joint_profile(delay, {d: _with_value(c, lag, t_l3)
                                          for d, c in base.items()}, sigmas, d0)
    if s_ld3 < s_ld:
        t_l2, t_d2, sd_l2, sd_d2, s_ld = t_l3, t_d3, sd_l3, sd_d3, s_ld3
    s_ld = min(s_ld, s_l, s_d)
    stats = {LAG: max(s_d - s_ld, 0.0), DELAY: max(s_l - s_ld, 0.0)}
    p = {n: float(chi2.sf(v, 1)) for n, v in stats.items()}
    adjusted = dict(zip(p, holm(list(p.values()))))
    needed = {n: adjusted[n] <= ALPHA for n in p}
    if needed[LAG] and needed[DELAY]:
        keep = {LAG: (t_l2, sd_l2), DELAY: (t_d2, sd_d2)}
        outcome = "both needed"
    elif needed[LAG]:
        keep, outcome = {LAG: (t_l, sd_l)}, "the lag needed, the delay not"
    elif needed[DELAY]:
        keep, outcome = {DELAY: (t_d, sd_d)}, "the delay needed, the lag not"
    else:
        keep, outcome = None, "neither needed beside the other: the selection's choice stays"
    record = {"method": "likelihood ratio of the lag and of the delay against the model "
                        "holding both, jointly over the DOFs the thrusters drive (Atkinson "
                        "1970; Davidson & MacKinnon 1981; Seber & Wild 1989 ch. 11), Holm "
                        "1979", "alpha": ALPHA, "dofs": list(targets),
              "costs": {"lag": s_l, "delay": s_d, "both": s_ld},
              "values": {"lag": t_l, "delay": t_d, "both": {"lag": t_l2, "delay": t_d2}},
              "tests": {n: {"statistic": stats[n], "dof": 1, "p_value": p[n],
                            "adjusted": adjusted[n]} for n in p},
              "selected_in": {n: list(v) for n, v in have.items()}, "outcome": outcome}
    if keep is None:        # recorded on the selection's timing steps
        per = {d: replace(r, steps=tuple(
            replace(s, comparison={**(s.comparison or {}), "timing": record})
            if s.effect in (LAG, DELAY) else s for s in r.steps)) for d, r in per.items()}
        return per, fits, record
    return (*_rewritten(per, fits, base, keep, have, record), record)


def _rewritten(per, fits, base, keep, have, record):
    """``(per, fits)`` with every DOF of ``base`` holding exactly the timing effects of
    ``keep`` (name -> (value, sd)): its steps of a removed effect replaced in place by the
    kept one (or dropped when it has it already), the kept ones added where missing."""
    per, fits = dict(per), dict(fits)
    template = next(s for d in per for s in per[d].steps if s.effect in (LAG, DELAY))
    for d, cfg in base.items():
        for name, (value, _) in keep.items():
            cfg = _with_value(cfg, get_effect(name), value)
        before, ev = refit(fits, d, cfg)
        steps, done = [], set()
        for s in per[d].steps:
            if s.effect not in (LAG, DELAY):
                steps.append(s)
                continue
            name = s.effect if s.effect in keep else next(
                (n for n in keep if n not in done and not any(t.effect == n
                                                              for t in per[d].steps)), None)
            if name is None or name in done:
                continue
            steps.append(_step(s, name, keep[name], d, record, before, ev))
            done.add(name)
        for name in keep:
            if name not in done:
                steps.append(_step(replace(template, dof=d), name, keep[name], d, record,
                                   before, ev, added=True))
        per[d] = replace(per[d], steps=tuple(steps), final_error=float(ev["error"]),
                         final_held_out_error=float(ev["held_out_error"]))
    return per, fits


def _step(step, name, value_sd, d, record, before, ev, added=False):
    """``step`` made the step of timing effect ``name`` at its jointly fitted value."""
    eff = get_effect(name)
    value, sd = value_sd
    key = eff.hyper[0]
    changed = added or step.effect != name
    out = replace(step, effect=name, dof=d, parameters={key: value}, std={key: sd},
                  units=dict(eff.parameters), source=eff.source,
                  magnitude=float(eff.magnitude({key: value})),
                  final_parameters={key: value},
                  comparison={**(step.comparison or {}), "timing": record})
    if changed:
        n = ev["full"]["resid"].size
        out = replace(out, released={}, mimics=None, band_excess=None,
                      signature=f"the thrusters' {key} [s], chosen by the comparison of lag "
                                f"and delay over {', '.join(record['dofs'])} "
                                f"({record['outcome']})",
                      error_before=before["error"], error_after=float(ev["error"]),
                      held_out_error_before=before["held_out_error"],
                      held_out_error_after=float(ev["held_out_error"]),
                      held_out_gain=float(1.0 - ev["held_out_error"]
                                          / max(before["held_out_error"], 1e-300)),
                      delta_bic=float(ev["bic"] + math.log(n) - before["bic"]),
                      z=float(value / sd) if sd and np.isfinite(sd) and sd > 0
                      else float("nan"), rejected_because=(), alternatives=())
    return out
