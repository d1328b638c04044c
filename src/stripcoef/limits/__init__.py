"""Steady manoeuvre limits of a :class:`~stripcoef.model.HydroModel`.

:mod:`.solver` (the force balance and the thruster allocation), :mod:`.plots` (figures).
Theory and conventions: docs/limits.md.

Depends on: model, thrusters, base.
"""

from stripcoef.limits.solver import (LimitOptions, LimitsResult, Manoeuvre, TurnPoint,
                                     check_model, solve_limits)

__all__ = ["LimitOptions", "LimitsResult", "Manoeuvre", "TurnPoint", "check_model",
           "solve_limits"]
