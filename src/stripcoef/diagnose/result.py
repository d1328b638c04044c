"""The result of a diagnosis: :class:`Diagnosis` (its JSON is ``diagnose --json``) and, per
diagnosed DOF, its result (:class:`DofResult`, with its :class:`Calibration` and its
:class:`Step` s; JSON ``per_dof.<dof>``) and its final fit (:class:`DofFit`).

Depends on: model, diagnose.fit, diagnose.priors.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, fields

import numpy as np

from stripcoef.conventions import DOF
from stripcoef.diagnose.fit import _Config, _fit
from stripcoef.diagnose.priors import ADDED_MASS_BAND_Z
from stripcoef.diagnose.settings import UNLIMITED
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


def _optional():
    """A field left out of the JSON while unset (None): set by a later stage (the validation,
    the read-back of the written model, a stop by a shape outside the library)."""
    return field(default=None, metadata={"optional": True})


def _frozen(value):
    """``value`` read-only: a mapping as :func:`frozen_mapping`, a list as a tuple (its
    mappings read-only too)."""
    if isinstance(value, dict):
        return frozen_mapping(value)
    if isinstance(value, list):
        return tuple(_frozen(v) for v in value)
    return value


class _Record:
    """A per-DOF record: frozen, its mappings read-only, its JSON form :meth:`to_dict`
    (the fields in order, a nested record as its own, an unset optional field left out)
    and :meth:`from_dict` its inverse."""

    def __post_init__(self):
        for f in fields(self):
            object.__setattr__(self, f.name, _frozen(getattr(self, f.name)))

    def to_dict(self) -> dict:
        """The JSON form (plain types, :func:`stripcoef.model.plain`)."""
        out = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if value is None and f.metadata.get("optional"):
                continue
            if isinstance(value, _Record):
                value = value.to_dict()
            elif isinstance(value, tuple) and value and isinstance(value[0], _Record):
                value = [v.to_dict() for v in value]
            out[f.name] = plain(value)
        return out


@dataclass(frozen=True, kw_only=True)
class Calibration(_Record):
    """The calibration of one DOF's prior coefficients (JSON ``per_dof.<dof>.calibration``;
    coefficient names ``M``, ``D_L``, ``D_Q``, ``M_<dof>``; values in the coefficient's
    units [kg, kg m^2, N s/m, N s^2/m^2, ...]).

    Attributes
    ----------
    parameters, std : mapping
        The MAP change from the prior of each calibrated coefficient and its 1-sigma
        uncertainty, fitted without effects
    prior : mapping
        The prior's value of each coefficient
    band_relative, band_source : mapping
        The 1-sigma width of its Gaussian prior relative to the prior value [-], and the row
        it came from
    band_z : mapping
        ``parameters`` in bands [-]
    kept_at_prior, information_ratio : mapping
        Coefficients the log does not determine (-> why), and each one's Fisher information
        ratio [-] (:func:`~stripcoef.diagnose.fit._identifiability`)
    final_parameters : mapping
        The change from the prior in the final fit (after :func:`read_back`: in the written
        model)
    kept : bool, optional
        Whether the validation by free simulation kept it (None: no validation)
    written : mapping, optional
        Each coefficient's value in the written model (set by :func:`read_back`)
    fitted_with : mapping, optional
        {``M_<dof>``: value [kg or kg m^2]} of each other DOF's added mass that this DOF's
        final fit held at a value other than the one written (that DOF's own calibration, or
        the weighted mean of several DOFs' fits: :mod:`stripcoef.diagnose.cross`): this
        DOF's written coefficients and effects were fitted beside it, and its final error is
        the written model's (set by :func:`read_back`; absent when there is none)
    """

    parameters: Mapping
    std: Mapping
    prior: Mapping
    band_relative: Mapping
    band_source: Mapping
    band_z: Mapping
    kept_at_prior: Mapping
    information_ratio: Mapping
    final_parameters: Mapping
    kept: bool | None = _optional()
    written: Mapping | None = _optional()
    fitted_with: Mapping | None = _optional()


@dataclass(frozen=True, kw_only=True)
class Step(_Record):
    """One effect added to a DOF (JSON ``steps[k]`` and ``per_dof.<dof>.steps[k]``).

    Attributes
    ----------
    effect, source : str
        The effect's name and its literature source
    applicable, significant : bool
        Always true for a step (the fields of a judged candidate)
    parameters, std, units : mapping
        Its parameters (as selected; after :func:`read_back` the written model's when kept),
        their 1-sigma uncertainties and units
    released : mapping
        The prior coefficients it releases -> their change
    signature, mimics : str or None
        The log's signature of the effect; without one, the prior coefficient it mimics
    band_excess : float or None
        The change it implies of the coefficient it mimics, in bands [-]
    error_before, error_after, held_out_error_before, held_out_error_after : float
        The metric and the held-out error before and after it, at its selection
        [N or N m]
    held_out_gain, delta_bic, z, magnitude : float
        Its relative held-out gain [-], the change of BIC [-], its largest parameter in
        standard deviations [-], the effect's size (:meth:`Effect.magnitude`)
    rejected_because : tuple of str
        Empty for a step
    alternatives : tuple of mapping
        The effects within ``TIE`` of it (effect, parameters, held-out error, signature)
    dof : str
        The DOF it acts in
    final_parameters : mapping
        Its parameters refitted with every other step (after :func:`read_back`: the written
        model's when kept)
    kept : bool, optional
        Whether it is in the written model (None before the validation and the read-back)
    selected_parameters : mapping, optional
        Its parameters at its selection (set by :func:`read_back`)
    comparison : mapping, optional
        The step's comparison of competing effects in the model holding both
        (:func:`~stripcoef.diagnose.select._competing`): each pair's likelihood-ratio tests,
        their Holm-adjusted p-values, the level, the effects a partner dominated, and the
        pair named together (``joint``), when there were competing effects
    evidence : mapping, optional
        The test of it against the model without it (:mod:`~stripcoef.diagnose.evidence`:
        the likelihood ratio on the effective number of windows, its p-value, the
        Holm-adjusted p-value, the level, the number of candidates; the paired held-out
        test's p-value, recorded)
    ambiguous_with : tuple of str, optional
        The effects the log does not tell from this one (:mod:`~stripcoef.diagnose.
        scalechoice`: a thrust scale and an added-mass change); the step is one of them,
        the one with the lower posterior cost
    choice : mapping, optional
        The test of a thrust scale against an added-mass change in the model holding both
        (:func:`~stripcoef.diagnose.scalechoice.choose`), when both were candidates
    not_determined : mapping, optional
        One DOF: the effect is named but its value depends on the thrusters' gains, which
        one DOF does not determine (:mod:`~stripcoef.diagnose.undetermined`): nothing is
        written for it (``kept`` false); its parameter fitted with each thruster's gain
        free and with the prior's map, their standard deviations, the test, the reason and
        the advice (run the whole-log diagnosis)
    """

    effect: str
    applicable: bool
    parameters: Mapping
    std: Mapping
    released: Mapping
    units: Mapping
    signature: str | None
    mimics: str | None
    band_excess: float | None
    error_after: float
    held_out_error_after: float
    held_out_gain: float
    delta_bic: float
    z: float
    significant: bool
    rejected_because: tuple
    magnitude: float
    source: str
    error_before: float
    held_out_error_before: float
    alternatives: tuple
    dof: str
    final_parameters: Mapping
    kept: bool | None = _optional()
    selected_parameters: Mapping | None = _optional()
    comparison: Mapping | None = _optional()
    evidence: Mapping | None = _optional()
    ambiguous_with: tuple | None = _optional()
    choice: Mapping | None = _optional()
    not_determined: Mapping | None = _optional()


@dataclass(frozen=True, kw_only=True)
class DofResult(_Record):
    """The diagnosis of one DOF (:func:`~stripcoef.diagnose.select.diagnose_dof`; JSON
    ``per_dof.<dof>``). Errors are RMS window force residuals [N or N m] (``units``).

    Attributes
    ----------
    dof, metric, units : str
    baseline_error, baseline_held_out_error : float
        The prior's error (held-out: the same; the prior is not fitted)
    calibration : Calibration
    calibrated_error, calibrated_held_out_error : float
        After the calibration, on all windows and blocked cross-validated
    structure_before, structure_after : mapping
        The residual's statistics after the calibration and at the end (bias, lag-1
        autocorrelation, runs test, sign dependence, correlation with each candidate)
    stopped_by_shape : mapping, optional
        The shape outside the library that stopped the selection, and why
    steps : tuple of Step
        The effects added, in order
    candidates : tuple of mapping
        Every effect judged at the first step (or why it is not applicable)
    final_error, final_held_out_error : float
        At the end (after :func:`read_back`: the written model's)
    unexplained : bool
        A structured residual remains that no library effect explains
    unexplained_evidence : mapping
        The generic basis's gain, the noise floor, ...
    unexplained_signature : str
        The residual's signature in words ('' when explained)
    withdrawn : tuple of mapping, optional
        Whole-log: steps the selection added and the shared fits made unnecessary, each
        ``effect``, ``parameters`` and ``reason`` (:mod:`.stepwise`); not written
    calibration_named : tuple of mapping, optional
        The written calibration's departures from the prior named as the effects that
        mimic them (option ``calibration_named``, :mod:`.calibnamed`): each ``effect``,
        ``parameters``, ``coefficient``, ``prior``, ``written``, ``relative``, ``bands``,
        ``z`` and ``rule``
    """

    dof: str
    metric: str
    units: str
    baseline_error: float
    baseline_held_out_error: float
    calibration: Calibration
    calibrated_error: float
    calibrated_held_out_error: float
    structure_before: Mapping
    stopped_by_shape: Mapping | None = _optional()
    steps: tuple
    candidates: tuple
    final_error: float
    final_held_out_error: float
    structure_after: Mapping
    unexplained: bool
    unexplained_evidence: Mapping
    unexplained_signature: str
    withdrawn: tuple | None = _optional()
    calibration_named: tuple | None = _optional()

    @classmethod
    def from_dict(cls, d: Mapping) -> DofResult:
        """The record of its JSON form (:meth:`to_dict`) or of the selection's working
        dictionary."""
        return cls(**{**d, "calibration": Calibration(**d["calibration"]),
                      "steps": tuple(Step(**s) for s in d["steps"])})


#: the keys of :meth:`Diagnosis.to_dict`, in order (the JSON contract of ``diagnose --json``)
_JSON_FIELDS = ("metric", "metric_description", "window_s", "log", "vehicle", "dof", "units",
                "baseline_error", "calibrated_error", "steps", "final_error", "unexplained",
                "per_dof", "dropped_dofs", "excited_dofs", "dofs_not_diagnosed",
                "kept_at_prior", "bounds_hit", "added_mass_band", "prior_widths", "fitted_on_s",
                "validation", "holdout", "thruster_gains",
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
    steps : tuple of Step
        The effects added, in order (effect, parameters, std, errors before and after ...)
    unexplained : bool
        A structured residual remains that no library effect explains
    per_dof : mapping
        DOF name -> its :class:`DofResult` (calibration, candidates, structure, steps ...)
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
    thruster_gains : dict, optional
        Whole-log: the thrusters' gains fitted jointly over the DOFs
        (:meth:`~stripcoef.diagnose.gains.ThrusterGains.to_dict`), None otherwise
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
    #: whole-log: the thrusters' gains fitted jointly (stripcoef.diagnose.gains), or None
    thruster_gains: dict | None = None
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
            if key == "per_dof":
                value = {d: r.to_dict() for d, r in value.items()}
            elif key == "steps":
                value = [s.to_dict() for s in value]
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
            # a finished diagnosis's figure: its fits were under the budget of the call
            # that made them, a deadline long past when a report asks for them later
            c = cfg.with_terms(cfg.terms[:k], budget=UNLIMITED)
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


