r"""A rejected alternative band of the base install's input ladder, kept for its measurement.

The base install's ladder is two nested pairs of different polyhedra
(:mod:`stripcoef.hull.input_ladder`).  Eça & Hoekstra's least squares with one error constant
per pair (:func:`eca_hoekstra_families`) gives the band :func:`ladder_least_squares_error`; it
narrows the one-constant band 7.6-9.9x -> 6.0-6.2x the actual error but covers only
86.8-91.2 % of the terms on four seeds (``python -m benchmarks.ladder_estimate_rules``,
benchmarks/data/ladder_pair_constants.md), so the package does not use it; it lives here, beside
the benchmark that measures it, rather than in ``src/``.
"""

from __future__ import annotations

import numpy as np

from stripcoef.hull.convergence import (EH_ORDER_HIGH, EH_ORDER_LOW, EH_ORDER_SEARCH,
                                        EH_SAFETY_GOOD, EH_SAFETY_POOR, GridUncertainty,
                                        _eh_uncertainty, _sigma, _weights)
from stripcoef.hull.panel_error import estimated_error


def eca_hoekstra_families(counts, values, families, order: float, *,
                          dimension: int = 2) -> GridUncertainty:
    r"""Eça & Hoekstra's least-squares uncertainty of the finest of ``values`` where the
    levels come in families of geometrically similar grids, each with its own error constant:

    .. math:: \phi_i = \phi_0 + \alpha_{f(i)}\,h_i^{p_f} \quad [\text{the unit of } \phi]

    one limit :math:`\phi_0` and one constant :math:`\alpha_f` per family ``families[i]``,
    the order :math:`p_f` the formal one (``order``).  Eça & Hoekstra's expansion
    :math:`\alpha h^p` takes one constant for all grids because their grids are geometrically
    similar (2014, J. Comput. Phys. 262, 104-130, sec. 2.1: the constant is a property of the
    grid family); a ladder of two nested pairs of different polyhedra (the base install's
    :mod:`stripcoef.hull.input_ladder`) is two families, whose different constants their one-
    constant fit reads as scatter (standard deviations above the data range, eq. 21's
    :math:`3\sigma/\Delta_\phi` factor).  The rest is theirs: the fit without weights and with
    :math:`w_i \propto 1/h_i` (eq. 16), the one of the smaller standard deviation (sec. 2.2,
    :math:`n_p = 1 +` the number of families), the data range (eq. 19), the safety factor
    1.25 where the observed order lies in [0.5, 2.1) and :math:`\sigma < \Delta_\phi`, else 3
    (sec. 3), and the uncertainty of eqs. 20-21.  The observed order is that of the same
    model with p free (a scan of (0, 8], the least residual; with two pairs it solves the
    four levels exactly).  Not in the paper: the per-family constant is this module's reading
    of their sec. 2.1, measured in ``python -m benchmarks.ladder_estimate_rules``.  Raises
    ValueError with fewer levels than the fit has parameters plus one."""
    n = np.asarray(counts, float)
    phi = np.asarray(values, float)
    fam = np.asarray(families)
    if not (len(n) == len(phi) == len(fam)):
        raise ValueError(f"one count, value and family per level; got {len(n)}, {len(phi)}, "
                         f"{len(fam)}")
    keys = sorted(set(fam.tolist()))
    n_params = 1 + len(keys)
    if len(n) <= n_params:
        raise ValueError(f"{len(keys)} families need at least {n_params + 1} levels; "
                         f"got {len(n)}")
    idx = np.argsort(-n)                        # finest first, as the paper numbers them
    n, phi, fam = n[idx], phi[idx], fam[idx]
    if np.any(np.diff(n) == 0):
        raise ValueError(f"levels of equal cell counts {n.tolist()}: expected distinct ones")
    h = (n[0] / n) ** (1.0 / dimension)
    ng = len(h)
    data_range = float(phi.max() - phi.min()) / (ng - 1)
    if data_range == 0.0:
        return GridUncertainty(0.0, float(phi[0]), float("nan"), "constant", False,
                               EH_SAFETY_GOOD, 0.0, 0.0, 0.0, 0.0)
    member = np.column_stack([fam == key for key in keys]).astype(float)

    def fit(p, w):
        a = np.column_stack([np.ones_like(h), member * (h ** p)[:, None]])
        sw = np.sqrt(w)
        c, *_ = np.linalg.lstsq(a * sw[:, None], phi * sw, rcond=None)
        return float(c[0]), phi - a @ c

    fits = []
    for weighted in (False, True):
        w = _weights(h, weighted)
        phi0, res = fit(order, w)
        fits.append((_sigma(res, w, n_params), weighted, phi0, phi[0] - res[0]))
    sigma, weighted, phi0, fit1 = min(fits, key=lambda f: f[0])
    w1 = _weights(h, False)
    scan = np.geomspace(1e-3, EH_ORDER_SEARCH, 800)
    s = [float(w1 @ (r * r)) for r in (fit(q, w1)[1] for q in scan)]
    p_obs = float(scan[int(np.argmin(s))])
    good = EH_ORDER_LOW <= p_obs < EH_ORDER_HIGH and sigma < data_range
    safety = EH_SAFETY_GOOD if good else EH_SAFETY_POOR
    error, residual = abs(fit1 - phi0), abs(phi[0] - fit1)
    u = _eh_uncertainty(safety, error, sigma, residual, data_range)
    return GridUncertainty(float(u), float(phi0), p_obs, f"families {order:g}",
                           bool(weighted), float(safety), float(sigma), data_range,
                           float(error), float(residual))


def ladder_least_squares_error(levels, counts, extrapolated, order: float) -> np.ndarray:
    r"""The band [kg, kg m, kg m^2] of the value ``extrapolated`` from the input ladder's four
    ``levels`` (6x6 matrices coarse to fine, not symmetrised; ``counts`` panels; two nested
    pairs :math:`(L_1, L_3)`, :math:`(L_2, L_4)`, :mod:`stripcoef.hull.input_ladder`):
    :func:`stripcoef.hull.panel_error.least_squares_error`'s rule with Eça & Hoekstra's fit given one error constant per
    pair at the formal ``order`` (:func:`eca_hoekstra_families`),
    moved to the value by the step (:func:`stripcoef.hull.panel_error.estimated_error`);
    symmetrised.  Measured against the one-constant band in
    ``python -m benchmarks.ladder_estimate_rules`` (benchmarks/data/ladder_estimate_rules.md);
    not used by the package."""
    mats = [np.asarray(m, float) for m in levels]
    if len(mats) != 4:
        raise ValueError(f"the ladder has four levels; got {len(mats)}")
    sym = np.stack([0.5 * (m + m.T) for m in mats])
    u = np.zeros((6, 6))
    for i in range(6):
        for j in range(i, 6):
            u[i, j] = u[j, i] = eca_hoekstra_families(counts, sym[:, i, j], (0, 1, 0, 1),
                                                      order).uncertainty
    a = np.asarray(extrapolated, float)
    return estimated_error(mats[-1], 0.5 * (a + a.T), u)
