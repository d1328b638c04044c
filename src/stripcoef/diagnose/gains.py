r"""Per-thruster gains, fitted jointly over every DOF of a whole-log diagnosis (issue 33).

Real thrusters of one model differ from each other (a few per cent to 10-15 % of their
bench thrust). A diagnosis that has only a common thrust scale per DOF
(:class:`~stripcoef.effects.thrust.ThrustEffectiveness`) or a per-DOF asymmetry sees the
spread as forces it cannot explain: with the four vectored thrusters of a BlueROV2 at
different gains a sway or yaw command pushes in surge, which the surge diagnosis then
names a drag or a thrust asymmetry (issue 33, whole-log failure kind (3)). The thrust
model of the library is :math:`\tau = T(\alpha) K u` (Fossen 2011, sec. 11.2.1, eq. 11.14):
the gains are the diagonal of K relative to the bench map,
:class:`~stripcoef.effects.thrust.ThrusterGain`.

**The joint fit.** With :math:`y_i` the window force residual of diagnosed DOF i
[N or N m] (:attr:`WindowData.e0`), :math:`H_i` its calibration columns (the DOF's own
inertia and drag and the added masses that reach it through :math:`C_A(\nu)\nu`,
:func:`~stripcoef.diagnose.select._dof_calibration`, with their band priors; an added
mass that is also a diagnosed DOF's own is *one* parameter of the joint fit, so that the
Munk and centripetal terms of a mis-sized added mass are not read as a gain; and a free
constant per DOF, a static force or trim moment held by constant thrusts) and
:math:`G_{i,k}` the window mean of :math:`B_{ik} T_k` (thruster k's prior thrust in DOF i),

.. math:: \min_{\theta, a}\ \sum_i \frac{\lVert y_i - H_i\theta - G_i P a\rVert^2}
          {\sigma_i^2} + \lVert \theta / s \rVert^2 + \frac{\lVert a\rVert^2}
          {\sigma_g^2},\qquad g = 1 + P a

(maximum a posteriori least squares, Tarantola 2005 eq. 3.37, the DOFs' window residuals
independent, a multiresponse model as in Seber & Wild 1989, ch. 11; the inertia columns'
velocity noise corrected as in Fuller 1987, :func:`_normal_equations`). P is an
orthonormal basis of the contrasts within each group of thrusters that drive the same
DOFs (:func:`thruster_groups`, :func:`contrast_basis`), :math:`\sum_{k\in G}(g_k - 1) = 0`:
a gain common to a group is the thrust effectiveness of the DOFs it drives (one rule per
concept), and it is also the direction the force balance's homogeneity leaves to the
calibration's bands. That holds exactly only for groups linked through the DOFs they act
in: on a BlueROV2 Heavy the vectored four and the vertical four are two groups although
both act in roll and pitch, so the vertical four's common gain against the vectored
four's, which shapes the roll and pitch thrust, is not fitted, and the truth's
per-thruster spread is left there (independent benchmark, fresh seed 1795929171, logs
1795930173 and 1795930174: of the truth's roll and pitch thrust the fitted gains miss 26 %
and 11 %, 17 % and 7 % of its RMS, where roll and pitch thrust scales were named; with the
groups linked 1 % and 0.4 %, 3 % and 1 %, and neither step named). The option
:attr:`~stripcoef.diagnose.settings.DiagnoseSettings.linked_gains` fits the contrasts within
the linked groups (``thruster_groups(..., linked=True)``); off by default: on the issue-size
seed's 22 BlueROV2-like whole-log library-effect rows the error cut >= 3x rose 12 -> 15 (six
gained, three lost), but one of its two dry-friction logs lost its 'unexplained' flag
(benchmarks/data/spread33d_trace.md). ``linked_gains="identified"`` links two groups only
where the shared DOF identifies their contrast (:func:`identified_groups`: its data-only
information, every DOF's thrust scale free, at least the bench band's prior precision,
Rothenberg 1971); the default since adopt33h with five other validation options
(:data:`~stripcoef.diagnose.settings.ADOPTED_TOGETHER`), built in
benchmarks/data/linked33f_trace.md. Each
:math:`\sigma_i` is re-estimated from the joint
fit's residual of its DOF (:data:`NOISE_PASSES` passes).

**One DOF** (:attr:`~stripcoef.diagnose.settings.DiagnoseSettings.dof_gains`): the same fit
on the diagnosed DOF's balance alone. A BlueROV2's four vectored thrusters at different gains
push in surge at every sway and yaw command; a surge diagnosis on the file's map bent its drag
and the other added masses to that force (issue 33, benchmarks/data/cut33_trace.md). On by
default (``gains33c``: one-DOF named first 39 -> 40 and error cut >= 3x 31 -> 38 of 44 on the
independent simulator's seed 29112026, docs/performance.md).

**The prior.** :math:`\sigma_g` is at least :data:`GAIN_SD`, the bench uncertainty of the
thrust maps (:data:`~stripcoef.effects.base.THRUST_BAND`, 5 %, Wang & Clark 2006 Table I:
thrust coefficients measured on a load cell), widened to the spread the log itself shows
(type-II maximum likelihood, :func:`spread_sd`), as the calibration's prior widths take the
measured vehicle mismatch with the method band as their floor. The vehicle file has no
per-thruster uncertainty key; where a bench record gives one it belongs there.

**What the log determines.** Some gain combinations are not excited by a given log (with
N thrusters and at most six DOFs, and a pilot that drives them through the
pseudo-inverse allocation, some combinations never change a force). The Fisher
information of the contrasts, the calibration profiled out (the Schur complement of the
information matrix, the calibration's band priors included), is decomposed into its
eigenvectors :math:`v_j` and eigenvalues :math:`\lambda_j`; a combination is determined
by the log when its data-only standard deviation :math:`1/\sqrt{\lambda_j}` is within
:data:`~stripcoef.diagnose.settings.MIN_INFORMATION_RATIO` of its prior's, the rule of the
calibration's own coefficients (Ljung 1999, sec. 9.2, eq. 9.29;
:func:`~stripcoef.diagnose.fit._identifiability`). The MAP estimate keeps the others at
the prior (their gains stay near 1); the record lists each combination in thruster
weights with its value and standard deviation.

**The bound.** A thruster delivers at least :data:`MIN_GAIN` of its map, the bound every
other thrust factor of the library is held to; a fit that puts a gain below it is not
written. In a one-DOF balance the contrasts are identified only through the other DOFs'
commands leaking into the DOF, which a closed-loop pilot correlates with the DOF's own
motion (Ljung 1999, sec. 13.4), so a thrust-shaped effect the prior omits (a delay, a scale)
can pull them far past any real spread: on the independent simulator's VideoRay-like logs
(two horizontal thrusters, their one contrast the yaw command in surge) 29112035 (an
actuation delay) and 29212036 (a thrust scale) gave a starboard gain of -0.087 and -1.03 for
the truth's 0.94 and 0.92 of the pair's mean, and the effect was then missed
(benchmarks/data/gains33c_trace.md).

**When the gains are written.** The fit with the contrasts is tested against the fit
without them by the likelihood ratio of the joint posterior costs at the joint noise
levels (as :func:`stripcoef.diagnose.compare.lr_test`; Wilks 1938), :math:`\chi^2` with
as many degrees of freedom as determined combinations, at
:data:`~stripcoef.diagnose.compare.ALPHA`. A significant fit is then validated like every
other change (:mod:`.validate`): on the validation log the prior with the gains must not
simulate the diagnosed DOFs worse than the prior, :math:`\sum_i r_i^2 \le n`
(:math:`r_i` each DOF's free-simulation error relative to the prior's). The gains, when
kept, are the prior of the rest of the diagnosis: each DOF's calibration and effects are
fitted on the thrusts of the gained maps, and the written model's thrusters carry them in
their efficiencies (:meth:`ThrusterGain.apply`).

Depends on: effects, diagnose.settings, diagnose.fit, diagnose.select, diagnose.compare.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.linalg import null_space
from scipy.stats import chi2

from stripcoef.conventions import DOF, parse_dof
from stripcoef.diagnose.compare import ALPHA
from stripcoef.diagnose.fit import _sigma
from stripcoef.diagnose.settings import (LINKED_IDENTIFIED, MIN_INFORMATION_RATIO, UNLIMITED,
                                         Budget, DiagnoseSettings)
from stripcoef.effects.base import THRUST_BAND
from stripcoef.effects.laws import get_effect

#: Prior standard deviation of each thruster's gain about 1 [-]: the bench uncertainty of
#: the thrust maps (THRUST_BAND; Wang & Clark 2006 Table I).
GAIN_SD = THRUST_BAND
#: Passes of the joint fit that re-estimate each DOF's noise level from its residual [-].
NOISE_PASSES = 3
#: Largest prior standard deviation of the gains the log may set (:func:`spread_sd`) [-]:
#: a thruster within +-100 % of its map at 1 sigma (a bound of the search, not a band).
MAX_GAIN_SD = 1.0
#: Smallest physical gain of a thruster [-]: it delivers at least 10 % of its map, the bound
#: the library already holds a thrust scale and a gain to (the thrust asymmetry's scale,
#: :meth:`~stripcoef.effects.thrust.ThrustAsymmetry.lower_bounds`; the tether's retest with
#: the gains free, :meth:`~stripcoef.effects.hydrodynamic.TetherDragGainsFree.nuisance_lower`).
#: A fit that puts a gain below it is not written (:func:`fit_thruster_gains`).
MIN_GAIN = 0.1


@dataclass(frozen=True)
class ThrusterGains:
    """The joint fit of the thrusters' gains (module docstring).

    Attributes
    ----------
    names : tuple of str
        The thrusters, in the model's order
    gains, std : tuple of float
        The fitted gain of each thruster and its posterior standard deviation [-]
    prior_sd : float
        The gains' prior standard deviation [-] (:data:`GAIN_SD`)
    combinations : tuple of dict
        Per eigenvector of the contrasts' Fisher information: ``weights`` (thruster ->
        weight of the unit combination), ``value`` (the combination of the fitted gains
        less 1), ``std`` (its posterior sd), ``information_ratio`` (prior sd / data-only
        sd) and ``determined`` (by the log)
    test : dict
        The likelihood-ratio test of the gains (``statistic``, ``dof``, ``p_value``,
        ``alpha``)
    noise : dict
        DOF -> the joint fit's noise level [N or N m]
    dofs : tuple of str
        The DOFs fitted jointly
    applied : bool
        Whether the gains are the prior of the rest of the diagnosis (and written)
    reason : str
        Why they are or are not
    validation : dict, optional
        The validation errors [m/s or rad/s] of the prior with and without the gains
    """

    names: tuple
    gains: tuple
    std: tuple
    prior_sd: float
    combinations: tuple
    test: dict
    noise: dict
    dofs: tuple
    applied: bool = False
    reason: str = ""
    validation: dict | None = None
    calibration: dict = field(default_factory=dict, repr=False, compare=False)
    links: list | None = None

    @property
    def significant(self) -> bool:
        return bool(self.test.get("p_value", 1.0) <= ALPHA)

    def parameters(self) -> dict:
        """``gain_<thruster>`` -> gain [-] (:class:`ThrusterGain`'s parameters)."""
        return {f"gain_{n}": float(g) for n, g in zip(self.names, self.gains)}

    def model(self, prior):
        """``prior`` with the gains in its thrusters' efficiencies (a new model)."""
        return get_effect("thruster_gain").apply(prior, None, self.parameters())

    def to_dict(self) -> dict:
        return {"effect": "thruster_gain", "source": get_effect("thruster_gain").source,
                "gains": dict(zip(self.names, map(float, self.gains))),
                "std": dict(zip(self.names, map(float, self.std))),
                "prior_sd": float(self.prior_sd),
                "prior_source": "THRUST_BAND: bench uncertainty of the thrust maps "
                                "(Wang & Clark 2006 Table I)",
                "constraint": "contrasts only: within each group of thrusters (the same DOFs, "
                              "or linked through the diagnosed DOFs with linked_gains), the "
                              "gains' sum is the group's size (a common gain is each DOF's "
                              "thrust_effectiveness)",
                "combinations": [dict(c) for c in self.combinations],
                "test": dict(self.test), "noise": dict(self.noise), "dofs": list(self.dofs),
                "applied": bool(self.applied), "reason": self.reason,
                "validation": self.validation,
                **({} if self.links is None else {"links": [
                    {**lk, "groups": [[self.names[k] for k in g] for g in lk["groups"]],
                     "dofs": list(lk["dofs"])} for lk in self.links]})}


def thruster_groups(alloc, rows=None, linked: bool = False, tol: float = 1e-9) -> list:
    r"""The thrusters grouped for the gains' contrasts: lists of thruster indices, in order
    of their first member. By default (``linked`` False) the thrusters that act in the same
    *set* of DOFs (the non-zero pattern of their column of B, all six rows). With ``linked``
    (:attr:`~stripcoef.diagnose.settings.DiagnoseSettings.linked_gains`) the groups are such
    that a gain common to a group, and only such a gain, is a thrust scale of each DOF of
    ``rows`` the group drives (the thrust effectiveness):

    Gains :math:`g` act as per-DOF thrust scales :math:`s` on the rows ``rows`` of the
    allocation matrix B (6, N) (all six by default; a diagnosis passes its DOFs) for every
    thrust T exactly when :math:`B_{ik} g_k = s_i B_{ik}` for all i in ``rows`` and all k,
    that is :math:`g_k = s_i` wherever :math:`B_{ik} \ne 0` (Fossen 2011, eq. 11.14,
    :math:`\tau = T K u`): g is constant on each connected component of the graph that
    links two thrusters when they act in a common DOF of ``rows``. Those components are the
    groups (a union-find over the DOFs); a thruster that acts in none of ``rows`` is alone.
    Any other direction of g changes the shape of some DOF's thrust, which no thrust scale
    can, so it is a contrast the fit must hold: on a BlueROV2 Heavy the vectored four act in
    roll and pitch too (their lever about the reference point), so the vertical four's
    common gain relative to theirs shapes the roll and pitch thrust (spread33d,
    benchmarks/data/spread33d_trace.md)."""
    alloc = np.asarray(alloc, float)
    n = alloc.shape[1]
    if not linked:
        keys = {}
        for k in range(n):
            keys.setdefault(tuple(np.abs(alloc[:, k]) > tol), []).append(k)
        return list(keys.values())
    rows = range(alloc.shape[0]) if rows is None else rows
    parent = list(range(n))

    def root(k):
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k
    for i in rows:
        acting = np.nonzero(np.abs(alloc[i]) > tol)[0]
        for k in acting[1:]:
            parent[root(int(k))] = root(int(acting[0]))
    groups = {}
    for k in range(n):
        groups.setdefault(root(k), []).append(k)
    return list(groups.values())


def gain_contrasts(alloc, dofs, settings: DiagnoseSettings, identified=None) -> np.ndarray:
    """The basis of the gains' contrasts (N, k) a fit of ``dofs`` holds: :func:`contrast_basis`
    of :func:`thruster_groups` with the settings' ``linked_gains``, one rule for the gains'
    fit and for their refit as an explanation of the residual
    (:func:`stripcoef.diagnose.regains.explain`). With ``linked_gains="identified"`` the
    groups are :func:`identified_groups`' (``identified``: its ``(blocks, prior_sd,
    sigmas)``, required in that mode)."""
    alloc = np.asarray(alloc, float)
    if settings.linked_gains == LINKED_IDENTIFIED:
        if identified is None:
            raise ValueError("linked_gains='identified' needs the log's blocks "
                             "(gain_contrasts(..., identified=(blocks, prior_sd, sigmas)))")
        groups = identified_groups(alloc, dofs, *identified)[0]
    else:
        groups = thruster_groups(alloc, rows=dofs, linked=bool(settings.linked_gains))
    return contrast_basis(groups, alloc.shape[1])


def _between_contrast(groups, a: int, b: int, n: int) -> np.ndarray:
    """The unit contrast (n,) of group ``a``'s common gain against group ``b``'s: weight
    :math:`1/|A|` on A's members and :math:`-1/|B|` on B's, normalised [-]."""
    w = np.zeros(n)
    w[groups[a]] = 1.0 / len(groups[a])
    w[groups[b]] = -1.0 / len(groups[b])
    return w / np.linalg.norm(w)


def contrast_information(blocks, prior_sd, sigmas, p_basis, w, gain_sd) -> float:
    r"""The data's Fisher information [-] on the gain contrast ``w`` (unit, (N,)) with every
    DOF's thrust scale free: the Schur complement of ``w``'s entry in the normal equations
    of :func:`_normal_equations` (each DOF's calibration with its band priors, its inertia's
    velocity noise corrected) extended by one free column per DOF, its prior thrust
    :math:`G_i \mathbf{1}` (the DOF's thrust effectiveness, no prior), the contrasts
    ``p_basis`` with their prior precision :math:`1/s^2` (``gain_sd``), and ``w`` with none
    (its data-only information, as :func:`_information`).

    A DOF only one of the two groups drives carries no information on ``w`` once its thrust
    scale is free (its thrust is that group's common gain times its map, a scale): only the
    DOFs both groups drive do, through the variation of their two shares (Fossen 2011
    eq. 11.14). That is the information the link through a shared DOF adds; without the free
    scales a contrast between a surge-driving and a heave-driving group would be 'determined'
    by the two DOFs' calibration bands, the prior, not by the log."""
    kc, nb, na = prior_sd.size, len(blocks), p_basis.shape[1]
    n = kc + nb + na + 1
    lam = np.zeros((n, n))
    for k, ((_, y, cols, idx, g, (jm, nv, _)), s) in enumerate(zip(blocks, sigmas)):
        h = np.zeros((y.size, n))
        h[:, idx] = cols
        h[:, kc + k] = g.sum(axis=1)
        h[:, kc + nb:kc + nb + na] = g @ p_basis
        h[:, -1] = g @ w
        lam += h.T @ h / s ** 2
        if jm is not None:
            lam[jm, jm] -= nv / s ** 2
    fin = np.nonzero(np.isfinite(prior_sd))[0]
    lam[fin, fin] += 1.0 / prior_sd[fin] ** 2
    lam[kc + nb:kc + nb + na, kc + nb:kc + nb + na] += np.eye(na) / gain_sd ** 2
    nuis = lam[:-1, :-1]
    info = lam[-1, -1] - lam[-1, :-1] @ np.linalg.pinv(nuis) @ lam[:-1, -1]
    return max(float(info), 0.0)


def identified_groups(alloc, rows, blocks, prior_sd, sigmas) -> tuple:
    r"""``(groups, links)``: the thrusters grouped for the gains' contrasts, the groups of
    :func:`thruster_groups` (the same set of DOFs) merged through a shared DOF only where the
    log identifies the contrast between them (``linked_gains="identified"``).

    A group's common gain against another's is a contrast of the gains only through the
    DOFs both drive (:func:`thruster_groups`, ``linked``); elsewhere it is a per-DOF thrust
    scale. Linking them makes the fit estimate it before selection, which is right where
    the shared DOF determines it and a prior-driven guess where it does not (on the
    VideoRay-like vehicle the three thrusters share only pitch, through 0.01 m levers, and
    the linked fit put the vertical against the pair at 1.41-2.02 for the truth's
    0.83-1.38, benchmarks/data/linked33e_trace.md). The criterion is the contrast's
    identifiability from the log (Rothenberg 1971, Econometrica 39, 577: a parameter is
    identified when its information matrix is non-singular; in a Bayesian fit the data,
    not the prior, determine it, Poirier 1998, Econometric Theory 14, 483, sec. 3): its
    data-only Fisher information :math:`\lambda_w` with every DOF's thrust scale, the
    calibration and the groups' own contrasts profiled out
    (:func:`contrast_information`) against its prior precision :math:`1/s^2`, s the gains'
    a-priori band :data:`GAIN_SD` (the bench uncertainty of the thrust maps, Wang & Clark
    2006 Table I): the prior the data are compared with must not come from the same data,
    so not the spread the log sets (:func:`spread_sd`; its ratio is recorded as
    ``information_ratio_spread``, not used). Linked when
    :math:`\lambda_w \ge 1/s^2`, i.e. information ratio :math:`s\sqrt{\lambda_w} \ge 1`:
    the posterior mean's weight on the data, :math:`\lambda_w/(\lambda_w + 1/s^2)`, is
    at least its weight on the prior (the linear-Gaussian posterior, Tarantola 2005
    eq. 3.37). The bound is the definition's, not a tuned value.

    The default since adopt33h, with five other validation options
    (:data:`~stripcoef.diagnose.settings.ADOPTED_TOGETHER`). Measured alone on the whole-log
    rows of seeds 1795938998 and 1795929171 (benchmarks/data/linked33f_trace.md), where it
    was not adopted: the VideoRay's pair links on 1 of 12 logs, so
    ``linked=True``'s VideoRay losses go, and the clean-log failure is fixed, but on the
    BlueROV2 the contrast is determined (ratios 1.03-2.07) and biased by the effect the fit
    leaves out on two logs (magnitude within 15 % 73 -> 71 of 88): the criterion bounds the
    contrast's variance, not its bias.

    Groups are merged one pair at a time, the most informative identified pair first, and
    the information recomputed on the merged groups, until no pair that shares a DOF of
    ``rows`` is identified. ``links``: one dict per pair considered (``groups``, ``dof``
    shared, ``information_ratio``, ``linked``), for the record."""
    alloc = np.asarray(alloc, float)
    n = alloc.shape[1]
    groups = thruster_groups(alloc)
    p0 = contrast_basis(groups, n)
    spread = GAIN_SD
    if p0.shape[1]:
        lam, rhs, kc = _normal_equations(blocks, prior_sd, sigmas, p0)
        spread = spread_sd(*_information(lam, rhs, kc))
    links = []
    while True:
        p_basis = contrast_basis(groups, n)
        best = None
        for a in range(len(groups)):
            for b in range(a + 1, len(groups)):
                shared = [DOF[i] for i in rows
                          if np.any(np.abs(alloc[i, groups[a]]) > 1e-9)
                          and np.any(np.abs(alloc[i, groups[b]]) > 1e-9)]
                if not shared:
                    continue
                w = _between_contrast(groups, a, b, n)
                info = contrast_information(blocks, prior_sd, sigmas, p_basis, w, GAIN_SD)
                ratio = GAIN_SD * math.sqrt(info)
                links.append({"groups": (tuple(groups[a]), tuple(groups[b])),
                              "dofs": tuple(shared), "information_ratio": float(ratio),
                              "linked": bool(ratio >= 1.0),
                              "information_ratio_spread": float(spread * math.sqrt(info))})
                if ratio >= 1.0 and (best is None or ratio > best[0]):
                    best = (ratio, a, b)
        if best is None:
            return groups, links
        _, a, b = best
        merged = sorted(groups[a] + groups[b])
        groups = [g for k, g in enumerate(groups) if k not in (a, b)] + [merged]
        groups.sort(key=min)


def contrast_basis(groups, n: int) -> np.ndarray:
    r"""An orthonormal basis P (n, n - number of groups) of the gains' contrasts within each
    group of :func:`thruster_groups`, :math:`\sum_{k \in G}(g_k - 1) = 0` for every group
    G: a gain common to a group is a thrust scale of the DOFs it drives (the thrust
    effectiveness), not a spread [-]."""
    c = np.zeros((len(groups), n))
    for row, members in enumerate(groups):
        c[row, members] = 1.0
    return null_space(c)


def _blocks(data, dofs, settings, excited):
    """``(blocks, names, sd)``: per DOF where a thruster acts, ``(dof, y, columns, index,
    gain columns, (inertia parameter or None, N v_i, M_ii))``, and the joint calibration's
    parameters (``<dof>.<coefficient>``) with their prior sd [units of each].

    Each DOF's calibration (:func:`~stripcoef.diagnose.select._dof_calibration`) holds its
    own inertia and drag and the added mass :math:`M_{jj}` of every other DOF that reaches
    it through :math:`C_A(\nu)\nu` (``M_<dof>``); an added mass that is also a
    diagnosed DOF's own is one parameter of the joint fit (one coefficient, one value),
    with that DOF's band. A free constant per DOF (``offset``): a static force or moment
    the prior lacks (a buoyancy or trim offset, held by constant thrusts) is not a gain,
    which is fitted on the thrusts' variation."""
    from stripcoef.diagnose.select import _dof_calibration

    names, sd, own_m, raw = [], [], {}, []
    for i in dofs:
        if not np.any(np.abs(data.alloc[i]) > 1e-9):
            continue
        cal = _dof_calibration(data, i, settings, excited, None)[0]
        idx = []
        for n, s_n in zip(cal.names, np.asarray(cal.sd, float)):
            if n.startswith("M_"):
                idx.append(None)
                continue
            idx.append(len(names))
            names.append(f"{DOF[i]}.{n}")
            sd.append(s_n)
            if n == "M":
                own_m[i] = idx[-1]
        idx.append(len(names))
        names.append(f"{DOF[i]}.offset")
        sd.append(np.inf)
        raw.append((i, cal, idx))
    blocks = []
    for i, cal, idx in raw:
        for c, n in enumerate(cal.names):
            if idx[c] is None:
                j = parse_dof(n[2:])
                if j in own_m:
                    idx[c] = own_m[j]
                else:
                    idx[c] = len(names)
                    names.append(f"{DOF[i]}.{n}")
                    sd.append(float(cal.sd[c]))
        cols = np.column_stack([cal.cols, np.ones(data.n_windows)])
        g = data.mean_held(data.thruster_force(i))
        nv = data.n_windows * data.rate_noise_variance(i)
        blocks.append((i, data.e0[:, i], cols, np.asarray(idx, int), g,
                       (own_m.get(i), nv, float(data.model.mass_matrix[i, i]))))
    return blocks, names, np.asarray(sd, float)


def _with_shared(blocks, names, sd, shared_names, columns):
    """``(blocks, names, sd)`` of :func:`_blocks` with the parameters ``shared_names``
    (free: prior sd inf) common to every block, their columns ``columns[dof]`` appended to
    each DOF's (:func:`fit_thruster_gains`' ``shared``)."""
    first = len(names)
    names = list(names) + [f"shared.{n}" for n in shared_names]
    sd = np.concatenate([sd, np.full(len(shared_names), np.inf)])
    at = np.arange(first, first + len(shared_names))
    out = []
    for i, y, cols, idx, g, inertia in blocks:
        out.append((i, y, np.column_stack([cols, np.asarray(columns[i], float)]),
                    np.concatenate([idx, at]), g, inertia))
    return out, names, sd


def _normal_equations(blocks, prior_sd, sigmas, p_basis, with_gains=True):
    r"""``(Lambda, b, kc)``: the corrected normal equations of the joint MAP fit (module
    docstring), the calibration's parameters first (``kc`` of them), then the contrasts.

    Each DOF's rows are whitened by its noise level :math:`\sigma_i`; the band priors add
    their precisions :math:`1/s^2` to the diagonal. The inertia column of DOF i (minus the
    window rate of its velocity) carries the velocity noise, of variance :math:`v_i` per
    window (:meth:`WindowData.rate_noise_variance`), which the residual also carries times
    the DOF's inertia :math:`M_{ii}`: corrected least squares (Fuller 1987, Measurement
    Error Models, sec. 2.2; the profiled inertia of :func:`stripcoef.diagnose.fit._solve`)
    takes :math:`N v_i/\sigma_i^2` off that column's diagonal entry and adds
    :math:`N v_i M_{ii}/\sigma_i^2` to its right-hand side, so that the noise does not
    shrink the inertia and with it the thrust of the thrusters that drive the DOF [-]."""
    kc = prior_sd.size
    na = p_basis.shape[1] if with_gains else 0
    lam = np.zeros((kc + na, kc + na))
    rhs = np.zeros(kc + na)
    for (i, y, cols, idx, g, (jm, nv, m_ii)), s in zip(blocks, sigmas):
        h = np.zeros((y.size, kc + na))
        h[:, idx] = cols
        if with_gains:
            h[:, kc:] = g @ p_basis
        lam += h.T @ h / s ** 2
        rhs += h.T @ y / s ** 2
        if jm is not None:
            lam[jm, jm] -= nv / s ** 2
            rhs[jm] += nv * m_ii / s ** 2
    fin = np.nonzero(np.isfinite(prior_sd))[0]
    lam[fin, fin] += 1.0 / prior_sd[fin] ** 2
    return lam, rhs, kc


def _information(lam, rhs, kc):
    r"""``(F, r)``: the information of the contrasts and their right-hand side with the
    calibration profiled out (the Schur complement),
    :math:`F = \Lambda_{aa} - \Lambda_{ac}\Lambda_{cc}^{-1}\Lambda_{ca}`,
    :math:`r = b_a - \Lambda_{ac}\Lambda_{cc}^{-1} b_c` [-]."""
    inv_cc = np.linalg.pinv(lam[:kc, :kc])
    f = lam[kc:, kc:] - lam[kc:, :kc] @ inv_cc @ lam[:kc, kc:]
    r = rhs[kc:] - lam[kc:, :kc] @ inv_cc @ rhs[:kc]
    return 0.5 * (f + f.T), r


def _map(lam, rhs, kc, gain_sd):
    """The joint MAP estimate (calibration, then contrasts) of the normal equations with
    the contrasts' prior precision :math:`1/s^2` [units of each]."""
    full = lam.copy()
    na = full.shape[0] - kc
    full[kc:, kc:] += np.eye(na) / gain_sd ** 2
    return np.linalg.lstsq(full, rhs, rcond=None)[0]


def spread_sd(f, r, floor: float = GAIN_SD, ceiling: float = MAX_GAIN_SD) -> float:
    r"""The gains' prior standard deviation from the log (type-II maximum likelihood,
    MacKay 1992, Neural Computation 4, 415, sec. 2; Gelman et al. 2013, Bayesian Data
    Analysis, sec. 5.3): in the eigenbasis of the information F (:math:`F v_j = \lambda_j
    v_j`) the data-only estimates of the combinations, :math:`z_j = v_j^T r / \lambda_j`,
    are independent with variance :math:`1/\lambda_j + s^2` under a prior of sd s on each
    contrast; s maximises their marginal likelihood

    .. math:: \min_s \sum_j \log(1/\lambda_j + s^2) + \frac{z_j^2}{1/\lambda_j + s^2}

    on [``floor``, ``ceiling``]: never below the bench uncertainty of the thrust maps
    (``floor``, :data:`GAIN_SD`), the log widening it when its thrusters differ by more
    [-]."""
    from scipy.optimize import minimize_scalar

    eig, vec = np.linalg.eigh(f)
    keep = eig > 1e-12 * max(float(eig.max(initial=0.0)), 1e-300)
    if not np.any(keep):
        return floor
    lam = eig[keep]
    z = (vec[:, keep].T @ r) / lam

    def cost(s):
        v = 1.0 / lam + s * s
        return float(np.sum(np.log(v) + z * z / v))
    sol = minimize_scalar(cost, bounds=(floor, ceiling), method="bounded",
                          options={"xatol": 1e-4})
    best = min((floor, ceiling, float(sol.x)), key=cost)
    return float(best)


def fit_thruster_gains(data, dofs, settings: DiagnoseSettings = DiagnoseSettings(), *,
                       excited=None, budget: Budget = UNLIMITED, shared=None):
    """The joint fit of the thrusters' gains over the diagnosed ``dofs`` (module
    docstring): a :class:`ThrusterGains`, or None when the log has no thrusters' commands,
    fewer than two thrusters or no diagnosed DOF they drive.

    ``shared``: ``(names, columns)``, parameters common to every DOF fitted free (no prior)
    beside the calibration, ``columns`` DOF index -> (windows, len(names)) [N or N m per unit
    of each] (a water current linearised about its value, :mod:`.regains`); profiled out of
    the contrasts' information like the calibration (:func:`_information`), so that the
    test and the determined combinations are those of the gains beside them."""
    if data.thrust is None or data.thrust.shape[1] < 2:
        return None
    budget.check()
    names = tuple(th.name for th in data.model.thrusters)
    if settings.linked_gains != LINKED_IDENTIFIED:
        p_basis = gain_contrasts(data.alloc, dofs, settings)
        if p_basis.shape[1] == 0:           # one thruster per group: no contrast to fit
            return None
    blocks, cal_names, prior_sd = _blocks(data, dofs, settings, excited)
    if not blocks:
        return None
    if shared is not None:
        blocks, cal_names, prior_sd = _with_shared(blocks, cal_names, prior_sd, *shared)
    sigmas = [_sigma(y, cols, np.full(cols.shape[1], np.inf)) for _, y, cols, *_ in blocks]
    links = None
    if settings.linked_gains == LINKED_IDENTIFIED:
        groups, links = identified_groups(data.alloc, dofs, blocks, prior_sd, sigmas)
        p_basis = contrast_basis(groups, len(names))
        if p_basis.shape[1] == 0:
            return None
    gain_sd = GAIN_SD
    for _ in range(NOISE_PASSES):
        budget.check()
        lam, rhs, kc = _normal_equations(blocks, prior_sd, sigmas, p_basis)
        f, r = _information(lam, rhs, kc)
        gain_sd = spread_sd(f, r)
        x = _map(lam, rhs, kc, gain_sd)
        sigmas = []
        for _, y, cols, idx, g, _ in blocks:
            res = y - cols @ x[idx] - g @ p_basis @ x[kc:]
            sigmas.append(max(float(np.sqrt(res @ res / max(y.size - cols.shape[1], 1))),
                              1e-12))
    lam, rhs, kc = _normal_equations(blocks, prior_sd, sigmas, p_basis)
    f, r = _information(lam, rhs, kc)
    post = f + np.eye(f.shape[0]) / gain_sd ** 2
    cov_a = np.linalg.pinv(post)
    a = cov_a @ r
    x = _map(lam, rhs, kc, gain_sd)
    gains = 1.0 + p_basis @ a
    cov_g = p_basis @ cov_a @ p_basis.T
    eig, vec = np.linalg.eigh(f)
    combos = []
    for j in np.argsort(eig)[::-1]:
        w = p_basis @ vec[:, j]
        w = w * np.sign(w[np.argmax(np.abs(w))])
        ratio = gain_sd * math.sqrt(max(float(eig[j]), 0.0))
        combos.append({"weights": dict(zip(names, map(float, w))),
                       "value": float(w @ (gains - 1.0)),
                       "std": float(math.sqrt(max(float(w @ cov_g @ w), 0.0))),
                       "information_ratio": float(ratio),
                       "determined": bool(ratio >= MIN_INFORMATION_RATIO)})
    # likelihood ratio of the contrasts: the fall of the joint posterior cost (a quadratic
    # form: its minimum is const - b^T Lambda^-1 b) when they are added, r^T (F + I/s^2)^-1 r
    k = sum(c["determined"] for c in combos)
    stat = max(float(r @ a), 0.0)
    test = {"statistic": stat, "dof": int(k),
            "p_value": float(chi2.sf(stat, k)) if k else 1.0, "alpha": ALPHA,
            "method": "likelihood ratio of the joint fit with and without the gains' "
                      "contrasts (Wilks 1938), at the joint noise levels"}
    dof_names = tuple(DOF[b[0]] for b in blocks)
    calib = {n: float(v) for n, v in zip(cal_names, x[:kc])}
    out = ThrusterGains(names=names, gains=tuple(map(float, gains)),
                        std=tuple(float(math.sqrt(max(v, 0.0))) for v in np.diag(cov_g)),
                        prior_sd=gain_sd, combinations=tuple(combos), test=test,
                        noise=dict(zip(dof_names, map(float, sigmas))), dofs=dof_names,
                        calibration=calib, links=links)
    if not out.significant:
        return replace(out, reason=f"not significant: p = {test['p_value']:.3g} > {ALPHA:g} "
                                   f"({k} combinations determined by the log)")
    low = {n: g for n, g in zip(names, gains) if g < MIN_GAIN}
    if low:     # a physical bound (module docstring, 'The bound'): not a gain
        return replace(out, reason=f"significant (p = {test['p_value']:.3g}) but outside the "
                       "physical bound: " + ", ".join(f"{n} {g:.3g}" for n, g in low.items())
                       + f" < {MIN_GAIN:g} (a thruster delivers at least {100 * MIN_GAIN:.0f} "
                       "% of its map, the library's bound on every thrust factor): not written")
    return replace(out, applied=True,
                   reason=f"significant: p = {test['p_value']:.3g} <= {ALPHA:g} ({k} "
                          "combinations determined by the log)")


def validated(gains: ThrusterGains, val_log, prior, dofs, logged=()) -> ThrusterGains:
    """``gains`` kept only if the prior with them simulates the validation log no worse
    than the prior (module docstring: :math:`\\sum_i r_i^2 \\le n`); unchanged without a
    validation log or when not applied."""
    if val_log is None or not gains.applied:
        return gains
    from stripcoef.diagnose.validate import validation_errors

    before = validation_errors(val_log, prior, dofs, logged)
    after = validation_errors(val_log, gains.model(prior), dofs, logged)
    record = {"prior": before, "with_gains": after}
    if before is None or after is None:
        return replace(gains, validation=record)
    r2 = [(after[d] / max(before[d], 1e-12)) ** 2 for d in before]
    record["sum_squared_ratio"] = float(sum(r2))
    if sum(r2) > len(r2):
        return replace(gains, applied=False, validation=record,
                       reason=gains.reason + "; removed by the validation: the prior with the "
                       f"gains simulates it worse (sum of squared error ratios {sum(r2):.3g} "
                       f"> {len(r2)})")
    return replace(gains, validation=record)
