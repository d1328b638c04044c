"""stripcoef: hydrodynamic models of underwater vehicles from their geometry.

Pipeline: geometry -> strips -> sections -> assembly -> HydroModel ->
limits / export / simulate / identify / diagnose.

Public API (see docs/):

- :func:`load_vehicle` - read and validate a vehicle file (YAML)
- :func:`estimate` - strip theory: a Vehicle in, a :class:`HydroModel` out
- :func:`solve_limits` - steady manoeuvre limits of a :class:`HydroModel` (docs/limits.md)
"""

from .errors import InputError, StripcoefError, UnreachableError
from .fluid import Fluid
from .model import HydroModel
from .thrusters import Thruster

__version__ = "0.1.0"

__all__ = ["Fluid", "HydroModel", "InputError", "StripcoefError", "Thruster",
           "UnreachableError", "estimate", "load_vehicle", "solve_limits", "__version__"]


def __getattr__(name):  # lazy imports keep `import stripcoef` fast
    if name == "load_vehicle":
        from .geometry.vehicle import load_vehicle
        return load_vehicle
    if name == "estimate":
        from .assemble import estimate
        return estimate
    if name == "solve_limits":
        from .limits import solve_limits
        return solve_limits
    raise AttributeError(f"module 'stripcoef' has no attribute {name!r}")
