r"""What one DOF cannot determine: an effect whose value depends on the thrusters' gains
(issue 33).

A tether's coefficient :math:`c_t` (:class:`~stripcoef.effects.hydrodynamic.TetherDrag`) is
told from the hull's drag by its dependence on the paid-out length, but a thrust map whose
per-thruster gains :math:`g_k` are off (Fossen 2011, sec. 11.2.1: :math:`\Delta F_i =
\sum_k (g_k - 1) B_{ik} T_k`) leaves a residual that leans on :math:`L u|u|` too. On a
vehicle whose thrusters are vectored (a BlueROV2's four horizontal thrusters each push in
surge, sway and yaw) the gains' *contrasts* carry the sway and yaw commands into surge: the
selection's retest with each thruster's gain free (:mod:`.gainfree`) finds the tether, but
the value fitted with the prior's map is biased by them (independent benchmark, BlueROV2-like
log 28113028: +88 %; ``benchmarks.tether_gain_probe``), and a common thrust scale of the DOF,
the one thrust nuisance one DOF can write, does not remove it (the contrasts are not a
scale). Only a whole-log diagnosis fits the gains over the DOFs and writes them
(:mod:`.gains`; there c_t 0.204 for 0.2026, +0.8 %).

**The rule** (one, whichever map the model writes). A one-DOF tether is *determined* when
it is identified apart from the thrusters' gains beside the thrust map the written model
holds -- the prior's, or the prior's with the gains fitted in the DOF's balance
(:attr:`~stripcoef.diagnose.settings.DiagnoseSettings.dof_gains`, :mod:`.gains`): (a) its
own test passes on that map, and (b) refitted with each thruster's gain free beside it
(:class:`~stripcoef.effects.hydrodynamic.TetherDragGainsFree`), its c_t stays
:data:`~stripcoef.diagnose.settings.MIN_Z` standard deviations from zero: a parameter is
locally identified only by the part of its column that the confounders' columns do not
span (Rothenberg 1971, Econometrica 39, 577-591, Theorem 1), the refit of
:func:`stripcoef.diagnose.crossscale.refitted_z` that every not-identified-apart rule of the
diagnosis uses (:func:`identified_z`). A step that fails (a) or (b) is named, its value not
determined by one DOF, nothing written. On the tests' seeded log
(``validation.synthetic.gains_off_log``: port and starboard at 0.8 and 1.2 of the map, c_t
0.1774) the two maps give the two answers of the one rule: on the prior's map the tether's
test fails and only the retest finds it (not determined, gain-free c_t 0.1995 reported);
with the gains fitted in surge (0.72 and 1.28) it passes there, 9.1 sd from zero with the
gains free, and c_t 0.181 (+2.0 %) is written beside them.

So in a one-DOF diagnosis a step of an effect with a gain-free variant
(:func:`.gainfree.variant`) that the selection found only through the retest with the gains
free (the test with the prior's map failed: the evidence for it is the gain-free fit's) is
*named, its value not determined by one DOF*. Its record also says how far its value moves
when the gains are freed, in standard deviations of the difference: Hausman's specification
test (Hausman 1978, Econometrica 46, 1251-1271, Lemma 2.1: under the hypothesis that the
prior's map is right, the fit with it is efficient and the gain-free fit consistent, and the
variance of their difference is the difference of their variances, :math:`V(\hat c) -
V(\hat a)`, here both at the consistent fit's noise level). Measured and not made a second
trigger (``z > MIN_Z``, :data:`~stripcoef.diagnose.settings.MIN_Z`): on the benchmark's
BlueROV2-like tether logs it also fires where the prior map's value is right (seed
28113027: z 6.4, c_t -1.8 % with the prior's map, -22 % with the gains free), because the
gain-free fit is not unbiased either (docs/performance.md, ``tether33e``).

Such a step stays in the diagnosis (named, with its test's statistics) but nothing is
written for it: the DOF's written fit leaves it out and its kept terms are refitted without
it (:func:`.calibrate.written_fit`), so the written model is the reported one; its record
(:attr:`~stripcoef.diagnose.result.Step.not_determined`) holds the gain-free fit's value and
standard deviation, the prior map's, the test, the reason, and the advice to run the
whole-log diagnosis. The gain-free value is not written either: it is fitted beside gains
that one DOF does not write (the written model would not be the fitted one) and on the
benchmark's BlueROV2-like logs it is within 15 % on 2 of 4 (``tether33d``,
docs/performance.md).

Depends on: effects, diagnose.gainfree, diagnose.fit, diagnose.settings, diagnose.crossscale.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from stripcoef.diagnose.fit import _fit
from stripcoef.diagnose.gainfree import retested, variant
from stripcoef.diagnose.settings import MIN_Z

#: What the text, the JSON and the report say to do about such a step
ADVICE = ("run the whole-log diagnosis (--dof all; diagnose(dof='all')), which fits each "
          "thruster's gain over the DOFs and writes them")


def _own(cfg, eff, hyper):
    """``(params, std)`` of effect ``eff`` fitted last in ``cfg``'s terms (its own linear
    parameters the last columns; :func:`~stripcoef.diagnose.fit._fit`) and the fit."""
    fit = _fit(cfg.with_terms(list(cfg.terms) + [(eff, hyper)]))
    n = eff.design(cfg.data, cfg.dof, hyper)[1].shape[1]
    nuis = eff.nuisance(cfg.data, cfg.dof)
    kn = 0 if nuis is None else nuis.shape[1]
    own = fit["theta"][-(n - kn):]
    cov = fit["cov"][-(n - kn):, -(n - kn):]
    return (eff.to_parameters(own, hyper, fit["theta"][-n:-(n - kn)] if kn else None),
            eff.std_of(own, cov, np.zeros(0)), fit)


def _gain_free_term(step, fit):
    """``(others, effect, hyper, gain-free variant)`` of step ``step`` in the final fit
    ``fit``: the fit's configuration without the step's term, the term, and its variant with
    each thruster's gain free; None for an effect without a one-parameter gain-free variant
    (no DOF: the tether's only; a heave bias is written)."""
    cfg = fit.config
    at = [k for k, (e, _) in enumerate(cfg.terms) if e.name == step.effect]
    if not at:
        return None
    eff, hyper = cfg.terms[at[0]]
    alt = variant(eff)
    if alt is None or len(eff.parameters) != 1:
        return None
    return cfg.with_terms([t for k, t in enumerate(cfg.terms) if k != at[0]]), eff, hyper, alt


def gain_dependence(step, fit) -> dict | None:
    """The test of step ``step`` (a :class:`~stripcoef.diagnose.result.Step`) of the DOF
    whose final fit is ``fit`` (:class:`~stripcoef.diagnose.result.DofFit`) against the
    thrusters' gains (module docstring): its one parameter fitted with the prior's map and
    with each thruster's gain free, the other terms as in the final fit; None for an effect
    without a gain-free variant. Returns ``parameter``, ``prior_map`` / ``prior_map_std``,
    ``gains_free`` / ``gains_free_std`` [the parameter's units], ``z`` (the difference in
    standard deviations of the difference, Hausman 1978) and ``retested``."""
    found = _gain_free_term(step, fit)
    if found is None:
        return None
    others, eff, hyper, alt = found
    name = next(iter(eff.parameters))
    pa, sa, fa = _own(others, eff, hyper)
    pc, sc, fc = _own(others, alt, hyper)
    # Hausman (1978): V(c - a) = V(c) - V(a), both at the consistent (gain-free) fit's noise
    var_a = sa[name] ** 2 * (fc["sigma"] / fa["sigma"]) ** 2 if fa["sigma"] > 0 else 0.0
    var_d = sc[name] ** 2 - var_a
    sd_d = math.sqrt(var_d) if var_d > 0 else sc[name]
    diff = pa[name] - pc[name]
    return {"parameter": name, "prior_map": float(pa[name]), "prior_map_std": float(sa[name]),
            "gains_free": float(pc[name]), "gains_free_std": float(sc[name]),
            "difference_std": float(sd_d),
            "z": float(abs(diff) / sd_d) if sd_d > 0 else math.inf,
            "retested": retested(step)}


def identified_z(step, fit) -> float | None:
    """How far the parameter of step ``step`` (an effect with a gain-free variant, the
    tether's) of the DOF whose final fit is ``fit`` stays from zero when refitted with each
    thruster's gain free beside it, in standard deviations [-]: the refit of
    :func:`stripcoef.diagnose.crossscale.refitted_z`, the rule every not-identified-apart
    test of the diagnosis uses (Rothenberg 1971, Theorem 1: identified only by the part of
    its column the gains' columns do not span). None for another effect or a singular
    refit."""
    from stripcoef.diagnose.crossscale import refitted_z

    found = _gain_free_term(step, fit)
    if found is None:
        return None
    others, eff, hyper, alt = found
    got = refitted_z(others.with_terms(list(others.terms) + [(eff, hyper)]), (alt, hyper))
    return None if got is None else got[1]


def mark(per: dict, fits: dict, gained: bool = False) -> dict:
    """The per-DOF results ``per`` of a one-DOF diagnosis (DOF -> :class:`DofResult`; new
    ones) with :attr:`Step.not_determined` set on each step that one DOF does not determine
    (module docstring, 'The rule'): found only with the thrusters' gains free, or, found
    on the written map, not identified apart from the gains (:func:`identified_z`).
    ``fits``: DOF -> :class:`DofFit`; ``gained``: whether the written map holds the gains
    fitted in the DOF (``dof_gains``), for the record's words."""
    out = {}
    where = ("the thrust map with the gains fitted in this DOF" if gained
             else "the prior's thrust map")
    for d, r in per.items():
        steps = []
        for s in r.steps:
            again = retested(s)
            z = None if again else identified_z(s, fits[d])
            # the record's test (two more fits) only for a step that is not determined
            test = (gain_dependence(s, fits[d]) if again or (z is not None and z < MIN_Z)
                    else None)
            why = None
            if test is not None and again:
                name = test["parameter"]
                why = (f"found only with each thruster's gain free (the test with {where} "
                       f"failed; its {name} moves by {test['z']:.1f} standard "
                       "deviations of the difference when the gains are freed)")
            elif test is not None:
                name = test["parameter"]
                why = (f"found with {where}, but not identified apart from the thrusters' "
                       f"gains: with each gain free beside it its {name} is {z:.1f} "
                       f"standard deviations from zero (< {MIN_Z:g})")
            if why is not None:
                s = replace(s, not_determined={
                    **test, "reason": f"{s.effect} in {d}: {why}; its {name} depends on the "
                                      "thrusters' gains, which one DOF does not determine: "
                                      "nothing is written for it",
                    "advice": ADVICE})
            steps.append(s)
        out[d] = replace(r, steps=tuple(steps))
    return out


def unwritten(result) -> set:
    """The effects of a DOF's result (:class:`DofResult`) named but not written because one
    DOF does not determine their value (:func:`mark`)."""
    return {s.effect for s in result.steps if getattr(s, "not_determined", None)}
