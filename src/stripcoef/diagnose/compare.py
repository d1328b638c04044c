r"""Non-nested comparison of competing effects of one selection step, and the joint fit of a
thrust scale with the effect it competes with (issue 33).

Two effects that explain the same window residual are two models that are not nested
(neither is a special case of the other): the best held-out error alone does not say which
the log supports, and a thrust scale, whose regressor the prior's inertia and drag
reproduce (:class:`~stripcoef.effects.thrust.ThrustEffectiveness`), takes part of any
force the residual holds. Each pair is compared in the comprehensive model that holds both
(Atkinson 1970; the J-test of Davidson & MacKinnon 1981 is its one-column form, and the
two coincide for one-column effects):

- :math:`H_A`: the current model plus effect A, :math:`H_B`: plus B, :math:`H_{AB}`: plus
  both, each fitted by the same MAP least squares (:func:`stripcoef.diagnose.fit._solve`:
  Gaussian band priors, the inertia change profiled on the noise-corrected cost);
- the statistic of "A is not needed" is the likelihood ratio of :math:`H_B` against
  :math:`H_{AB}`, :math:`\Lambda_A = C(H_B) - C(H_{AB})`, with :math:`C` the fit's
  :math:`-2\log` posterior (:func:`posterior_cost`) at the comprehensive model's noise
  level :math:`\sigma_{AB}`; under the null hypothesis it is :math:`\chi^2_k`, k the
  number of A's free parameters (Wilks 1938; a Gaussian band prior adds its own
  :math:`(\theta/s)^2` term to both fits and so is part of the test: the log's inertia
  information, the weighed rigid-body mass and the added-mass band, enters the thrust
  scale's statistic through the profiled inertia's prior);
- the p-values of every hypothesis tested in a step form one family, adjusted by Holm's
  step-down procedure (Holm 1979) at the stated level :data:`ALPHA`.

Outcomes of a pair (Davidson & MacKinnon 1981, sec. 2): A needed and B not -> A; B needed
and A not -> B (A only borrowed B's force); both needed -> both, fitted together (a thrust
gain and a drag both off); neither -> the log cannot tell them apart.

Depends on: diagnose.fit.
"""

from __future__ import annotations

import numpy as np
from scipy.stats import chi2

from stripcoef.diagnose.fit import _evaluate, _Nuisance, _profile_hyper, _solve

#: Family-wise significance level of the tests of one selection step (Holm 1979) [-]: the
#: conventional 5 %, stated, not fitted.
ALPHA = 0.05


def posterior_cost(cfg, sigma: float) -> float:
    r"""The MAP objective of configuration ``cfg`` at noise level ``sigma`` [N or N m]:
    :math:`C = |y - H\theta|^2/\sigma^2 + \sum_j (\theta_j/s_j)^2 - N (M + \mu)^2 v/\sigma^2`
    at its minimum (:func:`stripcoef.diagnose.fit._solve`: Tarantola 2005, eq. 3.37, for
    the band priors; Fuller 1987, sec. 2.2, for the noise correction of the profiled inertia
    change :math:`\mu`), i.e. :math:`-2\log` of the posterior up to a constant [-].
    The terms' nonlinear parameters are those stored in ``cfg`` (profiled by
    :func:`stripcoef.diagnose.fit._evaluate`)."""
    y, H, sd = cfg.design()
    m = cfg.m_info()
    theta, _, wres = _solve(y, H, sd, sigma, cfg.lower(), m, cfg.upper(), with_cov=False)
    cost = float(wres @ wres)
    if m is not None and len(m[0]):
        mu = float(np.sum(theta[list(m[0])]))
        cost -= y.size * (m[1] + mu) ** 2 * m[2] / sigma ** 2
    return cost


def n_free(cfg, eff, hyper) -> int:
    """The number of free parameters of effect ``eff`` in ``cfg``: its columns and its
    nonlinear parameters [-]."""
    cols = cfg.term(eff, hyper).cols.shape[1]
    return int(cols + (len(np.atleast_1d(hyper)) if eff.hyper and hyper is not None else 0))


def lr_test(full_cfg, full_ev, reduced_cfg, k: int) -> dict:
    r"""Likelihood-ratio test of the reduced configuration against the full one:
    :math:`\Lambda = C_{reduced} - C_{full}` at the full model's noise level
    (:func:`posterior_cost`), its p-value from :math:`\chi^2_k` (Wilks 1938)."""
    sigma = float(full_ev["full"]["sigma"])
    lam = max(posterior_cost(reduced_cfg, sigma) - posterior_cost(full_cfg, sigma), 0.0)
    return {"statistic": float(lam), "dof": int(k), "p_value": float(chi2.sf(lam, k))}


def holm(p_values) -> list:
    r"""Holm's (1979) step-down adjusted p-values: with :math:`p_{(1)} \le \dots \le p_{(m)}`,
    :math:`\tilde p_{(i)} = \max_{j \le i} \min(1, (m - j + 1) p_{(j)})`; hypothesis i is
    rejected at family-wise level :math:`\alpha` when :math:`\tilde p_i \le \alpha`."""
    p = np.asarray(list(p_values), float)
    m = p.size
    out = np.empty(m)
    running = 0.0
    for rank, i in enumerate(np.argsort(p, kind="stable")):
        running = max(running, min(1.0, (m - rank) * p[i]))
        out[i] = running
    return out.tolist()


def _profiled(cfg):
    """``cfg`` with its last term's nonlinear parameters profiled on every window when they
    are not set (:func:`stripcoef.diagnose.fit._profile_hyper`), a new configuration."""
    eff, hyper = cfg.terms[-1]
    if eff.hyper and hyper is None:
        h = _profile_hyper(cfg, np.ones(cfg.data.n_windows, bool))
        cfg = cfg.with_terms(list(cfg.terms[:-1]) + [(eff, h)])
    return cfg


def _without(cfg, member, other):
    """The reduced configuration of :func:`pair_tests`: ``cfg`` plus ``other`` (its
    nonlinear parameters profiled again) and, when ``member`` releases prior coefficients
    (:meth:`Effect.nuisance`), those released coefficients: the test is of the member's own
    force, as the single trial's reference (:func:`stripcoef.diagnose.select._judge`)."""
    terms = list(cfg.terms)
    if member.nuisance(cfg.data, cfg.dof) is not None:
        terms.append((_Nuisance(member), None))
    return _profiled(cfg.with_terms(terms + [(other, None)]))


def own_free(cfg, eff, hyper) -> int:
    """The number of free parameters of effect ``eff``'s own force in ``cfg`` (its columns
    less the nuisance columns, plus its nonlinear parameters) [-]."""
    nuis = eff.nuisance(cfg.data, cfg.dof)
    kn = 0 if nuis is None else nuis.shape[1]
    return max(n_free(cfg, eff, hyper) - kn, 1)


def pair_tests(cfg, first, second) -> dict:
    """The comprehensive-model tests of one pair of effects (each an ``Effect``) on top of
    ``cfg``: the joint configuration (``first`` then ``second``; each one's nonlinear
    parameters profiled with the other present) and its evaluation
    (:func:`stripcoef.diagnose.fit._evaluate`), and per member the test of its removal
    from the joint (:func:`lr_test` against :func:`_without`)."""
    base = list(cfg.terms)
    ha = None
    if first.hyper:         # first's profiled with second present (second's own profiled)
        hb = _profiled(cfg.with_terms(base + [(second, None)])).terms[-1][1]
        ha = _profiled(cfg.with_terms(base + [(second, hb), (first, None)])).terms[-1][1]
    joint = cfg.with_terms(base + [(first, ha), (second, None)])
    ev = _evaluate(joint)
    (ea, ha), (eb, hb) = joint.terms[-2], joint.terms[-1]
    return {"joint": joint, "ev": ev,
            "tests": {ea.name: lr_test(joint, ev, _without(cfg, ea, eb), own_free(joint, ea, ha)),
                      eb.name: lr_test(joint, ev, _without(cfg, eb, ea), own_free(joint, eb, hb))}}
