"""Detection benchmark of `stripcoef diagnose` on logs of an independent 6-DOF simulator.

The logs come from ``validation.independent`` (its own equations, integrator, thruster model,
pilot and noise; no code of stripcoef's simulate), for a VideoRay-like and a BlueROV2-Heavy-like
vehicle (the priors are stripcoef's models of ``geometry/videoray_pro3.yaml`` and
``geometry/bluerov2_heavy.yaml``; the truths are those priors with every coefficient family
scaled by U(0.75, 1.25)), one log per category and vehicle: each library effect at a random
strength, a clean log, and dry (Coulomb) friction, which no library effect describes. Each log
is diagnosed per DOF (the effect's DOF) and whole-log (``dof="all"``). A fresh seed every run
unless ``--seed`` is given; the seed is printed so that a run can be repeated.

Scores (issue 33's criteria):

- library effects: the right effect named first; its magnitude within 15 % of the truth
  (:func:`magnitude_truth`: for the thrust effectiveness, the DOF's whole thrust gain; a
  force effect or an added mass in the thrust's units, as the log determines them; each at
  the thrust the written model gives the DOF, whole-log thruster gains included); an
  effect named with its value "not determined by one DOF" (``not_determined``: a one-DOF
  tether whose c_t depends on the thrusters' gains, ``stripcoef.diagnose.undetermined``;
  nothing written) counts as named first, and its magnitude as not claimed: not within
  15 %, counted apart (``N not claimed``), the gain-free value it reports compared with the
  truth in the row only (``gains_free_error``); apart from it, the right effect named first or in the first step's ambiguous set (a
  thrust scale and an added-mass change the log does not tell apart,
  ``stripcoef.diagnose.scalechoice``; not counted as named first);
  the magnitude "held by the written model": within 15 % and the written model's own
  magnitude of the effect within 15 % too (``benchmarks.written_held``: whichever change
  wrote it, e.g. the calibration's inertia after an added-mass step is removed; a row
  written before mag33g by its step's ``kept``);
  the error cut at least 3x (baseline / final); in whole-log mode, no step in a DOF the
  effect does not act in (``ACTS_IN``: a thruster effect acts in every DOF the thrusters
  drive), counted for the steps named and for those the validation kept;
- the truth's background: every truth also carries a buoyancy drawn U(0.98, 1.02) x the
  prior's (a buoyancy offset in heave, roll and pitch) and thruster coefficients drawn
  U(0.75, 1.25) x the prior's (a thrust effectiveness of each DOF, :func:`thrust_gain`):
  real differences from the prior (:data:`BACKGROUND`). "Named first after background"
  passes over steps that name them; such a step is not spurious;
- clean logs: no effect added (and no effect other than the background);
- outside the library: ``unexplained``, or every step's held-out gain under 30 %.

Beside them, for every library effect, the oracle (``validation.detectability``): whether
the effect is detectable on the truth's own model without it, whether its own test passes
on the prior at the first step, and the error cut the truth's own model makes against the
prior (the ceiling of "error cut >= 3x"); the misses sorted into the draw, the prior's
other errors hiding the effect, and the selection's. ``--same-seeds`` seeds a run of a few
categories as a run of all would (the same logs); ``--validation-others`` is diagnose's.

Usage:
    python -m benchmarks.diagnose_independent [--seed S] [--duration 300] [--jobs 2]
        [--categories tether_drag,current,...] [--vehicles videoray_pro3,bluerov2_heavy]
        [--modes dof,all] [--repeats 1] [--write FILE.md] [--same-seeds]
        [diagnose's options: benchmarks.diagnose_flags, e.g. --linked-gains off]

Every option left out is diagnose's default (``DiagnoseSettings``); the defaults before
adopt33h (stop 56) are ``--validation-others logged --validation-horizon 10
--validation-judge all --validation-reference trivial --linked-gains off
--no-noise-with-bias``.
    python -m benchmarks.diagnose_independent --excitation [--seed S] [--repeats 3] ...

``--excitation`` diagnoses nothing: it generates the logs and prints how each excites its
DOFs (``validation.independent.excitation``): per driven DOF the shares of samples moving
each way, per thruster the share at its limit.
"""

from __future__ import annotations

import argparse
import multiprocessing
import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from benchmarks.diagnose_flags import add_flags, given

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

ROOT = Path(__file__).resolve().parent.parent
VEHICLES = ("videoray_pro3", "bluerov2_heavy")
#: A log's seed in a run: base + REPEAT_STRIDE repeat + VEHICLE_STRIDE vehicle + category.
REPEAT_STRIDE = 100000
VEHICLE_STRIDE = 1000


def run_categories() -> list:
    """The full run's categories in its order: the library's effects, the clean log, the
    effects outside the library (a log's category index in :func:`log_seed`)."""
    from validation.independent import OUTSIDE, STRENGTHS

    return list(STRENGTHS) + ["clean"] + list(OUTSIDE)


def log_seed(base: int, repeat: int, vehicle: int, category: int) -> int:
    """The seed of a run's log from the run's base seed and the log's repeat, vehicle index
    and category index (in :data:`VEHICLES` and :func:`run_categories`, or with a subset
    of them and no ``--same-seeds``, in the run's own lists)."""
    return base + REPEAT_STRIDE * repeat + VEHICLE_STRIDE * vehicle + category


def log_of(base: int, seed: int) -> tuple[str, str, int]:
    """``(vehicle, category, repeat)`` of the log ``seed`` of a full run from ``base``, the
    inverse of :func:`log_seed` ("clean" for a clean log); ValueError if no log of that run
    has this seed."""
    repeat, rest = divmod(seed - base, REPEAT_STRIDE)
    v, c = divmod(rest, VEHICLE_STRIDE)
    cats = run_categories()
    if seed < base or v >= len(VEHICLES) or c >= len(cats):
        raise ValueError(f"log seed {seed} is not a log of base seed {base}")
    return VEHICLES[v], cats[c], repeat


def _prior(vehicle: str):
    import stripcoef
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return stripcoef.estimate(ROOT / "geometry" / f"{vehicle}.yaml")


def with_truth_maps(prior, truth):
    """``prior`` whose thrusters carry the truth's thrust maps (each thruster's forward and
    backward :math:`C_t` in its efficiencies): the prior without the truth's thruster-gain
    background, the allocation matrix unchanged (the truth's thrusters sit where the
    prior's do: ``validation.independent`` keeps their positions, about the reference
    point)."""
    from dataclasses import replace
    # the log's own thruster effect stays out of the prior (validation.independent's
    # with_effect: a thrust effectiveness scales both branches, an asymmetry the backward)
    fwd = truth.strength if truth.effect == "thrust_effectiveness" else 1.0
    bwd = truth.strength if truth.effect in ("thrust_effectiveness", "thrust_asymmetry") else 1.0
    return replace(prior, thrusters=[
        replace(th, eta_forward=t["ct_forward"] / fwd / th.ct_forward,
                eta_backward=t["ct_backward"] / bwd / th.ct_backward)
        for th, t in zip(prior.thrusters, truth.thrusters)])


def run_one(vehicle: str, category: str | None, seed: int, duration: float,
            modes: tuple, validation_others: str | None = None,
            truth_maps: bool = False, one_added_mass: bool = False,
            dof_gains: bool = True, options: dict | None = None) -> list[dict]:
    """One log (simulated once) diagnosed in each of ``modes``: the rows of the score table
    (``validation_others``: :func:`stripcoef.diagnose.pipeline.diagnose`'s; ``truth_maps``:
    against the prior with the truth's thrust maps, :func:`with_truth_maps`, the gains of
    the background removed; ``one_added_mass``, ``dof_gains``, ``options``: diagnose's)."""
    from validation.independent import OUTSIDE, STRENGTHS, generate

    prior = _prior(vehicle)
    dof_name = ({**STRENGTHS, **OUTSIDE}.get(category) or ("surge",))[0]
    t0 = time.process_time()
    log, truth = generate(prior.to_dict(), category, seed, duration=duration)
    if truth_maps:
        prior = with_truth_maps(prior, truth)
    t1 = time.process_time()
    found = _oracle(log, prior, truth)
    rows = [{**_diagnosed(log, truth, prior, vehicle, category, seed, mode, dof_name, t1 - t0,
                          validation_others, one_added_mass, dof_gains, options),
             **_background(truth, prior.to_dict()), **found} for mode in modes]
    for row in rows:
        if row["mode"] == "all":
            row["truth_has"] = truth_effects(log, truth, prior, row)
    return rows


def _oracle(log, prior, truth) -> dict:
    """The row's record of the oracle test (``validation.detectability``): ``detectable``
    (one-DOF evidence gate), ``detectable_all`` (whole-log), ``truth_cut`` (the error cut
    the truth's own model makes against the prior in the effect's DOF, the ceiling of the
    row's ``cut``) and ``oracle`` (the test on the truth's model and on the prior), for a
    library effect; {} otherwise (clean, outside the library)."""
    from validation.detectability import oracle
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        got = oracle(log, prior, truth)
    if got is None:
        return {}
    return {"detectable": got["detectable"], "detectable_all": got["detectable_all"],
            "first_step_on_prior": got["first_step_on_prior"], "truth_cut": got["truth_cut"],
            "oracle": got}


def thrust_gain(truth, prior: dict, dof: int) -> float:
    r"""The truth's thrust in DOF ``dof`` per unit of the prior's thrust map [-]: the
    per-thruster factors :math:`f_k = C_{t,k}^{truth} / C_{t,k}^{prior}` (forward branch;
    they carry the U(0.75, 1.25) spread and a thrust effectiveness) averaged with the
    weights :math:`|B_{ik}| C_{t,k}^{prior}` of each thruster's reach in the DOF. The force
    balance :math:`\bar f\,\tau_{map} = M\dot\nu + D(\nu)\nu + F_{effect}` divided by
    :math:`\bar f` is what a log determines: inertia, drag and every force effect only as
    their ratio to :math:`\bar f` (the thrust map is the log's one absolute scale)."""
    w, fw = 0.0, 0.0
    for t, p in zip(truth.thrusters, prior["thrusters"]):
        c0 = float(p.get("ct_forward", 1.0)) * float(p.get("eta_forward", 1.0))
        b = np.concatenate([t["direction"], np.cross(t["position"], t["direction"])])[dof]
        w += abs(b) * c0
        fw += abs(b) * t["ct_forward"]
    return fw / w if w > 0 else 1.0


def _background(truth, prior: dict) -> dict:
    """The row's record of the truth's background (:func:`background`): ``buoyancy_change``,
    the truth's buoyancy minus the prior's [N] (the weight is the prior's; the buoyancy is
    drawn U(0.98, 1.02) x the prior's in every truth but the buoyancy_offset one, a real
    offset of up to 2 % of the weight in heave, roll and pitch), and ``thrust_gain`` per DOF
    (:func:`thrust_gain`) [-]."""
    from validation.independent import GRAVITY
    b0 = float(prior["density"]) * float(prior["volume"]) * GRAVITY
    from stripcoef.conventions import DOF
    out = {"buoyancy_change": float(truth.buoyancy - b0),
           "thrust_gain": {DOF[i]: float(thrust_gain(truth, prior, i)) for i in range(6)}}
    return out


def _diagnosed(log, truth, prior, vehicle, category, seed, mode, dof_name, t_sim,
               validation_others: str | None = None, one_added_mass: bool = False,
               dof_gains: bool = True, options: dict | None = None) -> dict:
    """One log diagnosed in one mode: the row of the score table (``one_added_mass``,
    ``dof_gains``: diagnose's options, recorded in the row; ``options``: further keyword
    arguments of diagnose, e.g. ``cross_mass_scale``)."""
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.effects import get_effect
    from validation.independent import STRENGTHS

    t1 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        # no wall-clock budget: on a shared machine the 300-s default stops whole-log runs
        # (CPU time is what the table reports)
        diagnosis = diagnose(log, prior, dof=dof_name if mode == "dof" else "all",
                             time_limit=float("inf"),
                             **({} if validation_others is None
                                else {"validation_others": validation_others}),
                             one_added_mass=one_added_mass, dof_gains=dof_gains,
                             **(options or {}))
        res = diagnosis.to_dict()
    t2 = time.process_time()
    per = res.get("per_dof") or {dof_name: res}
    prior_error = _prior_error(log, prior, dof_name, res["window_s"])
    own = per.get(dof_name, {"steps": [], "baseline_error": np.nan, "final_error": np.nan})
    steps = own["steps"]                 # the steps of the effect's own DOF
    every = [s for r in per.values() for s in r["steps"]]
    row = {"vehicle": vehicle, "category": category or "clean", "seed": seed, "mode": mode,
           "dof": dof_name, "truth": truth.strength, "one_added_mass": bool(one_added_mass),
           "dof_gains": bool(dof_gains),
           "first": steps[0]["effect"] if steps else None,
           "n_steps": len(every), "unexplained": bool(res["unexplained"]),
           "max_gain": max([s.get("held_out_gain", 0.0) or 0.0 for s in every], default=0.0),
           # the cut against the prior's error (the truth's cut's numerator): a whole-log
           # baseline_error is the error of the prior with the fitted thruster gains
           # (stripcoef.diagnose.pipeline), itself a change of the diagnosis
           "cut": (prior_error / own["final_error"]) if own["final_error"] else np.inf,
           "cut_baseline": ((own["baseline_error"] / own["final_error"])
                            if own["final_error"] else np.inf),
           "prior_error": prior_error,
           "t_simulate": t_sim, "t_diagnose": t2 - t1,
           "step_dofs": sorted(d for d, r in per.items() if r["steps"]),
           # what the written model holds: the steps the validation kept
           "first_kept": next((s["effect"] for s in steps if s.get("kept", True)), None),
           "step_dofs_kept": sorted(d for d, r in per.items()
                                    if any(s.get("kept", True) for s in r["steps"])),
           "n_steps_kept": sum(bool(s.get("kept", True)) for s in every),
           "step_effects": {d: [s["effect"] for s in r["steps"]] for d, r in per.items()
                            if r["steps"]},
           "step_effects_kept": {d: [s["effect"] for s in r["steps"] if s.get("kept", True)]
                                 for d, r in per.items()
                                 if any(s.get("kept", True) for s in r["steps"])},
           # each step's fitted parameters and z, and the whole-log thruster gains: what
           # truth_effects judges a step with against the truth on this log
           "step_detail": {d: [_step_detail(s) for s in r["steps"]] for d, r in per.items()
                           if r["steps"]},
           "thruster_gains": ((res.get("thruster_gains") or {}).get("gains")
                              if (res.get("thruster_gains") or {}).get("applied") else None)}
    choice = (res.get("validation") or {}).get("choice")
    if choice:
        # validation_choice="best_visited": which set was written (validate.validate_changes)
        row["validation_choice"] = choice["written"]
    if (res.get("thruster_gains") or {}).get("links") is not None:
        # linked_gains="identified": each pair of groups considered, its information ratio
        row["gain_links"] = res["thruster_gains"]["links"]
    # option calibration_named (stripcoef.diagnose.calibnamed): the written calibration's
    # departures named as the effects that mimic them; "first_named": the first step, or
    # in a DOF without steps the calibration's first named departure (named33i)
    cal_named = {d: [{"effect": c["effect"], "value": next(iter(c["parameters"].values())),
                      "relative": c["relative"], "bands": c["bands"]}
                     for c in r.get("calibration_named") or ()]
                 for d, r in per.items() if r.get("calibration_named")}
    if cal_named or (options or {}).get("calibration_named"):
        row["calibration_named"] = cal_named
        own_cal = cal_named.get(dof_name) or []
        row["first_named"] = row["first"] or (own_cal[0]["effect"] if own_cal else None)
    # a step that the log does not tell from other effects (scalechoice): its named set
    row["first_set"] = ([steps[0]["effect"]] + list(steps[0].get("ambiguous_with") or ())
                        if steps else [])
    if category in STRENGTHS:
        match = [s for s in steps if s["effect"] == category]
        if match:
            # the thrust scales the estimate was fitted beside (held_scales): a kept step's
            # value is the written model's, which holds only the kept scales
            scale = held_scales(steps, bool(match[0].get("kept", True)))
            g_w = written_gain(res, prior.to_dict(), dof_name)
            ref = magnitude_truth(truth, prior.to_dict(), category, dof_name, scale, g_w)
            row["magnitude_truth"] = float(ref)
            # the written model's thrust per unit of the prior's map in the DOF, and the
            # rule's mark: every effect's truth in the written model's units (fresh33f;
            # rows without it: benchmarks.written_units converts them)
            row["written_gain"] = float(g_w)
            row["magnitude_units"] = WRITTEN_UNITS
        cal = [c for c in row.get("calibration_named", {}).get(dof_name, [])
               if c["effect"] == category]
        if not steps and cal:
            # named by the calibration: its value is the written model's change (the
            # truth in the written model's units, no scale step held)
            g_w = written_gain(res, prior.to_dict(), dof_name)
            ref = magnitude_truth(truth, prior.to_dict(), category, dof_name, 1.0, g_w)
            row["calibration_estimate"] = float(cal[0]["value"])
            row["calibration_magnitude_truth"] = float(ref)
            row["calibration_magnitude_error"] = (abs(abs(cal[0]["value"]) - abs(ref))
                                                  / abs(ref))
        nd = match[0].get("not_determined") if match else None
        if nd:
            # named, its value not determined by one DOF (stripcoef.diagnose.undetermined):
            # no magnitude is claimed (nothing written); the gain-free fit's value, which
            # the diagnosis reports, and the prior map's are compared with the truth for
            # the record only
            row["magnitude_not_claimed"] = True
            row["not_determined"] = {k: nd[k] for k in ("gains_free", "gains_free_std",
                                                        "prior_map", "prior_map_std", "z",
                                                        "retested")}
            row["gains_free_error"] = (nd["gains_free"] - ref) / ref
            row["prior_map_error"] = (nd["prior_map"] - ref) / ref
        elif match:
            est = get_effect(category).magnitude(match[0].get("final_parameters",
                                                              match[0]["parameters"]))
            row["estimate"] = float(est)
            row["magnitude_error"] = abs(abs(est) - abs(ref)) / abs(ref)
            # whether the written model holds that value (the validation may remove the
            # step: its value is then reported, not written; benchmarks/data/mag33d_trace.md)
            row["magnitude_written"] = bool(match[0].get("kept", True))
            row["magnitude_error_drawn"] = (abs(abs(est) - abs(truth.strength))
                                            / abs(truth.strength))
            # what the written model itself holds of the effect, whichever change wrote it
            # (a removed added-mass step's inertia may be the calibration's; mag33g), against
            # the truth at the thrust scales the written model holds
            from benchmarks.written_held import written_magnitude
            held = magnitude_truth(truth, prior.to_dict(), category, dof_name,
                                   held_scales(steps, True), g_w)
            wm = written_magnitude(diagnosis.model, prior, category, dof_name)
            row["written_magnitude"] = float(wm)
            row["written_magnitude_truth"] = float(held)
            row["written_magnitude_error"] = abs(abs(wm) - abs(held)) / abs(held)
            # the naming step's own value (as selected, before the later steps' refits and
            # the validation), against the same reference as the row's estimate
            sel = get_effect(category).magnitude(match[0].get("selected_parameters")
                                                 or match[0]["parameters"])
            row["selected_magnitude_error"] = abs(abs(sel) - abs(ref)) / abs(ref)
    return row


def _prior_error(log, prior, dof_name: str, window: float) -> float:
    """The prior's RMS window force residual in DOF ``dof_name`` on the part of ``log`` a
    diagnosis fits (its first ``1 - VALIDATION_FRACTION``) [N or N m]: the numerator of
    the row's ``cut`` and of the truth's cut (``validation.detectability.truth_cut``)."""
    from stripcoef.conventions import parse_dof
    from stripcoef.diagnose.heldout import split
    from stripcoef.diagnose.settings import VALIDATION_FRACTION
    from stripcoef.diagnose.written import window_errors
    train, _ = split(log, VALIDATION_FRACTION, key="validation")
    return float(window_errors(train, prior, [parse_dof(dof_name)], window=window)[dof_name])


def _step_detail(step: dict) -> dict:
    """What the row keeps of a step: its effect, fitted parameters (refitted with the other
    steps where given), its z and whether the written model kept it."""
    par = step.get("final_parameters") or step["parameters"]
    return {"effect": step["effect"], "kept": bool(step.get("kept", True)),
            "z": float(step.get("z") or np.nan),
            "parameters": {k: float(v) for k, v in par.items() if isinstance(v, (int, float))}}


def truth_thrust(log, truth, dof: int) -> np.ndarray:
    """The truth's thruster force in ``dof`` at each sample of ``log`` [N or N m]: each
    thruster's thrust by the truth's own map (``validation.independent._thrust``: both
    branches, limits; a clean truth has no dead band, lag or delay) times its allocation in
    the truth (its direction, and its moment arm about the truth's reference point)."""
    from validation.independent import _thrust
    out = np.zeros(len(np.asarray(log["t"])))
    for t in truth.thrusters:
        b = np.concatenate([t["direction"], np.cross(t["position"], t["direction"])])[dof]
        if b == 0.0:
            continue
        n = np.asarray(log[f"n_{t['name']}"], float)
        out += b * np.array([_thrust(t, x) for x in n])
    return out


def truth_factors(log, truth, prior, dof: int) -> dict:
    """The truth's thrust in DOF ``dof`` against the prior's map on this log (module
    docstring): ``eta_forward``, ``eta_backward``, ``gain`` [-] and ``other`` [-]."""
    from stripcoef.effects.windows import window_data
    data = window_data(log, prior)
    fk = data.thruster_force(dof)
    y = truth_thrust(log, truth, dof)
    if fk is None or not np.any(fk):
        return {"eta_forward": np.nan, "eta_backward": np.nan, "gain": np.nan,
                "other": 1.0 if np.any(y) else 0.0}
    pos = np.where(data.thrust >= 0, fk, 0.0).sum(axis=1)
    neg = np.where(data.thrust < 0, fk, 0.0).sum(axis=1)
    (ef, eb), *_ = np.linalg.lstsq(np.column_stack([pos, neg]), y, rcond=None)
    total = pos + neg
    g = float(total @ y / (total @ total)) if np.any(total) else np.nan
    resid = y - ef * pos - eb * neg
    rms = float(np.sqrt(np.mean(y ** 2)))
    return {"eta_forward": float(ef), "eta_backward": float(eb), "gain": g,
            "other": float(np.sqrt(np.mean(resid ** 2)) / rms) if rms > 0 else 0.0}


#: The thruster effects whose truth on a log :func:`truth_effects` measures from the truth's
#: own thrusters: their change from the diagnosis's map [-] (the branches' ratio minus one, or
#: the DOF's thrust gain minus one) on the log's commands
TRUTH_MEASURED = {"thrust_asymmetry": lambda f: f["eta_backward"] / f["eta_forward"] - 1.0,
                  "thrust_effectiveness": lambda f: f["gain"] - 1.0}
FITTED_CHANGE = {"thrust_asymmetry": lambda p: p["eta_backward"] / p["eta_forward"] - 1.0,
                 "thrust_effectiveness": lambda p: p["scale"] - 1.0}


def truth_has(fitted: float, z: float, truth: float) -> bool:
    r"""Whether the truth carries the effect a step fitted with change ``fitted`` at ``z``
    standard deviations: the truth's own change on the log (``truth``) goes the same way and
    is itself at least ``MIN_Z`` of the step's standard deviations
    (:math:`|\Delta_f|/z`) from zero, i.e. the step's own test (the z gate of
    ``stripcoef.diagnose.settings.MIN_Z``) would find the truth's effect at the step's
    precision. No tolerance of the benchmark's: the step's standard deviation and the
    library's gate."""
    from stripcoef.diagnose.settings import MIN_Z
    if not (np.isfinite(fitted) and np.isfinite(truth) and np.isfinite(z) and z > 0):
        return False
    return fitted * truth > 0.0 and abs(truth) >= MIN_Z * abs(fitted) / z


def truth_effects(log, truth, prior, row: dict) -> dict:
    r"""For each step of a whole-log row in a DOF other than the effect's, whether the truth
    has such an effect on this log (:func:`truth_has`), measured from the truth itself: a
    thrust asymmetry or thrust effectiveness (:data:`TRUTH_MEASURED`) by the truth's
    thrusters' forward and backward thrust in the DOF regressed on the forward and backward
    parts of the map the diagnosis used (the prior with the whole-log thruster gains) on the
    log's commands (:func:`truth_factors`, as ``benchmarks.clean_background``: each thruster's own
    factor f_k, so a DOF pushed forward and backward by different thrusters has an asymmetry
    of the truth); a buoyancy offset in heave, roll or pitch by the truth's buoyancy change
    (heave: the offset's force b against minus the truth's buoyancy change, by
    :func:`truth_has`; roll and pitch: :func:`background`); any other effect: none. Returns ``{dof: [{effect, truth, fitted,
    z, has}]}``."""
    from stripcoef.conventions import parse_dof
    from stripcoef.effects import get_effect
    model = prior
    if row.get("thruster_gains"):
        model = get_effect("thruster_gain").apply(
            prior, None, {f"gain_{k}": float(g) for k, g in row["thruster_gains"].items()})
    # the truth's map without its dead band (a dead band is the deadband log's own effect)
    static = type(truth)(**{**truth.__dict__, "thrusters": [
        {**t, "deadband": 0.0} for t in truth.thrusters]})
    out = {}
    for d, steps in row.get("step_detail", {}).items():
        if d == row["dof"] and row["category"] != "clean":
            continue
        factors = None
        for s in steps:
            e = s["effect"]
            rec = {"effect": e, "truth": None, "fitted": None, "z": s["z"], "kept": s["kept"]}
            if e in TRUTH_MEASURED:
                if factors is None:
                    factors = truth_factors(log, static, model, parse_dof(d))
                rec["truth"] = float(TRUTH_MEASURED[e](factors))
                rec["fitted"] = float(FITTED_CHANGE[e](s["parameters"]))
                rec["has"] = truth_has(rec["fitted"], s["z"], rec["truth"])
            elif e == "buoyancy_offset" and d == "heave":
                # b is the heave force of the offset, positive down: -(the buoyancy change)
                rec["truth"] = -float(row["buoyancy_change"])
                rec["fitted"] = float(s["parameters"].get("b", np.nan))
                rec["has"] = truth_has(rec["fitted"], s["z"], rec["truth"])
            elif e == "buoyancy_offset":
                rec["has"] = background(row, d, e)
            else:
                rec["has"] = False
            out.setdefault(d, []).append(rec)
    return out


#: The effects whose magnitude is a force (per unit of its law's regressor) in the DOF's
#: balance: a log determines it only as its ratio to the thrust (:func:`magnitude_truth`)
FORCE_EFFECTS = ("tether_drag", "momentum_drag", "linear_drag", "buoyancy_offset")


def written_gain(res: dict, prior: dict, dof_name: str) -> float:
    r"""The thrust the diagnosis's written model gives DOF ``dof_name`` per unit of the
    prior's map [-]: 1, or with the whole-log thruster gains applied (``res``'s
    ``thruster_gains``, :class:`stripcoef.diagnose.gains.ThrusterGains`) their mean over the
    DOF's thrusters with :func:`thrust_gain`'s weights :math:`|B_{ik}| C_{t,k}^{prior}`."""
    from stripcoef.conventions import parse_dof
    rec = res.get("thruster_gains") or {}
    if not rec.get("applied"):
        return 1.0
    i, w, fw = parse_dof(dof_name), 0.0, 0.0
    for p in prior["thrusters"]:
        c0 = float(p.get("ct_forward", 1.0)) * float(p.get("eta_forward", 1.0))
        d = np.asarray(p["direction"], float) / np.linalg.norm(p["direction"])
        r = np.asarray(p["position"], float) - np.asarray(prior["reference_point"], float)
        b = abs(np.concatenate([d, np.cross(r, d)])[i]) * c0
        w += b
        fw += b * float(rec["gains"].get(p["name"], 1.0))
    return fw / w if w > 0 else 1.0


#: The mark of a row whose ``magnitude_truth`` is in the written model's units for every
#: effect (the thrust effectiveness and the added mass at the written gains too, and a kept
#: effect at the thrust scales the written model holds; fresh33f)
WRITTEN_UNITS = "written, kept scales"


def held_scales(steps: list[dict], kept: bool) -> float:
    r"""The product of the thrust-effectiveness scales of a DOF's ``steps`` that the effect's
    value was fitted beside [-]: for a kept effect (``kept``; its value is read back from the
    written model, ``stripcoef.diagnose.written.read_back``) the kept scales only, the written
    model holding no removed step; for a removed effect (its value that of the DOF's final fit
    of every selected step) every scale. Issue 33 (fresh33f): VideoRay linear drag 1796048664
    whole-log, scale 0.784 removed and the drag 2.820 kept, was 26 % off at the removed scale,
    1.7 % at the written model's 1."""
    return float(np.prod([(s.get("final_parameters") or s["parameters"]).get(
        "scale", s["parameters"].get("scale", 1.0)) for s in steps
        if s["effect"] == "thrust_effectiveness" and (s.get("kept", True) or not kept)]))


def prior_inertia(prior: dict, i: int) -> float:
    """The prior's inertia in DOF ``i``, :math:`M_{RB,ii} + M_{A,ii}` [kg or kg m^2]."""
    return float(np.asarray(prior["rigid_body_mass"], float)[i, i]
                 + np.asarray(prior["added_mass"], float)[i, i])


def magnitude_truth(truth, prior: dict, category: str, dof_name: str,
                    scale: float = 1.0, written: float = 1.0) -> float:
    r"""The size of the truth's effect that the diagnosis's ``magnitude`` is compared with,
    in the units the log determines it in: the drawn strength
    (:data:`~validation.independent.STRENGTHS`), except

    - the thrust effectiveness: its scale in the DOF is the drawn one times the thrusters'
      own U(0.75, 1.25) factors there (:func:`thrust_gain` g: the thrust the DOF gets per
      unit of the prior's map, the only scale a log of the DOF determines), over the
      written thrusters' gain :math:`g_w` (``written``): the written model's thrust in the
      DOF is :math:`s\,g_w` of the map, so the scale that makes it the truth's is
      :math:`g/g_w` (g without applied gains);
    - the added-mass error: a log determines the inertia only as its ratio to the thrust,
      :math:`(M_{RB} + M_A)/g`; expressed at the thrust the written model gives the DOF,
      the thrust scale ``scale`` the diagnosis fitted there (s, 1 without one) times the
      written thrusters' gain :math:`g_w`, the truth's change is
      :math:`(M_{RB} + M_{A,true})\,s\,g_w/g - (M_{RB} + M_{A,prior})`, the drawn
      strength when :math:`s\,g_w = g`. The same balance as a force effect's below
      (:math:`\bar f\,\tau_{map} = M\dot\nu + \dots` divided by :math:`\bar f`; Fossen
      2011 eq. 6.2 with the thrust as the only absolute scale). Issue 33 (fresh33f): before,
      :math:`g_w` was left out here, so a change that moves a DOF's mean gain off 1 was
      charged for it: BlueROV2 log 1796040005 with linked gains (:math:`g_w` = 0.856 in
      surge) was 34 % off by the rule, 3.5 % in the written model's units
      (benchmarks/data/linked33e_trace.md, item 8);
    - a force effect (:data:`FORCE_EFFECTS`: tether, momentum and linear drag, buoyancy
      offset): the same rule, :math:`\bar f\,\tau_{map} = \dots + F` divided by
      :math:`\bar f`: its coefficient as the log determines it is the drawn one times
      :math:`s\,g_w/g`, ``written`` :math:`g_w` the thrust of the written model's thrusters
      per unit of the prior's map (:func:`written_gain`: the whole-log thruster gains; 1
      without). Issue 33: the whole-log c_t of a BlueROV2-like tether log, 0.204 for a drawn
      0.2196, is 0.2026 in the thrust's units (g = 1.084);
    - an effect that *replaces* a term the prior already holds (the truth's buoyancy
      :math:`B_p + s`, the truth's surge linear drag :math:`X_u = s`,
      ``validation.independent.with_effect``): the prior's own term stays absolute in the
      model's balance (as :math:`M_{RB} + M_{A,prior}` above), so the change the log asks of
      the model is the truth's term at :math:`s\,g_w/g` less the prior's. The buoyancy offset
      (heave force, positive down; Fossen 2011 eq. 4.6 at small roll and pitch):
      :math:`b = (W - B_{true})\,s\,g_w/g - (W - B_p)`; the linear drag:
      :math:`d_L = X_{u,true}\,s\,g_w/g - X_{u,p}`. Issue 33 (mag33d): on a VideoRay log
      (prior :math:`W - B_p = -0.30` N, g = 1.246, drawn 0.302 N) the force rule's 0.242 N
      left out :math:`(W - B_p)(1/g - 1) = +0.059` N; the diagnosis's -0.180 N is -1.4 % of
      this rule's -0.183 N, -25.6 % of the force rule's.

    (The row's ``magnitude_error_drawn`` compares with the drawn strength.)"""
    from stripcoef.conventions import parse_dof
    i = parse_dof(dof_name)
    if category == "thrust_effectiveness":
        return thrust_gain(truth, prior, i) / written
    if category == "added_mass_error":
        m_rb = float(np.asarray(prior["rigid_body_mass"], float)[i, i])
        g = thrust_gain(truth, prior, i)
        return ((m_rb + float(truth.m_a[i, i])) * scale * written / g
                - prior_inertia(prior, i))
    k = scale * written / thrust_gain(truth, prior, i) if category in FORCE_EFFECTS else 1.0
    if category == "buoyancy_offset":
        from validation.independent import GRAVITY
        b_p = float(prior["density"]) * float(prior["volume"]) * GRAVITY
        return (float(truth.weight) - float(truth.buoyancy)) * k - (float(truth.weight) - b_p)
    if category == "linear_drag":
        return (float(np.asarray(truth.d_l, float)[i, i]) * k
                - float(np.asarray(prior["linear_damping"], float)[i, i]))
    if category in FORCE_EFFECTS:
        return float(truth.strength) * k
    return float(truth.strength)


#: The categories whose reference the written gains now enter (a force effect's took them
#: already; its reference is converted only for the scales, :func:`held_scales`)
CONVERTED = ("thrust_effectiveness", "added_mass_error")


def converted(row: dict, priors: dict | None = None) -> dict:
    """``row`` with its ``magnitude_truth`` and ``magnitude_error`` in the written model's units
    (``benchmarks.written_units``): the row itself when it is already marked, has no
    reference, or is a force effect's whose scales the rule does not change; otherwise a
    copy, marked, with ``written_gain`` (a row of :data:`CONVERTED` written before fresh33f),
    ``held_scale_ratio`` (:func:`held_scales` over the product of every scale) and
    ``magnitude_truth_before`` / ``magnitude_error_before`` kept. ``priors``: a cache of the
    vehicles' prior dicts."""
    from stripcoef.conventions import parse_dof
    from validation.independent import GRAVITY
    if (row.get("magnitude_units") == WRITTEN_UNITS or "magnitude_truth" not in row
            or row["category"] not in CONVERTED + FORCE_EFFECTS):
        return row
    own = [s for s in (row.get("step_detail") or {}).get(row["dof"], [])
           if s["effect"] == row["category"]]
    kept = bool(own[0]["kept"]) if own else True
    te = [s for s in (row.get("step_detail") or {}).get(row["dof"], [])
          if s["effect"] == "thrust_effectiveness"]
    # the scale the stored reference took (every scale) over the one the value was fitted
    # beside (held_scales); 1 for the thrust effectiveness's own row (no scale in its rule)
    ratio = (held_scales(te, kept) / held_scales(te, False)
             if te and row["category"] != "thrust_effectiveness" else 1.0)
    first = row.get("magnitude_units") is None           # before fresh33f: no g_w there
    if row["category"] in FORCE_EFFECTS and ratio == 1.0:
        return row
    priors = {} if priors is None else priors
    prior = priors.get(row["vehicle"])
    if prior is None:
        prior = priors[row["vehicle"]] = _prior(row["vehicle"]).to_dict()
    i = parse_dof(row["dof"])
    gains = row.get("thruster_gains")
    g_w = written_gain({"thruster_gains": {"applied": gains is not None,
                                           "gains": gains or {}}}, prior, row["dof"])
    g_w = g_w if first and row["category"] in CONVERTED else 1.0
    old = float(row["magnitude_truth"])
    # the reference is k T - base with k the thrust factor (s g_w / g): the prior's own term
    # (base) stays absolute (magnitude_truth)
    base = {"thrust_effectiveness": 0.0, "added_mass_error": prior_inertia(prior, i),
            "linear_drag": float(np.asarray(prior["linear_damping"], float)[i, i]),
            "buoyancy_offset": (float(prior["mass"]) - float(prior["density"])
                                * float(prior["volume"])) * GRAVITY}.get(row["category"], 0.0)
    if row["category"] == "thrust_effectiveness":
        new = old / g_w
    else:
        new = (old + base) * g_w * ratio - base
    out = {**row, "magnitude_truth": new, "magnitude_truth_before": old,
           "held_scale_ratio": ratio, "magnitude_units": WRITTEN_UNITS}
    if first and row["category"] in CONVERTED:
        out["written_gain"] = g_w
    if "estimate" in row:
        est = float(row["estimate"])
        out["magnitude_error_before"] = row.get("magnitude_error")
        out["magnitude_error"] = abs(abs(est) - abs(new)) / abs(new)
    return out


def converted_rows(rows: list[dict]) -> list[dict]:
    """Every row of ``rows`` through :func:`converted` (one prior per vehicle)."""
    priors: dict = {}
    return [converted(r, priors) for r in rows]


def _run(args):
    return run_one(*args)


def excitation_row(vehicle: str, category: str | None, seed: int, duration: float,
                   modes: tuple = (), validation_others: str = "",
                   truth_maps: bool = False, *_options) -> list[dict]:
    """One log, not diagnosed (``_options``: the diagnosis's, unused): its excitation (``validation.independent.excitation``) as a
    row: per driven DOF the shares of samples [-] moving each way, per thruster the share
    saturated, and ``two_way``, the smallest share of one direction over the driven DOFs."""
    from validation.independent import excitation, generate

    prior = _prior(vehicle)
    log, truth = generate(prior.to_dict(), category, seed, duration=duration)
    e = excitation(log, truth)
    return [{"vehicle": vehicle, "category": category or "clean", "seed": seed,
             "velocity": {c: e[c] for c in e["driven"]}, "saturated": e["saturated"],
             "two_way": min(min(e[c]["pos"], e[c]["neg"]) for c in e["driven"]),
             "max_saturated": max(e["saturated"].values(), default=0.0)}]


def _run_excitation(args):
    return excitation_row(*args)


def summarise_excitation(rows: list[dict]) -> str:
    """Per vehicle and category, over its logs: for each driven DOF the mean shares of
    samples moving each way (+/-, in %), the smallest one-direction share of any DOF of any
    log, and the largest share of samples with a thruster at its limit."""
    lines = ["| vehicle | category | logs | u +/- % | v +/- % | w +/- % | r +/- % "
             "| smallest one-way share % | most saturated thruster % |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    keys = sorted({(r["vehicle"], r["category"]) for r in rows})
    for vehicle, cat in keys:
        rs = [r for r in rows if r["vehicle"] == vehicle and r["category"] == cat]
        cells = []
        for c in ("u", "v", "w", "r"):
            vals = [r["velocity"][c] for r in rs if c in r["velocity"]]
            cells.append(f"{100 * np.mean([v['pos'] for v in vals]):.0f}/"
                         f"{100 * np.mean([v['neg'] for v in vals]):.0f}" if vals else "-")
        lines.append(f"| {vehicle} | {cat} | {len(rs)} | " + " | ".join(cells) +
                     f" | {100 * min(r['two_way'] for r in rs):.0f} | "
                     f"{100 * max(r['max_saturated'] for r in rs):.0f} |")
    worst = min(rows, key=lambda r: r["two_way"])
    lines += ["", f"Smallest one-way share of a driven DOF over all {len(rows)} logs: "
              f"{100 * worst['two_way']:.1f} % ({worst['vehicle']} {worst['category']} seed "
              f"{worst['seed']}); largest share of samples with a thruster at its limit: "
              f"{100 * max(r['max_saturated'] for r in rows):.1f} %."]
    return "\n".join(lines)


def _progress(row: dict) -> dict:
    """Print one finished diagnosis (a line, its row as JSON after ``row``) and return it."""
    import json
    print(f"  {row['vehicle']} {row['category']} seed {row['seed']} {row['mode']}: first "
          f"{row['first']}, steps in {row['step_dofs']}, cut {row['cut']:.2f}, "
          f"magnitude error {row.get('magnitude_error', float('nan')):.2f}"
          f"{' (not claimed: not determined by one DOF)' if row.get('magnitude_not_claimed') else ''}, "
          f"unexplained {row['unexplained']} row " + json.dumps(row, default=float),
          flush=True)
    return row


#: The DOFs each undeclared effect of ``validation.independent`` acts in, beyond its own
#: (STRENGTHS): the thruster effects change every thruster (so every DOF the thrusters
#: drive), the current every DOF (the relative velocity in D(nu_r) nu_r and C_A(nu_r) nu_r:
#: the translations' drag and the Munk moments in roll, pitch and yaw; one current written
#: for all six, stripcoef.diagnose.current); the buoyancy acts at the centre of buoyancy
#: (heave, and the roll and pitch restoring moments). A step naming the effect in one of
#: these DOFs is not spurious.
ACTS_IN = {name: ("surge", "sway", "heave", "roll", "pitch", "yaw")
           for name in ("thrust_asymmetry", "deadband", "thruster_lag", "actuation_delay",
                        "thrust_effectiveness")}
ACTS_IN.update({"current": ("surge", "sway", "heave", "roll", "pitch", "yaw"),
                "buoyancy_offset": ("heave", "roll", "pitch")})


#: Differences from the prior that every truth of ``validation.independent`` carries besides
#: its effect, as library effects: the buoyancy drawn U(0.98, 1.02) x the prior's (up to
#: 1 N on the VideoRay, 2.3 N on the BlueROV2, more than the buoyancy_offset category's own
#: 0.3-0.8 N) is a buoyancy offset in heave and, through the centre of buoyancy, roll and
#: pitch. A step naming it there is a true difference, not spurious.
#: The thruster coefficients, each drawn U(0.75, 1.25) x the prior's, are a thrust
#: effectiveness of the DOF (:func:`thrust_gain`) where they differ from 1 by more than the
#: thrust maps' bench uncertainty the library assumes (THRUST_BAND, 5 %): the data see it
#: through the weighed rigid-body mass, which no calibration band moves.
BACKGROUND = {"buoyancy_offset": ("heave", "roll", "pitch"),
              "thrust_effectiveness": ("surge", "sway", "heave", "roll", "pitch", "yaw")}


def background(row: dict, dof: str, effect: str) -> bool:
    """Whether ``effect`` in ``dof`` is a difference the truth of ``row`` carries besides
    its own effect (:data:`BACKGROUND`)."""
    from stripcoef.effects.base import THRUST_BAND
    if dof not in BACKGROUND.get(effect, ()):
        return False
    if effect == "buoyancy_offset":
        return abs(row.get("buoyancy_change", 0.0)) > 0.0
    gain = row.get("thrust_gain", {}).get(dof)
    return gain is not None and abs(gain - 1.0) > THRUST_BAND


def _first_after_background(row: dict):
    """The effect named first in the row's own DOF once the steps that name a
    :func:`background` difference are passed over."""
    return next((e for e in row.get("step_effects", {}).get(row["dof"], [])
                 if e == row["category"] or not background(row, row["dof"], e)), None)


def _spurious(row: dict, key: str, rule: str = "truth"):
    """Whether a whole-log row has a step in a DOF where the truth has no such effect
    (``key``: ``step_effects`` or ``step_effects_kept``), None when the row lacks it.
    ``rule`` ``"truth"``: :func:`_is_spurious` (the truth's own effect on the log where the
    row measured it, :func:`truth_effects`); ``"mean gain"``: the earlier rule, one averaged
    thrust gain per DOF against ``THRUST_BAND`` (:func:`background`)."""
    if key not in row:
        return None
    return any(_is_spurious(row, d, e, sum(x == e for x in effects[:k]), rule,
                            kept=key == "step_effects_kept")
               for d, effects in row[key].items() for k, e in enumerate(effects))


def _is_spurious(row: dict, dof: str, effect: str, k: int, rule: str = "truth",
                 kept: bool = False) -> bool:
    """Whether the ``k``-th step naming ``effect`` in ``dof`` (its place among the DOF's
    steps of that effect, among the kept ones with ``kept``) is one the truth of ``row``
    does not have (:func:`_spurious`; on a clean log every DOF counts)."""
    acts = ACTS_IN.get(row["category"], ())
    if (dof == row["dof"] and row["category"] != "clean") or (effect == row["category"]
                                                              and dof in acts):
        return False
    recs = [r for r in row.get("truth_has", {}).get(dof, []) if r["effect"] == effect
            and (r.get("kept", True) or not kept)]
    if rule == "truth" and "truth_has" in row and recs:
        return not recs[min(k, len(recs) - 1)]["has"]
    return not background(row, dof, effect)


def spurious_steps(rows: list[dict], rule: str = "truth") -> list[str]:
    """The spurious steps (:func:`_spurious`) of the whole-log rows, one text per row:
    ``vehicle truth seed: dof effect`` (``*`` when the written model kept it; for a thruster
    effect the fitted change and the truth's on the log, and the step's z)."""
    out = []
    for r in sorted(rows, key=lambda r: (r["vehicle"], r["category"], r["seed"])):
        if r["mode"] != "all" or "step_effects" not in r:
            continue
        kept = r.get("step_effects_kept", {})
        steps = []
        for d, effects in r["step_effects"].items():
            for i, e in enumerate(effects):
                k = sum(x == e for x in effects[:i])
                if not _is_spurious(r, d, e, k, rule):
                    continue
                recs = [x for x in r.get("truth_has", {}).get(d, []) if x["effect"] == e]
                x = recs[min(k, len(recs) - 1)] if recs else {}
                note = ""
                if x.get("truth") is not None:
                    note = (f" (fitted {x['fitted']:+.3f}, z {x['z']:.1f}; the truth's "
                            f"{x['truth']:+.3f})")
                steps.append(f"{d} {e}" + ("*" if e in kept.get(d, ()) else "") + note)
        if steps:
            out.append(f"{r['vehicle']} {r['category']} {r['seed']}: " + ", ".join(steps))
    return out


def summarise(rows: list[dict], seed: int, duration: float) -> str:
    from benchmarks.written_held import held as held_in_written
    from validation.independent import OUTSIDE, STRENGTHS

    n_logs = len({(r["vehicle"], r["category"], r["seed"]) for r in rows})
    lines = [f"Seed {seed}, {n_logs} logs of {duration:g} s at 10 Hz, {len(rows)} diagnoses.",
             ""]
    lines += ["| effect | mode | logs | named first | first or in its ambiguous set "
              "| named first after background "
              "| magnitude within 15 % | error cut >= 3x | the truth's own cut >= 3x "
              "| other DOFs named | spurious named | spurious kept |",
              "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    score, total = 0, 0
    spurious_all = {"step_effects": [0, 0], "step_effects_kept": [0, 0]}
    spurious_old = {"step_effects": [0, 0], "step_effects_kept": [0, 0]}
    mag_all, cut_all, after_all, set_all, mag_drawn = [0, 0], [0], [0], [0], [0]
    mag_written = [0]       # within 15 % and held by the written model
    ceiling = [0, 0, 0]     # rows with the truth's cut, of them >= 3x, of those measured >= 3x
    confusion: dict = {}
    for cat in STRENGTHS:
        for mode in ("dof", "all"):
            rs = [r for r in rows if r["category"] == cat and r["mode"] == mode]
            if not rs:
                continue
            n = len(rs)
            first = sum(r["first"] == cat for r in rs)
            in_set = sum(cat in r.get("first_set", [r["first"]]) for r in rs)
            after = sum(_first_after_background(r) == cat for r in rs)
            mag = sum(r.get("magnitude_error", np.inf) <= 0.15 for r in rs)
            # named, the value not determined by one DOF: no magnitude claimed
            unclaimed = sum(bool(r.get("magnitude_not_claimed")) for r in rs)
            mag_all[1] += unclaimed
            mag_drawn[0] += sum(r.get("magnitude_error_drawn", r.get("magnitude_error", np.inf))
                                <= 0.15 for r in rs)
            cut = sum(r["cut"] >= 3 for r in rs)
            known = [r for r in rs if "truth_cut" in r]
            allowed = [r for r in known if r["truth_cut"] >= 3]
            ceiling[0] += len(known)
            ceiling[1] += len(allowed)
            ceiling[2] += sum(r["cut"] >= 3 for r in allowed)
            ceiling_cell = f"{len(allowed)}/{len(known)}" if known else "-"
            spur = sum(any(d != r["dof"] for d in r["step_dofs"]) for r in rs) if mode == "all" \
                else 0
            # a step where the truth has no such effect, named and kept (the written model)
            cells = []
            for key in ("step_effects", "step_effects_kept"):
                known = [x for x in (_spurious(r, key) for r in rs) if x is not None]
                cells.append(f"{sum(known)}/{len(known)}" if mode == "all" and known else "-")
                if mode == "all" and known:
                    spurious_all[key][0] += sum(known)
                    spurious_all[key][1] += len(known)
                    old = [x for x in (_spurious(r, key, "mean gain") for r in rs)
                           if x is not None]
                    spurious_old[key][0] += sum(old)
                    spurious_old[key][1] += len(old)
            spur_cells = " | ".join(cells)
            score += first
            total += n
            for r in rs:
                confusion.setdefault(cat, {}).setdefault(str(r["first"]), 0)
                confusion[cat][str(r["first"])] += 1
            after_all[0] += after
            set_all[0] += in_set
            lines.append(f"| {cat} | {mode} | {n} | {first}/{n} | {in_set}/{n} | {after}/{n} "
                         f"| {mag}/{n}" + (f" ({unclaimed} not claimed)" if unclaimed else "")
                         + " | "
                         f"{cut}/{n} | {ceiling_cell} | "
                         + (f"{spur}/{n}" if mode == "all" else "-") + f" | {spur_cells} |")
            mag_all[0] += mag
            mag_written[0] += sum(held_in_written(r) for r in rs)
            cut_all[0] += cut
    clean = [r for r in rows if r["category"] == "clean"]
    outside = [r for r in rows if r["category"] in OUTSIDE]
    lines.append("")
    lines.append(f"Library effects named first: {score}/{total}"
                 + (f" ({100 * score / total:.0f} %)" if total else "")
                 + f"; named first or in the first step's ambiguous set (effects the log "
                 f"does not tell apart, counted apart from 'named first'): {set_all[0]}/{total}"
                 + f"; named first after the truth's background (buoyancy, thrust gains): "
                 f"{after_all[0]}/{total}; magnitude within 15 %: {mag_all[0]}/{total} (of the drawn "
                 f"strength, magnitude_error_drawn: {mag_drawn[0]}/{total}; within 15 % and held "
                 f"by the written model, not removed by its validation: {mag_written[0]}/{total}"
                 f", the written model's own magnitude within 15 % where the row has it, "
                 f"{sum('written_magnitude_error' in r for r in rows if r['category'] in STRENGTHS)}"
                 f" rows; the naming step's value as selected within 15 %: "
                 f"{sum(r.get('selected_magnitude_error', np.inf) <= 0.15 for r in rows)} of "
                 f"the {sum('selected_magnitude_error' in r for r in rows)} rows that have it)"
                 + (f" (named with the value not determined by one DOF, no magnitude "
                    f"claimed: {mag_all[1]}, counted as named first and not as within 15 %; "
                    f"of the {total - mag_all[1]} claimed: {mag_all[0]} within)"
                    if mag_all[1] else "") + "; error cut >= 3x: "
                 f"{cut_all[0]}/{total}"
                 + (f" (the truth's own model cuts the prior's error >= 3x in "
                    f"{ceiling[1]}/{ceiling[0]} of the rows with the oracle; of those the "
                    f"diagnosis does in {ceiling[2]}/{ceiling[1]})" if ceiling[0] else "")
                 + ".")
    unclaimed = [r for r in rows if r.get("magnitude_not_claimed")]
    if unclaimed:
        lines.append("Named, the value not determined by one DOF (nothing written; vehicle, "
                     "truth, seed: the gain-free fit's value ± sd and the prior map's, each "
                     "against the truth in the thrust's units, and the difference in sd): "
                     + "; ".join(
                         f"{r['vehicle']} {r['category']} {r['seed']}: "
                         f"{r['not_determined']['gains_free']:.3g} ± "
                         f"{r['not_determined']['gains_free_std']:.2g} "
                         f"({100 * r['gains_free_error']:+.1f} %), prior map "
                         f"{r['not_determined']['prior_map']:.3g} "
                         f"({100 * r['prior_map_error']:+.1f} %), "
                         f"{r['not_determined']['z']:.1f} sd"
                         + (", found only with the gains free"
                            if r['not_determined']['retested'] else "")
                         for r in unclaimed) + ".")
    named, kept = spurious_all["step_effects"], spurious_all["step_effects_kept"]
    if named[1]:
        measured = sum("truth_has" in r for r in rows if r["mode"] == "all")
        o_named, o_kept = spurious_old["step_effects"], spurious_old["step_effects_kept"]
        lines.append(f"Whole-log runs of library-effect logs with a spurious step (an effect in "
                     f"a DOF where the truth has none on the log: ACTS_IN, the buoyancy, and a "
                     f"thrust asymmetry or effectiveness measured from the truth's thrusters on "
                     f"the log's commands, truth_effects, in {measured} whole-log rows): named "
                     f"in {named[0]}/{named[1]}, kept in the written model in "
                     f"{kept[0]}/{kept[1]} (by the earlier rule, one mean thrust gain per DOF "
                     f"against THRUST_BAND: named {o_named[0]}/{o_named[1]}, kept "
                     f"{o_kept[0]}/{o_kept[1]}).")
        which = spurious_steps(rows)
        if which:
            lines.append("Spurious whole-log steps (vehicle, truth, seed: DOF effect, "
                         "* = kept in the written model): " + "; ".join(which) + ".")
        truths = _truth_named(rows)
        if truths:
            lines.append("Whole-log steps in other DOFs that the truth has on the log (not "
                         "spurious by the truth's rule; fitted change, z, the truth's change): "
                         + "; ".join(truths) + ".")
    if clean:
        fp = sum(r["n_steps"] > 0 for r in clean)
        kept = [r for r in clean if "n_steps_kept" in r]
        real = sum(any(not background(r, d, e) for d, es in r.get("step_effects", {}).items()
                       for e in es) for r in clean)
        real_truth = sum(bool(_spurious(r, "step_effects")) for r in clean
                         if r["mode"] == "all")
        lines.append(f"Clean logs: an effect named in {fp} of {len(clean)}"
                     + (f", kept in the written model in "
                        f"{sum(r['n_steps_kept'] > 0 for r in kept)} of {len(kept)}"
                        if kept else "")
                     + f"; an effect other than the background named in "
                       f"{real} of {len(clean)} (by the truth's own effects on the log, "
                       f"truth_effects, whole-log rows: {real_truth} of "
                       f"{sum(r['mode'] == 'all' for r in clean)}).")
    if outside:
        ok = sum(r["unexplained"] or r["max_gain"] < 0.3 for r in outside)
        lines.append(f"Dry friction (outside the library): 'unexplained' or held-out gains "
                     f"under 30 % in {ok} of {len(outside)}; named: "
                     + ", ".join(sorted({str(r['first']) for r in outside})) + ".")
    lines += calibration_named_lines(rows)
    lines += detectability_lines(rows)
    if confusion:
        lines += ["", "Confusion (truth -> effect named first, both modes):", ""]
        for cat, named in confusion.items():
            lines.append(f"- {cat}: " + ", ".join(f"{k} {v}" for k, v in sorted(named.items())))
    ts = np.mean([r["t_simulate"] for r in rows])
    td = np.mean([r["t_diagnose"] for r in rows])
    lines += ["", f"Mean CPU time per log: independent simulation {ts:.1f} s, diagnosis "
              f"{td:.1f} s."]
    return "\n".join(lines)


def calibration_named_lines(rows: list[dict]) -> list[str]:
    """The option ``calibration_named``'s count (rows that hold ``first_named``): named
    first when a DOF without steps counts the calibration's named departure
    (stripcoef.diagnose.calibnamed), its magnitude, and the departures named in clean logs
    and, whole-log, in DOFs other than the effect's. Apart from the table's "named first",
    which counts steps only."""
    from validation.independent import STRENGTHS

    rs = [r for r in rows if "first_named" in r]
    if not rs:
        return []
    lib = [r for r in rs if r["category"] in STRENGTHS]
    by_cal = [r for r in lib if r["first"] is None and r["first_named"] is not None]
    right = [r for r in by_cal if r["first_named"] == r["category"]]
    within = sum(r.get("calibration_magnitude_error", np.inf) <= 0.15 for r in right)
    clean = [r for r in rs if r["category"] == "clean"]
    clean_named = [f"{r['vehicle']} {r['seed']} {r['mode']}: " + ", ".join(
        f"{d} {c['effect']} {c['value']:.3g} ({100 * c['relative']:+.0f} %)"
        for d, cs in r["calibration_named"].items() for c in cs)
        for r in clean if r["calibration_named"]]
    other = [f"{r['vehicle']} {r['category']} {r['seed']}: " + ", ".join(
        f"{d} {c['effect']}" for d, cs in r["calibration_named"].items() if d != r["dof"]
        for c in cs)
        for r in lib if r["mode"] == "all"
        and any(d != r["dof"] for d in r["calibration_named"])]
    return ["", f"Calibration's named departures (calibration_named): library effects named "
            f"first, a DOF without steps counting the calibration's named departure: "
            f"{sum(r['first_named'] == r['category'] for r in lib)}/{len(lib)} (steps only: "
            f"{sum(r['first'] == r['category'] for r in lib)}/{len(lib)}); named by the "
            f"calibration alone in {len(by_cal)} rows, the right effect in {len(right)}, its "
            f"magnitude within 15 % in {within}; whole-log rows with a departure named in "
            f"another DOF: {len(other)}" + (" (" + "; ".join(other) + ")" if other else "")
            + f"; clean logs with a departure named: {len(clean_named)} of {len(clean)}"
            + (" (" + "; ".join(clean_named) + ")" if clean_named else "") + "."]


def _truth_named(rows: list[dict]) -> list[str]:
    """The whole-log steps in another DOF that name a thruster effect the truth has on the
    log (:func:`truth_effects`), one text per step."""
    out = []
    for r in sorted(rows, key=lambda r: (r["vehicle"], r["category"], r["seed"])):
        for d, recs in r.get("truth_has", {}).items():
            for x in recs:
                if x["has"] and x.get("truth") is not None:
                    out.append(f"{r['vehicle']} {r['category']} {r['seed']} {d} {x['effect']} "
                               f"{x['fitted']:+.3f} (z {x['z']:.1f}), the truth's "
                               f"{x['truth']:+.3f}")
    return out


def _detectable(row: dict) -> bool:
    """Whether the row's effect passes the oracle's gate at its mode's level (one DOF:
    ``detectable``; whole-log: ``detectable_all``, Bonferroni over the excited DOFs)."""
    return bool(row.get("detectable_all" if row["mode"] == "all" else "detectable"))


def detectability_lines(rows: list[dict]) -> list[str]:
    """The oracle's verdict (``validation.detectability``) on the rows that carry one: per
    effect and mode the logs named first among all and among the detectable ones, the
    measured error cut against the truth's own; then one line per log (its test on the
    truth's model against the level, on the prior with the true force fixed, the truth's cut
    and the diagnosis's cut per mode), and the misses sorted: detection misses (detectable,
    not named first) and undetectable draws."""
    tested = [r for r in rows if "detectable" in r]
    if not tested:
        return []
    out = ["", "Detectability (`validation.detectability`: the effect's own test, its "
           "coefficient free with its nuisance, on the truth's model without the effect, "
           "passes every gate of a step and the evidence gate at alpha / candidates, "
           "whole-log rows at alpha / (candidates x excited DOFs); no threshold changed). "
           "The truth's cut: the prior's RMS window residual in the effect's DOF over the "
           "truth's own model's, on the windows of the diagnosis's baseline and final "
           "errors (the cut a log allows):", ""]
    for cat in [c for c in _categories(tested)]:
        for mode in ("dof", "all"):
            rs = [r for r in tested if r["category"] == cat and r["mode"] == mode]
            if not rs:
                continue
            det = [r for r in rs if _detectable(r)]
            allowed = [r for r in rs if r.get("truth_cut", 0.0) >= 3]
            out.append(f"- {cat} {mode}: named first {sum(r['first'] == cat for r in rs)}/"
                       f"{len(rs)}; detectable {len(det)}/{len(rs)}, of them named first "
                       f"{sum(r['first'] == cat for r in det)}/{len(det)}, magnitude within "
                       f"15 % {sum(r.get('magnitude_error', np.inf) <= 0.15 for r in det)}/"
                       f"{len(det)}; error cut >= 3x {sum(r['cut'] >= 3 for r in rs)}/"
                       f"{len(rs)}, the truth's >= 3x {len(allowed)}/{len(rs)}, of those "
                       f"the diagnosis's {sum(r['cut'] >= 3 for r in allowed)}/{len(allowed)}")
    missed = [r for r in tested if r["first"] != r["category"]]
    if missed:
        def said(rs):
            return ", ".join(f"{r['category']} {r['vehicle']} {r['seed']} {r['mode']} -> "
                             f"{r['first']}" for r in rs) or "none"
        det = [r for r in missed if _detectable(r)]
        # passing its test on the prior, named after a difference the truth's background
        # carries (buoyancy, thrust gain; :func:`background`): filed apart from the rest
        sel_all = [r for r in det if r.get("first_step_on_prior") is True]
        after_bg = [r for r in sel_all if _first_after_background(r) == r["category"]]
        sel = [r for r in sel_all if r not in after_bg]
        hid = [r for r in det if r.get("first_step_on_prior") is False]
        unknown = [r for r in det if "first_step_on_prior" not in r]
        out += ["", f"Misses (not named first): {len(missed)}. Not detectable on the truth's "
                f"model (the draw): {len(missed) - len(det)}: "
                + said([r for r in missed if not _detectable(r)])
                + f". Detectable, but the effect's own test fails on the prior (the prior's "
                f"other errors hide it at the first step): {len(hid)}: " + said(hid)
                + f". Detectable and passing its test on the prior, named after a "
                f"difference of the truth's background (buoyancy, thrust gain): "
                f"{len(after_bg)}: " + said(after_bg)
                + f". Detectable and passing its test on the prior (the selection's misses): "
                f"{len(sel)}: " + said(sel)
                + (f". Detectable, rows without the test on the prior: {len(unknown)}: "
                   + said(unknown) if unknown else "") + "."]
    seen = set()
    out += ["", "Per log (truth's model: z, likelihood ratio, p against the level, the gates "
            "it fails; prior: the same test, and p of the true force fixed, the true force beyond the "
            "reference's columns over its noise; the truth's cut, and per mode the effect "
            "named first and the diagnosis's cut):", ""]
    for r in sorted(tested, key=lambda r: (r["category"], r["vehicle"], r["seed"])):
        key = (r["category"], r["vehicle"], r["seed"])
        if key in seen:
            continue
        seen.add(key)
        t, p = r["oracle"]["truth"], r["oracle"]["prior"]
        named = ", ".join(f"{x['mode']} {x['first']} (cut {x['cut']:.2f})" for x in tested
                          if (x["category"], x["vehicle"], x["seed"]) == key)
        fails = "; ".join(t.get("rejected_because") or [])
        out.append(f"- {r['category']} {r['vehicle']} {r['seed']} (truth {r['truth']:.3g}): "
                   f"{'detectable' if r['detectable'] else 'not detectable'}"
                   f"{'' if r.get('detectable_all', r['detectable']) == r['detectable'] else ' (not whole-log)'}"
                   f": truth's model z {t['z']:.1f}, LR {t['statistic']:.1f}, p "
                   f"{t['p_value']:.2g} vs {t['level']:.2g}, estimate {t['estimate']:.3g}, "
                   f"force/noise {t['snr']:.2f}" + (f", fails: {fails}" if fails else "")
                   + f"; prior: the effect's test z {p['z']:.1f}, p {p['p_value']:.2g}"
                   + ("" if r.get("first_step_on_prior") else
                      " (fails: " + "; ".join(p.get("rejected_because") or ["evidence"]) + ")")
                   + f", the true force fixed p {p['fixed_p_value']:.2g}, force/noise "
                   f"{p['snr']:.2f}; "
                   f"the truth's cut {r.get('truth_cut', np.nan):.2f}; named first: {named}")
    return out


def _categories(rows: list[dict]) -> list[str]:
    """The rows' categories in the order of ``validation.independent.STRENGTHS``."""
    from validation.independent import STRENGTHS
    present = {r["category"] for r in rows}
    return [c for c in STRENGTHS if c in present]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=None, help="base seed (default: a fresh one)")
    ap.add_argument("--duration", type=float, default=300.0, help="log length [s]")
    ap.add_argument("--categories", default=None,
                    help="comma-separated (default: every library effect, clean, "
                         "coulomb_friction)")
    ap.add_argument("--vehicles", default=",".join(VEHICLES))
    ap.add_argument("--modes", default="dof,all")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--repeats", type=int, default=1,
                    help="logs per category and vehicle (each its own seed)")
    ap.add_argument("--write", default=None, help="write the table to this markdown file")
    ap.add_argument("--same-seeds", action="store_true",
                    help="seed each log as a run of every category and vehicle would (a run "
                         "of a few categories or one vehicle then diagnoses the same logs as "
                         "the full run)")
    ap.add_argument("--excitation", action="store_true",
                    help="generate the logs and print their excitation, no diagnosis")
    ap.add_argument("--truth-maps", action="store_true",
                    help="diagnose against the prior with the truth's thrust maps (each "
                         "thruster's C_t; the log's own thruster effect left out): the "
                         "thruster-gain background removed, an oracle")
    ap.add_argument("--only-seeds", default=None,
                    help="comma-separated log seeds: diagnose only these logs of the run (a "
                         "log's seed names its vehicle and category)")
    ap.add_argument("--from-rows", default=None,
                    help="summarise the 'row' lines of earlier runs' outputs (comma-separated "
                         "files; partial runs' too; with --only-seeds and --modes, those rows) "
                         "instead of running; rows of runs before fresh33f scored in the "
                         "written model's units (benchmarks.written_units)")
    add_flags(ap)
    args = ap.parse_args(argv)
    options = given(args)       # every option left out: diagnose's default
    validation_others = options.pop("validation_others", None)
    one_added_mass = options.pop("one_added_mass", False)     # recorded in the rows
    dof_gains = options.pop("dof_gains", True)
    seed = args.seed if args.seed is not None else int(np.random.SeedSequence().entropy % 10**6)
    cats = args.categories.split(",") if args.categories else run_categories()
    jobs = []
    modes = tuple(args.modes.split(","))
    if args.from_rows:
        import json
        from stripcoef.files import read_text
        rows = [json.loads(line.split(" row ", 1)[1]) for path in args.from_rows.split(",")
                for line in read_text(path, kind="benchmark output").splitlines()
                if " row {" in line]
        if args.only_seeds:
            keep = {int(x) for x in args.only_seeds.split(",")}
            rows = [r for r in rows if r["seed"] in keep]
        rows = [r for r in rows if r["mode"] in modes]
        # rows written before fresh33f: their added-mass and thrust-scale references at the
        # written gains too (converted, benchmarks.written_units; a no-op where no gain moved the DOF)
        rows = converted_rows(rows)
        text = summarise(rows, seed, args.duration)
        print(text)
        if args.write:
            _write(args.write, " ".join(sys.argv[1:] if argv is None else argv), text)
        return 0
    every = run_categories()
    for rep in range(args.repeats):
        for v, vehicle in enumerate(args.vehicles.split(",")):
            # --same-seeds: the vehicle's and the category's places in the full run's lists,
            # so that a run of some vehicles or categories draws the full run's logs
            v = VEHICLES.index(vehicle) if args.same_seeds and vehicle in VEHICLES else v
            for c, cat in enumerate(cats):
                c = every.index(cat) if args.same_seeds else c
                jobs.append((vehicle, None if cat == "clean" else cat,
                             log_seed(seed, rep, v, c), args.duration, modes,
                             validation_others, args.truth_maps, one_added_mass, dof_gains,
                             options or None))
    if args.only_seeds:
        keep = {int(x) for x in args.only_seeds.split(",")}
        jobs = [j for j in jobs if j[2] in keep]
    # in a seeded random order: the rows of a run stopped early are a random sample of the
    # categories and vehicles (summarise them with --from-rows)
    jobs = [jobs[k] for k in np.random.default_rng(seed).permutation(len(jobs))]
    if args.excitation:
        import json
        print(f"seed {seed}: {len(jobs)} logs, excitation only", flush=True)
        if args.jobs > 1:
            with multiprocessing.Pool(args.jobs) as pool:
                rows = [r for rs in pool.imap_unordered(_run_excitation, jobs) for r in rs]
        else:
            rows = [r for j in jobs for r in _run_excitation(j)]
        for r in sorted(rows, key=lambda r: (r["vehicle"], r["category"], r["seed"])):
            print("  excitation row " + json.dumps(r), flush=True)
        text = summarise_excitation(rows)
        print(text)
        if args.write:
            _write(args.write, " ".join(sys.argv[1:] if argv is None else argv), text)
        return 0
    print(f"seed {seed}: {len(jobs)} logs, {len(jobs) * len(modes)} diagnoses", flush=True)
    if args.jobs > 1:
        with multiprocessing.Pool(args.jobs) as pool:
            rows = [_progress(r) for rs in pool.imap_unordered(_run, jobs) for r in rs]
    else:
        rows = [_progress(r) for j in jobs for r in _run(j)]
    text = summarise(rows, seed, args.duration)
    print(text)
    if args.write:
        _write(args.write, " ".join(sys.argv[1:] if argv is None else argv), text)
    return 0


def _write(path, args: str, text: str) -> None:
    """The markdown file of a run: its command, then the summary."""
    from stripcoef.files import write_text
    write_text(path, "# Diagnosis on an independent simulator\n\nMeasured by "
               f"`python -m benchmarks.diagnose_independent {args}`.\n\n{text}\n")


if __name__ == "__main__":
    raise SystemExit(main())
