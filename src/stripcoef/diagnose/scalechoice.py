r"""A thrust scale or an added-mass change: which one the log supports, or that it cannot
tell them apart (issue 33).

In one DOF the force balance is homogeneous: a thrust scale s
(:class:`~stripcoef.effects.thrust.ThrustEffectiveness`) is the same balance as the inertia
and the drag both divided by s, :math:`\tau = (M/s)\dot\nu + (D/s)\nu`. Only forces the
thrust map does not carry separate the two -- the weighed rigid-body mass in the
rigid-body Coriolis force, the other DOFs' added masses in :math:`C_A(\nu)\nu`, restoring
forces, a current -- and, beyond the log, the prior bands of the inertia and the drag.
Both the scale and the release of the added mass from its band
(:class:`~stripcoef.effects.hydrodynamic.AddedMassError`) are therefore judged by what the
Gaussian band priors say together with the data, the fit's :math:`-2\log` posterior
(:func:`stripcoef.diagnose.compare.posterior_cost`): a residual-based gate (held-out gain,
BIC) cannot see them when the calibration has already absorbed the change within its bands
(issue 33: a thrust effectiveness of 0.69 on a BlueROV2-like log, whose calibration moved
the surge added mass 3.1 bands and the drag 1.8 bands, had a held-out gain of -0.1 %).

- :func:`scale_evidence`: the scale's test against the model without it, the likelihood
  ratio of the two posteriors (Wilks 1938, as :func:`~stripcoef.diagnose.compare.lr_test`;
  the band priors are part of it), counted on the effective number of windows of the
  coloured residual (:func:`stripcoef.diagnose.evidence.step_test`'s fraction, Bretherton
  et al. 1999 eq. 31: conservative, the prior's part of the statistic is not coloured). It
  takes the place of the residual-based evidence, held-out gain and BIC gates; the scale
  must not raise the held-out error beyond ``TIE`` (the rule of a released coefficient),
  and still passes the z, plausibility and inertia-change gates of
  :func:`~stripcoef.diagnose.select._judge`.
- :func:`choose`: when both are candidates of a step, the model holding both
  (:func:`~stripcoef.diagnose.compare.pair_tests`: Atkinson 1970, Davidson & MacKinnon
  1981) says which is needed, Holm (1979) over the two tests at ``ALPHA``. One needed and
  the other not: that one. Both needed: both, the one with the lower posterior cost first,
  the other next (:func:`both`: at the joint fit's scale, when it passes its gates).
  Neither: the log's information (data and bands) does not separate them -- the step
  writes the one with the lower posterior cost and names the other as
  ``ambiguous_with``; the record of the test is the step's ``choice``.

Depends on: diagnose.compare, diagnose.evidence, diagnose.fit, effects.
"""

from __future__ import annotations

from scipy.stats import chi2

from stripcoef.diagnose.compare import ALPHA, holm, pair_tests, posterior_cost
from stripcoef.diagnose.evidence import step_test
from stripcoef.effects.laws import get_effect

#: The two effects this module chooses between.
SCALE, RELEASE = "thrust_effectiveness", "added_mass_error"


def judged_with_bands(eff) -> bool:
    """Whether effect ``eff`` is judged by :func:`scale_evidence`: a thrust scale, or the
    release of the DOF's added mass from its band (module docstring)."""
    return bool(getattr(eff, "scales_prior", False)) or getattr(eff, "mimics", None) == "M"


def scale_evidence(cfg, ev: dict, ref_ev: dict) -> dict:
    r"""The test of a thrust scale or an added-mass release (:func:`judged_with_bands`),
    the last term of ``cfg`` (evaluated: ``ev``), against
    the same configuration without it (evaluated: ``ref_ev``): the posterior likelihood
    ratio :math:`\Lambda = C_0 - C_1` at the scale's noise level, times the effective
    fraction of the windows, :math:`\chi^2_1` (module docstring). The record has
    :func:`~stripcoef.diagnose.evidence.step_test`'s keys (so that
    :func:`~stripcoef.diagnose.evidence.judge_family` adjusts it with the step's other
    candidates) and ``posterior_statistic``, the ratio before the effective fraction."""
    rec = step_test(ref_ev, ev, 1)
    sigma = float(ev["full"]["sigma"])
    ref = cfg.with_terms(list(cfg.terms[:-1]))
    lam = max(posterior_cost(ref, sigma) - posterior_cost(cfg, sigma), 0.0)
    frac = rec["effective_windows"] / rec["windows"] if rec["windows"] else 1.0
    stat = lam * frac
    return {**rec, "statistic": float(stat), "p_value": float(chi2.sf(stat, 1)),
            "posterior_statistic": float(lam),
            "method": "likelihood ratio of the posteriors (band priors included) on the "
                      "effective number of windows"}


#: The rejections of a release that leave it a contender of the choice: its size in bands
#: and its evidence, the two things the model holding both weighs again
_RELEASE_GATES = ("no signature in this log and the M change", "not beyond chance")
#: The same for a scale: its evidence, and a held-out error that rises (in a log with no
#: force the thrust does not carry, the cross-validation folds cannot place the scale
#: between the inertia and the drag: the choice then finds the two not told apart)
_SCALE_GATES = ("held-out error rises", "not beyond chance")


def contender(trial: dict) -> bool:
    """Whether a judged candidate (:func:`~stripcoef.diagnose.select._judge`'s record) is a
    contender in the choice: the scale, significant or rejected only by
    :data:`_SCALE_GATES`; the release, significant or rejected only for its size in bands
    or its evidence (the inertia change a scale implies is the same change: issue 33, a
    2.1x added mass on a VideoRay-like log, seed 771904, released 2.06 bands, was named a
    scale of 0.97 whose inertia change was 2.55 bands)."""
    gates = {SCALE: _SCALE_GATES, RELEASE: _RELEASE_GATES}.get(trial["effect"])
    if gates is None:
        return False
    reasons = trial.get("rejected_because") or ()
    return bool(trial["significant"] or trial.get("_only_evidence")
                or (reasons and all(r.startswith(gates) for r in reasons)))


def choose(cfg, scale: dict, release: dict) -> dict:
    """The choice between a scale and a release (module docstring), both judged records of
    one step on top of ``cfg``: ``{"first": the record to add, "other": the other record,
    "both": both needed, "ambiguous": neither needed, "record": the tests}``."""
    r = pair_tests(cfg, get_effect(RELEASE), get_effect(SCALE))
    sigma = float(r["ev"]["full"]["sigma"])
    costs = {t["effect"]: posterior_cost(t["_cfg"], sigma) for t in (scale, release)}
    p = [r["tests"][RELEASE]["p_value"], r["tests"][SCALE]["p_value"]]
    q = holm(p)
    need = {RELEASE: q[0] <= ALPHA, SCALE: q[1] <= ALPHA}
    if need[SCALE] != need[RELEASE]:
        first = scale if need[SCALE] else release
    else:
        first = min((scale, release), key=lambda t: costs[t["effect"]])
    other = release if first is scale else scale
    record = {"method": "likelihood ratio of each effect against the model holding both "
                        "(Atkinson 1970; Davidson & MacKinnon 1981), Holm 1979",
              "alpha": ALPHA, "pair": [RELEASE, SCALE],
              "posterior_cost": {k: float(v) for k, v in costs.items()},
              "posterior_cost_joint": float(posterior_cost(r["joint"], sigma)),
              "tests": {n: {**dict(r["tests"][n]), "p_adjusted": float(v)}
                        for n, v in zip((RELEASE, SCALE), q)},
              "needed": need}
    joint_hyper = {e.name: h for e, h in r["joint"].terms[-2:]}
    ambiguous = not (need[SCALE] or need[RELEASE])
    if ambiguous:
        record["reason"] = (
            "the log does not tell a thrust scale from an added-mass change in this DOF: "
            "in the model holding both neither is needed (Holm-adjusted p = "
            f"{q[1]:.2g} for the scale, {q[0]:.2g} for the added mass, > {ALPHA:g}); "
            f"written: {first['effect']}, the lower posterior cost")
    return {"first": first, "other": other, "both": need[SCALE] and need[RELEASE],
            "ambiguous": ambiguous, "record": record, "joint_hyper": joint_hyper}


def unforced(cfg, pair: dict, good: list, settings=None) -> list:
    """The step's candidates that passed, ``good``; or, with the setting
    ``scale_choice_unforced`` (the default), when none passed and a thrust scale and an
    added-mass release are both contenders (``pair``: effect -> judged record, :func:`contender`), the one the
    model holding both needs (:func:`choose`: each effect's likelihood-ratio test against
    the comprehensive model, Atkinson 1970, Davidson & MacKinnon 1981, Holm 1979 over the
    two), none when the choice is ambiguous. Each contender was refused only by a gate the
    choice weighs again (:data:`_SCALE_GATES`, :data:`_RELEASE_GATES`); without this the
    choice runs only when one of them passed its own gates."""
    if good or len(pair) != 2 or not getattr(settings, "scale_choice_unforced", False):
        return good
    choice = choose(cfg, pair[SCALE], pair[RELEASE])
    return [] if choice["ambiguous"] else [choice["first"]]


def both(cfg, cur: dict, choice: dict, judge):
    """The two steps of a choice whose members are both needed (:func:`choose`), in the
    choice's order, each at the joint fit's nonlinear parameters (the scale profiled with
    the release present: alone it takes part of the inertia change): ``(first, other)``,
    each ``judge(effect, cfg, ev, ref_ev)``'s record (the selection's single-step
    judgment) on top of ``cfg`` (evaluated: ``cur``) and of the first. The other's size in
    bands and its evidence are those the model holding both has just tested (its reasons
    of :data:`_RELEASE_GATES` are dropped: the test with the band priors replaces them)."""
    from stripcoef.diagnose.fit import _evaluate

    hyper = choice["joint_hyper"]
    first, other = (get_effect(choice[k]["effect"]) for k in ("first", "other"))
    # the nonlinear parameters are given: the evaluation profiles only unset ones, so they
    # are handed to the judgment with it (as select._judge_pair does)
    c1 = cfg.with_terms(list(cfg.terms) + [(first, hyper[first.name])])
    e1 = {**_evaluate(c1), "hyper": hyper[first.name]}
    t1 = judge(first, c1, e1, cur)
    c2 = c1.with_terms(list(c1.terms) + [(other, hyper[other.name])])
    t2 = judge(other, c2, {**_evaluate(c2), "hyper": hyper[other.name]}, e1)
    kept = [r for r in t2["rejected_because"] if not r.startswith(_RELEASE_GATES)]
    return t1, {**t2, "rejected_because": kept, "significant": not kept}


def partner_step(t: dict, cur: dict, dof: str, choice: dict) -> dict:
    """The step of the other member of a pair both needed (:func:`both`), added after the
    first (evaluated: ``cur``), in DOF ``dof``, with the choice's record."""
    return {**{k: v for k, v in t.items() if not k.startswith("_")},
            "error_before": cur["error"], "alternatives": [],
            "held_out_error_before": cur["held_out_error"], "dof": dof,
            "choice": choice["record"]}


def named_order(joint: dict):
    """``(steps, cfg, ev)`` of a joint pair of the selection
    (:func:`stripcoef.diagnose.select._competing`'s ``joint``: its two judged records
    ``steps``, its configuration and evaluation), the member with the larger likelihood
    ratio (its ``evidence`` statistic: the one whose removal costs more) first, the
    configuration's last two terms in the same order and evaluated again (a step's
    parameters are read from its term's place). Issue 33: a thrust effectiveness of 0.74
    (BlueROV2-like log, seed 872903, whole-log) was named after a momentum drag that was
    needed only beside it."""
    from stripcoef.diagnose.fit import _evaluate

    steps, cfg = list(joint["steps"]), joint["cfg"]
    stat = [t["evidence"]["statistic"] for t in steps]
    if stat[1] <= stat[0]:
        return steps, cfg, joint["ev"]
    terms = list(cfg.terms)
    cfg = cfg.with_terms(terms[:-2] + [terms[-1], terms[-2]])
    return steps[::-1], cfg, _evaluate(cfg)
