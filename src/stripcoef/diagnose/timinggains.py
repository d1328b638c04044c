r"""The thrusters' gains fitted again beside the lag or delay the diagnosis found (issue 33,
calib33g; option :attr:`~stripcoef.diagnose.settings.DiagnoseSettings.gains_beside_timing`,
off by default).

A diagnosis fits the per-thruster gains (:mod:`.gains`) first, on the prior's window
residual, before any effect is selected; a DOF's calibration and its effects are then
fitted together (:func:`~stripcoef.diagnose.fit._evaluate`: the lag's time constant or the
delay profiled with the calibration's columns free, Golub & Pereyra 1973). A first-order
thruster lag :math:`T` holds back every thrust, :math:`\tau_{lag} \approx \tau - T\dot\tau`
(Fossen 2011, sec. 9.3), a force shaped like the thrust itself, which the gains' joint fit
has no regressor for: the gains take the part of it their contrasts can imitate (the
omitted-variable bias of least squares, :math:`E[\hat a] = a + (G^T G)^{-1} G^T F_T` for the
omitted force :math:`F_T`; Greene 2012, Econometric Analysis, 7th ed., sec. 4.3.2). The
lag or delay, the calibration's inertia (the two trade: about -23 kg per s of delay on the
traced delay log) and the drag are then estimated beside a biased thrust map
(benchmarks/data/calib33g_trace.md: on the traced one-DOF delay log the calibration
fitted *with* the timing effect is within 0.12 kg of the truth's added mass at the truth's
delay; it is the timing value, biased by the thrust map, that moves it, and the validation
then refuses even the truth's drag beside that map).

With the option, once the thrusters' one lag or delay is known
(:func:`~stripcoef.diagnose.calibrate.share_timing`, whole-log also
:func:`~stripcoef.diagnose.timing.compare_timing`) the gains are fitted again on the window
residual of the prior *with that timing effect* (its window forces subtracted, as a
calibrated model's effects are): one backfitting cycle of an additive model, each part
refitted on the residual of the others (Hastie & Tibshirani 1990, Generalized Additive
Models, sec. 4.4), the joint estimate Ljung (1999, sec. 7.3) asks of a model whose parts
share one output. They are validated as the first fit was
(:func:`~stripcoef.diagnose.gaingate.validate_gains`, against the prior with the timing
effect), and the DOFs are diagnosed again on the prior with the new gains (on the prior's
maps when they are not kept), where the timing effect is selected, shared and validated like
any effect: nothing of the first pass is written. The pattern of
:mod:`.regains` (the gains beside a found current), applied to the thrusters' own timing.

Measured on the lag and delay logs of the independent benchmark's four stored seeds (64 rows,
benchmarks/data/calib33g_trace.md): error cut >= 3x 46 -> 52, named first 64 -> 64, magnitude
within 15 % 61 -> 60, whole-log spurious steps named 4 -> 4 (one seed +1, another -1), kept
0 -> 0. Off by default for the seed that names one more and the one that loses a magnitude (a
one-DOF refit validated by the prior's rule, not inside the written model as
``gains_judge="written"`` would; not traced).

Depends on: diagnose.calibrate (SHARED_TIMING), diagnose.regains (refit_beside), effects.
"""

from __future__ import annotations

from stripcoef.diagnose.calibrate import SHARED_TIMING
from stripcoef.diagnose.regains import refit_beside
from stripcoef.effects.laws import model_window_data


def found_timing(fits: dict) -> dict | None:
    """``{"name": effect, "parameters": {key: value}}`` of the thrusters' lag or delay a
    diagnosis's fits hold (after :func:`~stripcoef.diagnose.calibrate.share_timing`: one
    value in every DOF; the first of :data:`SHARED_TIMING` found), or None."""
    for name in SHARED_TIMING:
        for f in fits.values():
            for eff, hyper in f.config.terms:
                if eff.name == name and hyper is not None:
                    return {"name": name,
                            "parameters": {eff.hyper[0]: float(hyper.ravel()[0])}}
    return None


def with_found_timing(prior, fits: dict):
    """``prior`` with the timing effect of :func:`found_timing` acting in all six DOFs
    (``dof: all``, as a written model holds it), or None when no DOF holds one."""
    found = found_timing(fits)
    if found is None:
        return None
    return prior.with_effects({"name": found["name"], "dof": "all",
                               "parameters": found["parameters"]})


def refit_gains(timed, prior, data0, train_log, val_log, dofs, excited, settings, budget):
    """:func:`~stripcoef.diagnose.regains.refit_beside` the timing effect ``timed`` holds
    (the prior with the lag or delay found, :func:`with_found_timing`), validated against
    ``timed`` unless ``settings.gains_judge`` is ``"none"``."""
    entry = timed.effects[-1]
    (key, value), = entry["parameters"].items()
    return refit_beside(model_window_data(train_log, timed, window=settings.window), timed,
                        prior, data0, train_log, val_log, dofs, excited, settings, budget,
                        beside=f"the thrusters' {entry['name']} the DOFs found "
                               f"({key} {value:.4g} s)",
                        validate=settings.gains_judge != "none")
