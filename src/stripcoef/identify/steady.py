r"""Steady-state regression: drag, bias and thruster efficiency from constant-input trials.

At steady state (:math:`\dot\nu = 0`) a decoupled DOF balances the applied force
against drag and a constant bias.  Caccia (Indiveri 1998, sec. 4.2.4) writes three heave models,
all linear in the parameters (:math:`y = H\theta + \varepsilon`):

standard, eq. 4.15 with :math:`\dot w = 0`:

.. math:: F = k_w w + k_{w|w|} w|w| - W

eta, eq. 4.16 (propeller-hull interaction weakens the upward thrust):

.. math:: \eta F = k_w w + k_{w|w|} w|w| - W, \qquad
          \eta = 1 \text{ for } F \ge 0, \quad \eta < 1 \text{ for } F < 0

eta-md (eq. 4.17's third model; momentum drag of the horizontal thrusters
:math:`F_{md} = -\alpha n_h w`, sec. 3.3.1):

.. math:: \eta F = k_w w + k_{w|w|} w|w| - W + \alpha n_h w

Rows with :math:`F \ge 0` give :math:`y = F`; rows with :math:`F < 0` give :math:`y = 0`
and a column :math:`-F` for :math:`\eta`.  Here ``F`` is the applied generalized force along
the DOF in FRD body axes (for heave, positive downward) [N or N m], ``w`` the steady velocity
[m/s or rad/s] and ``W`` the net weight along z (weight minus buoyancy, positive = sinks) [N].

For one DOF without hydrostatics (yaw, Indiveri 1998 sec. 4.2.5) the four models are

.. math::
    \tau = k_r r + k_{r|r|} |r| r + b \;(LQB), \quad \tau = k_r r + k_{r|r|}|r| r \;(LQNB),
    \quad \tau = k_r r + b \;(LB), \quad \tau = k_r r \;(LNB)

fitted to the positive direction, the negative one, and both together.
:func:`compare_models` ranks them by AICc, J_LS and the relative errors.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from stripcoef.conventions import DOF, FORCES, POSE, VELOCITIES, parse_dof
from stripcoef.errors import InputError, unknown_name
from stripcoef.identify.estimators import FitResult, linear_lstsq

#: Model name -> (linear, quadratic, bias, eta, momentum drag)
MODELS = {
    "standard": (True, True, True, False, False),
    "eta": (True, True, True, True, False),
    "eta-md": (True, True, True, True, True),
    "LQB": (True, True, True, False, False),
    "LQNB": (True, True, False, False, False),
    "LB": (True, False, True, False, False),
    "LNB": (True, False, False, False, False),
}
COMPARISON_MODELS = ("LQB", "LQNB", "LB", "LNB")
DIRECTIONS = ("both", "positive", "negative")
#: A parameter is "significant" when |theta| > 2 sigma, i.e. relative error < 50 %.
SIGNIFICANT_PERCENT = 50.0


@dataclass
class SteadyPoints:
    """Steady-state points of one DOF.

    Attributes
    ----------
    dof : str
        DOF name (``heave``...).
    velocity : (m,) array
        Steady velocity [m/s or rad/s], FRD body axes.
    force : (m,) array
        Applied generalized force along the DOF [N or N m], FRD body axes.
    n_h : (m,) array or None
        Mean |command| of the horizontal thrusters (for eta-md) [command units].
    source : str
    """

    dof: str
    velocity: np.ndarray
    force: np.ndarray
    n_h: np.ndarray | None = None
    source: str = "<memory>"

    def __post_init__(self):
        self.velocity = np.asarray(self.velocity, dtype=float).reshape(-1)
        self.force = np.asarray(self.force, dtype=float).reshape(-1)
        if self.n_h is not None:
            self.n_h = np.asarray(self.n_h, dtype=float).reshape(-1)

    def __len__(self):
        return self.velocity.size

    def select(self, direction: str) -> "SteadyPoints":
        """Points moving in the positive or negative direction, or all (``both``)."""
        if direction not in DIRECTIONS:
            raise unknown_name("direction", direction, DIRECTIONS)
        if direction == "both":
            return self
        keep = self.velocity > 0 if direction == "positive" else self.velocity < 0
        return SteadyPoints(self.dof, self.velocity[keep], self.force[keep],
                            None if self.n_h is None else self.n_h[keep], self.source)


def _names(dof: str, model: str):
    v = VELOCITIES[parse_dof(dof)]
    lin, quad, bias, eta, md = MODELS[model]
    heave = DOF[parse_dof(dof)] == "heave"
    names = []
    if lin:
        names.append(f"k_{v}")
    if quad:
        names.append(f"k_{v}{v}")
    if bias:
        names.append("W" if heave else "b")
    if eta:
        names.append("eta")
    if md:
        names.append("alpha")
    return names


def regression(points: SteadyPoints, model: str):
    r"""Build :math:`y` and :math:`H` for a steady-state model (Indiveri 1998, eqs. 4.15-4.17).

    .. math:: y = H\theta,\quad H = [w,\ w|w|,\ \mp 1,\ -F\,[F<0],\ n_h w],\quad
              y = F\,[F \ge 0 \text{ or no } \eta]

    (columns as the model has them: bias -1 for heave's W, +1 for b; see module docstring).
    ``points``: velocity w [m/s or rad/s], force F [N or N m], n_h [command units].

    Returns
    -------
    y : (m,) array, H : (m, p) array, names : list of str
    """
    if model not in MODELS:
        raise unknown_name("steady-state model", model, MODELS)
    lin, quad, bias, eta, md = MODELS[model]
    w, f = points.velocity, points.force
    heave = DOF[parse_dof(points.dof)] == "heave"
    up = f < 0.0 if eta else np.zeros(f.size, dtype=bool)
    cols = []
    if lin:
        cols.append(w)
    if quad:
        cols.append(w * np.abs(w))
    if bias:
        # heave: F = drag - W (W the net weight, down positive); otherwise tau = drag + b
        cols.append(-np.ones_like(w) if heave else np.ones_like(w))
    if eta:
        cols.append(np.where(up, -f, 0.0))
    if md:
        if points.n_h is None:
            raise InputError("missing column for the momentum-drag model", file=points.source,
                             key="n_h", expected="a column n_h (mean |command| of the horizontal "
                             "thrusters) or --vehicle with horizontal thrusters' n_<name> columns")
        cols.append(points.n_h * w)
    y = np.where(up, 0.0, f)
    return y, np.column_stack(cols), _names(points.dof, model)


def fit_steady(points: SteadyPoints, model: str = "standard", *,
               direction: str = "both") -> FitResult:
    r"""Fit one steady-state model by least squares (Indiveri 1998, eqs. 4.5, 4.6, 4.12).

    Adds the SNAME derivatives as derived parameters (``Z_w = -k_w``, ``Z_ww = -k_ww``...).
    :math:`\hat\theta = (H^TH)^{-1}H^Ty` on :func:`regression`'s y, H; units: k [N s/m or
    N m s/rad], k_2 [N s^2/m^2 or N m s^2/rad^2], W, b [N or N m], eta [-].
    """
    pts = points.select(direction)
    i = parse_dof(pts.dof)
    y, H, names = regression(pts, model)
    label = model if direction == "both" else f"{model} {direction}"
    v = VELOCITIES[i]
    units_v = "m/s" if i < 3 else "rad/s"
    units_f = "N" if i < 3 else "N m"
    units = {f"k_{v}": f"{units_f} s/{units_v.split('/')[0]}",
             f"k_{v}{v}": f"{units_f} s^2/{units_v.split('/')[0]}^2",
             "W": "N", "b": units_f, "eta": "-", "alpha": f"{units_f} s/{units_v.split('/')[0]}"
                                                           " per command"}
    fit = linear_lstsq(H, y, names, method="steady", model=label, dof=DOF[i],
                       units={n: units[n] for n in names}, what=f"{pts.source}: {DOF[i]} points")
    for n in names:
        if n == f"k_{v}":
            fit.derive(f"{FORCES[i]}_{v}", lambda p, n=n: -p[n], unit=units[n])
        elif n == f"k_{v}{v}":
            fit.derive(f"{FORCES[i]}_{v}{v}", lambda p, n=n: -p[n], unit=units[n])
    fit.data.update({"velocity": pts.velocity, "force": pts.force,
                     "predicted": predicted_force(fit, pts)})
    fit.notes.append(f"{len(pts)} steady-state points; residuals in {units_f} (Indiveri 1998 eq. 4.12)")
    return fit


def predicted_force(fit: FitResult, points: SteadyPoints) -> np.ndarray:
    r"""Applied force the fitted model needs for each point's velocity [N or N m]:
    :math:`\hat F = (k w + k_2 w|w| \mp W + \alpha n_h w) / \eta` (eta on upward points).

    Inverse of the module docstring's models (Indiveri 1998, eqs. 4.15-4.17); here "upward" is
    where the predicted drag side is negative. ``points.velocity`` [m/s or rad/s].
    """
    i = parse_dof(points.dof)
    v = VELOCITIES[i]
    p = fit.parameters
    w = points.velocity
    drag = p.get(f"k_{v}", 0.0) * w + p.get(f"k_{v}{v}", 0.0) * w * np.abs(w)
    drag = drag - p.get("W", 0.0) + p.get("b", 0.0)
    if "alpha" in p and points.n_h is not None:
        drag = drag + p["alpha"] * points.n_h * w
    if "eta" in p:
        drag = np.where(drag < 0, drag / p["eta"], drag)
    return drag


# ---------------------------------------------------------------------------
# Model comparison (Indiveri 1998, sec. 4.2.5 tables)
# ---------------------------------------------------------------------------

@dataclass
class Candidate:
    """One way of describing all the data: a model fitted to both directions together
    (``direction="both"``), or to each direction separately (``"separate"``: J and p summed),
    or to one direction only.

    ``values`` and ``rel_errors`` hold the estimates and 100 sd/|theta| of every parameter
    (per-direction names suffixed ``_pos``/``_neg`` for separate fits).
    """

    label: str
    model: str
    direction: str
    n_obs: int
    n_params: int
    cost: float
    values: dict
    rel_errors: dict
    fits: list = field(default_factory=list)

    @classmethod
    def from_fits(cls, label, model, direction, fits):
        values, rel = {}, {}
        for f, suffix in zip(fits, ("_pos", "_neg") if len(fits) == 2 else ("",)):
            for n in f.names:
                values[n + suffix] = f.parameters[n]
                rel[n + suffix] = f.relative_error_percent[n]
        return cls(label, model, direction, sum(f.n_obs for f in fits),
                   sum(f.n_params for f in fits), sum(f.cost for f in fits), values, rel,
                   list(fits))

    @property
    def aicc(self) -> float:
        k, n = self.n_params, self.n_obs
        aic = n * math.log(max(self.cost, 1e-300) / n) + 2 * k
        return aic + (2 * k * (k + 1) / (n - k - 1) if n - k - 1 > 0 else math.inf)

    @property
    def bic(self) -> float:
        n = self.n_obs
        return n * math.log(max(self.cost, 1e-300) / n) + self.n_params * math.log(n)

    @property
    def max_relative_error(self) -> float:
        return max(self.rel_errors.values()) if self.rel_errors else 0.0

    def problems(self) -> list:
        """Why the candidate is not admissible: insignificant terms, negative drag."""
        out = [f"{n} {r:.0f} %" for n, r in self.rel_errors.items()
               if not r < SIGNIFICANT_PERCENT]
        out += [f"{n} = {v:.3g} < 0" for n, v in self.values.items()
                if n.startswith("k_") and v < 0]
        return out

    @property
    def all_significant(self) -> bool:
        return not self.problems()


def recommend(cands: list):
    r"""Rank candidates by AICc and pick the best admissible one.

    Admissible (Indiveri 1998, sec. 4.2.5's two arguments made explicit): every parameter beyond
    2 sigma (relative error < 50 %) and no negative drag coefficient (a negative k is
    unphysical).  Returns (ranked list, recommended, explanation).
    """
    ranked = sorted(cands, key=lambda c: c.aicc)
    best = ranked[0]
    ok = [c for c in ranked if not c.problems()]
    rec = ok[0] if ok else best
    lines = [f"Lowest AICc: {best.label} (AICc {best.aicc:.2f}, J_LS {best.cost:.4g})."]
    if rec is not best:
        for c in ranked[:ranked.index(rec)]:
            lines.append(f"{c.label} rejected: {', '.join(c.problems())}.")
        lines.append(f"Recommended: {rec.label} (AICc {rec.aicc:.2f}, J_LS {rec.cost:.4g}), the "
                     "best-ranked model with every parameter beyond 2 sigma and no negative "
                     f"drag (largest relative error {rec.max_relative_error:.1f} %).")
    elif not ok:
        lines.append("No candidate has every parameter beyond 2 sigma and positive drag: more "
                     "data (a wider velocity range) are needed to separate the terms.")
    else:
        lines.append(f"It is admissible: every parameter beyond 2 sigma (largest relative "
                     f"error {rec.max_relative_error:.1f} %), no negative drag.")
    return ranked, rec, " ".join(lines)


def merge_directions(fp: FitResult, fn: FitResult) -> FitResult:
    """One FitResult from the two per-direction fits: names suffixed ``_pos`` / ``_neg``,
    block-diagonal covariance, costs and observations summed."""
    names = [f"{n}_pos" for n in fp.names] + [f"{n}_neg" for n in fn.names]
    p1, p2 = fp.n_params, fn.n_params
    cov = np.zeros((p1 + p2, p1 + p2))
    cov[:p1, :p1] = fp.cov
    cov[p1:, p1:] = fn.cov
    model = fp.model.rsplit(" ", 1)[0]
    out = FitResult(method=fp.method, model=f"{model} +/- separately", dof=fp.dof, names=names,
                    theta=np.concatenate([fp.theta, fn.theta]), cov=cov,
                    residuals=np.concatenate([fp.residuals, fn.residuals]),
                    cost=fp.cost + fn.cost, n_obs=fp.n_obs + fn.n_obs,
                    units={f"{n}_{d}": u for d, f in (("pos", fp), ("neg", fn))
                           for n, u in f.units.items()})
    for d, f in (("pos", fp), ("neg", fn)):
        for n, (v, sd) in f.derived.items():
            out.derived[f"{n}_{d}"] = (v, sd)
    out.data = {k: np.concatenate([fp.data[k], fn.data[k]])
                for k in ("velocity", "force", "predicted", "y", "fitted")}
    out.notes = fp.notes[:1] + fn.notes[:1]
    return out


@dataclass
class Comparison:
    """Models ranked for one DOF, with the recommended one and why."""

    dof: str
    candidates: list       # ranked by AICc (best first)
    single: list           # every single-direction fit (the paper's tables)
    recommended: Candidate
    explanation: str


def compare_models(points: SteadyPoints, models=COMPARISON_MODELS) -> Comparison:
    r"""Fit LQB / LQNB / LB / LNB to each direction and to both (Indiveri 1998, sec. 4.2.5).

    Candidates for describing *all* the data: each model fitted to both directions together,
    and each model fitted to the two directions separately (J summed, p summed).  Ranked by
    AICc (small samples: Indiveri 1998 has 4 to 14 points); the recommended model is the best-ranked
    admissible one (:func:`recommend`: every parameter beyond 2 sigma, no negative drag),
    which formalises the paper's argument for LNB.
    """
    single = []
    cands = []
    for model in models:
        fits = {}
        for d in DIRECTIONS:
            try:
                fits[d] = fit_steady(points, model, direction=d)
            except InputError:
                fits[d] = None
            if fits[d] is not None and d != "both":
                single.append(fits[d])
        if fits["both"] is not None:
            cands.append(Candidate.from_fits(f"{model} together", model, "both",
                                             [fits["both"]]))
        if fits["positive"] is not None and fits["negative"] is not None:
            cands.append(Candidate.from_fits(f"{model} +/- separately", model, "separate",
                                             [fits["positive"], fits["negative"]]))
    if not cands:
        raise InputError("no model could be fitted", file=points.source, key=points.dof,
                         value=len(points), expected="more steady-state points than parameters")
    ranked, rec, text = recommend(cands)
    return Comparison(points.dof, ranked, single, rec, text)


def recommended_fit(cmp: Comparison) -> FitResult:
    """The recommended candidate as one FitResult (per-direction fits merged)."""
    c = cmp.recommended
    return c.fits[0] if len(c.fits) == 1 else merge_directions(*c.fits)


# ---------------------------------------------------------------------------
# Steady points from a log
# ---------------------------------------------------------------------------

def steady_points(log, dof, *, force=None, n_h=None, settle: float = 8.0, trim: int = 0,
                  tol: float = 1e-9, min_samples: int = 5) -> SteadyPoints:
    r"""Steady-state points of one DOF from a log.

    A log without ``t`` is a table of points: the velocity column (``w`` for heave) and the
    force column (``Z``), or ``force`` given by the caller (thruster map).  A time series is cut
    into segments of constant input; in each, the first ``settle`` seconds (the transient) and
    the last ``trim`` samples are dropped (Indiveri 1998, sec. 4.2.4) and the steady velocity is the
    mean of the velocity column, or, when only the pose is logged (``z``, ``psi``), the slope
    of the least-squares line :math:`y(t) = \dot\psi t + \psi_0` (Indiveri 1998, eq. 4.18;
    angles are unwrapped first, so full turns at a constant yaw rate are fine).

    Parameters
    ----------
    log : stripcoef.logfile.Log
    dof : str
    force : (n,) array, optional
        Applied force along the DOF [N, N m]; default the log's force column.
    n_h : (n,) array, optional
        Mean |command| of horizontal thrusters; default the log's ``n_h`` column if present.
    settle : float
        Seconds dropped at the start of each constant-input segment [s].
    """
    i = parse_dof(dof)
    vname, fname, pname = VELOCITIES[i], FORCES[i], POSE[i]
    f = np.asarray(force, dtype=float) if force is not None else log.require(fname)
    nh = n_h if n_h is not None else log.get("n_h")
    if not log.is_time_series:
        return SteadyPoints(DOF[i], log.require(vname), f, nh, log.source)
    t = log.require("t")
    if vname in log:
        vel, use_pose = log[vname], False
    elif pname in log:
        vel, use_pose = (np.unwrap(log[pname]) if i >= 3 else log[pname]), True
    else:
        log.require(vname)  # raises, naming the column
    change = np.nonzero(np.abs(np.diff(f)) > tol * max(1.0, float(np.abs(f).max())))[0] + 1
    bounds = np.concatenate([[0], change, [f.size]])
    pv, pf, pn = [], [], []
    for a, b in zip(bounds[:-1], bounds[1:]):
        keep = np.arange(a, b - trim)
        keep = keep[t[keep] >= t[a] + settle]
        if keep.size < min_samples:
            continue
        if use_pose:
            A = np.column_stack([t[keep] - t[keep].mean(), np.ones(keep.size)])
            pv.append(float(np.linalg.lstsq(A, vel[keep], rcond=None)[0][0]))
        else:
            pv.append(float(vel[keep].mean()))
        pf.append(float(f[a]))
        if nh is not None:
            pn.append(float(np.mean(np.asarray(nh)[keep])))
    if len(pv) == 0:
        raise InputError("no steady segment found", file=log.source, key=fname,
                         expected=f"constant-input segments longer than settle={settle} s "
                         f"plus {min_samples} samples")
    return SteadyPoints(DOF[i], np.array(pv), np.array(pf),
                        np.array(pn) if nh is not None else None, log.source)
