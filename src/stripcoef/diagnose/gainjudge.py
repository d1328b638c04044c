r"""The thrusters' gains of a one-DOF diagnosis judged inside the written model (issue 33,
gains33f; option :attr:`~stripcoef.diagnose.settings.DiagnoseSettings.gains_judge`).

With ``"prior"`` (the rule before gains33f) a significant one-DOF gain fit (:mod:`.gains`, ``dof_gains``) is
validated alone, on the prior, before the selection
(:func:`~stripcoef.diagnose.gains.validated`): the prior with the gains must simulate the
validation log no worse than the prior. Where the log holds an effect the prior lacks (a dead
band, a buoyancy offset, an added mass), both free simulations carry that effect's error and
the comparison decides on it or on noise: on the independent simulator's second fresh seed
(1795938998) 6 of 26 BlueROV2-like one-DOF fits significant by their likelihood-ratio test
(p down to 1e-221) were refused by sums of squared error ratios of 1.0004 to 1.24
(benchmarks/data/fresh33d_compare.md, section 1).

``"written"`` (the default): the gains are judged as every other change of a diagnosis is
(:func:`~stripcoef.diagnose.validate.validate_changes`): kept only if they lower the
validation error of the *written* model (cross-validation on data not fitted, Ljung 1999,
*System Identification*, 2nd ed., sec. 16.4; issue 33's rule "an effect is kept only if it
lowers the held-out error"), and removed with the changes fitted together with them. Every
calibration and effect of the DOF was selected and fitted on the gained thrust maps, so all of
them are the gains' partners (:func:`~stripcoef.diagnose.validate.partners`' rule): removing
the gains means the DOF selected again from the prior's maps. The diagnosis therefore runs
twice when the fit is significant and written (:func:`judged`): with the gains as the prior
of the selection (not validated alone, ``"none"``) and on the prior's maps (``dof_gains``
off), each with its own validation of its changes; the two written models' free-simulation
errors on the validation log are scored as :func:`~stripcoef.diagnose.validate.
validate_changes` scores a model (the number of DOFs simulated worse than the prior, then
the sum of squared error ratios to the prior's), and the gains are kept only when their
written model scores strictly better (a tie goes to the simpler model, without the gains,
as in the backward elimination). No tolerance: the ratio is compared with 1 as the
validation compares every change. Measured on the 52 BlueROV2-like one-DOF rows of seeds
1795938998 and 1795929171 against ``"prior"`` (benchmarks/data/gains33f_trace.md): named
first 39 -> 41 of 44, magnitude within 15 % 38 -> 41, error cut >= 3x 44/44, clean logs and
dry friction unchanged; a buoyancy 17.6 -> 3.9 % off; the gains removed in the three logs
where the written model without them simulates better. The cost is the second diagnosis:
CPU 1.7x over those logs. On every one-DOF row of the benchmark's four seeds, both vehicles
(docs/performance.md): named first 311 -> 315 of 352, magnitude within 15 % 295 -> 302, error
cut >= 3x 269 -> 270, clean logs and dry friction unchanged; the newest seed, unseen when the
rule was built, gains most (named first 80 -> 82, magnitude 75 -> 80 of 88). A whole-log
diagnosis keeps ``"prior"``'s rule unless ``"written_all"``.

``"written_all"`` (an option, issue 33, real33g): the same judgement in a whole-log diagnosis
too. The whole-log gains (one multiresponse fit over the diagnosed DOFs, :mod:`.gains`) are
the prior of every DOF's selection, so all the DOFs' calibrations, effects and shared fits
(timing, current) are their partners: the log is diagnosed with the gains (applied without
their validation alone, ``"none"``) and again on the prior's maps (the gains not fitted,
``"off"``), each with its own validation of its changes, and the gains are kept only if their
written model scores strictly better on the validation log by the same score
(:func:`~stripcoef.diagnose.validate.ratio_score`; cross-validation on data not fitted, Ljung
1999 sec. 16.4). The gains' validation alone on the prior (:func:`~stripcoef.diagnose.gains.
validated`, ``gains_validation``) is then not run. Why: on the issue-33 real-style current
log (seed 7, forward split) the written model differs from the prior only in the eight
whole-log gains, which passed their validation alone on the prior (sum of squared ratios
3.80 <= 6) and lose the held-out part in every DOF: they absorb the water current they were
fitted without, while the current itself and the calibrations were removed
(benchmarks/data/real33f_trace.md); judged against the model selected without them, the
current has its chance. The cost is a second whole-log diagnosis where the gains' fit is
significant (2.1-2.5x the diagnosis CPU on the BlueROV2-like real-style logs). One DOF: as
``"written"``. Off: on the real-style logs seed 7 keeps 28 of 44 cells (every held-out error
as main's: the current log's gains validate at 0 / 3.80 against 3 / 7.54 for the model
selected without them) and seed 21's current log goes 8 -> 4 of 12 (reverse: the gains'
written model is worse than the prior in one DOF of the validation part, better held out in
four); on the independent benchmark's whole-log current, thrust-effectiveness,
thrust-asymmetry and clean rows a spurious step kept appears on seed 1795938998 and a cut is
lost and one gained on 1795948659 (benchmarks/data/real33g_trace.md).

``"off"``: the thrusters' gains not fitted (the file's maps; in one DOF as ``dof_gains``
False, in a whole-log diagnosis the second pass of ``"written_all"``).

``"none"``: a significant fit within the gains' physical bound is applied without any
validation (the first of ``"written"``'s two runs; also what fresh33d measured as "applied").

Depends on: diagnose.settings, diagnose.gains (its records), diagnose.validate (its score),
conventions.
"""

from __future__ import annotations

import math
from dataclasses import replace

#: ``gains_judge`` values (module docstring).
PRIOR = "prior"
WRITTEN = "written"
NONE = "none"
WRITTEN_ALL = "written_all"
OFF = "off"
GAINS_JUDGES = (PRIOR, WRITTEN, NONE, WRITTEN_ALL, OFF)


def fitted(settings, dofs) -> bool:
    """Whether the thrusters' gains are fitted at all: always in a whole-log diagnosis (more
    than one DOF of ``dofs``), in one DOF with ``dof_gains``; never with ``"off"``."""
    return settings.gains_judge != OFF and (len(dofs) > 1 or settings.dof_gains)


def after_selection(settings, dofs, val_log, gains) -> bool:
    """Whether ``gains`` (a fit, or None) are judged inside the written model
    (:func:`judged`): option ``"written"`` and one DOF, or ``"written_all"`` and any DOFs;
    a validation log; and a fit that is significant and within its bound (``applied``)."""
    rule = settings.gains_judge == WRITTEN_ALL or (settings.gains_judge == WRITTEN
                                                  and len(dofs) == 1)
    return rule and val_log is not None and gains is not None and gains.applied


def score(errors: dict, prior: dict) -> tuple:
    """:func:`~stripcoef.diagnose.validate.validate_changes`' score of a model from its
    validation errors ``errors`` and the prior's ``prior`` (DOF -> RMS [m/s or rad/s]):
    (number of DOFs with :math:`r_i = E_i / E_i^{prior} > 1`, :math:`\\sum_i r_i^2`);
    ``(inf, inf)`` when a simulation diverged."""
    from stripcoef.diagnose.validate import ratio_score

    if not errors or not prior or any(errors.get(d) is None for d in prior):
        return (math.inf, math.inf)
    return ratio_score(errors[d] / max(prior[d], 1e-12) for d in prior)


def judged(run, log, model, dof, settings, budget, *, whole: bool = False):
    """The diagnosis of ``log`` against ``model`` in DOF ``dof`` (``"all"`` with ``whole``:
    a whole-log diagnosis) with the thrusters' gains judged inside the written model (module
    docstring): ``run`` is :func:`stripcoef.diagnose.pipeline.run`; returns the
    :class:`~stripcoef.diagnose.result.Diagnosis` of the better written model, its
    ``thruster_gains`` record saying what was compared."""
    with_gains = run(log, model, dof=dof, settings=replace(settings, gains_judge=NONE),
                     budget=budget)
    off = replace(settings, gains_judge=OFF) if whole else replace(settings, dof_gains=False)
    without = run(log, model, dof=dof, settings=off, budget=budget)
    record = dict(with_gains.thruster_gains)
    va, vb = with_gains.validation or {}, without.validation or {}
    prior = vb.get("prior")
    a, b = va.get("kept_changes"), vb.get("kept_changes")
    sa, sb = score(a, prior), score(b, prior)
    record["validation"] = {
        "description": "RMS free-simulation velocity error [m/s or rad/s] on the validation "
                       "log of the written model with the gains (selected on the gained maps) "
                       "and without them (selected again on the prior's maps), each after its "
                       "own validation; the gains are kept only if their written model scores "
                       "better (DOFs worse than the prior, then the sum of squared error "
                       "ratios to the prior's)",
        "rule": WRITTEN, "prior": prior, "written_with_gains": a,
        "written_without_gains": b,
        "score_with_gains": [float(x) for x in sa], "score_without_gains": [float(x) for x in sb]}
    if sa < sb:
        record["reason"] = (record["reason"] + "; kept by the validation of the written model "
                            f"(sum of squared error ratios {sa[1]:.4g} with the gains, "
                            f"{sb[1]:.4g} without)")
        return replace(with_gains, thruster_gains=record)
    record["applied"] = False
    record["reason"] = (record["reason"] + "; removed by the validation of the written model "
                        "with every change fitted on the gained maps, the DOF selected again "
                        f"on the prior's (sum of squared error ratios {sa[1]:.4g} with the "
                        f"gains, {sb[1]:.4g} without)")
    return replace(without, thruster_gains=record)
