"""Steady manoeuvre limits of a :class:`~stripcoef.model.HydroModel`.

:mod:`.balance` (the steady-state force a motion requires), :mod:`.solver` (the balance with
thrusters and the thruster allocation), :mod:`.steering` (vehicles steered by rudders and
elevators: trim, turning circle, dive), :mod:`.plots` (figures).
Theory and conventions: docs/limits.md.

Depends on: model, thrusters, base.
"""

from stripcoef.limits.solver import (LimitOptions, LimitsResult, Manoeuvre, TurnPoint,
                                     check_model, solve_limits)
from stripcoef.limits.steering import (Flight, SteeringLimits, dive, free_flight, level_trim,
                                       rudder_turn, steering_limits)

__all__ = ["Flight", "LimitOptions", "LimitsResult", "Manoeuvre", "SteeringLimits",
           "TurnPoint", "check_model", "dive", "free_flight", "level_trim", "rudder_turn",
           "solve_limits", "steering_limits"]
