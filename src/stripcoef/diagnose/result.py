"""The result of a diagnosis: :class:`Diagnosis` (its JSON is ``diagnose --json``) and, per
diagnosed DOF, its final fit (:class:`DofFit`).

Depends on: model, diagnose.fit, diagnose.priors.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from stripcoef.conventions import DOF
from stripcoef.diagnose.fit import _Config, _fit
from stripcoef.diagnose.priors import ADDED_MASS_BAND_Z
from stripcoef.model import frozen_mapping, plain


@dataclass(frozen=True)
class DofFit:
    """The final fit of one DOF's diagnosis, beyond its JSON: what the calibrated model and
    the residual plots are computed from.

    Attributes
    ----------
    config : the calibration columns and the accepted effects (with their nonlinear
        parameters) of the final fit
    evaluation : dict
        Its fit on all windows (``full``: ``theta``, ``cov``, ``resid``, ...) and held-out
        errors
    prior_residual : (n_windows,) array
        The prior's window force residual e_i [N or N m]
    """

    config: _Config
    evaluation: dict
    prior_residual: np.ndarray


#: the keys of :meth:`Diagnosis.to_dict`, in order (the JSON contract of ``diagnose --json``)
_JSON_FIELDS = ("metric", "metric_description", "window_s", "log", "vehicle", "dof", "units",
                "baseline_error", "calibrated_error", "steps", "final_error", "unexplained",
                "per_dof", "dropped_dofs", "excited_dofs", "dofs_not_diagnosed",
                "kept_at_prior", "bounds_hit", "added_mass_band", "prior_widths", "fitted_on_s",
                "validation", "holdout",
                "resimulated_velocity_rms", "resimulated_velocity_description")


def _finite_or_none(x):
    """``x`` (plain JSON types, :func:`stripcoef.model.plain`) with non-finite floats as None."""
    if isinstance(x, dict):
        return {k: _finite_or_none(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_finite_or_none(v) for v in x]
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


@dataclass(frozen=True)
class Diagnosis:
    """The result of :func:`diagnose`.

    Attributes
    ----------
    metric, metric_description : str
        The error metric (:data:`METRIC`; ``..._relative`` for several DOFs)
    window_s : float
        Window of the one-step residual [s]
    log, vehicle : str
        The log's source and the prior model's name
    dof, units : str
        The DOF diagnosed (or ``all``) and the metric's units
    baseline_error, calibrated_error, final_error : float
        The metric for the prior, after the calibration, after the added effects (several
        DOFs: RMS over the DOFs of each DOF's error relative to its baseline)
    steps : tuple of dict
        The effects added, in order (effect, parameters, std, errors before and after ...)
    unexplained : bool
        A structured residual remains that no library effect explains
    per_dof : mapping
        DOF name -> its detailed result (calibration, candidates, structure, steps ...)
    model : HydroModel
        The calibrated model (the prior with its calibration and the added effects)
    resimulated_velocity_rms : dict, optional
        DOF -> RMS re-simulated velocity error of the prior, the calibrated prior and the
        final model [m/s or rad/s] (with ``resimulate``)
    resimulated_velocity_description : str, optional
    dropped_dofs : mapping
        DOFs ``dof='all'`` left out, and why (no column, no applied force, not excited)
    excited_dofs : tuple of str
        The DOFs the log excites (:func:`select_dofs`)
    dofs_not_diagnosed : mapping
        Every DOF not diagnosed -> why; its coefficients are those of the prior
    kept_at_prior : mapping
        DOF -> {coefficient (or ``all coefficients``): why the log does not determine it}
        (not excited, too little Fisher information: :func:`_identifiability`)
    bounds_hit : mapping
        DOF -> {coefficient: text} for each calibrated coefficient at a physical bound
        (:func:`bounds_hit`)
    prior_widths : dict, optional
        :meth:`PriorWidths.to_dict` of the method-table widths the calibration's Gaussian
        priors took (a vehicle file), None with the fixed :data:`BANDS` (a model file)
    added_mass_band : dict, optional
        The method uncertainty of the prior's added mass the calibration was bounded by
        (``relative_sd`` per DOF, ``z``), when known (``added_mass_sd``)
    fitted_on_s : tuple
        (start, end) [s] of the part of the log the coefficients were fitted on
    validation : dict, optional
        Free-simulation validation of every change (:func:`validate_changes`), or
        ``{"skipped": reason}``
    holdout : dict, optional
        With ``holdout``: the held-out free-simulation errors [m/s or rad/s] of the prior,
        the calibrated model as written and hold-last-velocity (:func:`heldout_errors`)
    fits : mapping
        DOF name -> :class:`DofFit` (for :meth:`residual_curves`)
    test_log : Log, optional
        The held-out end of the log (not in the JSON)
    diagnosed : tuple of int
        Indices of the diagnosed DOFs (not in the JSON)
    """

    metric: str
    metric_description: str
    window_s: float
    log: str
    vehicle: str
    dof: str
    units: str
    baseline_error: float
    calibrated_error: float
    steps: tuple
    final_error: float
    unexplained: bool
    per_dof: Mapping
    model: object
    resimulated_velocity_rms: dict | None = None
    resimulated_velocity_description: str | None = None
    #: DOFs of dof='all' left out, and why (no column, no applied force, not excited)
    dropped_dofs: Mapping = field(default_factory=dict)
    excited_dofs: tuple = ()
    dofs_not_diagnosed: Mapping = field(default_factory=dict)
    kept_at_prior: Mapping = field(default_factory=dict)
    bounds_hit: Mapping = field(default_factory=dict)
    fitted_on_s: tuple | None = None
    validation: dict | None = None
    holdout: dict | None = None
    added_mass_band: dict | None = None
    prior_widths: dict | None = None
    fits: Mapping = field(default_factory=dict, repr=False, compare=False)
    test_log: object = field(default=None, repr=False, compare=False)
    diagnosed: tuple = field(default=(), repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "steps", tuple(self.steps))
        object.__setattr__(self, "per_dof", frozen_mapping(self.per_dof))
        object.__setattr__(self, "fits", frozen_mapping(self.fits))
        for key in ("dropped_dofs", "dofs_not_diagnosed", "kept_at_prior", "bounds_hit"):
            object.__setattr__(self, key, frozen_mapping(getattr(self, key)))

    def to_dict(self) -> dict:
        """The JSON output of ``diagnose --json`` (no model; non-finite numbers as null)."""
        out = {}
        for key in _JSON_FIELDS:
            value = getattr(self, key)
            if value is not None or not key.startswith("resimulated"):
                out[key] = value
        return _finite_or_none(plain(out))

    def residual_curves(self, dof: str):
        """Window mid-times [s] and the window force residual [N or N m] of DOF ``dof``:
        ``(t, [(label, residual), ...])`` for the prior, the calibrated prior and after
        each added effect."""
        fit = self.fits[dof]
        cfg = fit.config
        data = cfg.data
        tw = 0.5 * (data.t[data.i0] + data.t[data.i1])
        curves = [("prior", fit.prior_residual)]
        for k in range(len(cfg.terms) + 1):
            c = cfg.with_terms(cfg.terms[:k])
            label = "calibrated" if k == 0 else f"+ {cfg.terms[k - 1][0].name}"
            curves.append((label, _fit(c)["resid"]))
        return tw, curves



def _band_record(added_mass_sd):
    """The JSON record of the added-mass bands a diagnosis ran with (None without)."""
    if added_mass_sd is None:
        return None
    return {"relative_sd": {DOF[i]: (float(v) if np.isfinite(v) else None)
                            for i, v in enumerate(added_mass_sd)},
            "z": ADDED_MASS_BAND_Z,
            "description": "method uncertainty of the prior's added mass (1 sigma of ln M, "
                           "about relative; stripcoef.study.sources); the calibrated added mass "
                           f"stays within a factor e^(+-{ADDED_MASS_BAND_Z:g} sigma) (99.7 %)"}


