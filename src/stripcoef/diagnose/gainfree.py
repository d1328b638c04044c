r"""The tether's signature tested with the thrust map's per-thruster gains free (issue 33).

A tether is told from a change of the hull's own drag by its dependence on the paid-out
length L (:class:`~stripcoef.effects.hydrodynamic.TetherDrag`; Hoerner 1965, ch. 3: drag per
unit length of cable). A thrust map that is off (each thruster's gain g_k, Fossen 2011,
sec. 11.2.1) leaves a residual that follows the drag balance, and so leans on
:math:`L u|u|` as the speeds change along the log: it hides the tether or biases c_t. When the
tether's test fails, the selection repeats it with those gains free in the reference and
with the tether (:class:`~stripcoef.effects.hydrodynamic.TetherDragGainsFree`); the
candidate is then significant when that test passes (held-out gain, BIC, z, the same
thresholds) and the fit without the gains has no physical objection of its own. The step
reports the repeated test's statistics (the selection compares them), and its ``signature``
says so; the model it adds is the fit without the gains (its parameters refitted with the
other steps, :func:`stripcoef.diagnose.select.diagnose_dof`, and written: the gains are
not).

The same holds for a bias (a buoyancy offset, :class:`~stripcoef.effects.hydrodynamic.
BuoyancyOffsetGainsFree`): a thrust map off by a factor leaves a force proportional to the
mean thrust, nearly constant while the vehicle holds its depth, which takes or hides the
bias; the published identifications fit the bias beside the thrust's gain (Indiveri 1998,
eq. 4.16: ROMEO's weight-buoyancy term with the thrusters' efficiency eta; Wang & Clark
2006, eqs. 8-9: the bias delta beside the input's coefficient). Its test is repeated the
same way in heave, where the bias is the weight-buoyancy term W the published heave model
fits beside the efficiency (issue 33, seed 28112027: two BlueROV2-like heave logs whose
0.67-0.70 N offset failed the held-out gain with the prior's map, 8.3 % and 0.4 %). Not in
the other DOFs: there the bias is no weight term, and on that seed's BlueROV2 linear-drag
log (28113032, one DOF) the repeated test named a surge bias the truth does not have.

The same holds for the momentum drag in heave (:class:`~stripcoef.effects.hydrodynamic.
MomentumDragBiasFree`), with the weight-buoyancy term free instead of the gains: the published
heave model that defines the drag fits it beside W (Indiveri 1998, sec. 3.3.1 and eq. 4.17,
the *eta-md* model), and a W the prior has wrong leaves a constant heave residual that biases
the drag's fit (issue 33, seed 29112028: held-out gain -4.6 % with the prior's W, 55 % with
the truth's). Its step is written without the buoyancy column (the buoyancy is its own
effect's).

Depends on: effects.
"""

from __future__ import annotations

from stripcoef.effects.hydrodynamic import (BIAS_RETESTED, BuoyancyOffset,
                                            BuoyancyOffsetGainsFree, LinearDrag,
                                            LinearDragBiasFree, MomentumDrag,
                                            MomentumDragBiasFree, TetherDrag,
                                            TetherDragGainsFree)

#: The one instance of the repeated test's effect (frozen, as every effect)
GAINS_FREE = TetherDragGainsFree()
#: The bias's test with the gains free (:class:`BuoyancyOffsetGainsFree`)
BIAS_GAINS_FREE = BuoyancyOffsetGainsFree()
#: The momentum drag's test in heave with the buoyancy free (:class:`MomentumDragBiasFree`)
DRAG_BIAS_FREE = MomentumDragBiasFree()
#: The linear drag's test in surge and sway with the buoyancy free (:class:`LinearDragBiasFree`)
LINEAR_BIAS_FREE = LinearDragBiasFree()

#: The rejections that are statistics of the test (the repeated test may answer them); any
#: other (an implausible or pinned parameter, a physical problem) stands
_STATISTICAL = ("held-out gain ", "delta BIC ", "z = ")


#: The words a retested step's signature carries (:func:`with_retest`, :func:`retested`)
RETESTED = "tested with each thruster's gain free"


def retested(step) -> bool:
    """Whether a step (a :class:`~stripcoef.diagnose.result.Step`) was judged by the retest
    with the thrust gains free (:func:`with_retest`: its signature says so)."""
    return any(w in (step.signature or "") for w in (RETESTED, BIAS_RETESTED))


#: The DOF whose bias is the weight-buoyancy term the published method fits beside the
#: thrust's efficiency (Indiveri 1998 eq. 4.16: W^T e_z, heave) [-]
BIAS_DOF = 2


def variant(eff, dof: int | None = None, settings=None):
    """The effect whose test is repeated with the thrust gains free for ``eff`` in DOF
    ``dof``, or None: the tether's (any DOF), and the bias's in heave (:data:`BIAS_DOF`,
    module docstring); the momentum drag's in heave, repeated with the buoyancy free."""
    if isinstance(eff, TetherDrag) and not isinstance(eff, TetherDragGainsFree):
        return GAINS_FREE
    if (isinstance(eff, BuoyancyOffset) and not isinstance(eff, BuoyancyOffsetGainsFree)
            and dof == BIAS_DOF):
        return BIAS_GAINS_FREE
    if (isinstance(eff, MomentumDrag) and not isinstance(eff, MomentumDragBiasFree)
            and dof == BIAS_DOF):
        return DRAG_BIAS_FREE     # the buoyancy free, not the gains (module docstring)
    if (isinstance(eff, LinearDrag) and not isinstance(eff, LinearDragBiasFree)
            and dof in (0, 1) and getattr(settings, "restoring_free", False)):
        return LINEAR_BIAS_FREE   # the restoring force's change in surge and sway
    return None


def needs_retest(trial: dict) -> bool:
    """Whether a rejected candidate failed only on the test's statistics."""
    reasons = trial["rejected_because"]
    return bool(reasons) and all(r.startswith(_STATISTICAL) for r in reasons)


def with_retest(trial: dict, retest: dict, alt=None) -> dict:
    """``trial`` (the fit without the gains) judged by ``retest`` (the same candidate with
    the gains free, :func:`stripcoef.diagnose.select._judge`'s record): when the retest is
    significant, its statistics (z, held-out gain, delta BIC, the errors after it, its
    parameters, at the selection), which the selection compares with the other candidates
    and the out-of-library shapes, with ``trial``'s model (``_cfg``, ``_ev``: the fit without
    the gains, what is refitted and written) and released coefficients, and a signature text
    that says so; else ``trial`` unchanged."""
    if not retest["significant"]:
        return trial
    bias = (BIAS_RETESTED in (retest.get("signature") or "")
            or isinstance(alt, LinearDragBiasFree))
    text = (f"{trial['signature']} ({BIAS_RETESTED if bias else RETESTED}: "
            f"{', '.join(f'{k} = {v:.3g}' for k, v in retest['parameters'].items())}, "
            f"z = {retest['z']:.1f}, held-out gain {100 * retest['held_out_gain']:.1f} %, "
            f"delta BIC {retest['delta_bic']:.1f}; written without "
            f"{'it' if bias else 'the gains'})")
    # an effect without a signature of its own (the linear drag, LinearDragBiasFree) keeps
    # none: the selection's guard against out-of-library shapes (an effect without a
    # signature must beat every shape) still applies to it (issue 33, named33d: with the
    # text as its signature a BlueROV2-like dry-friction log, seed 29113038, kept a linear
    # drag whole-log)
    return {**retest, "effect": trial["effect"],
            "signature": text if trial["signature"] else None,
            "released": trial["released"], "_cfg": trial["_cfg"], "_ev": trial["_ev"],
            "_retested": not bias}   # only the gains-free retest holds a common scale


def borrows_from_scale(trial: dict) -> bool:
    """Whether a thrust scale may be paired with ``trial`` to take its force
    (:func:`stripcoef.diagnose.select._competing`): not when the trial was judged by the
    retest, whose reference holds every thruster's gain of the DOF free, so a common scale
    of those thrusters (their gains moving together) is already in it: the retest found
    the tether beyond any thrust scale (issue 33: on a BlueROV2-like log, seed 1731, the
    pair test without the gains gave the tether p = 0.62 beside a scale that alone was
    not significant, and nothing was named where the retest had z = 6.9)."""
    return not trial.get("_retested", False)
