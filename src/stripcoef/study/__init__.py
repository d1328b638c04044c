"""Studies of a vehicle design: uncertainty bands and sweeps (docs/uncertainty.md).

:func:`~stripcoef.study.uncertainty.uncertainty` propagates the method's error and the
vehicle file's declared input uncertainties by quasi-Monte Carlo to every coefficient and
limit; :func:`~stripcoef.study.sweep.sweep` evaluates a grid of vehicle-file values. Both run
locally (processes) or on a Dask cluster (:mod:`.runner`) with the same numbers.

Depends on: limits, assembly, geometry, model, base.
"""

from stripcoef.study.sweep import Vary, parse_vary, sweep
from stripcoef.study.uncertainty import UncertaintyResult, uncertainty

__all__ = ["UncertaintyResult", "Vary", "parse_vary", "sweep", "uncertainty"]
