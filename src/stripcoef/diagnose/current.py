r"""One water current for the whole vehicle: the earth-frame current fitted jointly over every
diagnosed DOF, then every DOF's calibration conditioned on it (issue 33).

A current is one vector of the water, :math:`V_c = [V_N, V_E, 0]` [m/s] in NED (constant
here), that every DOF sees through the rotation to the body frame: the relative velocity
:math:`\nu_r = \nu - [R^T(\Theta) V_c; 0]` (Fossen 2011, sec. 8.3 and 10.3, eq. 10.1;
:class:`~stripcoef.effects.hydrodynamic.Current`). Fitted per DOF, each DOF's fit invents its
own (the issue-33 real-style current log, seed 58: surge and sway each a different current).
:func:`share_current` replaces them by one, the minimum of the joint cost of a
multiresponse model (Seber & Wild 1989, Nonlinear Regression, ch. 11):

.. math:: S(V_c) = \sum_i \lVert W_i\,(y_i - H_i(V_c)\,\hat\theta_i(V_c)) \rVert^2

over every diagnosed DOF i (the water's drag and added-mass forces act on :math:`\nu_r` in
all six: the Munk moments of :math:`C_A(\nu_r)\nu_r` in roll, pitch and yaw, the heave
drag once the vehicle pitches; where the DOF's selection did not name the current, its
force alone, :class:`_Water`), each DOF's window residual whitened by its own noise level
:math:`\sigma_i` and its calibration's band priors (:func:`stripcoef.diagnose.fit._solve`),
each DOF's linear parameters :math:`\hat\theta_i` profiled (variable projection, Golub &
Pereyra 1973). The prior of the
current is the effect's own law (:meth:`Current.max_magnitude`): a current no faster than
the log's 95th-percentile horizontal speed; a minimum outside that disk is replaced by the
minimum on its edge and reported at the bound.

Its uncertainty: the Gauss-Newton covariance :math:`C = (J^T J)^{-1}` of the stacked
whitened residual (S is minus twice the log likelihood; Seber & Wild 1989, sec. 2.1), which
holds when the model is right, widened by :math:`\max(1, \lambda_{max}(C^{-1} C_J))` so that
it holds the block jackknife's :math:`C_J` in every direction (:func:`block_jackknife`,
Kunsch 1989: refits without each block of windows, which need no right model); both are
recorded. The speed's :math:`s_{|V|} = \sqrt{g^T C g}`, :math:`g = V_c/|V_c|` (delta
method). The model writes the current once (``dof: all``,
:func:`stripcoef.diagnose.calibrate.calibrated_model`).

Whether the log supports it at all, counted once: the likelihood ratio of "no current" (the
current's released drag kept, :func:`stripcoef.diagnose.compare.posterior_cost`) against the
one shared current, :math:`\Lambda = \sum_i [C_i(0) - C_i(\hat V_c)]`, is
:math:`\chi^2_2` under the null hypothesis (Wilks 1938): the two components are two
parameters of the whole model, not two per DOF. When it does not reject at
:data:`~stripcoef.diagnose.compare.ALPHA`, the current each DOF found is one the other DOFs
refute, and it is removed from every DOF (the DOF's candidates say why).

Depends on: effects, diagnose.fit, diagnose.compare, diagnose.settings.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from scipy.optimize import least_squares
from scipy.stats import chi2

from stripcoef.diagnose.compare import ALPHA, posterior_cost
from stripcoef.diagnose.fit import _solve, grid_minimum, refit
from stripcoef.diagnose.settings import N_BLOCKS
from stripcoef.effects.hydrodynamic import Current

#: The effect shared: the water current (:class:`~stripcoef.effects.hydrodynamic.Current`).
CURRENT = "current"
#: Its parameters, in the order of the effect's nonlinear parameters.
KEYS = ("current_north", "current_east")


class _Water(Current):
    """The shared current as a term of a DOF whose selection did not name it: its force
    (:meth:`Current.offset`, in any of the six DOFs) and the relative velocity the DOF's
    calibration acts on, releasing no prior coefficient (the selection's current releases
    D_L and D_Q to judge its own signature; here the current is already judged)."""

    nuisance_names = ()
    dofs = tuple(range(6))

    def design(self, data, dof, hyper=None):
        return self.own_design(data, dof, hyper)


#: The one instance (an effect is immutable; a fit's terms are cached by its identity).
WATER = _Water()


def _with_current(cfg, eff, vc):
    """``cfg`` with the current at ``vc`` = (V_N, V_E) [m/s]: its term's value replaced, or
    the term appended (a new configuration; ``eff``: the term appended)."""
    terms = list(cfg.terms)
    at = [k for k, (e, _) in enumerate(terms) if e.name == CURRENT]
    value = np.asarray(vc, float).copy()
    if at:
        terms[at[0]] = (terms[at[0]][0], value)
    else:
        terms.append((eff, value))
    return cfg.with_terms(terms)


def _without_current(cfg):
    """``cfg`` with the current's term taken out (a new configuration)."""
    return cfg.with_terms([t for t in cfg.terms if t[0].name != CURRENT])


def _stacked(cfgs: dict, sigmas: dict, eff, vc, mask=None) -> np.ndarray:
    """The whitened MAP residuals (data and prior rows) of every DOF's configuration with
    the current at ``vc``, stacked: :math:`S(V_c)` is its squared norm [-]; ``mask``: the
    windows used (all when None)."""
    out = []
    for d, cfg in cfgs.items():
        c = _with_current(cfg, eff, vc)
        y, H, sd = c.design()
        if mask is not None:
            y, H = y[mask], H[mask]
        out.append(_solve(y, H, sd, sigmas[d], c.lower(), c.m_info(), c.upper(),
                          with_cov=False)[2])
    return np.concatenate(out)


def joint_current(cfgs: dict, sigmas: dict, eff, starts, vmax: float) -> dict:
    r"""The one current minimising :math:`S(V_c)` (module docstring) over the DOFs of
    ``cfgs`` (DOF -> configuration; ``sigmas``: DOF -> noise level [N or N m]), within
    :math:`|V_c| \le` ``vmax`` [m/s]: Levenberg-Marquardt from each of ``starts`` (as the
    per-DOF profile, :func:`stripcoef.diagnose.fit._profile_hyper`; to 1e-6 of 0.1 m/s),
    the best kept; a
    minimum outside the disk replaced by the minimum on its edge (a bounded scalar search
    of the direction, :func:`stripcoef.diagnose.fit.grid_minimum`). Returns ``value`` (2,),
    ``cov`` (2, 2) [m^2/s^2], ``cost`` and ``at_bound`` ('' or ``"upper"``)."""
    def vec(v):
        return _stacked(cfgs, sigmas, eff, v)

    best = None
    for start in starts:
        sol = least_squares(vec, np.asarray(start, float), method="lm", x_scale=0.1,
                            xtol=1e-6)
        if best is None or sol.cost < best.cost:
            best = sol
    value, at_bound = np.asarray(best.x, float), ""
    if np.hypot(*value) > vmax:
        def on_edge(angle):
            return float(np.sum(vec(vmax * np.array([math.cos(angle), math.sin(angle)])) ** 2))
        a0 = math.atan2(value[1], value[0])
        angle, _ = grid_minimum(on_edge, a0 + np.linspace(-math.pi, math.pi, 25))
        value, at_bound = vmax * np.array([math.cos(angle), math.sin(angle)]), "upper"
    r0 = vec(value)
    jac = np.empty((r0.size, 2))
    for k in range(2):
        step = 1e-4 * max(1.0, abs(value[k]))
        hp, hm = value.copy(), value.copy()
        hp[k] += step
        hm[k] -= step
        jac[:, k] = (vec(hp) - vec(hm)) / (2 * step)
    cov = np.linalg.pinv(jac.T @ jac)
    return {"value": value, "cov": cov, "cost": float(r0 @ r0), "at_bound": at_bound}


def block_jackknife(cfgs: dict, sigmas: dict, eff, value) -> np.ndarray:
    r"""The block-jackknife covariance of the joint current (2, 2) [m^2/s^2]: the joint fit
    redone without each of the :data:`~stripcoef.diagnose.settings.N_BLOCKS` contiguous
    blocks of windows of the blocked cross-validation,
    :math:`C_J = \frac{g-1}{g}\sum_b (\hat V_{(b)} - \bar V)(\hat V_{(b)} - \bar V)^T`
    (Kunsch 1989, the jackknife for dependent data). Each refit is one Gauss-Newton step from
    the joint value on the reduced data, every DOF's linear parameters profiled again there
    (:math:`\hat V_{(b)} = \hat V - (J_b^T J_b)^{-1} J_b^T r_b`, forward differences; the
    jackknife's linear approximation, whose difference from the full refit is of second
    order in the shift; Efron & Tibshirani 1993, ch. 11). Unlike :math:`(J^TJ)^{-1}` it does not
    assume the model right: a current that different parts of the log set differently
    (coefficients the log keeps at the prior, a thrust map off) shows in it."""
    n = next(iter(cfgs.values())).data.n_windows
    folds = np.array_split(np.arange(n), N_BLOCKS)
    value = np.asarray(value, float)
    got = []
    for fold in folds:
        mask = np.ones(n, bool)
        mask[fold] = False
        r0 = _stacked(cfgs, sigmas, eff, value, mask)
        jac = np.empty((r0.size, 2))
        for k in range(2):
            step = 1e-4 * max(1.0, abs(value[k]))
            hp = value.copy()
            hp[k] += step
            jac[:, k] = (_stacked(cfgs, sigmas, eff, hp, mask) - r0) / step
        got.append(value - np.linalg.pinv(jac.T @ jac) @ (jac.T @ r0))
    got = np.array(got)
    dev = got - got.mean(axis=0)
    return (len(folds) - 1) / len(folds) * dev.T @ dev


def joint_test(cfgs: dict, sigmas: dict, eff, vc) -> dict:
    r"""The likelihood ratio of "no current" against the one current ``vc`` over the DOFs
    of ``cfgs``: :math:`\Lambda = \sum_i [C_i(0) - C_i(V_c)]`, C the MAP objective at each
    DOF's noise level (:func:`stripcoef.diagnose.compare.posterior_cost`; the current's
    released drag in both), its p-value from :math:`\chi^2_2` (Wilks 1938): the current's
    two components counted once for the whole model."""
    lam = sum(posterior_cost(_with_current(c, eff, (0.0, 0.0)), sigmas[d])
              - posterior_cost(_with_current(c, eff, vc), sigmas[d]) for d, c in cfgs.items())
    lam = max(float(lam), 0.0)
    return {"statistic": lam, "dof": len(KEYS), "p_value": float(chi2.sf(lam, len(KEYS))),
            "level": ALPHA}


def share_current(per: dict, fits: dict) -> tuple[dict, dict]:
    """``(per, fits)`` (new dictionaries) with the current that the selection found in some
    DOF fitted once (:func:`joint_current`) over every diagnosed DOF it acts in, and each of
    those DOFs' fit redone with it (the effect added where the selection had not added it:
    a step marked not significant on its own, its ``signature`` saying it is shared). Every
    current step records the shared fit (``comparison.shared_current``: value, covariance,
    speed and its uncertainty, the DOFs, the joint test). When the joint test
    (:func:`joint_test`) does not reject "no current", the current is removed from every
    DOF and each DOF's ``candidates`` says why. A diagnosis of one DOF that found a current
    is left as it is (the joint fit of one DOF is its own fit)."""
    have = [d for d, f in fits.items() if any(e.name == CURRENT for e, _ in f.config.terms)]
    if not have:
        return per, fits
    eff = next(e for e, _ in fits[have[0]].config.terms if e.name == CURRENT)
    targets = list(fits)        # every DOF sees the water: D and C_A act on nu_r in all six
    if len(targets) < 2:
        return per, fits
    per, fits = dict(per), dict(fits)
    cfgs = {d: fits[d].config for d in targets}
    sigmas = {d: float(fits[d].evaluation["full"]["sigma"]) for d in targets}
    data = cfgs[targets[0]].data
    vmax = float(eff.max_magnitude(data))
    own = [np.asarray(h, float) for d in have for e, h in cfgs[d].terms if e.name == CURRENT]
    starts = [np.mean(own, axis=0)]     # the DOFs' own currents lie close: their mean
    fit = joint_current(cfgs, sigmas, WATER, starts, vmax)
    value = fit["value"]
    jack = block_jackknife(cfgs, sigmas, WATER, value)
    # the band reported: the model's (J^T J)^-1, widened (never narrowed) until it holds
    # the block jackknife's in every direction (its largest generalized eigenvalue)
    gn = fit["cov"]
    widen = max(1.0, float(np.max(np.real(np.linalg.eigvals(np.linalg.pinv(gn) @ jack)))))
    cov = widen * gn
    sd = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    speed = float(np.hypot(*value))
    g = value / speed if speed > 0 else np.zeros(2)
    speed_sd = float(math.sqrt(max(float(g @ cov @ g), 0.0)))
    test = joint_test(cfgs, sigmas, WATER, value)
    params = {k: float(v) for k, v in zip(KEYS, value)}
    std = {k: float(s) for k, s in zip(KEYS, sd)}
    record = {"current_north": params["current_north"], "current_east": params["current_east"],
              "std": std, "covariance": cov.tolist(),
              "covariance_gauss_newton": fit["cov"].tolist(),
              "covariance_block_jackknife": jack.tolist(), "widened_by": widen,
              "speed": speed, "speed_std": speed_sd,
              "speed_bound": vmax, "at_bound": fit["at_bound"], "dofs": list(targets),
              "selected_in": {d: {k: float(v) for k, v in zip(KEYS, h)}
                              for d, h in zip(have, own)},
              "joint_test": test,
              "description": "one earth-frame current (NED) [m/s] fitted jointly on "
                             + ", ".join(targets) + " (diagnose.current.share_current)"}
    if test["p_value"] > ALPHA:
        return _removed(per, fits, have, record)
    share = ", ".join(targets)
    for d in targets:
        cfg = _with_current(cfgs[d], WATER, value)
        before, ev = refit(fits, d, cfg)
        r = per[d]
        steps = list(r.steps)
        if d in have:
            steps = [replace(s, final_parameters=dict(params), std=dict(std),
                             comparison={**dict(s.comparison or {}), "shared_current": record})
                     if s.effect == CURRENT else s for s in steps]
        else:
            template = next(s for s in per[have[0]].steps if s.effect == CURRENT)
            gain = 1.0 - ev["held_out_error"] / max(before["held_out_error"], 1e-300)
            steps.append(replace(
                template, dof=d, parameters=dict(params), std=dict(std), released={},
                signature=(f"shared: the one earth-frame current, fitted jointly on {share} "
                           f"(selected alone in {', '.join(have)})"),
                mimics=None, band_excess=None, error_before=before["error"],
                error_after=ev["error"], held_out_error_before=before["held_out_error"],
                held_out_error_after=ev["held_out_error"], held_out_gain=float(gain),
                delta_bic=float(ev["bic"] - before["bic"]
                                + len(KEYS) * math.log(cfg.data.n_windows)),
                z=float(speed / speed_sd) if speed_sd > 0 else float("nan"),
                significant=False, rejected_because=(), alternatives=(),
                magnitude=speed, final_parameters=dict(params),
                comparison={"shared_current": record}))
        per[d] = replace(r, steps=tuple(steps), final_error=float(ev["error"]),
                         final_held_out_error=float(ev["held_out_error"]))
    return per, fits


def _removed(per: dict, fits: dict, have, record) -> tuple[dict, dict]:
    """``(per, fits)`` with the current taken out of every DOF that selected it (each DOF's
    fit redone without it, its step moved to ``candidates`` with the reason)."""
    test = record["joint_test"]
    why = (f"the one current fitted jointly on {', '.join(record['dofs'])} "
           f"({record['current_north']:.3g}, {record['current_east']:.3g}) m/s N, E is not "
           f"supported by them together: likelihood ratio {test['statistic']:.3g}, "
           f"p = {test['p_value']:.3g} > {ALPHA:g} (chi-squared, 2 degrees of freedom)")
    for d in have:
        _, ev = refit(fits, d, _without_current(fits[d].config))
        r = per[d]
        step = next(s for s in r.steps if s.effect == CURRENT)
        cand = {**step.to_dict(), "significant": False, "rejected_because": [why],
                "shared_current": record}
        per[d] = replace(r, steps=tuple(s for s in r.steps if s.effect != CURRENT),
                         candidates=tuple(r.candidates) + (cand,),
                         final_error=float(ev["error"]),
                         final_held_out_error=float(ev["held_out_error"]))
    return per, fits
