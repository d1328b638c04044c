"""Closing the loop: the residual between a model and a log, traced to an effect.

:mod:`.pipeline` (calibration, effect selection, re-simulation), :mod:`.report` (text and
markdown). docs/diagnose.md.

Depends on: identify, simulate, effects, model, logfile, base.
"""

from stripcoef.diagnose.pipeline import diagnose

__all__ = ["diagnose"]
