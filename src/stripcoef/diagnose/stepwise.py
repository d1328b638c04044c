r"""Whole-log: what the shared fits change after the DOFs' selections (issue 33, spurious
steps in other DOFs).

A whole-log diagnosis selects each DOF's effects alone (:func:`~stripcoef.diagnose.select.
diagnose_dof`), then fits the vehicle's shared effects once over the DOFs (the thrusters'
lag or delay, :func:`~stripcoef.diagnose.calibrate.share_timing`,
:func:`~stripcoef.diagnose.timing.compare_timing`; the water current,
:func:`~stripcoef.diagnose.current.share_current`) and writes them into DOFs whose
selection did not have them, or at another value. Three rules follow, none with a threshold
of its own:

- **A shared timing the joint fit does not resolve is not written.** The joint value is
  profiled on the effect's own grid; at its lower end (0.1 sampling interval) it is pinned at
  a bound of its search, where a z has no meaning (Self & Liang 1987, JASA 82, 605,
  Theorem 2; :func:`~stripcoef.diagnose.select._judge`'s pinned-parameter rule), and a lag
  or delay shorter than the effect's resolvable fraction of the sampling interval is the
  effect's own implausible value (:meth:`~stripcoef.effects.timing._TimedInputEffect.
  implausible`; the window integrals' quadrature error, not a time constant). The step the
  selection found in one DOF is then contradicted by the others jointly and withdrawn from
  every DOF (:func:`unresolved_timing`). Issue 33, seed 29112026, VideoRay log 29212027
  (thrust asymmetry): a yaw lag (z 4.0) fitted jointly at 0.01 s, the grid's lowest point,
  and written in surge, heave, pitch and yaw (z 1.8), three of them spurious and kept.
- **A step is tested again in the model the shared fits wrote** (:func:`retest_steps`).
  Stepwise regression re-examines at every stage the terms entered before, and removes one
  that the later terms make unnecessary, by the same test it entered with (Efroymson 1960,
  "Multiple regression analysis", in Ralston & Wilf, Mathematical Methods for Digital
  Computers; Draper & Smith 1998, Applied Regression Analysis, 3rd ed., sec. 15.2). A DOF's
  steps were judged in a model without the current or the lag that the shared fit later
  wrote into it; each of its own steps (not a shared one) is judged again, with the
  selection's own rule (:func:`~stripcoef.diagnose.select._judge`, and its evidence at the
  Bonferroni level of its step, :func:`~stripcoef.diagnose.evidence.supported`), in the DOF's
  written model without it; the worst failing step is withdrawn and the rest judged again.
  Issue 33, seed 29112026: a heave dead band (VideoRay current log 29112030) and a heave
  linear drag (29212030) selected before the current was shared into heave.
- **A bias outside the weight's DOFs must stand beside the thrusters' gains**
  (:func:`bias_beside_gains`). A constant force or moment in heave, roll or pitch is the
  weight-buoyancy term of the restoring force (Fossen 2011, eq. 4.6); in surge and sway
  :math:`g(\eta)` has only :math:`(W - B)\sin\theta` and :math:`-(W - B)\cos\theta
  \sin\phi`, small at small trim angles, and in yaw only products of the centres' offsets
  with the angles, so the bias there is mostly the generic offset :math:`\delta` of Wang &
  Clark's one-DOF model (Wang & Clark 2006, eqs. 8-9), which they fit beside the input's
  coefficient :math:`\gamma`. (A trimmed pitch gives surge a real constant: fresh seed
  41129026's clean VideoRay log 41129037, trimmed at -1.16 deg with a buoyancy change of
  0.98 N, names a surge bias of -0.032 N, z 3.9, for the 0.020 N that term gives; it stands
  beside the gains and is kept here.) A thrust map off
  by a factor leaves a force proportional to the mean thrust, which a bias takes
  (:mod:`.gainfree`). So in a whole-log run such a bias is refitted with each acting
  thruster's gain free beside it (:class:`~stripcoef.effects.hydrodynamic.
  BuoyancyOffsetGainsFree`) and refused when it is then under ``MIN_Z`` standard
  deviations from zero: not identified apart from the gains (Rothenberg 1971, Econometrica
  39, 577, Theorem 1; the rule :mod:`.thrusterparts` applies to a translational thrust
  asymmetry beside a buoyancy change). Issue 33, seed 29112026, VideoRay clean log 29212037:
  a yaw bias of -0.0009 N m (z 4.0) is +0.0007 N m, z 2.6, with the horizontal pair's gains
  free.

Depends on: diagnose.select, diagnose.thrusterparts, diagnose.fit, diagnose.evidence,
diagnose.gainfree, diagnose.scalechoice, effects, conventions.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from stripcoef.conventions import DOF, parse_dof
from stripcoef.diagnose import gainfree, scalechoice
from stripcoef.diagnose.calibrate import SHARED_EFFECTS, SHARED_TIMING
from stripcoef.diagnose.crossscale import refitted_z
from stripcoef.diagnose.evidence import supported
from stripcoef.diagnose.fit import _evaluate, _Nuisance, refit
from stripcoef.diagnose.select import _judge
from stripcoef.diagnose.settings import MIN_Z
from stripcoef.diagnose.thrusterparts import OneDofParts, ThrusterParts
from stripcoef.effects.laws import get_effect

#: The DOFs whose constant force is the restoring force's weight-buoyancy term at small roll
#: and pitch (Fossen 2011, eq. 4.6): heave, roll, pitch
WEIGHT_DOFS = (2, 3, 4)


def terms_record(fits: dict) -> dict:
    """Each DOF's terms as (name, hyper) pairs: what :func:`changed_dofs` compares."""
    return {d: [(e.name, None if h is None else tuple(np.atleast_1d(h).tolist()))
                for e, h in f.config.terms] for d, f in fits.items()}


def changed_dofs(before: dict, fits: dict) -> list:
    """The DOFs whose terms (``before``: :func:`terms_record` of the selections' fits)
    the shared fits changed: an effect added or removed, or a value moved."""
    after = terms_record(fits)
    return [d for d in fits if after[d] != before.get(d)]


def _without(per, fits, d, name, reason, params):
    """``(per, fits)`` with effect ``name`` taken out of DOF ``d``'s fit and steps, the
    withdrawal recorded with its ``reason``."""
    cfg = fits[d].config
    cfg = cfg.with_terms([(e, h) for e, h in cfg.terms if e.name != name])
    _, ev = refit(fits, d, cfg)
    r = per[d]
    record = {"effect": name, "parameters": params, "reason": reason}
    per[d] = replace(r, steps=tuple(s for s in r.steps if s.effect != name),
                     final_error=float(ev["error"]),
                     final_held_out_error=float(ev["held_out_error"]),
                     withdrawn=tuple(r.withdrawn or ()) + (record,))
    return per, fits


def unresolved_timing(per: dict, fits: dict) -> tuple[dict, dict]:
    """``(per, fits)`` (new dictionaries) without a shared timing effect whose one value
    the joint fit leaves at the lower end of its grid or below its resolvable time (module
    docstring), withdrawn from every DOF that holds it."""
    per, fits = dict(per), dict(fits)
    for name in SHARED_TIMING:
        have = [d for d, f in fits.items() if any(e.name == name for e, _ in f.config.terms)]
        if not have:
            continue
        eff = get_effect(name)
        d0 = have[0]
        cfg = fits[d0].config
        hyper = next(h for e, h in cfg.terms if e.name == name)
        if hyper is None:
            continue
        key = eff.hyper[0]
        value = float(np.atleast_1d(hyper)[0])
        low = float(np.min(eff.grid(cfg.data, parse_dof(d0))))
        reason = eff.implausible({key: value}, cfg.data, parse_dof(d0))
        if value <= low * (1.0 + 1e-6):
            reason = "; ".join(x for x in (reason, (
                f"the joint {key} {value:.3g} s is at the lower end of its search "
                f"({low:.3g} s): pinned at a bound, no valid z (Self & Liang 1987)")) if x)
        if not reason:
            continue
        why = (f"the thrusters' one {key}, fitted jointly on {', '.join(have)}: {reason}; "
               "withdrawn from every DOF")
        for d in have:
            per, fits = _without(per, fits, d, name, why, {key: value})
    return per, fits


def _own_steps(r, scales: bool = False) -> list:
    """The steps of a DOF's result that :func:`retest_steps` judges again: its own (not a
    shared effect), tested by the selection's plain rule (not a step found by the gains-free
    retest), and a scale judged with the bands (a thrust scale, an added-mass release,
    :func:`~stripcoef.diagnose.scalechoice.judged_with_bands`) only with ``scales``
    (``DiagnoseSettings.retest_scales``): :func:`~stripcoef.diagnose.select._judge` makes
    their band tests too, and stepwise regression re-examines every term entered before
    (Efroymson 1960). Issue 33, adopt33g (benchmarks/data/adopt33g_trace.md): on the
    BlueROV2-like thruster-lag log 1795940006 (seed 1795938998) roll's scale 1.78 was
    fitted before the shared lag joined roll (the lag's held-out gain there beside it
    -2.4); judged again beside the lag it is 1.51 and its implied inertia change is within
    2.5 bands of the added mass (the scale-or-inertia test), so it is withdrawn (the truth's
    roll gain on the log 0.93). Off by default: the same test withdraws the right heave
    scale of VideoRay lag log 1796060454 (seed 1795960446)."""
    return [s for s in r.steps if s.effect not in SHARED_EFFECTS and not gainfree.retested(s)
            and (scales or not scalechoice.judged_with_bands(get_effect(s.effect)))
            and not s.not_determined]


def retest_steps(per: dict, fits: dict, dofs, n_dofs: int,
                 scales: bool = False) -> tuple[dict, dict]:
    """``(per, fits)`` (new dictionaries) with the own steps of each DOF of ``dofs`` judged
    again in its written model (module docstring): the failing one with the lowest held-out
    gain withdrawn, until every remaining step passes (``scales``: :func:`_own_steps`)."""
    per, fits = dict(per), dict(fits)
    for d in dofs:
        i = parse_dof(d)
        while True:
            cfg = fits[d].config
            failed = []
            for s in _own_steps(per[d], scales):
                k = next((j for j, (e, _) in enumerate(cfg.terms) if e.name == s.effect), None)
                if k is None:
                    continue
                eff = cfg.terms[k][0]
                rest = [t for j, t in enumerate(cfg.terms) if j != k]
                base = cfg.with_terms(rest)
                trial_cfg = cfg.with_terms(rest + [(eff, None)])     # profiled as a candidate
                try:
                    ev = _evaluate(trial_cfg)
                    ref = _evaluate(base if eff.nuisance(cfg.data, i) is None
                                    else base.with_terms(rest + [(_Nuisance(eff), None)]))
                    t = _judge(eff, trial_cfg, ev, ref, cfg.data, i, list(cfg.cal.names),
                               np.asarray(cfg.cal.sd, float), cfg.settings)
                except (np.linalg.LinAlgError, ValueError):
                    continue
                n_cand = int((s.evidence or {}).get("candidates") or 1)
                reasons = list(t["rejected_because"])
                if t["significant"] and not supported(t, n_cand, n_dofs):
                    p = t["evidence"]["p_value"]
                    reasons.append(f"not beyond chance (p = {p:.2g} at its step's level over "
                                   f"{n_cand} candidates and {n_dofs} DOFs)")
                if reasons:
                    failed.append((t["held_out_gain"], s.effect, t["parameters"], reasons))
            if not failed:
                break
            gain, name, params, reasons = min(failed, key=lambda x: x[0])
            why = ("judged again in the model the shared fits wrote into " + d + " (Efroymson "
                   "1960; Draper & Smith 1998 sec. 15.2): " + "; ".join(reasons))
            per, fits = _without(per, fits, d, name, why, dict(params))
    return per, fits


def bias_beside_gains(trial: dict, dof: int) -> str:
    """Why the bias ``trial`` (a significant buoyancy offset) of DOF ``dof`` outside
    :data:`WEIGHT_DOFS` is not identified apart from the acting thrusters' gains (module
    docstring), '' when it is, or for another effect or DOF, or a DOF no thruster acts in."""
    cfg = trial.get("_cfg")
    if (trial["effect"] != "buoyancy_offset" or dof in WEIGHT_DOFS or cfg is None
            or trial.get("_retested")):
        return ""
    eff = gainfree.BIAS_GAINS_FREE
    if eff.nuisance(cfg.data, dof) is None:
        return ""
    got = refitted_z(cfg, (eff, None))
    if got is None:
        return ""
    value, z = got
    return "" if z >= MIN_Z else (
        f"not identified apart from the thrusters' gains: with each acting thruster's gain "
        f"free beside it (Wang & Clark 2006 eqs. 8-9) the {DOF[dof]} bias is "
        f"{value:.3g}, {z:.1f} standard deviations from zero (< {MIN_Z:g})")


class _BiasBesideGains:
    """The refusal of :func:`bias_beside_gains` added to a parts class's contradictions (one
    rule, shared by :class:`WholeLogParts` and :class:`OneDofBiasParts`)."""

    def contradictions(self, trial: dict, dof: int) -> list:
        out = super().contradictions(trial, dof)
        why = bias_beside_gains(trial, dof)
        return out + [why] if why else out


class WholeLogParts(_BiasBesideGains, ThrusterParts):
    """:class:`~stripcoef.diagnose.thrusterparts.ThrusterParts` that also refuses a bias
    outside the weight's DOFs that the thrusters' gains take (:func:`bias_beside_gains`)."""


class OneDofBiasParts(_BiasBesideGains, OneDofParts):
    """:class:`~stripcoef.diagnose.thrusterparts.OneDofParts` that also refuses a bias
    outside the weight's DOFs that the acting thrusters' gains take (:func:`bias_beside_gains`;
    option ``bias_gains_one_dof``, off by default). A one-DOF run fits the gains' contrasts
    only (the common gain is the DOF's thrust effectiveness), so a thrust map off by a factor
    leaves a constant force in proportion to the mean thrust there as in a whole-log run.
    Issue 33 (named33i): VideoRay thrust effectiveness 1795971251 (seed 1795971241), one DOF:
    a surge bias of 0.036 N (held-out gain 18.6 %) was named first over the scale (0.698,
    19.8 %: within TIE, the bias preferred for its signature), and removed by the validation;
    the whole-log run refuses it by this test and names the scale first
    (benchmarks/data/named33i_trace.md)."""
