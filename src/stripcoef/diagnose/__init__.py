"""Closing the loop: the residual between a model and a log, traced to an effect.

:mod:`.pipeline` (the orchestration: :func:`diagnose` -> :class:`Diagnosis`) runs
:mod:`.settings` (thresholds, :class:`DiagnoseSettings`, :class:`Budget`), :mod:`.priors`
(the calibration's prior widths), :mod:`.fit` (MAP least squares), :mod:`.select` (effect
selection), :mod:`.calibrate` (the fitted values written into the model), :mod:`.validate`
(validation by free simulation), :mod:`.written` (what is reported about the calibrated
model, read back from it as written) and :mod:`.result`; :mod:`.heldout` (free-simulation
errors), :mod:`.report` (text and markdown). docs/diagnose.md.

Depends on: identify, simulate, effects, model, logfile, base.
"""

from stripcoef.diagnose.fit import EffectFit, fit_effects
from stripcoef.diagnose.pipeline import diagnose
from stripcoef.diagnose.priors import PriorWidths, load_prior, method_prior_widths, prior_widths
from stripcoef.diagnose.result import Calibration, Diagnosis, DofFit, DofResult, Step
from stripcoef.diagnose.settings import Budget, DiagnoseSettings

__all__ = ["Budget", "Calibration", "DiagnoseSettings", "Diagnosis", "DofFit", "DofResult",
           "EffectFit", "PriorWidths", "Step", "diagnose", "fit_effects", "load_prior",
           "method_prior_widths", "prior_widths"]
