r"""What a diagnosis reports, read back from the model it writes (issue 33: one model).

After the selection and the validation, the calibrated model is built once
(:func:`stripcoef.diagnose.calibrate.calibrated_model`) and written; every value the text,
the JSON and the report print about it is then taken from that model, read back through its
dictionary form (what ``--out`` writes), never from an earlier stage of the fits:

- each calibrated coefficient's value (``calibration.written``) from the model's matrices;
- each kept effect's parameters from the model (its ``effects`` entry; a native effect, folded
  into the matrices or thrusters, from the model's ``provenance.diagnose`` record of what
  was applied); the values at the step's selection stay as ``selected_parameters``;
- the final error, the RMS window force residual of the written model on the fitting
  windows (:mod:`stripcoef.effects.windows`; its own effects' window forces subtracted,
  :func:`stripcoef.effects.laws.effect_window_forces`), in the commanded force's units
  (divided by the DOF's thrust scale, :func:`thrust_scale`) [N or N m].

Depends on: effects, conventions, diagnose.calibrate, diagnose.couplings, diagnose.fit,
diagnose.priors.
"""

from __future__ import annotations

from dataclasses import replace

from stripcoef.conventions import DOF, parse_dof
from stripcoef.diagnose.calibrate import written_fit
from stripcoef.diagnose.couplings import coupling_dof
from stripcoef.diagnose.fit import _evaluate, _rms
from stripcoef.diagnose.priors import TERM_MATRIX
from stripcoef.effects.laws import effect_window_forces
from stripcoef.effects.windows import window_data

def coefficient(model, dof: int, name: str) -> float:
    """The value in ``model`` of the calibration coefficient ``name`` of DOF ``dof``
    (``M``, ``D_L``, ``D_Q``: the diagonal of that DOF; ``M_<dof>``: that DOF's added mass;
    ``D_Q_<dof>``: the drag coupling :math:`D_Q[dof, j]`)
    [kg, kg m^2, N s/m, ...]."""
    if name in TERM_MATRIX:
        return float(getattr(model, TERM_MATRIX[name])[dof, dof])
    coupled = coupling_dof(name)
    if coupled is not None:         # a drag coupling D_Q[dof, j] (diagnose.couplings)
        return float(model.quadratic_damping[dof, coupled])
    j = parse_dof(name[2:])
    return float(model.added_mass[j, j])


def written_effects(model, dof: str) -> dict:
    """{effect name: parameters} of the effects a diagnosis wrote into ``model`` for DOF
    ``dof``: a non-native effect's from its ``effects`` entry, a native one's from the
    ``provenance.diagnose`` record of what was applied."""
    out = {}
    for entry in model.provenance.get("diagnose", ()) or ():
        if entry.get("dof") == dof:
            out.update({k: dict(v) for k, v in (entry.get("parameters") or {}).items()})
    for entry in model.effects:
        # a shared timing effect (the thrusters' one lag) is one entry for all DOFs
        if isinstance(entry, dict) and entry.get("dof") in (dof, "all") \
                and entry.get("name") in out:
            out[entry["name"]] = {k: float(v) for k, v in entry["parameters"].items()}
    return out


def window_errors(log, model, dofs, *, window: float) -> dict:
    """RMS window force residual [N or N m] of ``model`` on ``log`` for each DOF index in
    ``dofs``: DOF name -> error (the metric of :mod:`stripcoef.diagnose.pipeline`, with the
    model's effects as part of its prediction)."""
    data = window_data(log, model, window=window)
    resid = data.e0 - effect_window_forces(data, model) if model.effects else data.e0
    return {DOF[i]: _rms(resid[:, i]) / thrust_scale(model, DOF[i]) for i in dofs}


def thrust_scale(model, dof: str) -> float:
    """The product of the thrust scales ``model`` holds in DOF ``dof`` (its
    ``thrust_effectiveness`` entries for the DOF or for all six), 1 without one [-]: the
    residual of a scaled balance is divided by it, in the commanded force's units as the
    selection measures it (:meth:`stripcoef.diagnose.fit._Config.residual_scale`)."""
    s = 1.0
    for entry in model.effects:
        if isinstance(entry, dict) and entry.get("name") == "thrust_effectiveness" \
                and entry.get("dof") in (dof, "all"):
            s *= float(entry["parameters"]["scale"])
    return s


def fitted_with(d: str, cfg, theta, written, prior_values) -> dict:
    r"""{``M_<dof>``: value [kg or kg m^2]} of the other DOFs' added masses that DOF ``d``'s
    fit ``(cfg, theta)`` (:func:`~stripcoef.diagnose.calibrate.written_fit`, calibration
    columns first) holds at a value other than the one in the model ``written``: the prior's
    value ``prior_values[name]`` plus the fitted change, where it differs from the written one
    by more than 1e-9 relative. In a whole-log diagnosis another DOF's added mass enters
    DOF d's balance through :math:`C_A(\nu)\nu` (Fossen 2011, eq. 6.43) and is written once
    (:mod:`stripcoef.diagnose.cross`); a DOF fitted beside another value has its other
    coefficients written as fitted, and its final error is then the written model's, not
    its fit's."""
    out = {}
    for name, change in zip(cfg.cal.names, theta[:len(cfg.cal.names)]):
        if not name.startswith("M_") or name[2:] == d:
            continue
        value = float(prior_values[name]) + float(change)
        have = coefficient(written, parse_dof(d), name)
        if abs(value - have) > 1e-9 * max(abs(have), 1e-12):
            out[name] = value
    return out


def read_back(per: dict, fits: dict, written, fit_log, *, window: float,
              exclude=frozenset(), fitted=None) -> dict:
    """The per-DOF results ``per`` (DOF -> :class:`~stripcoef.diagnose.result.DofResult` of
    :func:`stripcoef.diagnose.select.diagnose_dof`; new ones returned) with every value that
    describes the written model replaced by the value read back from ``written`` (the model
    as written: ``type(m).from_dict(m.to_dict())``), on the fitting log ``fit_log``:

    - ``calibration.written``: each calibrated coefficient's value in the model, and
      ``calibration.final_parameters``: its change from the prior there;
    - each step: ``kept`` (in the model or not), ``parameters`` and ``final_parameters`` the
      written ones when kept (``selected_parameters``: those it had when selected); for a
      step whose value one DOF does not determine (``not_determined``, never written) the
      value fitted with each thruster's gain free and its sd, as its record says;
    - ``final_error``: the written model's error; ``final_held_out_error``: the blocked
      cross-validation of the written structure (refitted when the validation removed a
      change of the DOF or a step is not written, ``Step.not_determined``);
    - ``calibration.fitted_with``: the other DOFs' added masses the DOF's written fit held at
      another value than the written one (:func:`fitted_with`; ``fitted``: DOF -> ``(config,
      theta)`` the model was written from, :func:`~stripcoef.diagnose.calibrate.
      calibrated_fits`; none recorded without it).
    """
    dofs = [parse_dof(d) for d in per]
    errors = window_errors(fit_log, written, dofs, window=window)
    out = {}
    for d, r in per.items():
        i = parse_dof(d)
        cal = r.calibration
        values = {n: coefficient(written, i, n) for n in cal.parameters}
        beside = (fitted_with(d, *fitted[d], written, cal.prior)
                  if fitted is not None and d in fitted else {})
        cal = replace(cal, written=values,
                      final_parameters={n: values[n] - float(cal.prior[n])
                                        for n in cal.parameters},
                      fitted_with=beside or None)
        effects = written_effects(written, d)
        steps = []
        for s in r.steps:
            kept = s.effect in effects
            nd = s.not_determined
            # a step one DOF does not determine (diagnose.undetermined) is reported with
            # its gain-free fit's value, said so; never the prior map's fit's
            unset = ({"parameters": {nd["parameter"]: nd["gains_free"]},
                      "final_parameters": {nd["parameter"]: nd["gains_free"]},
                      "std": {nd["parameter"]: nd["gains_free_std"]}} if nd else {})
            steps.append(replace(s, selected_parameters=dict(s.parameters), kept=kept,
                                 **({"parameters": dict(effects[s.effect]),
                                     "final_parameters": dict(effects[s.effect])}
                                    if kept else unset)))
        held_out = r.final_held_out_error
        if any(c[1] == d for c in exclude) or any(s.not_determined for s in r.steps):
            cfg, _ = written_fit(d, r, fits[d], exclude)
            held_out = float(_evaluate(cfg)["held_out_error"])
        out[d] = replace(r, calibration=cal, steps=tuple(steps), final_error=errors[d],
                         final_held_out_error=held_out)
    return out

