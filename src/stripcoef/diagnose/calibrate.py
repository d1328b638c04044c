"""Model surgery: the fitted values of a diagnosis written into the prior model (a new
:class:`~stripcoef.model.HydroModel`), the added mass kept within its bounds, and the
coefficients at a bound listed.

The thrusters' timing (a first-order lag, a pure delay) is one property of the actuators,
not of a DOF: :func:`share_timing` fits it once for all the DOFs the thrusters drive (the
water current, one vector of the water, likewise: :mod:`stripcoef.diagnose.current`).

Depends on: model, conventions, diagnose.priors, diagnose.settings, diagnose.fit,
diagnose.cross, diagnose.couplings.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from stripcoef.conventions import DOF, parse_dof
from stripcoef.diagnose.couplings import coupling_dof
from stripcoef.diagnose.cross import shared_value, with_known
from stripcoef.diagnose.fit import _Config, _fit, _solve, grid_minimum, refit
from stripcoef.diagnose.priors import added_mass_bounds


def clip_added_mass(prior, calibrated, added_mass_sd=None):
    """``(model, clipped)``: ``calibrated`` with each diagonal added mass clipped to
    :func:`added_mass_bounds` of the prior's (a new model if anything moved), and
    ``{dof: (value before, value after)}`` [kg or kg m^2] of the clipped ones. The fits are
    bounded already; this catches what an effect adds to the matrix afterwards."""
    ma = np.array(calibrated.added_mass, float)
    clipped = {}
    for i in range(6):
        ma0 = float(prior.added_mass[i, i])
        if ma0 == 0.0 or ma[i, i] == ma0:
            continue
        lo, hi = added_mass_bounds(i, ma0, None if added_mass_sd is None
                                   else float(added_mass_sd[i]))
        value = float(np.clip(ma[i, i], lo, hi))
        if value != ma[i, i]:
            clipped[DOF[i]] = (float(ma[i, i]), value)
            ma[i, i] = value
    if not clipped:
        return calibrated, clipped
    return replace(calibrated, added_mass=ma, added_mass_error=None), clipped


def bounds_hit(prior, calibrated, added_mass_sd=None, clipped=None) -> dict:
    """The coefficients of a calibrated model at a physical bound: DOF -> {name: text}, for
    an added mass at a limit of :func:`added_mass_bounds` (the 99.7 % method band with
    ``added_mass_sd``; ``clipped``: :func:`clip_added_mass`'s record), a drag at zero and
    an effect written with a parameter at a bound of its fit (e.g. a thrust scale at its
    lower bound 0.05; the model's provenance)."""
    out = {}
    clipped = clipped or {}
    for i in range(6):
        hits = {}
        ma0, ma = float(prior.added_mass[i, i]), float(calibrated.added_mass[i, i])
        if ma0 != 0.0:
            sd = None if added_mass_sd is None else float(added_mass_sd[i])
            lo, hi = added_mass_bounds(i, ma0, sd)
            band = (f"the 99.7 % band of its method uncertainty ({100 * sd:g} % at 1 sigma) "
                    "and its plausible range" if sd is not None and np.isfinite(sd) and sd > 0
                    else "its plausible range")
            for value, name in ((lo, "lower"), (hi, "upper")):
                # within the bounded scalar search's tolerance (1e-6 of the DOF's whole
                # inertia M_RB + M_A, a few 1e-6 of M_A): at the bound
                if ma != ma0 and abs(ma - value) <= 1e-5 * max(abs(value), 1e-12):
                    hits["M"] = (f"added mass {ma:.4g} at the {name} bound of {band} "
                                 f"[{lo:.4g}, {hi:.4g}]")
                    if DOF[i] in clipped:
                        hits["M"] += f", clipped from {clipped[DOF[i]][0]:.4g}"
        for key, attr in (("D_L", "linear_damping"), ("D_Q", "quadratic_damping")):
            d0, d = float(getattr(prior, attr)[i, i]), float(getattr(calibrated, attr)[i, i])
            if d0 != 0.0 and d != d0 and abs(d) <= 1e-9 * abs(d0):
                hits[key] = f"{key} {d:.3g} at its bound 0 (no negative drag)"
        for name, side in _effects_at_bound(calibrated, DOF[i]).items():
            hits[name] = side
        if hits:
            out[DOF[i]] = hits
    return out


def _effects_at_bound(model, dof: str) -> dict:
    """{effect: text} for the effects of DOF ``dof`` that a diagnosis wrote with a fitted
    parameter at a bound of its fit (the model's provenance, :func:`calibrated_model`)."""
    out = {}
    for entry in model.provenance.get("diagnose", ()) or ():
        if entry.get("dof") != dof:
            continue
        for name, side in (entry.get("at_bound") or {}).items():
            params = (entry.get("parameters") or {}).get(name, {})
            out[name] = (f"{name} " + ", ".join(f"{k} = {v:.4g}" for k, v in params.items())
                         + f" at the {side} bound of its fit")
    return out


def _changes(per: dict) -> list:
    """The changes a diagnosis makes to the prior: each DOF's calibration and each effect."""
    out = []
    for d, r in per.items():
        if any(v != 0.0 for v in r.calibration.final_parameters.values()):
            out.append(("calibration", d))
        # a step one DOF does not determine is never written (diagnose.undetermined)
        out += [("effect", d, s.effect) for s in r.steps if not s.not_determined]
    return out



def _writable_matrices(model) -> dict:
    """Writable copies of a model's M_A, D_L, D_Q under the calibration's names."""
    return {"M": np.array(model.added_mass, float), "D_L": np.array(model.linear_damping, float),
            "D_Q": np.array(model.quadratic_damping, float)}


def _with_matrices(model, mats: dict):
    """``model`` with the matrices of :func:`_writable_matrices` (a new model); a calibrated
    added mass is no longer the panel method's, so its estimated error goes."""
    changed = not np.array_equal(mats["M"], model.added_mass)
    return replace(model, added_mass=mats["M"], linear_damping=mats["D_L"],
                   quadratic_damping=mats["D_Q"],
                   added_mass_error=None if changed else model.added_mass_error)


def written_fit(d: str, result, fit, exclude=frozenset(), known=None):
    """``(config, theta)``: the fit of DOF ``d`` whose values are written, given the changes
    ``exclude``d (:func:`calibrated_model`). Without exclusions, the diagnosis's final fit;
    with some, the kept terms refitted without the removed ones (their nonlinear parameters
    as selected), so that no kept parameter compensates a term that is not there (so too
    without a step whose value one DOF does not determine, ``Step.not_determined``) -- and,
    when the DOF's calibration is removed, without the calibration columns (its
    coefficients stay at the prior): the effects fitted together with it are refitted
    alone. ``theta`` starts with the calibration's values (none when it is removed).

    ``known``: {``M_<dof>``: change [kg or kg m^2]} of other DOFs' added masses beyond
    those the DOF's window data already hold as known forces (:func:`consistent_fits`):
    their force through :math:`C_A(\nu)\nu` is taken out too and the kept terms are
    refitted (a calibration column of the same name is then dropped)."""
    cfg = fit.config
    theta = fit.evaluation["full"]["theta"]
    # the changes removed, and the steps named whose value one DOF does not determine
    # (diagnose.undetermined: nothing written for them)
    unwritten = {s.effect for s in result.steps if s.not_determined}
    dropped = [t for t in cfg.terms if ("effect", d, t[0].name) in exclude
               or t[0].name in unwritten]
    no_cal = ("calibration", d) in exclude and len(cfg.cal.names) > 0
    if no_cal:
        cfg = _Config(cfg.data, cfg.dof, cfg.cal.subset([]), list(cfg.terms),
                      settings=cfg.settings, budget=cfg.budget)
    if dropped:
        cfg = cfg.with_terms([t for t in cfg.terms if t not in dropped])
    known = {k: v for k, v in (known or {}).items() if v != 0.0}
    if known:
        cfg = _with_known(cfg, known)
    if (dropped or no_cal or known) and (cfg.terms or not no_cal):
        theta = _fit(cfg)["theta"]
    elif no_cal:
        theta = np.zeros(0)
    return cfg, theta


def _with_known(cfg, known: dict):
    """``cfg`` with the added-mass changes ``known`` taken out of its DOF's residual as known
    forces (:func:`stripcoef.diagnose.cross.with_known`, at the velocity relative to the
    water when a term defines it, as
    :meth:`~stripcoef.diagnose.fit._Config.calibration_columns`) and those columns left out
    of the calibration (a new configuration)."""
    nur = next((eff.relative_velocity(cfg.data, h) for eff, h in cfg.terms
                if h is not None and hasattr(eff, "relative_velocity")), None)
    data = with_known(cfg.data, cfg.dof, known, nur)
    keep = [j for j, n in enumerate(cfg.cal.names) if n not in known]
    return _Config(data, cfg.dof, cfg.cal.subset(keep), list(cfg.terms), settings=cfg.settings,
                   budget=cfg.budget)


#: Sweeps of :func:`consistent_fits` at most, and the relative change of the diagnosed DOFs'
#: added masses [-] below which the sweeps stop (the fits are linear given the selected
#: nonlinear parameters: a fixed point of one coefficient per DOF)
CONSISTENT_SWEEPS, CONSISTENT_TOL = 8, 1e-6


def consistent_fits(model, per: dict, fits: dict, exclude=frozenset()) -> dict:
    r"""DOF -> :func:`written_fit` of each DOF of ``per``; a DOF selected with other diagnosed
    DOFs' added masses as known forces (:func:`contradicted`; its window data's
    ``known_added_mass``) is refitted with the values written for them, so that it is written
    beside the same values it is fitted with (one coefficient, one value:
    :mod:`stripcoef.diagnose.cross`). Each DOF's own added mass moves with the others'
    (Gauss-Seidel sweeps of the linear refits until the written added masses change by less
    than ``CONSISTENT_TOL`` relative, at most ``CONSISTENT_SWEEPS``)."""
    fitted = {d: written_fit(d, r, fits[d], exclude) for d, r in per.items()}
    held = {d: dict(fits[d].config.data.known_added_mass) for d in per}
    if not any(held.values()):
        return fitted
    prior = np.diag(np.asarray(model.added_mass, float))
    own = _own_added_mass(model, per, fitted)
    for _ in range(CONSISTENT_SWEEPS):
        for d, r in per.items():
            if held[d]:
                known = {k: own[k[2:]] - prior[parse_dof(k[2:])] - v
                         for k, v in held[d].items()}
                fitted[d] = written_fit(d, r, fits[d], exclude, known)
        new = _own_added_mass(model, per, fitted)
        moved = max(abs(new[e] - own[e]) / max(abs(prior[parse_dof(e)]), 1e-12) for e in per)
        own = new
        if moved < CONSISTENT_TOL:
            break
    return fitted


def contradicted(model, per: dict, fits: dict, difference: bool = False) -> dict:
    r"""The DOFs of a whole-log diagnosis whose fit holds another diagnosed DOF's added mass
    ``M_<dof>`` (:mod:`stripcoef.diagnose.cross`) at a value that contradicts the one written
    for it, its own DOF's (:func:`calibrated_model` before the validation): more than
    ``MIN_Z`` of the fit's standard deviation from it (the selection's rule of a parameter
    told from a value, :data:`~stripcoef.diagnose.settings.MIN_Z`). DOF -> {``M_<dof>``:
    the written change [kg or kg m^2]} of every diagnosed DOF it feels: the known forces it
    is selected again with (:func:`stripcoef.diagnose.cross.with_known`). Issue 33: on the
    VideoRay-like issue-16 log (seed 7, 0.49 of the thrust acting) yaw's Munk moment held the
    sway added mass at +5.2 kg (sd 0.57) where sway's own balance, written, gave +0.5 kg: the
    free added mass had taken the yaw thrust scale (the balance is homogeneous in thrust,
    inertia and drag; :mod:`stripcoef.diagnose.scalechoice`) and the model written had
    neither.

    ``difference``: the two estimates contradict each other only when their difference is
    more than ``MIN_Z`` sd of the difference, :math:`\sqrt{s_d^2 + s_j^2}` with
    :math:`s_j` the sd of DOF j's own calibrated added mass, 0 where its calibration does
    not hold it (independent estimates: the variance of their difference is the sum of
    their variances, Bevington & Robinson 2003, Data Reduction and Error Analysis, ch. 3)."""
    from stripcoef.diagnose.settings import MIN_Z
    fitted = {d: written_fit(d, r, fits[d]) for d, r in per.items()}
    prior = np.diag(np.asarray(model.added_mass, float))
    own = _own_added_mass(model, per, fitted)
    out = {}
    for d in per:
        ev = fits[d].evaluation["full"]
        names = list(fits[d].config.cal.names)
        mine = {n: k for k, n in enumerate(names) if n.startswith("M_") and n[2:] in per}
        written = {n: own[n[2:]] - prior[parse_dof(n[2:])] for n in mine}
        far = [n for n, k in mine.items()
               if abs(ev["theta"][k] - written[n])
               > MIN_Z * math.sqrt(max(float(ev["cov"][k, k]), 0.0)
                                   + (_own_variance(fits[n[2:]]) if difference else 0.0))]
        if far:
            out[d] = written
    return out


def _own_variance(fit) -> float:
    """The variance of a DOF's own calibrated added mass ``M`` in its final fit [kg^2 or
    kg^2 m^4]; 0 when its calibration does not hold it."""
    names = list(fit.config.cal.names)
    if "M" not in names:
        return 0.0
    k = names.index("M")
    return max(float(fit.evaluation["full"]["cov"][k, k]), 0.0)


def _own_added_mass(model, per: dict, fitted: dict) -> dict:
    """DOF -> its diagonal added mass in the model :func:`_build` writes from ``fitted``
    [kg or kg m^2] (its calibration, an added-mass effect folded in)."""
    m = _build(model, per, fitted)
    return {d: float(m.added_mass[parse_dof(d), parse_dof(d)]) for d in per}


def calibrated_model(model, per: dict, fits: dict, exclude=frozenset()):
    """The prior with its calibrated coefficients and the added effects (a new model);
    ``per``: DOF -> its result (:class:`DofResult`), ``fits``: DOF -> its :class:`DofFit`;
    ``exclude``: changes left out, ``("calibration", dof)`` or ``("effect", dof, name)``
    (see :func:`validate_changes`); the values written are those of :func:`written_fit`.

    The calibration of DOF i adds its own M, D_L, D_Q and the other DOFs' added mass
    ``M_<dof>`` seen through C_A -- unless that DOF is diagnosed itself, whose own
    calibration then holds; an added mass calibrated in several DOFs is written once, their
    inverse-variance weighted mean (:func:`stripcoef.diagnose.cross.shared_value`). The model's provenance (``diagnose``) records, per DOF, the
    calibration changes applied and the parameters of each effect as applied (a native
    effect's, folded into the matrices or thrusters, included). A timing effect of
    :data:`SHARED_TIMING` written in several DOFs (:func:`share_timing`: one value) is
    written once, as one entry for all DOFs (``dof: all``: one force law of the
    thrusters' lag in a simulation instead of one per DOF, the same forces); so is the one
    water current (:func:`stripcoef.diagnose.current.share_current`), which acts in all six
    DOFs through the relative velocity."""
    return calibrated_fits(model, per, fits, exclude)[0]


def calibrated_fits(model, per: dict, fits: dict, exclude=frozenset()):
    """``(model, fitted)``: :func:`calibrated_model` and the fits it writes from (DOF ->
    ``(config, theta)``, :func:`consistent_fits`), for :func:`stripcoef.diagnose.written.
    read_back` to say which values each DOF was fitted beside."""
    fitted = consistent_fits(model, per, fits, exclude)
    return _build(model, per, fitted), fitted


def _build(model, per: dict, fitted: dict):
    """The model :func:`calibrated_model` writes from the fits ``fitted`` (DOF ->
    ``(config, theta)``, :func:`written_fit`)."""
    m = model
    mats = _writable_matrices(m)
    record = []
    # DOFs whose written fit holds each shared timing effect (share_timing)
    shared_in = {}
    for cfg, _ in fitted.values():
        for eff, _ in cfg.terms:
            shared_in[eff.name] = shared_in.get(eff.name, 0) + 1
    shared, cross = {}, {}
    for d, r in per.items():
        i = parse_dof(d)
        cfg, theta = fitted[d]
        k = len(cfg.cal.names)
        steps = {s.effect: s for s in r.steps}
        # a released coefficient's calibration is written as part of its effect (one change)
        fold = {eff.name: folded_key(eff, steps[eff.name].mimics, cfg.cal.names)
                for eff, _ in cfg.terms}
        fold = {name: key for name, key in fold.items() if key}
        applied = {}
        for key, value in zip(cfg.cal.names, theta[:k]):
            if key in fold.values():
                continue
            if key in ("M", "D_L", "D_Q"):
                mats[key][i, i] += value
                applied[key] = float(value)
            elif coupling_dof(key) is not None:    # a drag coupling D_Q[i, j] (couplings)
                mats["D_Q"][i, coupling_dof(key)] += value
                applied[key] = float(value)
            elif key.startswith("M_") and key[2:] not in per:
                # a DOF that moves but is not diagnosed: its added mass may be calibrated
                # in several DOFs, one value written after the loop (cross.shared_value)
                cross.setdefault(key, []).append(
                    (float(value), float(r.calibration.std.get(key, math.nan))))
                applied[key] = float(value)
        kept_effects, parameters, at_bound = [], {}, {}
        low, up = cfg.lower(), cfg.upper()
        for eff, hyper in cfg.terms:
            ncol = eff.design(cfg.data, i, hyper)[1].shape[1]
            nuis = eff.nuisance(cfg.data, i)
            kn = 0 if nuis is None else nuis.shape[1]
            tn = theta[k:k + kn]
            own = np.array(theta[k + kn:k + ncol], float)
            if eff.name in fold:
                own[0] += theta[list(cfg.cal.names).index(fold[eff.name])]
            params = eff.to_parameters(own, hyper, tn)
            side = (_pinned(theta[k + kn:k + ncol], low[k + kn:k + ncol], up[k + kn:k + ncol])
                    or (eff.at_bound(params) if hasattr(eff, "at_bound") else ""))
            if side:
                at_bound[eff.name] = side
            k += ncol
            for name, value in zip(eff.nuisance_names, tn):
                if name in mats:  # a prior coefficient released by this effect
                    mats[name][i, i] += float(value)
            if eff.name in SHARED_EFFECTS and shared_in.get(eff.name, 0) > 1:
                # the thrusters' one lag or delay (share_timing): one entry for all DOFs,
                # written once below (one force law, not one per DOF, in a simulation)
                shared[eff.name] = (eff, params, steps[eff.name].std)
            else:
                # a native effect adds its term to the matrices calibrated so far
                m = eff.apply(_with_matrices(m, mats), i, params, steps[eff.name].std)
                mats = _writable_matrices(m)
            kept_effects.append(eff.name)
            parameters[eff.name] = {n: float(v) for n, v in params.items()}
        record.append({"dof": d, "calibration": applied, "effects": kept_effects,
                       "parameters": parameters, "at_bound": at_bound})
    for key, estimates in cross.items():
        mats["M"][parse_dof(key[2:]), parse_dof(key[2:])] += shared_value(estimates)[0]
    m = _with_matrices(m, mats)
    for eff, params, std in shared.values():
        m = m.with_effects({"name": eff.name, "dof": "all", "parameters": dict(params),
                            "std": dict(std or {}), "units": dict(eff.parameters)})
    m = m.with_provenance(diagnose=record)
    return replace(m, name=f"{model.name}-calibrated")


def folded_key(eff, mimics: str | None, cal_names) -> str:
    """The calibration coefficient that an effect without a signature releases
    (``mimics``, its step's, e.g. ``M`` for an added-mass error, ``D_L`` for a linear drag the
    prior has), when it is calibrated too and the effect's one parameter is that
    coefficient's change: the calibration and the effect are then one change of the same
    coefficient, reported and written as the effect's, the total from the prior (issue 33:
    an added mass 2x the prior's reported as the effect's share alone); else ''."""
    key = mimics
    if key and key in cal_names and getattr(eff, "native", False) \
            and len(eff.parameters) == 1 and not eff.nuisance_names:
        return key
    return ""


def _pinned(theta, low, up) -> str:
    """``"lower"``/``"upper"`` when a fitted column sits at its bound (within 1e-4 of the
    bound's magnitude, the bounded solver's tolerance; :func:`stripcoef.diagnose.select._judge`
    uses the same test), else ''."""
    for values, bound, name in ((theta, low, "lower"), (theta, up, "upper")):
        fin = np.isfinite(bound)
        tol = 1e-4 * np.maximum(1.0, np.abs(np.where(fin, bound, 0.0)))
        if np.any(fin & (np.abs(values - np.where(fin, bound, 0.0)) <= tol)):
            return name
    return ""


#: Effects of the thrusters' timing: one value for all of a vehicle's thrusters
#: (:func:`share_timing`); the validation keeps or removes each as one change
#: (:func:`stripcoef.diagnose.validate.partners`).
SHARED_TIMING = ("thruster_lag", "actuation_delay")
#: Effects fitted once for the whole vehicle: the thrusters' timing (:func:`share_timing`)
#: and the water current (:func:`stripcoef.diagnose.current.share_current`, one earth-frame
#: current written with the same value in each DOF it acts in): the validation keeps or
#: removes each as one change in all its DOFs, and not with one DOF's calibration
#: (:func:`stripcoef.diagnose.validate.partners`).
SHARED_EFFECTS = SHARED_TIMING + ("current",)


def _with_value(cfg, eff, value):
    """``cfg`` (a DOF's final configuration) with effect ``eff`` at the one parameter
    ``value``: its term's parameter replaced, or the term appended (a new configuration)."""
    terms = [(e, h) for e, h in cfg.terms]
    at = [k for k, (e, _) in enumerate(terms) if e.name == eff.name]
    if at:
        terms[at[0]] = (terms[at[0]][0], np.array([float(value)]))
    else:
        terms.append((eff, np.array([float(value)])))
    return cfg.with_terms(terms)


def _joint_cost(cfgs: dict, sigmas: dict, eff, value) -> float:
    """Sum over the DOFs of ``cfgs`` of the squared whitened MAP residuals (data and prior
    terms, :func:`~stripcoef.diagnose.fit._solve`) of each DOF's configuration with ``eff``
    at ``value``, each weighted by its own noise level ``sigmas[d]`` [-]: minus twice the
    joint log posterior, the DOFs' window residuals independent."""
    total = 0.0
    for d, cfg in cfgs.items():
        c = _with_value(cfg, eff, value)
        y, H, sd = c.design()
        wres = _solve(y, H, sd, sigmas[d], c.lower(), c.m_info(), c.upper(), with_cov=False)[2]
        total += float(wres @ wres)
    return total


def joint_profile(eff, cfgs: dict, sigmas: dict, d0: str) -> tuple[float, float, float]:
    r"""``(value, cost, std)`` of ``eff``'s one parameter profiled jointly over the DOFs'
    configurations ``cfgs`` (:func:`_joint_cost`): the grid then Brent
    (:func:`~stripcoef.diagnose.fit.grid_minimum`) on ``d0``'s grid; its sd from the cost's
    curvature, :math:`\sqrt{2/S''}` [s] (the cost is minus twice a log-likelihood, so half
    its curvature is the Fisher information), the step 1 % of the value (at least 1e-5 s)."""
    def cost(c):
        return _joint_cost(cfgs, sigmas, eff, c)
    data = cfgs[d0].data
    value, best = grid_minimum(cost, eff.grid(data, parse_dof(d0)))
    h = 1e-2 * max(value, 1e-3)
    curv = (cost(value + h) - 2.0 * best + cost(max(value - h, 1e-9))) / h ** 2
    return value, best, (math.sqrt(2.0 / curv) if curv > 0 else float("nan"))


def share_timing(per: dict, fits: dict) -> tuple[dict, dict]:
    r"""``(per, fits)`` (new dictionaries) with each timing effect of :data:`SHARED_TIMING`
    that the selection found in some DOF fitted once for all the diagnosed DOFs the
    thrusters drive, and written in each of them with that one value.

    A thruster lag (delay) is the actuators' own: every thrust follows its command with the
    same time constant :math:`T_l` [s], so every component of the generalized force
    :math:`\tau = B f` lags with it (the map B being linear in the thrusts; Fossen 2011,
    sec. 9.3). Fitted per DOF, each DOF gets its own :math:`T_l` and the DOFs where the
    per-DOF test missed it get none (the issue-33 real-style lag log: lags in sway, heave and
    pitch, none in roll and yaw, whose free simulations then ring). Here it is one parameter
    of a multiresponse model (Seber & Wild 1989, Nonlinear Regression, ch. 11): the value
    minimising the joint cost

    .. math:: S(T) = \sum_{i} \lVert W_i (y_i - H_i(T)\,\hat\theta_i(T)) \rVert^2

    over the diagnosed DOFs i where the thrusters act (each DOF's window residual whitened
    by its own noise level :math:`\sigma_i` and its calibration's prior,
    :func:`_joint_cost`; each DOF's linear parameters :math:`\hat\theta_i` profiled), by
    the grid of the effect (:meth:`grid`) and a bounded scalar search between the best
    point's neighbours, as :func:`stripcoef.diagnose.fit._profile_hyper` does for one DOF;
    its 1-sigma uncertainty :math:`\sqrt{2 / S''(T)}` (S is minus twice the log
    likelihood). Each of those DOFs' fits is then redone with that value (the effect added
    where the selection had not added it: a step marked not significant on its own, its
    ``signature`` saying it is shared). The validation keeps or removes it in all DOFs at
    once (:func:`stripcoef.diagnose.validate.partners`)."""
    per, fits = dict(per), dict(fits)
    for name in SHARED_TIMING:
        have = [d for d, f in fits.items() if any(e.name == name for e, _ in f.config.terms)]
        if not have:
            continue
        eff = next(e for e, _ in fits[have[0]].config.terms if e.name == name)
        template = next(s for s in per[have[0]].steps if s.effect == name)
        targets = [d for d in fits
                   if eff.applicable(fits[d].config.data, parse_dof(d))[0]]
        cfgs = {d: fits[d].config for d in targets}
        sigmas = {d: float(fits[d].evaluation["full"]["sigma"]) for d in targets}
        value, _, std = joint_profile(eff, cfgs, sigmas, targets[0])
        key = eff.hyper[0]
        share = ", ".join(targets)
        for d in targets:
            cfg = _with_value(cfgs[d], eff, value)
            before, ev = refit(fits, d, cfg)
            r = per[d]
            steps = list(r.steps)
            if d not in have:
                n = cfg.data.n_windows
                gain = 1.0 - ev["held_out_error"] / max(before["held_out_error"], 1e-300)
                steps.append(replace(
                    template, dof=d, parameters={key: value}, std={key: std}, released={},
                    signature=(f"shared: the thrusters' one {key} [s], fitted jointly on "
                               f"{share} (selected alone in {', '.join(have)})"),
                    mimics=None, band_excess=None, error_before=before["error"],
                    error_after=ev["error"],
                    held_out_error_before=before["held_out_error"],
                    held_out_error_after=ev["held_out_error"], held_out_gain=float(gain),
                    delta_bic=float(ev["bic"] + math.log(n) - before["bic"]),
                    z=float(value / std) if std > 0 else float("nan"),
                    significant=False, rejected_because=(), alternatives=(),
                    magnitude=float(eff.magnitude({key: value})),
                    final_parameters={key: value}))
            else:
                steps = [replace(s, final_parameters={key: value}) if s.effect == name
                         else s for s in steps]
            per[d] = replace(r, steps=tuple(steps), final_error=float(ev["error"]),
                              final_held_out_error=float(ev["held_out_error"]))
    return per, fits
