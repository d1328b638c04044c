r"""The thrusters' gains fitted again beside a water current the diagnosis found (issue 33;
option :attr:`~stripcoef.diagnose.settings.DiagnoseSettings.gains_beside_current`).

A whole-log diagnosis fits the per-thruster gains (:mod:`.gains`) first, on the prior's
window residual, before any effect is selected. A water current acts in every DOF through
the relative velocity :math:`\nu_r = \nu - [R^T V_c; 0]` (Fossen 2011, eq. 10.1), a force
that turns with the heading; the gains' joint fit has no such regressor, so when the log
holds a current the gains take the part of its force that their contrasts can imitate: the
omitted-variable bias of a least-squares fit, :math:`E[\hat a] = a + (G^T G)^{-1} G^T F_c`
for the omitted force :math:`F_c` (Greene 2012, Econometric Analysis, 7th ed., sec. 4.3.2;
Seber & Lee 2003, Linear Regression Analysis, sec. 9.2). The current the DOFs then find is
judged beside gains that already hold part of it (the issue-33 real-style current log,
seed 9: the gained prior simulates the validation part better than the prior in every DOF,
the current added to it worse in five of six, and the held-out part worse than the prior in
every DOF: ``benchmarks/data/real33_trace.md``).

With the option, once the DOFs' shared current :math:`\hat V_c`
(:func:`stripcoef.diagnose.current.share_current`) is known the gains are fitted again on
the window residual of the prior *with that current* (its window forces subtracted, as a
calibrated model's effects are, :func:`stripcoef.effects.laws.effect_window_forces`): one
backfitting cycle of an additive model, each part refitted on the residual of the others
(Hastie & Tibshirani 1990, Generalized Additive Models, sec. 4.4; Breiman & Friedman 1985).
They are validated as before (:func:`stripcoef.diagnose.gains.validated`) against the prior
with the current, and the DOFs are diagnosed again on the prior with the new gains, where
the current is selected, shared and validated like any effect: nothing of the first pass
is written but the gains' values.

**Mode** ``"joint"``. Held at the DOFs' value, the current was itself found beside the
biased gains, and its error stays in the refitted gains. In this mode the current's two
components are parameters of the gains' joint fit, free (no prior) and common to every DOF,
their columns the derivatives of the current's window force at the DOFs' value
(:func:`current_columns`; one Gauss-Newton step of the joint least squares, Seber & Wild
1989, sec. 2.1). They are profiled out of the gains' information with the calibration
(the Schur complement, :func:`stripcoef.diagnose.gains._information`), so the gains'
likelihood-ratio test and the combinations the log determines are those *beside a free
current*: a combination the current's columns span is not identified apart from it
(Rothenberg 1971, Econometrica 39, 577-591, Theorem 1, the rule of
:func:`stripcoef.diagnose.crossscale.refitted_z`) and stays at the prior. And the gains so
fitted are the current's fitted partner (as a DOF's effects are its calibration's,
:func:`stripcoef.diagnose.validate.partners`): they were validated with the current in the
model, so when the second pass's validation removes the current from every DOF (or no DOF
selects it) they are not written without it, and the first pass (its gains, fitted
without a current, and its steps, validated as before) is the diagnosis
(:func:`current_kept`).

**Mode** ``"test"``. The two explanations are compared instead of combined. A current is
constant in the world frame, so in the body frame it turns with the heading,
:math:`u_c = V_c\cos(\beta_c - \psi)`, :math:`v_c = V_c\sin(\beta_c - \psi)` (Fossen 2011,
sec. 10.3, eq. 10.34-10.35), while a thruster's gain scales its own thrust whatever the
heading. Where the log turns the two have different regressors, and which one the log holds
is a choice between two non-nested models fitted on the same window residual of the prior,
each with the DOFs' joint calibration (:func:`explain`): *gains* (the contrasts of
:mod:`.gains`, fitted without a current, as the first pass did) against *current* (its two
components free, the thrusters at their maps). Vuong's (1989, Econometrica 57, 307-333)
likelihood-ratio statistic :math:`z = (\sum_t \ell_{C,t} - \ell_{G,t} - \tfrac{p_C - p_G}{2}
\ln n) / (\sqrt{n}\,\hat\omega)` (his eq. 5.6 with the Schwarz correction of sec. 5, the
windows' log-densities at each model's maximum-likelihood noise levels, :math:`\hat\omega^2`
their difference's long-run variance, Newey & West 1987 with the lag of Newey & West 1994,
since windows of one closed-loop log are serially correlated) is N(0, 1) when the two are
equally close to the truth: :math:`|z|` beyond the two-sided ALPHA point names one. Where
the log does not turn, the current's columns lie in the span of the gains' (the current's
variance inflation beside the gains, :math:`1/\rho_{min}` of the generalised eigenvalues of
its information with and without the contrasts profiled out, above :data:`MAX_VIF`): the two
are not identified apart (Rothenberg 1971, Theorem 1) and no test can choose. A choice for
the gains keeps the first pass. A choice for the current is followed by the nested question,
whether gains are there beside it: the contrasts fitted with the current free (as mode
``"joint"``) must raise the log-likelihood by more than the Schwarz (1978, Ann. Stat. 6,
461) penalty, half their determined combinations times ln n; if so mode ``"joint"`` runs,
else the gains are withdrawn. No choice, or no identification, withdraw them too (the
prior's maps); withdrawn, the DOFs are diagnosed again on the prior, where the current is
selected and validated like any effect. The gains' record says which and why. Measured on
the real-style current log (``benchmarks/data/real33e_trace.md``): the log turns through
1500-2600 deg, the current is identified apart (VIF 1.0) and chosen (z 19.4 and 8.3 on
seeds 7 and 21), and the gains beside it pass the Schwarz penalty, so the rows equal mode
``"joint"``'s (seed 7 28 -> 30 of 44 cells, seed 21 34 -> 34; a fresh seed's current log 2
-> 4 of 12). Without the nested step seed 21 lost 6 cells (the truth has gains too). Off by
default for that reason: where it differs from ``"joint"`` it was not shown to help.

Depends on: diagnose.gains, diagnose.gaingate, diagnose.heldout, diagnose.settings, diagnose.compare, effects,
model.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from stripcoef.conventions import DOF
from stripcoef.diagnose.gaingate import validate_gains
from stripcoef.diagnose.gains import fit_thruster_gains
from stripcoef.diagnose.heldout import long_run_variance
from stripcoef.effects.laws import model_window_data

#: The effect whose force the gains' first fit omitted.
CURRENT = "current"
#: :attr:`~stripcoef.diagnose.settings.DiagnoseSettings.gains_beside_current`'s mode that
#: fits the current free beside the gains (:func:`current_columns`); ``True`` holds it at the
#: value the DOFs found.
JOINT = "joint"
#: :attr:`~stripcoef.diagnose.settings.DiagnoseSettings.gains_beside_current`'s mode that
#: tests the gains against the current as two explanations of the same residual
#: (:func:`explain`).
TEST = "test"
#: The largest variance inflation of the current's components beside the gains' contrasts
#: for which they are identified apart [-]: the rule of thumb of Marquardt (1970,
#: Technometrics 12, 591-612) that Kutner, Nachtsheim, Neter & Li (2005, Applied Linear
#: Statistical Models, 5th ed., sec. 10.5) give, a VIF above 10 marking collinearity that
#: unduly influences the estimates.
MAX_VIF = 10.0


def found_current(per: dict) -> dict | None:
    """The parameters (``current_north``, ``current_east`` [m/s]) of the current a
    diagnosis's DOFs selected (:class:`~stripcoef.diagnose.result.DofResult` per DOF, after
    :func:`~stripcoef.diagnose.current.share_current`: one value in every DOF), or None."""
    for r in per.values():
        for s in r.steps:
            if s.effect == CURRENT:
                p = s.final_parameters or s.parameters
                return {"current_north": float(p["current_north"]),
                        "current_east": float(p["current_east"])}
    return None


def with_found_current(prior, per: dict):
    """``prior`` with the current of :func:`found_current` as an effect of all six DOFs
    (``dof: all``), or None when no DOF selected one."""
    vc = found_current(per)
    if vc is None:
        return None
    return prior.with_effects({"name": CURRENT, "dof": "all", "parameters": vc})


#: Step of the central differences of the current's window force [m/s]: a thousandth of a
#: typical 0.1 m/s pool current; the force is smooth in V_c (quadratic drag and Munk terms
#: of the relative velocity), so the step's truncation error is of order its square.
CURRENT_STEP = 1e-4


def current_columns(data, vc: dict, dofs) -> dict:
    r"""DOF index -> (windows, 2): the derivative of the current's window force
    :math:`\partial \bar F_i / \partial (V_N, V_E)` at ``vc`` [N or N m per m/s]
    (:meth:`~stripcoef.effects.hydrodynamic.Current.window_force`, central differences of
    :data:`CURRENT_STEP`): the current's columns in the gains' joint fit, linearised about
    the value the DOFs found (Gauss-Newton, one step: Seber & Wild 1989, sec. 2.1)."""
    from stripcoef.effects.laws import get_effect

    eff = get_effect(CURRENT)
    keys = ("current_north", "current_east")
    out = {}
    for i in dofs:
        cols = []
        for k in keys:
            up, down = dict(vc), dict(vc)
            up[k] += CURRENT_STEP
            down[k] -= CURRENT_STEP
            cols.append((eff.window_force(data, up, i) - eff.window_force(data, down, i))
                        / (2.0 * CURRENT_STEP))
        out[i] = np.column_stack(cols)
    return out


def current_kept(per: dict, exclude) -> bool:
    """Whether some DOF of ``per`` (:class:`~stripcoef.diagnose.result.DofResult` per DOF)
    selected the current and the validation kept it (not in ``exclude``,
    :func:`~stripcoef.diagnose.validate.validate_changes`' removed changes)."""
    return any(s.effect == CURRENT and not s.not_determined
               and ("effect", d, CURRENT) not in exclude
               for d, r in per.items() for s in r.steps)


def withdrawn(gains, first):
    """The first pass's gains record (``first``, a
    :class:`~stripcoef.diagnose.gains.ThrusterGains` or None) with why the gains fitted
    beside the current (``gains``) were withdrawn (module docstring, mode ``"joint"``)."""
    why = ("; the gains fitted beside the current (" + ", ".join(
        f"{g:.4g}" for g in gains.gains) + ") withdrawn with it: the validation removed "
        "the current they were fitted beside (their fitted partner) or no DOF selected it")
    return None if first is None else replace(first, reason=first.reason + why)


def refit_beside(data_f, found, prior, data0, train_log, val_log, dofs, excited, settings,
                 budget, beside: str, shared=None, validate: bool = True):
    """``(gains, model, data)``: the thrusters' gains fitted again on ``data_f``, the window
    data of ``found`` (the prior with an effect the DOFs found: a current here, the
    thrusters' lag or delay in :mod:`.timinggains`), over ``dofs`` (``shared``: columns
    free beside them, as :func:`~stripcoef.diagnose.gains.fit_thruster_gains`), validated
    against ``found`` unless not ``validate``; ``model`` the prior with them when kept (else
    ``prior``) and ``data`` its window data (``data0``, the prior's, when not kept). The
    gains' record says what they were fitted ``beside``. ``gains`` None when the fit is not
    possible (as :func:`~stripcoef.diagnose.gains.fit_thruster_gains`)."""
    gains = fit_thruster_gains(data_f, dofs, settings, excited=excited, budget=budget,
                               shared=shared)
    if gains is None:
        return None, prior, data0
    if validate:
        gains = validate_gains(gains, val_log, found, dofs, settings)
    gains = replace(gains, reason=gains.reason + f"; fitted beside {beside}, the DOFs "
                    "diagnosed again on them")
    if not gains.applied:
        return gains, prior, data0
    model = gains.model(prior)
    return gains, model, model_window_data(train_log, model, window=settings.window)


def refit_gains(water, prior, data0, train_log, val_log, dofs, excited, settings, budget):
    """:func:`refit_beside` the current ``water`` holds (the prior with the current found),
    validated against ``water`` (:func:`~stripcoef.diagnose.gains.validated`); mode
    ``"joint"``: the current's columns free beside the gains."""
    data_c = model_window_data(train_log, water, window=settings.window)
    vc = water.effects[-1]["parameters"]
    shared = None
    if settings.gains_beside_current == JOINT:
        shared = (("current_north", "current_east"), current_columns(data_c, vc, dofs))
    return refit_beside(data_c, water, prior, data0, train_log, val_log, dofs, excited,
                        settings, budget, shared=shared,
                        beside=f"the current the DOFs found (north {vc['current_north']:.4g}, "
                               f"east {vc['current_east']:.4g} m/s)")


def _log_density(res) -> np.ndarray:
    """Per window, the Gaussian log-density of the DOFs' residuals ``res`` (windows, DOFs)
    at their maximum-likelihood noise levels [-]."""
    s2 = np.maximum(np.mean(res ** 2, axis=0), 1e-300)
    return np.sum(-0.5 * np.log(2.0 * np.pi * s2) - res ** 2 / (2.0 * s2), axis=1)


def _residuals(blocks, x, gain_part=None) -> np.ndarray:
    """(windows, blocks): each block's residual at the joint estimate ``x``."""
    out = []
    for _, y, cols, idx, g, _ in blocks:
        r = y - cols @ x[idx]
        if gain_part is not None:
            r = r - g @ gain_part
        out.append(r)
    return np.column_stack(out)


def _vif(lam, kc, cur) -> float:
    """The current's largest variance inflation beside the contrasts (:data:`MAX_VIF`):
    ``lam`` the data-only normal equations (calibration with the current at ``cur``, then
    the contrasts from ``kc``); the calibration profiled out, 1 / the smallest generalised
    eigenvalue of the current's information with the contrasts profiled out too against
    without [-]."""
    from scipy.linalg import eigh

    n = lam.shape[0]
    cal = [k for k in range(kc) if k not in cur]
    rest = list(cur) + list(range(kc, n))
    s = (lam[np.ix_(rest, rest)] - lam[np.ix_(rest, cal)]
         @ np.linalg.pinv(lam[np.ix_(cal, cal)]) @ lam[np.ix_(cal, rest)])
    m = len(cur)
    fixed = 0.5 * (s[:m, :m] + s[:m, :m].T)
    free = fixed - s[:m, m:] @ np.linalg.pinv(s[m:, m:]) @ s[m:, :m]
    try:
        rho = eigh(0.5 * (free + free.T), fixed, eigvals_only=True)
    except np.linalg.LinAlgError:
        return float("inf")
    return float(1.0 / max(float(np.min(rho)), 1e-300))


def _gains_beside(blocks, sd, sigmas, p_basis, gain_sd, res_c):
    r"""``(gain, k)``: the log-likelihood the gains' contrasts add beside the free current
    (the blocks' shared columns), :math:`\sum_t \ell_{GC,t} - \ell_{C,t}` at each model's
    maximum-likelihood noise levels (``res_c`` the current's residuals), and the number of
    combinations the log determines beside it (:data:`MIN_INFORMATION_RATIO` of
    :mod:`.gains`) [-]."""
    from stripcoef.diagnose.gains import NOISE_PASSES, _information, _map, _normal_equations
    from stripcoef.diagnose.settings import MIN_INFORMATION_RATIO

    sig = list(sigmas)
    for _ in range(NOISE_PASSES):
        lam, rhs, kc = _normal_equations(blocks, sd, sig, p_basis)
        x = _map(lam, rhs, kc, gain_sd)
        res = _residuals(blocks, x, p_basis @ x[kc:])
        sig = [max(float(np.sqrt(np.mean(r ** 2))), 1e-12) for r in res.T]
    f, _ = _information(lam, rhs, kc)
    eig = np.linalg.eigvalsh(f)
    k = int(np.sum(gain_sd * np.sqrt(np.maximum(eig, 0.0)) >= MIN_INFORMATION_RATIO))
    return float(np.sum(_log_density(res)) - np.sum(_log_density(res_c))), k


def explain(gains, water, data0, train_log, dofs, excited, settings) -> dict:
    """Which explanation of the prior's window residual the log holds (module docstring,
    mode ``"test"``): ``gains`` (the first pass's applied
    :class:`~stripcoef.diagnose.gains.ThrusterGains`, fitted on ``data0``, the prior's window
    data) or the current of ``water`` (the prior with the current the DOFs found), each
    beside the DOFs' joint calibration. A dict: ``choice`` (``"gains"``, ``"current"``,
    ``"not distinguished"`` or ``"not identified"``), ``z`` (Vuong's statistic, > 0 for the
    current), ``critical``, ``vif``, ``heading_span_deg``, ``windows``, ``parameters``, the
    current refitted without gains (``current_north``, ``current_east`` [m/s]) and
    ``text``."""
    from scipy.stats import norm

    from stripcoef.diagnose.compare import ALPHA
    from stripcoef.diagnose.gains import (NOISE_PASSES, _blocks, _map, _normal_equations,
                                          _with_shared, gain_contrasts)

    # the gains: the first pass's fit again (its noise levels, its prior sd)
    b0, _, sd0 = _blocks(data0, dofs, settings, excited)
    sig0 = [gains.noise.get(DOF[b[0]], 1.0) for b in b0]
    p_basis = gain_contrasts(data0.alloc, dofs, settings, identified=(b0, sd0, sig0))
    lam, rhs, kc = _normal_equations(b0, sd0, sig0, p_basis)
    x = _map(lam, rhs, kc, gains.prior_sd)
    res_g = _residuals(b0, x, p_basis @ x[kc:])
    p_g = sum(bool(c["determined"]) for c in gains.combinations)
    # the current: its components free (linearised about the DOFs' value), no gains
    vc = dict(water.effects[-1]["parameters"])
    data_c = model_window_data(train_log, water, window=settings.window)
    bc, names_c, sdc = _blocks(data_c, dofs, settings, excited)
    keys = ("current_north", "current_east")
    bc, names_c, sdc = _with_shared(bc, names_c, sdc, keys,
                                    current_columns(data_c, vc, [b[0] for b in bc]))
    cur = [len(names_c) - 2, len(names_c) - 1]
    sig = list(sig0)
    for _ in range(NOISE_PASSES):
        lam_c, rhs_c, kcc = _normal_equations(bc, sdc, sig, p_basis, with_gains=False)
        xc = np.linalg.lstsq(lam_c, rhs_c, rcond=None)[0]
        res_c = _residuals(bc, xc)
        sig = [max(float(np.sqrt(np.mean(r ** 2))), 1e-12) for r in res_c.T]
    refit = {k: float(vc[k] + xc[c]) for k, c in zip(keys, cur)}
    # identification: the current beside the contrasts, data only (no prior on them)
    lam_i, _, kci = _normal_equations(bc, sdc, sig, p_basis)
    vif = _vif(lam_i, kci, cur)
    psi = np.unwrap(np.asarray(data0.eta[:, 5], float))
    span = float(np.degrees(np.ptp(psi)))
    n = res_g.shape[0]
    d = _log_density(res_c) - _log_density(res_g)
    p_c = len(keys)
    lr = float(np.sum(d)) - 0.5 * (p_c - p_g) * np.log(n)
    omega = np.sqrt(max(long_run_variance(d), 0.0) * n)
    z = lr / omega if omega > 0 else 0.0
    crit = float(norm.ppf(1.0 - ALPHA / 2.0))
    if not vif <= MAX_VIF:
        choice = "not identified"
        why = (f"the current's variance inflation beside the gains' contrasts {vif:.3g} > "
               f"{MAX_VIF:g} (the log's heading spans {span:.0f} deg): a current and a gain "
               "change are not identified apart (Rothenberg 1971); the prior's gains kept")
    elif z > crit:
        # nested: the gains beside the free current (Schwarz 1978: their log-likelihood
        # gain against half their determined combinations times ln n)
        gain_ll, k_b = _gains_beside(bc, sdc, sig, p_basis, gains.prior_sd, res_c)
        both = gain_ll > 0.5 * k_b * np.log(n)
        choice = "current and gains" if both else "current"
        why = (f"Vuong z = {z:.3g} > {crit:.3g}: the current explains the residual better; "
               f"the gains beside it raise the log-likelihood by {gain_ll:.3g} against the "
               f"Schwarz penalty {0.5 * k_b * np.log(n):.3g} ({k_b} combinations determined "
               "beside the current): " + ("they are fitted again beside it (mode 'joint')"
                                          if both else "the prior's gains kept"))
    elif z < -crit:
        choice = "gains"
        why = f"Vuong z = {z:.3g} < -{crit:.3g}: the gains explain the residual better"
    else:
        choice = "not distinguished"
        why = (f"Vuong |z| = {abs(z):.3g} <= {crit:.3g}: neither explains the residual "
               "better; the prior's gains kept")
    text = (f"gains (p = {p_g}) vs the current (p = {p_c}) as explanations of the prior's "
            f"residual over {n} windows, heading span {span:.0f} deg, VIF {vif:.3g}: {why}")
    return {"choice": choice, "z": float(z), "critical": crit, "vif": vif,
            "heading_span_deg": span, "windows": int(n), "parameters": (p_g, p_c),
            **refit, "text": text}


def tested(gains, water, data0, train_log, dofs, excited, settings):
    """``(gains, keep)``: mode ``"test"`` (:func:`explain`) on the first pass's significant
    ``gains`` (applied, or removed by their validation or bound); ``keep`` True when they
    stay (the log chose them), :data:`JOINT` when the log holds the current and gains beside
    it (fitted again beside the free current, mode
    ``"joint"``, the first pass restored if the current is removed), else False: they are
    withdrawn (not applied, the record says why) and the DOFs are to be diagnosed again on
    the prior."""
    out = explain(gains, water, data0, train_log, dofs, excited, settings)
    if out["choice"] == "gains":
        return replace(gains, reason=gains.reason + "; chosen over the current the DOFs "
                       "found: " + out["text"]), True
    if out["choice"] == "current and gains":
        return replace(gains, reason=gains.reason + "; tested beside the current the DOFs "
                       "found: " + out["text"]), JOINT
    return replace(gains, applied=False, reason=gains.reason + "; not kept beside the "
                   "current the DOFs found: " + out["text"]), False
