r"""Validation by free simulation: each change of a diagnosis kept only if it improves the
simulation of data it was not fitted on; the re-simulated and held-out velocity errors
(:mod:`stripcoef.diagnose.heldout`).

Depends on: diagnose.heldout, diagnose.horizon, diagnose.combination, diagnose.calibrate,
diagnose.settings, progress.
"""

from __future__ import annotations

import math
from dataclasses import replace

from stripcoef.conventions import DOF, parse_dof
from stripcoef.diagnose.calibrate import (SHARED_EFFECTS, SHARED_TIMING, _changes,
                                          calibrated_model)
from stripcoef.diagnose.settings import RESIMULATION_HORIZON, UNLIMITED, Budget
from stripcoef.effects.base import TRANSLATIONAL
from stripcoef.progress import track


def heldout_errors(result, prior, written) -> dict:
    """Held-out free-simulation errors of the prior, the model as written and
    hold-last-velocity on the held-out part of the log of a :func:`diagnose` result
    (:mod:`stripcoef.diagnose.heldout`) [m/s or rad/s]."""
    from stripcoef.diagnose.heldout import HORIZON, compare, paired_record

    test_log, dofs = result.test_log, list(result.diagnosed)
    models = {"prior": prior, "calibrated": written}
    errors = compare(test_log, models, dofs)
    return {"description": "RMS free-simulation velocity error on the held-out end of the log "
                           f"[m/s or rad/s]: {HORIZON:g}-s simulations from the logged state; "
                           "hold_last_velocity predicts the velocity at each start",
            "held_out_s": [float(test_log["t"][0]), float(test_log["t"][-1])],
            "horizon_s": HORIZON, "errors": errors,
            # whether those differences are more than the segments' noise (issue 33)
            "paired_tests": paired_record(test_log, models, dofs)}



def ratio_score(ratios) -> tuple[int, float]:
    r"""The validation's score of a model from its error ratios :math:`r_i = E_i / E_i^{ref}`
    over the judged DOFs [-]: (the number of DOFs with :math:`r_i > 1`, beyond 1e-9 of
    round-off; :math:`\sum_i r_i^2`), compared lexicographically (fewer DOFs worse first,
    then the sum; :func:`validate_changes`). The one rule by which a change, the thrusters'
    gains (:mod:`.gaingate`) and a written model with or without them (:mod:`.gainjudge`)
    are scored."""
    r = list(ratios)
    return sum(x > 1.0 + 1e-9 for x in r), float(sum(x * x for x in r))


def validate_changes(val_log, prior, per: dict, fits: dict, dofs, *,
                     budget: Budget = UNLIMITED, logged=(),
                     skill: bool | str = True, horizon=None,
                     judge: str = "all", reference: str = "trivial",
                     choice: str = "greedy") -> tuple[set, dict]:
    r"""Keep a change only if it improves the free simulation of data it was not fitted on.

    Backward elimination (Hastie, Tibshirani & Friedman 2009, sec. 3.3.2) on the validation
    log: with :math:`r_i = E_i / E_i^{prior}` the free-simulation error of DOF i [m/s or
    rad/s] (:func:`stripcoef.diagnose.heldout.free_simulation_errors`) relative to the
    prior's, a model's score is the pair (number of DOFs with :math:`r_i > 1`,
    :math:`\sum_i r_i^2`), compared in that order; the change (a DOF's calibration or one
    effect) whose removal gives the best score is removed while that score is no worse than
    the current one (ties go to the simpler model), so the result never simulates an
    excited DOF worse than the prior on the validation data unless every subset does.

    A DOF's effects were fitted together with its calibration: removing the calibration
    removes them with it (:func:`partners`; an effect whose values compensate a calibration
    that is not written would be a silent wrong answer, issue 33); the effects kept after
    another one is removed are refitted without it
    (:func:`stripcoef.diagnose.calibrate.written_fit`). The thrusters' shared timing
    (:func:`stripcoef.diagnose.calibrate.share_timing`) is one change in all its DOFs.

    Then, per DOF: the summed score can keep a change that makes its own DOF worse because
    it helps the others through the coupling terms (the issue-33 current log: a surge
    calibration 0.248 against the prior's 0.193 m/s on the validation part, 0.295 against
    0.243 held out). A DOF's own changes (its calibration and effects, not the shared
    timing) are removed while its validation error is not below the prior's there
    (:math:`r_i \ge 1`), the DOF with the largest :math:`r_i` first, and the rest scored
    again. The backward elimination then runs again on what is left, the two in turn until
    neither removes a change: a shared change (the current, the thrusters' timing) kept
    beside calibrations the veto removed is judged without them. The Diebold-Mariano
    statistic of each DOF's free-simulation losses against the prior's over the validation
    segments (:func:`stripcoef.diagnose.heldout.diebold_mariano`,
    HAC variance) is recorded (``per_dof_test``): it says how strong the evidence behind
    each kept DOF is (the held-out part's test on rolling segments is ``--holdout``'s
    ``paired_tests``). It is not made the rule: on 5-6 segments it has little power, and
    keeping only what it finds significant (a t statistic beyond 1, the one-standard-error
    rule) removed on the current log a sway calibration whose held-out error was 35 % below
    the prior's (README of reference_tables/real_logs).

    ``logged``: the DOFs (indices, not diagnosed) whose velocities the free simulations
    take from the log (:func:`stripcoef.diagnose.heldout.segment_squared_errors`;
    :data:`~stripcoef.diagnose.settings.VALIDATION_OTHERS`).

    With ``logged`` :data:`~stripcoef.diagnose.heldout.EACH` in a whole-log diagnosis (each
    DOF simulated alone, the five others logged) the veto's reference of DOF i is the best
    of the prior and the two trivial predictors on the same segments (hold-last-velocity
    and zero velocity, :data:`~stripcoef.diagnose.heldout.TRIVIAL_PREDICTORS`): a DOF's own
    changes stay only where its simulation has skill, a mean squared error below the
    reference forecast's (the skill score :math:`1 - MSE / MSE_{ref}` positive: Murphy
    1988, Mon. Weather Rev. 116, 2417-2424; the more accurate naive forecast, persistence
    or climatology, as the reference: Murphy 1992, Weather Forecast. 7, 692-698). A DOF the log's pilot holds by
    feedback (a level or heading hold) is replayed open loop, its own feedback left out
    (Ljung 1999, sec. 13.4): its simulated error is the missing loop's, and a change that
    shrinks it (a thrust scale below 1 damps the replayed commands) is not a better model of
    the vehicle. Where no model of the DOF beats predicting its velocity held or zero, the
    simulation cannot judge its changes, and they stay at the prior (issue 33, each33c:
    benchmarks/data/each33c_trace.md). The summed score is unchanged. ``skill=False``: the
    prior alone is the veto's reference (as before; ``benchmarks.each33c_rules`` compares);
    ``skill="score"`` (a trial): a DOF where the prior has no skill is also left out of the
    summed score (its errors judge no change there).

    ``horizon``: the validation segments' horizon [s], one number or one per DOF of
    ``dofs`` (None: :data:`~stripcoef.diagnose.heldout.HORIZON`; the k-step-ahead
    prediction error of :mod:`stripcoef.diagnose.horizon`, e.g. its
    :func:`~stripcoef.diagnose.horizon.correlation_horizons`). The trivial predictors are
    judged on the same segments; the record's ``horizon_s`` holds it.

    ``judge``: ``"all"`` (default) scores a removal on every DOF (the summed score above);
    ``"own"`` (an option, issue 33, closed33d) on the DOFs of the changes it removes only
    (:data:`JUDGES`): the equation decoupling of output-error identification, each
    equation's change judged on its own output with the other equations' states measured
    (Klein & Morelli 2006, Aircraft System Identification, ch. 6), so that a DOF whose
    simulation a change does not address (a held roll replayed open loop) does not veto it.
    The per-DOF veto is unchanged. ``"coupled"`` (an option, issue 33, adopt33g): as
    ``"own"``, and also on every other DOF where the prior's simulation has skill (its error
    below the better trivial predictor's; with ``logged`` :data:`~stripcoef.diagnose.heldout.
    EACH` in a whole-log diagnosis, else as ``"own"``). The equation decoupling separates
    equations whose parameters are disjoint (Klein & Morelli 2006, ch. 6); a change written
    into the thrusters (a dead band, an asymmetry), into the restoring force (a heave bias
    is a buoyancy change, which acts in roll and pitch too: Fossen 2011, eq. 4.6) or into an
    added mass (it enters the other DOFs' :math:`C_A(\nu)\nu`, Fossen 2011, eq. 6.43) moves
    the simulations of other DOFs, each simulated alone, and they are outputs of the change
    too; a DOF the change does not enter keeps its error exactly and weighs nothing in the
    comparison. Of those DOFs only the ones whose open-loop replay predicts their velocity
    judge (the skill veto's criterion, Murphy 1988, 1992): a held DOF replayed open loop
    judges nothing (``"own"``'s reason). Measured on VideoRay-like actuation-delay log
    1796039007 (seed 1795938998): a heave bias -0.048 N (the truth's buoyancy change -0.002
    N) that ``"own"`` keeps (heave 0.0117 against 0.0131 m/s without it) moves pitch, which
    the prior predicts (0.030 against 0.200 rad/s), from 0.037 to 0.042 rad/s, worse than
    the prior; ``"coupled"`` removes it with heave's calibration, pitch 0.017 rad/s. Off:
    on that seed's 15 rows where it matters it loses 3 of the 13 cuts >= 3x ``"own"`` gains,
    a DOF with skill vetoing the effect DOF's calibration (benchmarks/data/adopt33g_trace.md).

    ``reference``: with the skill veto above, ``"trivial"`` (default) as described;
    ``"combination"`` (an option, issue 33, cut33f): in a DOF where the prior has no skill,
    the veto's reference is the least-squares combination of the prior's simulation and the
    trivial predictors on the same segments (:mod:`stripcoef.diagnose.combination`: a
    change that only scales the replayed commands of a held DOF toward the trivial
    predictors is a rescaled prior forecast, not a better model; Granger & Ramanathan 1984,
    forecast encompassing).

    ``choice``: ``"greedy"`` (default) writes the set the elimination and the veto end with.
    A backward elimination is greedy: it stops when no single removal scores better, so it
    can end on a set that scores worse than removing two changes at once, the prior
    included (issue 33, real33g: the seed-7 current log's forward split, diagnosed without
    the thrusters' gains, kept the current and the sway calibration at (3 DOFs worse,
    7.54) against the prior's (0, 6): each removal alone scored no better, both together
    did), and a ``"own"`` removal or a veto can raise the summed score. ``"best_visited"``
    (an option, issue 33, real33h): the final model is the best of the set they ended with,
    every other set of changes they scored and the prior (no change), among those the veto
    admits (no DOF whose own changes are kept simulated no better than its veto
    reference): each in the order scored, the prior last, challenges the best so far and
    wins when it scores better, or as well with fewer changes, on the DOFs that judge a
    removal (``judge`` above: every judged DOF; with ``"own"`` the DOFs of the changes in
    which the two sets differ; ``"coupled"`` and the DOFs with skill). The written model
    then never scores worse than the prior on the validation data by the rule that judges
    its changes:
    the subset selection's final comparison of the candidate models on the validation set
    (Hastie, Tibshirani & Friedman 2009, sec. 7.2-7.3: the model chosen is the one of least
    validation error among those compared), with no new constant. The record's
    ``choice`` says which set was written and their scores.

    Returns ``(excluded changes, record)``; :func:`with_kept` marks them in the per-DOF
    results.
    """
    from stripcoef.diagnose.combination import COMBINATION, combination_errors
    from stripcoef.diagnose.heldout import EACH, HORIZON, diebold_mariano
    from stripcoef.diagnose.horizon import dof_losses, per_dof, rms, trivial_errors

    horizon = per_dof(HORIZON if horizon is None else horizon, dofs)

    def errors(got):
        return None if got is None else rms(got)

    if not (isinstance(logged, str) and logged == EACH):
        logged = sorted(int(j) for j in logged)
    base_sse = dof_losses(val_log, prior, dofs, logged=logged, horizon=horizon)
    base = errors(base_sse)
    hold, zero = trivial_errors(val_log, dofs, horizon)
    ref = base if base is not None else hold
    ref = [max(e, 1e-12) for e in ref]
    # each DOF alone, whole-log: the veto's reference is the best of the prior and the
    # trivial predictors (skill, docstring)
    trivial = (None if not (skill and isinstance(logged, str) and logged == EACH
                            and len(dofs) > 1)
               else [min(a, b) for a, b in zip(hold, zero)])
    veto_ref = ref if trivial is None else [min(a, max(b, 1e-12))
                                            for a, b in zip(ref, trivial)]
    combined = None
    if trivial is not None and reference == COMBINATION and base is not None:
        # where the prior has no skill, the best rescaling of its forecast toward the
        # trivial ones (docstring, diagnose/combination.py)
        combined = combination_errors(val_log, prior, dofs, horizon=horizon, logged=logged)
        if combined is not None:
            veto_ref = [min(v, max(c, 1e-12)) if p >= tr else v
                        for v, c, p, tr in zip(veto_ref, combined, base, trivial)]
    # judge "coupled": besides the removed changes' own DOFs, the DOFs where the prior's
    # decoupled simulation has skill (docstring)
    skilled = ([b < t for b, t in zip(base, trivial)]
               if judge == COUPLED and trivial is not None and base is not None
               else [False] * len(dofs))
    # skill="score": a DOF where the prior has no skill is left out of the summed score too
    judge_mask = [True] * len(dofs) if trivial is None or skill != "score" else \
        [a <= b for a, b in zip(ref, trivial)]
    cache = {}

    changes = _changes(per)

    def score(excl):
        key = frozenset(partners(excl, changes))
        if key not in cache:
            budget.check()
            got = dof_losses(val_log, calibrated_model(prior, per, fits, key), dofs,
                             logged=logged, horizon=horizon)
            e = errors(got)
            if e is None:
                cache[key] = ((math.inf, math.inf), None, None)
            else:
                cache[key] = (ratio_score(a / b for a, b, j in zip(e, ref, judge_mask) if j),
                              e, got)
        return cache[key]

    def on(entry, ks):
        """The score of a cached ``entry`` on the DOFs at positions ``ks`` only."""
        if entry[1] is None:
            return (math.inf, math.inf)
        return ratio_score(entry[1][k] / ref[k] for k in ks if judge_mask[k])

    def eliminate_own(excl, cur):
        """Backward elimination from ``excl``, each removal judged on the DOFs of the
        changes it removes (``judge="own"``), and on the DOFs with skill (``"coupled"``)."""
        while len(excl) < len(changes):
            trials = []
            for c in [c for c in changes if c not in excl]:
                names = {g[1] for g in partners(excl | {c}, changes) - excl}
                ks = [k for k, i in enumerate(dofs) if DOF[i] in names or skilled[k]]
                new, old = on(score(excl | {c}), ks), on(cur, ks)
                if math.inf in new or math.inf in old:
                    delta = (0.0, 0.0) if new == old else \
                        ((math.inf, 0.0) if math.inf in new else (-math.inf, 0.0))
                else:
                    delta = (new[0] - old[0], new[1] - old[1])
                trials.append((delta, c))
            delta, c = min(trials, key=lambda x: x[0])
            if delta[0] > 0 or (delta[0] == 0 and delta[1] > 0):
                break
            excl = partners(excl | {c}, changes)
            cur = score(excl)
        return excl, cur

    def eliminate(excl, cur):
        """Backward elimination from ``excl`` (the summed score, above)."""
        if judge in (OWN, COUPLED):
            return eliminate_own(excl, cur)
        while len(excl) < len(changes):
            trials = [(score(excl | {c}), c) for c in
                      track([c for c in changes if c not in excl],
                            desc="diagnose: validating the changes", unit="model")]
            (best, *_), c = min(trials, key=lambda x: x[0][0])
            if best[0] > cur[0][0] or (best[0] == cur[0][0] and best[1] > cur[0][1]):
                break
            excl = partners(excl | {c}, changes)
            cur = score(excl)
        return excl, cur

    def own(d, excl):
        """The changes of DOF ``d`` still kept, the shared timing and current left out."""
        return {c for c in changes if c[1] == d and c not in excl
                and not (c[0] == "effect" and c[2] in _shared(changes))}

    excl = set()
    cur = score(excl)
    first = cur[1]
    vetoed = []
    while True:
        excl, cur = eliminate(excl, cur)
        before = len(excl)
        while cur[1] is not None:
            worse = [(e / b, DOF[i]) for e, b, i in zip(cur[1], veto_ref, dofs)
                     if e >= b and own(DOF[i], excl)]
            if not worse:
                break
            _, d = max(worse)
            vetoed.append(d)
            excl = partners(excl | own(d, excl), changes)
            cur = score(excl)
        # the veto removed changes the shared ones (current, timing) were kept beside: the
        # summed score is judged again on what is left (issue 33: the seed-7 current log's
        # shared current, once the DOFs' calibrations were vetoed, simulated five of six
        # DOFs worse than the prior on the validation part and was still written)
        if len(excl) == before:
            break
    chosen = None
    if choice == BEST_VISITED:
        def judged(a, b):
            """Sets ``a`` and ``b``'s scores on the DOFs that judge them (``judge``)."""
            if judge not in (OWN, COUPLED):
                return cache[a][0], cache[b][0]
            names = {c[1] for c in set(a) ^ set(b)}
            ks = [k for k, i in enumerate(dofs) if DOF[i] in names or skilled[k]]
            return on(cache[a], ks), on(cache[b], ks)

        excl, cur, chosen = _best_visited(excl, cache, changes, base, base_sse, ref,
                                          veto_ref, judge_mask, dofs, own, judged)
    tests = {}
    if base_sse is not None and cur[2] is not None:
        # on the consecutive segments the scoring already simulated: the rolling segments
        # (heldout.rolling_segments, about 4x as many) cost a third more CPU per diagnosis
        # for a record that decides nothing; --holdout reports them (holdout.paired_tests)
        for k, i in enumerate(dofs):
            tests[DOF[i]] = diebold_mariano(cur[2][k][0], base_sse[k][0])
    def named(e):
        return _named(e, dofs)

    record = {"description": "RMS free-simulation velocity error [m/s or rad/s] on the last "
                             "part of the fitting log, not used to fit: each change is kept "
                             "only if removing it makes this worse",
              "validation_s": [float(val_log["t"][0]), float(val_log["t"][-1])],
              "horizon_s": _named(horizon, dofs),
              "logged_dofs": (logged if isinstance(logged, str)
                              else [DOF[j] for j in logged]),
              "prior": named(base), "all_changes": named(first), "kept_changes": named(cur[1]),
              "removed_for_own_dof": vetoed,
              **({} if chosen is None else {"choice": chosen}),
              # each DOF alone, whole-log: the better trivial predictor's error, the veto's
              # reference where it is below the prior's (docstring)
              **({} if trivial is None else {"trivial_predictor": named(trivial)}),
              # the prior combined with the trivial predictors (reference "combination")
              **({} if combined is None else {"combined_reference": named(combined)}),
              "per_dof_test": {"description": "Diebold-Mariano test (HAC variance, "
                                              "Harvey et al. small-sample factor) of the kept "
                                              "model's free-simulation losses per validation "
                                              "segment against the prior's: a negative "
                                              "statistic favours the kept model; p_value "
                                              "one-sided", **tests},
              "removed": [_removed_text(c, excl, changes) for c in changes if c in excl],
              # the changes fitted together with a removed one are refitted without it
              # (calibrate.written_fit): their values as written differ from the selection's
              "refitted": {d: kept for d, kept in (
                  (d, [("calibration" if c[0] == "calibration" else c[2])
                       for c in changes if c[1] == d and c not in excl])
                  for d in per if any(c[1] == d for c in excl)) if kept}}
    return excl, record



#: :func:`validate_changes`' ``choice`` values: the set the elimination ends with, or the best
#: of the prior and every set it scored.
GREEDY = "greedy"
BEST_VISITED = "best_visited"
CHOICES = (GREEDY, BEST_VISITED)


def _best_visited(excl, cache, changes, base, base_sse, ref, veto_ref, judge_mask, dofs,
                  own, judged):
    """``(excluded, score entry, record)``: :func:`validate_changes`' ``"best_visited"``
    choice among the prior and the scored sets of ``cache`` (excluded changes -> (score,
    errors, squared errors)) that the veto admits (``veto_ref``, ``own``), ``excl`` the set
    the elimination and the veto ended with. Each set, in the order scored and the prior
    last, challenges the best so far, judged as the elimination judges a removal:
    ``judged(a, b)`` gives both sets' scores on the DOFs that judge them (every judged DOF;
    with ``judge`` ``"own"`` those of the changes in which they differ, ``"coupled"`` and
    the DOFs with skill); it wins when it scores better, or as well with fewer changes."""
    ended = frozenset(partners(excl, changes))
    everything = frozenset(partners(set(changes), changes))
    if base is not None:        # the prior: every ratio 1 exactly, no simulation needed
        cache.setdefault(everything, (
            ratio_score(b / r for b, r, j in zip(base, ref, judge_mask) if j), base,
            base_sse))

    def admitted(key):
        e = cache[key][1]
        return e is not None and not any(e[k] >= veto_ref[k] and own(DOF[i], key)
                                         for k, i in enumerate(dofs))

    best = ended
    order = [key for key in cache if key != everything] + (
        [everything] if everything in cache else [])
    for key in order:
        if key == best or not admitted(key):
            continue
        new, old = judged(key, best)
        if new < old or (new == old and len(key) > len(best)):
            best = key
    record = {"rule": BEST_VISITED,
              "written": ("the set the elimination ended with" if best == ended
                          else "the prior" if best == everything else "another set scored"),
              "score": list(cache[best][0]), "ended_score": list(cache[ended][0]),
              "ended_kept": [_change_text(c) for c in changes if c not in ended],
              "kept": [_change_text(c) for c in changes if c not in best],
              "prior_score": (list(cache[everything][0]) if everything in cache else None),
              "sets_scored": len(cache), "sets_admitted": sum(map(admitted, cache))}
    return set(best), cache[best], record


def _change_text(c) -> str:
    """A change's words: ``"surge calibration"`` or ``"surge current"``."""
    return f"{c[1]} calibration" if c[0] == "calibration" else f"{c[1]} {c[2]}"


#: :func:`validate_changes`' ``judge`` values: every DOF, the removed changes' own, or those
#: and the other DOFs whose prior simulation has skill.
OWN = "own"
COUPLED = "coupled"
JUDGES = ("all", OWN, COUPLED)


def with_kept(per: dict, excl) -> dict:
    """The per-DOF results ``per`` (DOF -> :class:`DofResult`, new ones) with ``kept`` set
    on each calibration and step: not in the changes ``excl`` that :func:`validate_changes`
    removed."""
    return {d: replace(r, calibration=replace(r.calibration,
                                              kept=("calibration", d) not in excl),
                       steps=tuple(replace(s, kept=("effect", d, s.effect) not in excl)
                                   for s in r.steps))
            for d, r in per.items()}


def resimulated_errors(log, prior, per: dict, fits: dict, calibrated,
                       exclude=frozenset()) -> dict:
    """RMS of the re-simulated velocity of each diagnosed DOF for the prior, the prior with
    only its calibrated coefficients, and the final model [m/s or rad/s] (None when the
    simulation diverges)."""
    no_effects = set(exclude) | {c for c in _changes(per) if c[0] == "effect"}
    only_cal = calibrated_model(prior, per, fits, no_effects)
    dofs = [parse_dof(d) for d in per]
    rows = {name: resimulate_rms(log, m, dofs) for name, m in
            track((("baseline", prior), ("calibrated", only_cal), ("final", calibrated)),
                  desc="diagnose: re-simulating", unit="model")}
    return {DOF[i]: {name: (None if rows[name] is None else rows[name][k])
                     for name in rows} for k, i in enumerate(dofs)}




def resimulate_rms(log, model, dofs, *, horizon: float = RESIMULATION_HORIZON):
    """RMS differences between the logged and the re-simulated velocities of ``dofs``
    (list) over segments of ``horizon`` seconds, or None if a simulation diverges
    (:func:`stripcoef.diagnose.heldout.free_simulation_errors`, tolerances 1e-6, 1e-8)."""
    from stripcoef.diagnose.heldout import free_simulation_errors
    return free_simulation_errors(log, model, dofs, horizon=horizon, tolerances=(1e-6, 1e-8))




def partners(excl, changes) -> set:
    """``excl`` with the changes fitted together with an excluded one that cannot stand
    without it: the effects of a DOF whose calibration is excluded, except the thrusters'
    shared timing and the one current of several DOFs (:func:`_shared`: refitted without
    that calibration, :func:`~stripcoef.diagnose.calibrate.written_fit`), each of which goes
    in all its DOFs when it goes in one."""
    out = set(excl)
    names = _shared(changes)
    shared = {c[2] for c in out if c[0] == "effect" and c[2] in names}
    for c in changes:
        if c[0] != "effect":
            continue
        if c[2] in names:                 # one timing, one current: all its DOFs at once
            if c[2] in shared:
                out.add(c)
        elif ("calibration", c[1]) in out or _admitted_beside(c, out, changes):
            out.add(c)
    return out


def _removed_text(c, excl, changes) -> str:
    """The validation record's words for the removed change ``c``: a calibration, or an
    effect with the partner it went with (:func:`partners`: its DOF's calibration, or the
    buoyancy offset it was admitted beside)."""
    if c[0] != "effect":
        return f"{c[1]} calibration"
    text = " ".join(c[1:][::-1])
    if ("calibration", c[1]) in excl:
        return text + f" (with the {c[1]} calibration it was fitted with)"
    if _admitted_beside(c, excl, changes):
        return text + f" (with the {c[1]} buoyancy_offset it was admitted beside)"
    return text


def _admitted_beside(c, out, changes) -> bool:
    """Whether the change ``c`` is a translation's thrust asymmetry selected after that
    DOF's buoyancy offset, which ``out`` removes. It was selected, and its identification
    apart from a buoyancy change tested
    (:meth:`~stripcoef.diagnose.thrusterparts.ThrusterParts.buoyancy_confounded`;
    Rothenberg 1971, Theorem 1), with the offset in the model; refitted without it, the
    asymmetry's column (the backward part of the thrust, one-signed where the thrusters
    mostly hold the vehicle against its restoring force) takes the bias, a value that no
    test admitted (issue 33, asym33s: VideoRay-like log 1795929178 of seed 1795929171,
    before the identification test was applied beside an offset: selected
    eta_b / eta_f - 1 = -0.32 beside the offset, written +2.06 without it). It goes with
    the offset."""
    if c[2] != "thrust_asymmetry" or parse_dof(c[1]) not in TRANSLATIONAL:
        return False
    b = ("effect", c[1], "buoyancy_offset")
    return b in out and b in changes and changes.index(b) < changes.index(c)


def _shared(changes) -> set:
    """The effects of :data:`~stripcoef.diagnose.calibrate.SHARED_EFFECTS` that are one
    change of several DOFs in ``changes``: the thrusters' timing always, the current when
    more than one DOF holds it (:func:`stripcoef.diagnose.current.share_current`; a
    one-DOF diagnosis's current is that DOF's, and goes with its calibration)."""
    count = {}
    for c in changes:
        if c[0] == "effect":
            count[c[2]] = count.get(c[2], 0) + 1
    return set(SHARED_TIMING) | {e for e in SHARED_EFFECTS if count.get(e, 0) > 1}


def _named(errors, dofs):
    """{DOF name: error} of a list of errors of ``dofs`` (indices), None for None."""
    return None if errors is None else {DOF[i]: float(v) for i, v in zip(dofs, errors)}


def validation_errors(val_log, model, dofs, logged=(), horizon=None):
    """{DOF name: RMS free-simulation error} of ``model`` on the validation log [m/s or
    rad/s] (the record's ``kept_changes`` form), None when a simulation diverges;
    ``logged`` and ``horizon`` as for :func:`validate_changes`."""
    from stripcoef.diagnose.heldout import free_simulation_errors

    if horizon is None:
        return _named(free_simulation_errors(val_log, model, dofs, logged=logged), dofs)
    from stripcoef.diagnose.horizon import dof_losses, rms
    got = dof_losses(val_log, model, dofs, logged=logged, horizon=horizon)
    return _named(None if got is None else rms(got), dofs)

