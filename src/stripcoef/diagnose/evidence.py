r"""The evidence of a selection step: does a candidate effect explain more of the window
residual than chance would, given autocorrelated residuals and the many candidates tried?

The selection (:func:`stripcoef.diagnose.select.diagnose_dof`) judges each candidate by its
relative held-out gain, the change of BIC and its largest parameter's z. BIC and z count
every window as an independent observation; the window residual of a real log is coloured
(the prior's mismatch is a smooth force, not white noise: lag-1 autocorrelations up to 0.5
on the independent simulator's clean 120-s logs, seed 431977), so both overstate the evidence; and every step tries about ten effects in each of
up to six DOFs, so one of them passing by chance is likely on a log without any (issue 33:
clean logs named an effect in 6 of 8, whole-log runs named effects in DOFs the truth does
not touch in 24 of 44).

The test (:func:`step_test`): the likelihood ratio of the model with the candidate
against the reference without it, :math:`\Lambda = n \ln(\mathrm{RSS}_0/\mathrm{RSS}_1)`
over the n windows (Wilks 1938: :math:`\chi^2_k` under the null, k the candidate's free
parameters), counted on the effective number of independent windows instead of n,

.. math:: \Lambda_{eff} = \frac{n_{eff}}{n}\Lambda, \qquad
          \frac{n_{eff}}{n} = \frac{1 - \rho_e \rho_g}{1 + \rho_e \rho_g}

with :math:`\rho_e` the lag-1 autocorrelation of the reference's residual (the noise under
the null) and :math:`\rho_g` that of the force the candidate explains (the difference of the
two fits' residuals): the effective sample size of a regression of one AR(1) series on
another (Bretherton, Widmann, Dymnikov, Wallace & Bladé 1999, J. Climate 12, 1990-2009,
eq. 31; Bartlett 1935). :math:`n_{eff}` is never taken above n (a negative product would
credit the log with more windows than it has).

The family (:func:`judge_family`): the candidates of one step in one DOF are one family,
adjusted by Holm's (1979) step-down procedure; in a whole-log diagnosis the DOFs are
diagnosed separately, so each DOF's family is tested at :math:`\alpha / n_{DOF}`
(Bonferroni over the DOFs): the probability of a spurious step anywhere in the log stays
at most :math:`\alpha` per step. :math:`\alpha` is the conventional 5 %
(:data:`stripcoef.diagnose.compare.ALPHA`), stated, not fitted.

The paired Diebold-Mariano test of the cross-validated window losses (the held-out
question asked directly; :func:`stripcoef.diagnose.heldout.diebold_mariano`, Newey-West
variance) is recorded beside it (``held_out_p_value``) but does not decide: on the 20-60
windows of a 2-5 minute log its squared-loss differences are heavy-tailed and it has little
power (measured, issue 33, the BlueROV2 buoyancy-offset log of seed 432980, 120 s: a 0.42 N
offset with a 57 % held-out gain had p = 0.0015, against 8e-13 for the likelihood ratio on
its effective windows; with Holm over ten candidates and six DOFs that test named nothing
on that log nor on the added-mass log 432984; the held-out gain gate of
:func:`~stripcoef.diagnose.select._judge` stays).

The test adds a gate; it removes none: a candidate must still pass the held-out gain, BIC,
z and plausibility gates of :func:`~stripcoef.diagnose.select._judge`. A candidate that
judges itself without the BIC and held-out gain gates -- the release of a calibrated
coefficient (an added-mass error: its gate is the change from the prior in bands) -- must
pass it too: the release is named only if it explains more of the residual than the
calibration already did (issue 33: a clean VideoRay log, seed 531988, named a surge
added-mass error 2.5 bands from the prior with a 1 % held-out gain). The release of the
added mass and a thrust scale, which both explain an inertia change the calibration may
have made already within its bands, are tested instead by the likelihood ratio of the
posteriors, band priors included (:func:`stripcoef.diagnose.scalechoice.scale_evidence`),
adjusted here with the others (a record that failed only this gate carries
``_only_evidence``).

Depends on: diagnose.compare, diagnose.heldout, identify (residual autocorrelation).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.stats import chi2

from stripcoef.diagnose.compare import ALPHA, holm
from stripcoef.diagnose.heldout import diebold_mariano
from stripcoef.identify.estimators import residual_autocorrelation

METHOD = ("likelihood ratio on the effective number of windows (Bretherton et al. 1999, "
          "eq. 31), Holm 1979 over the step's candidates, Bonferroni over the DOFs")


def _lag1(x) -> float:
    x = np.asarray(x, float)
    return float(residual_autocorrelation(x, 1)[1]) if x.size > 2 else 0.0


def effective_fraction(rho_e: float, rho_g: float) -> float:
    r""":math:`n_{eff}/n = (1 - \rho_e\rho_g)/(1 + \rho_e\rho_g)` [-] (Bretherton et al.
    1999, eq. 31), at most 1."""
    p = float(rho_e) * float(rho_g)
    if not math.isfinite(p) or p <= 0.0:
        return 1.0
    p = min(p, 1.0 - 1e-12)
    return (1.0 - p) / (1.0 + p)


def step_test(ref_ev: dict, ev: dict, n_params: int) -> dict:
    r"""The test of a candidate's fit ``ev`` against the reference's ``ref_ev`` (both
    :func:`stripcoef.diagnose.fit._evaluate`'s records on the same windows), the candidate
    adding ``n_params`` free parameters (at least 1): ``{"statistic"`` (:math:`\Lambda_{eff}`),
    ``"p_value"`` (:math:`\chi^2_k`), ``"dof"``, ``"windows"``, ``"effective_windows"``,
    ``"rho_residual"``, ``"rho_effect"``, ``"held_out_p_value"`` (the paired
    Diebold-Mariano test, recorded only)} (module docstring)."""
    e0 = np.asarray(ref_ev["full"]["resid"], float)
    e1 = np.asarray(ev["full"]["resid"], float)
    if e0.shape != e1.shape:
        raise ValueError(f"residuals on different windows: {e0.size} and {e1.size}")
    n = e0.size
    k = max(int(n_params), 1)
    rss0, rss1 = float(e0 @ e0), float(e1 @ e1)
    lam = n * math.log(rss0 / rss1) if rss1 > 0.0 and rss0 > 0.0 else 0.0
    rho_e, rho_g = _lag1(e0), _lag1(e0 - e1)
    frac = effective_fraction(rho_e, rho_g)
    stat = max(lam * frac, 0.0)
    dm = diebold_mariano(np.asarray(ev["held_out_resid"], float) ** 2,
                         np.asarray(ref_ev["held_out_resid"], float) ** 2)
    return {"statistic": float(stat), "p_value": float(chi2.sf(stat, k)), "dof": k,
            "windows": int(n), "effective_windows": float(n * frac),
            "rho_residual": rho_e, "rho_effect": rho_g,
            "held_out_p_value": float(dm["p_value"])}


def family_level(n_dofs: int, alpha: float = ALPHA) -> float:
    """The family-wise level of one DOF's step [-]: ``alpha`` over the diagnosed DOFs
    (Bonferroni; module docstring)."""
    return float(alpha) / max(int(n_dofs), 1)


def judge_family(trials: list, n_dofs: int = 1, alpha: float = ALPHA) -> None:
    r"""Holm-adjust the tests of one step's candidates ``trials`` (the records of
    :func:`~stripcoef.diagnose.select._judge`, each with ``evidence`` from
    :func:`step_test`) at level :func:`family_level`, in place: each test gets
    ``p_adjusted``, ``level`` and ``candidates``; a significant candidate whose adjusted
    p-value is above the level is made not significant, with the reason."""
    tested = [t for t in trials if t.get("evidence") is not None]
    if not tested:
        return
    level = family_level(n_dofs, alpha)
    p = [t["evidence"]["p_value"] for t in tested]
    adjusted = holm([x if math.isfinite(x) else 1.0 for x in p])
    for t, q in zip(tested, adjusted):
        ev = {**t["evidence"], "p_adjusted": float(q), "level": level,
              "candidates": len(tested)}
        t["evidence"] = ev
        if t["significant"] and not q <= level:
            t["rejected_because"] = list(t["rejected_because"]) + [
                f"not beyond chance on {ev['effective_windows']:.0f} effective windows of "
                f"{ev['windows']} (likelihood ratio {ev['statistic']:.1f}, p = "
                f"{ev['p_value']:.2g}, Holm-adjusted over {len(tested)} candidates "
                f"{q:.2g} > {level:.2g})"]
            t["significant"] = False
            t["_only_evidence"] = True      # every other gate passed


def supported(t: dict, n_candidates: int, n_dofs: int = 1, alpha: float = ALPHA) -> bool:
    """Whether a record judged outside its step's family (a member of a joint pair judged
    against its partner alone, :func:`~stripcoef.diagnose.select._judge_pair`) passes its
    test at the Bonferroni level of the step's ``n_candidates`` and the DOFs."""
    test = t.get("evidence")
    if test is None:
        return True
    level = family_level(n_dofs, alpha) / max(int(n_candidates), 1)
    return math.isfinite(test["p_value"]) and test["p_value"] <= level
