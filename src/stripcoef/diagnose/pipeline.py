r"""Closing the loop: find the residual, trace it to the effect the model lacks, add it.

Steps, for each degree of freedom (issue 7):

1. **Baseline**: the prior (strip-theory) model predicts the log; the error is the RMS of the
   window force residual :math:`e_i` of :mod:`stripcoef.effects.laws` [N or N m] (the
   one-step form of Wang & Clark 2006, eqs. 14-17, over windows of ``window`` seconds), and, when
   ``resimulate`` is on, the RMS of the re-simulated velocity [m/s or rad/s].
2. **Calibration** of the prior's own coefficients of that DOF (inertia M_ii, linear and
   quadratic damping D_L,ii and D_Q,ii) *within their bands*: a Gaussian prior on each
   correction with standard deviation ``band * prior value`` (maximum a posteriori least
   squares, Tarantola 2005 eq. 3.37; ridge regression). Bands, from the analytical vs
   experimental columns of Wang & Clark 2006 Table I: translational added mass 30 %, linear drag
   60 %, quadratic drag 30 %; rotational added mass 100 %, linear and quadratic drag 300 %
   (N_r is off by 4.8x and N_r|r| by 50x there: strip theory barely constrains rotation).
   With a vehicle file (its shape class known) the bands are instead the method table's
   sd of ln c per matrix and DOF group (:class:`PriorWidths`, issue 19: the added mass
   measured, the translational quadratic drag measured for the classes with published 3D
   body drag and assumed otherwise, the rotational drag assumed, the linear drag not
   predicted: a very wide prior) as the floor of the measured vehicle mismatch (issue 33:
   how far real vehicles' identified coefficients are from their geometric predictions,
   :func:`~.priors.vehicle_mismatch`), the larger of the two.
   A coefficient the prior has as zero is not calibrated (strip theory says it is absent).
3. **Structure** of the residual: bias, lag-1 autocorrelation, runs test, dependence on the
   sign of the velocity and of the thrust, correlation with each candidate's regressors.
4. **Effects**: every applicable effect of the library is fitted together with the
   calibration (nonlinear parameters profiled); it is *significant* when all of
   - the held-out error (blocked cross-validation: the log's windows in ``N_BLOCKS``
     contiguous blocks, each predicted by a fit on the others) drops by at least
     ``MIN_HELD_OUT_GAIN``,
   - the Bayesian information criterion on all windows drops by at least
     ``MIN_DELTA_BIC`` (Schwarz 1978; windows do not overlap, so residuals are close to
     independent and N is the number of windows),
   - a parameter of the effect is at least ``MIN_Z`` standard deviations from zero,
   - its likelihood ratio, counted on the effective number of windows of the coloured
     residual (Bretherton et al. 1999, eq. 31), is significant at 5 % after Holm's
     adjustment over the step's candidates and, whole-log, Bonferroni's over the DOFs
     (:mod:`.evidence`; issue 33: clean logs named effects the BIC and z of white
     residuals let through),
   - its parameters are physically plausible (a drag is positive, an efficiency in (0.1, 3)),
   - an effect without a signature in this log (it only mimics a prior coefficient, e.g. a
     tether drag without a ``tether_length`` column looks like a larger D_Q) must also push
     that coefficient more than ``MIMIC_BANDS`` bands away from the prior; when the log
     cannot calibrate that coefficient within its band (kept at the prior by the
     identifiability test), the effect's column is a new free column, judged by the
     held-out gain, BIC and z as an effect with a signature, and its change must also lie
     beyond ``MIMIC_BANDS`` bands (issue 33: a linear drag 70x the prior's); having no
     structure of its own, it must also beat every out-of-library shape below;
   The significant effect with the lowest held-out error is added; effects within ``TIE``
   of it are reported as alternatives, and an effect with a signature is preferred over one
   without; a thrust scale and the release of the added mass are judged with the band
   priors (the posterior likelihood ratio, :mod:`.scalechoice`; the scale's residual in
   the commanded force's units) and, when both are candidates, the model holding both says
   which the log needs, or that it cannot tell them apart (the step then names the other
   in ``ambiguous_with``); a thrust scale must change
   the inertia the log shows by ``MIMIC_BANDS`` bands of the added mass
   (:func:`~.select._scale_inertia_test`); an effect's released prior coefficients keep
   their physical bound (drag >= 0). No step raises the held-out error (a released coefficient included). Before a
   step, one-column shapes outside the library (:func:`~.select._generic_shapes`: sign(v),
   v^3, ...) are fitted in its place; one that explains the residual better (held-out error
   below ``1 - MIN_HELD_OUT_GAIN`` of the best effect's) stops the selection, and the DOF is
   ``unexplained`` with the residual's signature (``unexplained_signature``). Repeat until
   nothing is significant. In a whole-log diagnosis (``dof="all"``) an effect of the
   thrusters (dead band, thrust asymmetry, lag, delay: :data:`~.select.THRUSTER_EFFECTS`)
   found in one DOF must also hold in every other diagnosed DOF the same thrusters drive:
   at its parameters it must not raise their held-out error by more than ``TIE``
   (:class:`~.select.Siblings`); one of each thruster's own map (dead band, asymmetry) found
   in a DOF that several groups of thrusters drive must not be contradicted by every DOF
   that parts of them drive alone, and a thrust asymmetry in a translation must stay
   significant with a buoyancy change's column free beside it (:mod:`.thrusterparts`). Before the DOFs are diagnosed, a whole-log diagnosis fits
   the thrusters' gains jointly over them (:mod:`.gains`: contrasts within each group of
   thrusters, kept when significant and not worse on the validation log; the rest of the
   run then diagnoses against the prior with them); after it, a thruster lag and an
   actuation delay are compared over every DOF the thrusters drive (:mod:`.timing`), and
   what the shared fits (timing, current) change is judged again (:mod:`.stepwise`: a
   joint lag or delay not resolved is withdrawn; a DOF's own steps are judged again in its
   written model; a bias outside heave, roll and pitch must stand beside the thrusters'
   gains).
   A one-DOF diagnosis fits the same gains in its DOF's balance (``dof_gains``, on by
   default; a fit with a gain under :data:`.gains.MIN_GAIN` is not written; a significant fit
   is judged inside the written model after the selection, the DOF diagnosed with and
   without it, :mod:`.gainjudge`, ``gains_judge``). In a one-DOF
   diagnosis a tether not identified apart from the thrusters' gains beside the map the
   model writes (found only with each thruster's gain free, or whose c_t, refitted with
   them free, is under ``MIN_Z`` sd from zero) is named with its value "not determined by
   one DOF" and not written (:mod:`.undetermined`: the whole-log diagnosis writes the
   gains).
5. **What remains**: a generic basis (velocities of every DOF, their squares and cubes,
   signs, applied force, heading, other logged channels) is fitted to the final residual; if
   it cuts the held-out error by ``UNEXPLAINED_GAIN`` the residual is still structured and,
   no library effect explaining it, ``unexplained`` is true.

The stages, one module each: :mod:`.settings` (thresholds, :class:`DiagnoseSettings`,
:class:`Budget`), :mod:`.priors` (the calibration's prior widths), :mod:`.fit` (the MAP
least-squares fit), :mod:`.select` (effect selection per DOF), :mod:`.calibrate` (the fitted
values written into the model), :mod:`.validate` (validation by free simulation),
:mod:`.written` (every value reported about the calibrated model read back from it as
written), :mod:`.result` (:class:`Diagnosis`, per DOF :class:`DofResult`); this module runs
them in order.

Depends on: the modules above, effects, logfile.
"""


from __future__ import annotations

import warnings
from dataclasses import replace

import numpy as np

from stripcoef.conventions import DOF, VELOCITIES, parse_dof
from stripcoef.diagnose.calibrate import (bounds_hit, calibrated_fits,  # noqa: F401
                                          calibrated_model, clip_added_mass, contradicted,
                                          share_timing)
from stripcoef.diagnose.cross import moving_dofs, with_known
from stripcoef.diagnose.current import share_current
from stripcoef.diagnose.fit import EffectFit, fit_effects  # noqa: F401
from stripcoef.diagnose import buoyancy, calibnamed, gainjudge, timinggains, undetermined
from stripcoef.diagnose.gainjudge import GAINS_JUDGES
from stripcoef.diagnose.gaingate import GAIN_VALIDATIONS, validate_gains
from stripcoef.diagnose.gains import fit_thruster_gains
from stripcoef.diagnose.regains import (JOINT, TEST, current_kept, refit_gains, tested,
                                        with_found_current,
                                        withdrawn)
from stripcoef.diagnose.stepwise import (OneDofBiasParts, WholeLogParts, changed_dofs,
                                         retest_steps,
                                         terms_record, unresolved_timing)
from stripcoef.diagnose.thrusterparts import OneDofParts
from stripcoef.diagnose.timing import compare_timing
from stripcoef.diagnose.priors import (ADDED_MASS_BAND_Z, PriorWidths,  # noqa: F401
                                       added_mass_bounds, load_prior, method_added_mass_sd,
                                       method_prior_widths, prior_added_mass_sd, prior_widths)
from stripcoef.diagnose.result import Diagnosis, DofFit, _band_record  # noqa: F401
from stripcoef.diagnose.select import (Siblings, _physical_problems,  # noqa: F401
                                       diagnose_dof, excited_dofs, select_dofs)
from stripcoef.diagnose.settings import (BANDS, DEFAULT_WINDOW, MAX_STEPS,  # noqa: F401
                                         LINKED_IDENTIFIED, METRIC, METRIC_TEXT, MIMIC_BANDS,
                                         MIN_DELTA_BIC,
                                         MIN_HELD_OUT_GAIN, MIN_Z, N_BLOCKS,
                                         RESIMULATION_HORIZON, TIE, TIME_LIMIT,
                                         ONE_ADDED_MASS, UNEXPLAINED_GAIN,
                                         VALIDATION_FRACTION, VALIDATION_OTHERS, Budget,
                                         DiagnoseSettings, default_time_limit)
from stripcoef.diagnose.combination import REFERENCES
from stripcoef.diagnose.validate import (CHOICES, JUDGES, heldout_errors,  # noqa: F401
                                         resimulate_rms, resimulated_errors, validate_changes,
                                         validation_errors, with_kept)
from stripcoef.diagnose.written import read_back
from stripcoef.effects.laws import model_window_data
from stripcoef.effects.windows import window_data
from stripcoef.diagnose.heldoutrise import RULES as RISE_RULES
from stripcoef.errors import InputError, ModelWarning


#: the diagnosis' default options (:class:`DiagnoseSettings`), read by :func:`diagnose`'s signature
_DEFAULTS = DiagnoseSettings()


def diagnose(log, model, *, dof="all", window: float = DEFAULT_WINDOW, effects=None,
             resimulate: bool = False, bands=None, max_steps: int = MAX_STEPS,
             time_limit: float | None = None,
             validation: float | None = VALIDATION_FRACTION,
             holdout: float | None = None, added_mass_sd=None,
             prior_widths: PriorWidths | None = None,  # noqa: F811 (the function re-exported above)
             # the options' defaults are DiagnoseSettings' (one place, its docstring says why)
             validation_others: str = _DEFAULTS.validation_others,
             one_added_mass: bool = _DEFAULTS.one_added_mass,
             not_determined: bool = _DEFAULTS.not_determined,
             gains_beside_current: bool | str = _DEFAULTS.gains_beside_current,
             dof_gains: bool = _DEFAULTS.dof_gains,
             cross_mass_scale: bool = _DEFAULTS.cross_mass_scale,
             drag_couplings: bool = _DEFAULTS.drag_couplings,
             restoring_free: bool = _DEFAULTS.restoring_free,
             scale_choice_unforced: bool = _DEFAULTS.scale_choice_unforced,
             heldout_rise: str = _DEFAULTS.heldout_rise,
             validation_horizon: float | str = _DEFAULTS.validation_horizon,
             validation_judge: str = _DEFAULTS.validation_judge,
             linked_gains: bool | str = _DEFAULTS.linked_gains,
             gains_validation: str = _DEFAULTS.gains_validation,
             validation_reference: str = _DEFAULTS.validation_reference,
             gains_judge: str = _DEFAULTS.gains_judge,
             noise_with_bias: bool = _DEFAULTS.noise_with_bias,
             buoyancy_carry: bool = _DEFAULTS.buoyancy_carry,
             gains_beside_timing: bool = _DEFAULTS.gains_beside_timing,
             retest_scales: bool = _DEFAULTS.retest_scales,
             validation_choice: str = _DEFAULTS.validation_choice,
             calibration_named: bool = _DEFAULTS.calibration_named,
             bias_gains_one_dof: bool = _DEFAULTS.bias_gains_one_dof) -> Diagnosis:
    """Diagnose a log against a prior model (module docstring).

    Parameters
    ----------
    log : Log
        Time series with ``t``, velocities and inputs (commands or forces).
    model : HydroModel
        The prior (strip-theory) model; its ``effects`` (a calibrated model's) are part of
        the residual, so they are not found again.
    dof : str
        A DOF name (surge..yaw, u..r, X..N) or ``"all"`` (every excited DOF).
    window : float
        Window length of the one-step residual [s].
    effects : list of str, optional
        Candidate effects (default: the whole library).
    resimulate : bool
        Also report the RMS of the re-simulated velocity (baseline, calibrated, final).
    time_limit : float, optional
        CPU-time budget [s] (:func:`time.process_time`; default :func:`default_time_limit`: :data:`TIME_LIMIT`, in
        proportion to the rows past :data:`BUDGET_ROWS`; ``inf``: none); past it an
        :class:`~stripcoef.errors.UnreachableError` says so instead of grinding.
    validation : float or None
        Fraction of the fitting log (its end) kept to validate every change by free
        simulation (:func:`validate_changes`); None or 0 keeps every change.
    holdout : float or None
        Fraction of the log (its end) never used for fitting: the held-out free-simulation
        errors of the prior, the calibrated model (as written) and hold-last-velocity are
        reported on it (:attr:`Diagnosis.holdout`).
    added_mass_sd : (6,) array, optional
        Relative 1-sigma method uncertainty [-] of the prior's added mass per DOF
        (:func:`method_added_mass_sd`; NaN where unknown): the calibrated added mass stays
        within its 99.7 % band (:func:`added_mass_bounds`); one outside it is clipped to it
        and listed in ``bounds_hit``. Default: that of ``prior_widths``.
    prior_widths : PriorWidths, optional
        The widths of the calibration's Gaussian priors from the method table
        (:func:`method_prior_widths`, :func:`prior_widths` of a vehicle file), in the place
        of :data:`BANDS`; ``bands``, when given, overrides them. Recorded in the JSON with
        the row each width came from (``prior_widths``, ``per_dof.<dof>.calibration.
        band_source``).
    validation_others : str
        ``"each"`` (default): every diagnosed DOF simulated alone, the other five from the
        log, a whole-log diagnosis too; ``"logged"``: the validation's free simulations of
        a one-DOF diagnosis take the other DOFs from the log (a whole-log diagnosis
        simulates every DOF); ``"simulated"``: from the model
        (:data:`~stripcoef.diagnose.settings.VALIDATION_OTHERS`).
    one_added_mass : bool or str
        Whole-log: select again a DOF whose fit contradicts a diagnosed DOF's own added mass
        (:attr:`DiagnoseSettings.one_added_mass`; off by default; ``"difference"``: judged
        on the sd of the two estimates' difference, :data:`~stripcoef.diagnose.settings.
        ONE_ADDED_MASS`).
    not_determined : bool
        One DOF: a tether not identified apart from the thrusters' gains beside the written
        map is named with its c_t not determined by one DOF and not written
        (:mod:`.undetermined`; on by default); False: written from the fit on that map
        (:attr:`DiagnoseSettings.not_determined`).
    gains_beside_current : bool or str
        Whole-log: when the DOFs find a water current, the thrusters' gains are fitted again
        beside it and the DOFs diagnosed again on them (:mod:`.regains`; off by default,
        :attr:`DiagnoseSettings.gains_beside_current`); ``"joint"``: with the current free
        beside them, and withdrawn with it; ``"test"``: the gains and the current compared as
        two explanations of the prior's residual (Vuong 1989), the gains kept only when the
        log chooses them.
    dof_gains : bool
        One DOF: the thrusters' gains fitted in that DOF's balance
        (:attr:`DiagnoseSettings.dof_gains`; on by default); False: the prior's map.
    cross_mass_scale : bool
        Whole-log: a thrust scale must stay identified with the other DOFs' added masses
        free beside it (:mod:`.crossscale`; on by default); False: not tested
        (:attr:`DiagnoseSettings.cross_mass_scale`).
    drag_couplings : bool
        A moment DOF's calibration also holds its drag couplings to the translations
        (:mod:`.couplings`; off by default, :attr:`DiagnoseSettings.drag_couplings`).
    restoring_free : bool
        The linear drag's test in surge and sway repeated with the buoyancy change free
        (:attr:`DiagnoseSettings.restoring_free`).
    scale_choice_unforced : bool
        A thrust scale and an added-mass release, both contenders of a step no candidate
        passes, decided by the model holding both
        (:attr:`DiagnoseSettings.scale_choice_unforced`; on by default).
    heldout_rise : str
        ``"tie"`` (default) or ``"diebold_mariano"``: when a scale or a released coefficient
        raises the held-out error (:mod:`.heldoutrise`, :attr:`DiagnoseSettings.heldout_rise`).
    validation_horizon : float or str
        ``"correlation"`` (default: each DOF's velocity's integral time scale,
        :mod:`.horizon`) or the horizon of the validation's segments [s]
        (:attr:`DiagnoseSettings.validation_horizon`).
    validation_judge : str
        ``"own"`` (default), ``"all"`` or ``"coupled"``: the DOFs whose validation errors
        judge removing a change (:attr:`DiagnoseSettings.validation_judge`).
    linked_gains : bool or str
        The thrusters' gains' contrasts within groups linked through the diagnosed DOFs
        (:attr:`DiagnoseSettings.linked_gains`); ``"identified"`` (default): linked only
        where the log identifies the groups' contrast; False: not linked.
    gains_validation : str
        ``"consecutive"``, ``"rolling"`` or ``"rolling_test"``: how the thrusters' gains are
        validated
        (:attr:`DiagnoseSettings.gains_validation`, :mod:`.gaingate`).
    validation_reference : str
        ``"combination"`` (default) or ``"trivial"``: the skill veto's reference forecast
        (:attr:`DiagnoseSettings.validation_reference`; :mod:`.combination`).
    gains_judge : str
        ``"written"`` (default), ``"prior"`` or ``"none"``: how a significant one-DOF gain fit
        is validated (:mod:`.gainjudge`, :attr:`DiagnoseSettings.gains_judge`);
        ``"written_all"``: a whole-log fit too; ``"off"``: the gains not fitted.
    noise_with_bias : bool
        The calibration's identifiability judged with the noise level fitted beside a free
        constant (:attr:`DiagnoseSettings.noise_with_bias`; on by default).
    buoyancy_carry : bool
        Heave's buoyancy offset written as one change of the buoyancy B, acting in every DOF
        through the restoring force, and, whole-log, carried into the other DOFs' fits
        (:mod:`.buoyancy`, :attr:`DiagnoseSettings.buoyancy_carry`; off by default).
    gains_beside_timing : bool
        The thrusters' gains fitted again beside the lag or delay the DOFs found, the DOFs
        diagnosed again on them (:mod:`.timinggains`; off by default).
    retest_scales : bool
        Whole-log: a thrust scale or an added-mass release judged again in the model the
        shared fits wrote (:attr:`DiagnoseSettings.retest_scales`; off by default).
    validation_choice : str
        ``"greedy"`` (default) or ``"best_visited"``: the validation's final model, the set
        its elimination ends with or the best of the prior and every set it scored
        (:attr:`DiagnoseSettings.validation_choice`).
    calibration_named : bool
        The written calibration's departures from the prior beyond ``MIMIC_BANDS`` bands
        named as the effects that mimic them (:mod:`.calibnamed`,
        :attr:`DiagnoseSettings.calibration_named`; off by default).
    bias_gains_one_dof : bool
        One DOF: a bias outside heave, roll and pitch must stand beside the acting
        thrusters' gains, as in a whole-log run (:class:`~.stepwise.OneDofBiasParts`,
        :attr:`DiagnoseSettings.bias_gains_one_dof`; off by default).

    Returns
    -------
    Diagnosis
        ``metric``, ``baseline_error``, ``calibrated_error``, ``steps`` (each with
        ``effect``, ``parameters``, ``std``, ``error_before``, ``error_after``,
        ``held_out_error_before``, ``held_out_error_after``), ``final_error``,
        ``unexplained``, ``excited_dofs``, ``dofs_not_diagnosed``, ``kept_at_prior``,
        ``bounds_hit``, ``validation``, ``holdout``, ``per_dof`` details, ``model`` (the
        calibrated HydroModel); :meth:`Diagnosis.to_dict` is the JSON contract (everything
        but the model).
    """
    limit = default_time_limit(len(log)) if time_limit is None else float(time_limit)
    if not limit > 0:
        raise InputError("not a positive time budget", key="time_limit", value=time_limit,
                         expected="a number of seconds > 0 (inf: none)")
    for key, value in (("holdout", holdout), ("validation", validation)):
        if value is not None and not (isinstance(value, (int, float))
                                      and 0.0 <= float(value) < 1.0):
            raise InputError("not a fraction", key=key, value=value,
                             expected="a number in [0, 1), e.g. 0.3")
    if prior_widths is not None and not isinstance(prior_widths, PriorWidths):
        raise InputError("not prior widths", key="prior_widths",
                         value=type(prior_widths).__name__,
                         expected="a PriorWidths (method_prior_widths(vehicle)) or None")
    for key, value, names, what in (
            ("validation_others", validation_others, VALIDATION_OTHERS,
             "a way to move the DOFs not diagnosed"),
            ("gains_validation", gains_validation, GAIN_VALIDATIONS,
             "a way to validate the thrusters' gains"),
            ("validation_reference", validation_reference, REFERENCES,
             "a reference forecast of the validation's skill veto"),
            ("validation_judge", validation_judge, JUDGES,
             "a way to judge a validation's removal"),
            ("heldout_rise", heldout_rise, RISE_RULES, "a rule for a held-out rise"),
            ("gains_judge", gains_judge, GAINS_JUDGES, "a way to validate the thrusters' gains"),
            ("validation_choice", validation_choice, CHOICES,
             "a way to choose the validation's final model")):
        if value not in names:
            raise InputError(f"not {what}", key=key, value=value,
                             expected="one of " + ", ".join(names))
    if one_added_mass not in ONE_ADDED_MASS:
        raise InputError("not a rule for one added mass", key="one_added_mass",
                         value=one_added_mass,
                         expected="one of " + ", ".join(map(repr, ONE_ADDED_MASS)))
    if gains_beside_current not in (False, True, JOINT, TEST):
        raise InputError("not a mode of the gains beside the current",
                         key="gains_beside_current", value=gains_beside_current,
                         expected=f"False, True, {JOINT!r} or {TEST!r}")
    if cross_mass_scale not in (False, True):
        raise InputError("not a rule for a thrust scale beside the other DOFs' added masses",
                         key="cross_mass_scale", value=cross_mass_scale,
                         expected="True or False")
    if linked_gains not in (False, True, LINKED_IDENTIFIED):
        raise InputError("not a way to group the thrusters' gains", key="linked_gains",
                         value=linked_gains, expected=f"False, True or {LINKED_IDENTIFIED!r}")
    if added_mass_sd is None and prior_widths is not None:
        added_mass_sd = prior_widths.added_mass_sd
    if added_mass_sd is not None:
        added_mass_sd = np.asarray(added_mass_sd, float).reshape(-1)
        if added_mass_sd.size != 6 or np.any(added_mass_sd[np.isfinite(added_mass_sd)] < 0):
            raise InputError("not six relative standard deviations", key="added_mass_sd",
                             value=added_mass_sd.tolist(),
                             expected="6 numbers >= 0 (NaN where unknown), one per DOF")
    settings = DiagnoseSettings(
        window=window, effects=None if effects is None else tuple(effects),
        resimulate=bool(resimulate), bands=bands, max_steps=max_steps,
        validation=validation or None, holdout=holdout or None,
        added_mass_sd=added_mass_sd, prior_widths=prior_widths,
        validation_others=validation_others,
        one_added_mass=one_added_mass, not_determined=bool(not_determined),
        gains_beside_current=(gains_beside_current if gains_beside_current in (JOINT, TEST)
                              else bool(gains_beside_current)),
        dof_gains=bool(dof_gains),
        cross_mass_scale=bool(cross_mass_scale),
        drag_couplings=bool(drag_couplings), restoring_free=bool(restoring_free),
        scale_choice_unforced=bool(scale_choice_unforced), heldout_rise=heldout_rise,
        validation_horizon=_horizon_setting(validation_horizon),
        validation_judge=validation_judge,
        linked_gains=(LINKED_IDENTIFIED if linked_gains == LINKED_IDENTIFIED
                      else bool(linked_gains)),
        gains_validation=gains_validation, validation_reference=validation_reference,
        gains_judge=gains_judge, noise_with_bias=bool(noise_with_bias),
        buoyancy_carry=bool(buoyancy_carry),
        gains_beside_timing=bool(gains_beside_timing),
        retest_scales=bool(retest_scales), validation_choice=validation_choice,
        calibration_named=bool(calibration_named),
        bias_gains_one_dof=bool(bias_gains_one_dof))
    budget = Budget.start(limit, rows=len(log), source=log.source)
    return run(log, model, dof=dof, settings=settings, budget=budget)


def run(log, model, *, dof="all", settings: DiagnoseSettings = DiagnoseSettings(),
        budget: Budget = Budget()) -> Diagnosis:
    """:func:`diagnose` with its options as one :class:`DiagnoseSettings` (checked by
    :func:`diagnose`) inside the CPU-time ``budget``."""
    from stripcoef.diagnose.heldout import split

    window, validation, holdout = settings.window, settings.validation, settings.holdout
    added_mass_sd, widths = settings.added_mass_sd, settings.prior_widths
    bands = settings.bands

    if str(dof).lower() != "all":
        log.require(VELOCITIES[parse_dof(dof)])       # never a missing column read as zeros
    fit_log, test_log = (log, None) if not holdout else split(log, holdout, key="holdout")
    train_log, val_log, skipped = fit_log, None, None
    if validation:
        try:
            train_log, val_log = split(fit_log, validation, key="validation")
            window_data(train_log, model, window=window)
        except InputError as exc:  # too short to spare a validation part: fit on all of it
            train_log, val_log, skipped = fit_log, None, str(exc)
    data = model_window_data(train_log, model, window=window)
    excited, not_excited = select_dofs(data)
    dropped = {}
    if str(dof).lower() == "all":
        dofs, dropped = excited, dict(not_excited)
        if not dofs:
            raise InputError("no excited degree of freedom", file=log.source,
                             expected="a log where some DOF has its velocity column, an "
                             "applied force and motion above its noise (" + "; ".join(
                                 f"{k}: {v}" for k, v in dropped.items()) + ")")
        if dropped:
            warnings.warn(f"{log.source}: dof='all' diagnoses " + ", ".join(DOF[i] for i in dofs)
                          + " and drops " + "; ".join(f"{k} ({v})" for k, v in dropped.items()),
                          ModelWarning, stacklevel=3)
    else:
        dofs = [parse_dof(dof)]
    not_diagnosed = {k: v for k, v in not_excited.items() if parse_dof(k) not in dofs}
    absent = [v for v in VELOCITIES if v not in log]
    if absent:
        warnings.warn(f"{log.source}: no column {', '.join(absent)}: the coupling terms "
                      "(C(nu) nu of the diagnosed DOFs) take them as 0", ModelWarning,
                      stacklevel=3)
    # the thrusters' gains fitted jointly over the DOFs (gains.py; one DOF too, on its own
    # balance, settings.dof_gains); when kept, they are the prior of the rest of the
    # diagnosis and written with the model
    prior, gains = model, None
    data0 = data
    if gainjudge.fitted(settings, dofs):
        gains = fit_thruster_gains(data, dofs, settings, excited=excited, budget=budget)
        if gainjudge.after_selection(settings, dofs, val_log, gains):
            # judged inside the written model, the DOF(s) diagnosed with and without them
            # (gainjudge.py)
            return gainjudge.judged(run, log, model, dof, settings, budget,
                                    whole=len(dofs) > 1)
        if gains is not None and settings.gains_judge != gainjudge.NONE:
            gains = validate_gains(gains, val_log, model, dofs, settings)
        if gains is not None and gains.applied:
            model = gains.model(model)
            data = model_window_data(train_log, model, window=window)
    per, fits = _fit_dofs(data, model, dofs, excited, settings, budget)
    # option (settings.gains_beside_current): the gains were fitted before any effect; a
    # water current found since is a regressor their fit omitted, which biases them
    # (regains.py): they are fitted again beside it and the DOFs diagnosed again on them
    water = (with_found_current(prior, per)
             if settings.gains_beside_current and gains is not None else None)
    first = None        # mode "joint": the first pass, restored if the current is removed
    if water is not None and settings.gains_beside_current == TEST:
        if gains.significant and len(dofs) > 1:     # whole-log: two explanations
            applied = gains.applied
            gains, keep = tested(gains, water, data0, train_log, dofs, excited, settings)
            if keep == JOINT:   # both: mode "joint" (regains.py)
                before = (gains, model, per, fits)
                gains, model, data = refit_gains(water, prior, data0, train_log, val_log,
                                                 dofs, excited, replace(
                                                     settings, gains_beside_current=JOINT),
                                                 budget)
                per, fits = _fit_dofs(data, model, dofs, excited, settings, budget)
                first = before if gains is not None and gains.applied else None
            elif not keep and applied:      # withdrawn: the DOFs on the prior's maps
                model, data = prior, data0
                per, fits = _fit_dofs(data, model, dofs, excited, settings, budget)
    elif water is not None:
        before = (gains, model, per, fits)
        gains, model, data = refit_gains(water, prior, data0, train_log, val_log, dofs,
                                         excited, settings, budget)
        per, fits = _fit_dofs(data, model, dofs, excited, settings, budget)
        if settings.gains_beside_current == JOINT and gains is not None and gains.applied:
            first = before
    # option (settings.gains_beside_timing): the gains were fitted before any effect; the
    # thrusters' lag or delay found since is a thrust-shaped force their fit omitted: they
    # are fitted again beside it and the DOFs diagnosed again on them (timinggains.py)
    timed = (timinggains.with_found_timing(prior, fits)
             if settings.gains_beside_timing and gains is not None and first is None
             else None)
    if timed is not None:
        applied = gains.applied
        gains, model, data = timinggains.refit_gains(timed, prior, data0, train_log, val_log,
                                                     dofs, excited, settings, budget)
        if applied or (gains is not None and gains.applied):
            per, fits = _fit_dofs(data, model, dofs, excited, settings, budget)
    if len(dofs) == 1 and settings.not_determined:   # depends on the gains: not written
        per = undetermined.mark(per, fits, gained=gains is not None and gains.applied)
    exclude, record = set(), None
    if val_log is not None:
        horizon = settings.validation_horizons(val_log, dofs)
        exclude, record = validate_changes(val_log, model, per, fits, dofs, budget=budget,
                                           logged=settings.logged_dofs(dofs),
                                           horizon=horizon, judge=settings.validation_judge,
                                           reference=settings.validation_reference,
                                           choice=settings.validation_choice)
        if first is not None and not current_kept(per, exclude):
            # mode "joint": the gains fitted beside the current are its partner (regains.py)
            gains = withdrawn(gains, first[0])
            model, per, fits = first[1:]
            exclude, record = validate_changes(val_log, model, per, fits, dofs,
                                               budget=budget,
                                               logged=settings.logged_dofs(dofs),
                                               horizon=horizon,
                                               judge=settings.validation_judge,
                                               reference=settings.validation_reference,
                                               choice=settings.validation_choice)
        per = with_kept(per, exclude)
    calibrated, fitted = calibrated_fits(model, per, fits, exclude)
    calibrated, clipped = clip_added_mass(model, calibrated, added_mass_sd)
    # one model: what is reported about the calibrated model is read back from it as written
    written = type(calibrated).from_dict(calibrated.to_dict())
    per = read_back(per, fits, written, train_log, window=window, exclude=exclude,
                    fitted=fitted)
    if settings.calibration_named:  # the written calibration's departures (calibnamed.py)
        per = calibnamed.named(per)
    if record is not None and clipped:      # the validated model was clipped afterwards
        record["kept_changes"] = validation_errors(
            val_log, written, dofs, settings.logged_dofs(dofs),
            settings.validation_horizons(val_log, dofs))
    if len(dofs) == 1:
        r = per[DOF[dofs[0]]]
        summary = {"metric": METRIC, "dof": r.dof, "units": r.units,
                   "baseline_error": r.baseline_error,
                   "calibrated_error": r.calibrated_error,
                   "steps": r.steps, "final_error": r.final_error,
                   "unexplained": r.unexplained}
    else:
        def rel(key):
            return float(np.sqrt(np.mean([(getattr(r, key) / r.baseline_error) ** 2
                                          for r in per.values()])))
        summary = {"metric": METRIC + "_relative", "dof": "all",
                   "units": "relative to each DOF's baseline",
                   "baseline_error": 1.0, "calibrated_error": rel("calibrated_error"),
                   "steps": [s for r in per.values() for s in r.steps],
                   "final_error": rel("final_error"),
                   "unexplained": any(r.unexplained for r in per.values())}
    kept = {d: dict(r.calibration.kept_at_prior) for d, r in per.items()}
    for d, why in not_diagnosed.items():
        j = parse_dof(d)
        # a DOF that moves without being diagnosed: its added mass may have been
        # calibrated through C_A in the diagnosed DOFs (cross.py); its drags stay
        moved = float(calibrated.added_mass[j, j]) != float(model.added_mass[j, j])
        kept[d] = ({"linear and quadratic damping": why} if moved
                   else {"all coefficients": why})
    if settings.resimulate:
        summary["resimulated_velocity_rms"] = resimulated_errors(train_log, model, per, fits,
                                                                 calibrated, exclude)
        summary["resimulated_velocity_description"] = (
            "RMS of logged minus re-simulated velocity [m/s or rad/s] of each diagnosed DOF "
            "on the fitting log: the prior, the prior with its calibrated coefficients, and "
            "the final model")
    result = Diagnosis(metric_description=METRIC_TEXT, window_s=window, log=log.source,
                       vehicle=model.name, per_dof=per, model=calibrated, fits=fits,
                       dropped_dofs=dropped, excited_dofs=tuple(DOF[i] for i in excited),
                       dofs_not_diagnosed=not_diagnosed, kept_at_prior=kept,
                       bounds_hit=bounds_hit(model, calibrated, added_mass_sd, clipped),
                       added_mass_band=_band_record(added_mass_sd),
                       prior_widths=(widths.to_dict() if widths is not None
                                     and bands is None else None),
                       validation=record if skipped is None else {"skipped": skipped},
                       fitted_on_s=(float(train_log["t"][0]), float(train_log["t"][-1])),
                       test_log=test_log, diagnosed=tuple(dofs),
                       thruster_gains=None if gains is None else gains.to_dict(), **summary)
    if test_log is not None:
        # recomputed from the model as it is written (its dictionary form, read back)
        result = replace(result, holdout=heldout_errors(result, prior, written))
    return result


def _fit_dofs(data, model, dofs, excited, settings: DiagnoseSettings, budget: Budget):
    """``(per, fits)``: every diagnosed DOF's calibration and effects against ``model`` (the
    prior, with the thrusters' gains when kept) on the window data ``data``, the whole-log
    rules applied (one added mass, one timing, one current)."""
    # the added masses of the other DOFs that move, calibrated in each diagnosed DOF they
    # reach; written once (a diagnosed DOF's own calibration; cross.py)
    cross = moving_dofs(data)
    # whole-log: a thruster effect found in one DOF must hold in every DOF its thrusters
    # drive; one DOF: a translation's asymmetry identified apart from a buoyancy change
    siblings = (WholeLogParts if len(dofs) > 1 else OneDofBiasParts
                if settings.bias_gains_one_dof else OneDofParts)(
        data, dofs, settings, budget=budget, excited=excited, cross=cross)
    per, fits = {}, {}
    carry = settings.buoyancy_carry         # heave first, its buoyancy change carried
    for i in (buoyancy.order(dofs) if carry else dofs):
        per[DOF[i]], fits[DOF[i]] = diagnose_dof(data, i, settings, budget=budget,
                                                 excited=excited, cross=cross,
                                                 siblings=siblings)
        if carry and i == buoyancy.HEAVE:   # written as one change of B (buoyancy.py)
            fits[DOF[i]] = buoyancy.written_as_change(fits[DOF[i]])
            delta_b = buoyancy.heave_change(per[DOF[i]])
            if delta_b is not None and len(dofs) > 1:
                data = buoyancy.carried(data, delta_b)
                siblings = type(siblings)(data, dofs, settings, budget=budget,
                                          excited=excited, cross=cross)
    per, fits = {DOF[i]: per[DOF[i]] for i in dofs}, {DOF[i]: fits[DOF[i]] for i in dofs}
    # option (settings.one_added_mass): a DOF whose fit contradicts a diagnosed DOF's own
    # added mass is selected again with the diagnosed DOFs' added masses held at the prior,
    # and written refitted with their written values (calibrate.contradicted,
    # consistent_fits)
    undiagnosed = [j for j in cross if DOF[j] not in per]
    again = (contradicted(model, per, fits,
                          difference=settings.one_added_mass == "difference")
             if len(dofs) > 1 and settings.one_added_mass else {})
    for d, known in again.items():
        i = parse_dof(d)
        per[d], fits[d] = diagnose_dof(with_known(data, i, dict.fromkeys(known, 0.0)), i,
                                       settings, budget=budget, excited=excited,
                                       cross=undiagnosed, siblings=siblings)
    selected = terms_record(fits)
    per, fits = share_timing(per, fits)     # the thrusters' one lag/delay (calibrate.py)
    if len(dofs) > 1:       # whole-log: lag or delay, compared over the DOFs (timing.py)
        per, fits, _ = compare_timing(per, fits)
        per, fits = unresolved_timing(per, fits)    # not resolved jointly: withdrawn
    per, fits = share_current(per, fits)    # the water's one current (current.py)
    if len(dofs) > 1:       # whole-log: steps judged again where the shared fits changed
        per, fits = retest_steps(per, fits, changed_dofs(selected, fits), len(dofs),
                                 scales=settings.retest_scales)
    return per, fits


def _horizon_setting(value):
    """``validation_horizon`` checked: ``"correlation"`` or a number of seconds > 0."""
    from stripcoef.diagnose.horizon import CORRELATION

    if isinstance(value, str) and value == CORRELATION:
        return value
    if isinstance(value, (int, float)) and not isinstance(value, bool) and value > 0 \
            and np.isfinite(value):
        return float(value)
    raise InputError("not a validation horizon", key="validation_horizon", value=value,
                     expected=f"a number of seconds > 0 or {CORRELATION!r}")
