r"""When a released coefficient or a thrust scale "raises the held-out error": the gate of
:func:`stripcoef.diagnose.select._judge` for the effects that explain what the calibration
may already have absorbed within its bands (an added-mass release, an effect without a
signature mimicking a prior coefficient, a thrust scale; :mod:`.scalechoice`).

Such a candidate is accepted by its likelihood ratio (:mod:`.evidence`,
:func:`.scalechoice.scale_evidence`), not by a held-out gain; the gate only refuses one that
does not generalise, one whose blocked cross-validation error (:func:`.fit._evaluate`: each of
``N_BLOCKS`` contiguous blocks of windows predicted by a fit on the others) is higher than the
reference's. Two rules (setting ``heldout_rise``):

- ``"tie"`` (default): the relative rise of the held-out RMS error beyond
  :data:`~stripcoef.diagnose.settings.TIE` (2 %). 2 % is the tolerance the selection uses to
  call two effects' held-out errors a tie (alternatives of a step); it is not a published
  criterion and carries no sample size: on 40 windows a 3 % rise is well within the spread
  of the two models' window losses, on 4,000 it is not.
- ``"diebold_mariano"``: the rise counts only when it is beyond chance: the one-sided
  Diebold-Mariano test of equal accuracy of the two models' cross-validated window losses
  (their squared held-out residuals on the same windows; Diebold & Mariano 1995, J. Business
  & Economic Statistics 13: 253-263, Harvey, Leybourne & Newbold 1997's small-sample factor,
  Newey & West 1987/1994 long-run variance: :func:`stripcoef.diagnose.heldout.diebold_mariano`)
  rejects, at :data:`~stripcoef.diagnose.compare.ALPHA`, in favour of the reference. The
  windows do not overlap, and the residuals of blocked cross-validation are those of a fit
  that did not see the block. The test has little power on a few dozen windows
  (:mod:`.evidence`): as the acceptance test it is weak, as a veto it asks for evidence
  that the candidate predicts worse before refusing it, which is what the gate claims.

Measured in benchmarks/data/named33f_trace.md (issue 33, VideoRay thrust effectiveness
1795939008: the scale's held-out RMS rose 2.9 %, one-sided Diebold-Mariano p = 0.28).

Depends on: diagnose.compare, diagnose.heldout, diagnose.settings.
"""

from __future__ import annotations

import numpy as np

from stripcoef.diagnose.compare import ALPHA
from stripcoef.diagnose.heldout import diebold_mariano
from stripcoef.diagnose.settings import TIE

#: The values of the setting ``heldout_rise`` (module docstring).
RULES = ("tie", "diebold_mariano")


def rise_test(ev: dict, ref_ev: dict) -> dict:
    """The one-sided Diebold-Mariano test that the reference ``ref_ev`` predicts the held-out
    windows better than the candidate ``ev`` (both :func:`stripcoef.diagnose.fit._evaluate`'s
    records on the same windows): :func:`~stripcoef.diagnose.heldout.diebold_mariano`'s
    record with the reference's squared held-out residuals as ``a`` [force units squared];
    a small ``p_value`` says the candidate's held-out error is higher beyond chance."""
    return diebold_mariano(np.asarray(ref_ev["held_out_resid"], float) ** 2,
                           np.asarray(ev["held_out_resid"], float) ** 2)


def rise_reasons(gain: float, ev: dict, ref_ev: dict, what: str, settings=None) -> list:
    """The gate's reason (a list of at most one string, starting "held-out error rises",
    the prefix :mod:`.scalechoice` weighs again) for a candidate evaluated as ``ev`` against
    the reference ``ref_ev`` with relative held-out gain ``gain`` [-]; ``what`` names the
    candidate in the reason ("the scale", "the released M"). The rule is the setting
    ``heldout_rise`` (module docstring)."""
    rule = getattr(settings, "heldout_rise", "tie")
    if rule not in RULES:
        raise ValueError(f"heldout_rise {rule!r}: expected one of {', '.join(RULES)}")
    if not gain < (-TIE if rule == "tie" else 0.0):
        return []
    if rule == "tie":
        return [f"held-out error rises ({100 * gain:.1f}% gain, beyond {100 * TIE:g}%): "
                f"{what} does not generalise"]
    test = rise_test(ev, ref_ev)
    p = test["p_value"]
    if not p <= ALPHA:          # NaN (under two windows) refuses nothing
        return []
    return [f"held-out error rises ({100 * gain:.1f}% gain; Diebold-Mariano p = {p:.2g} "
            f"<= {ALPHA:g} on {test['segments']} windows): {what} does not generalise"]
