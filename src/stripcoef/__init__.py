"""stripcoef: hydrodynamic models of underwater vehicles from their geometry.

Pipeline: geometry -> strips -> sections -> assembly -> HydroModel ->
limits / export / simulate / identify / diagnose.

Public API (see docs/):

- :func:`load_vehicle` - read and validate a vehicle file (YAML)
- :func:`estimate` - strip theory: a vehicle file, a mesh file or a :class:`Vehicle` in,
  a :class:`HydroModel` out; its options by keyword or as an :class:`EstimateOptions`
- :class:`Vehicle` - the geometry (``Vehicle.from_mesh`` for a CAD mesh)
- :func:`load_model` - a HydroModel from a model file (JSON/YAML) or a vehicle file
- :func:`solve_limits` - steady manoeuvre limits of a :class:`HydroModel` (docs/limits.md)
- :func:`export_model` / :func:`write_export` - simulator and data formats (docs/export/)

Everything but the exception classes is imported lazily, so that ``import stripcoef``
(and the CLI's start-up) does not load numpy before the CLI has set up its environment.
"""

from importlib import import_module

from stripcoef.errors import InputError, StripcoefError, UnreachableError

__version__ = "0.1.0"

#: public name -> (module, attribute)
_LAZY = {
    "Fluid": ("fluid", "Fluid"),
    "HydroModel": ("model", "HydroModel"),
    "Thruster": ("thrusters", "Thruster"),
    "load_vehicle": ("geometry.vehicle", "load_vehicle"),
    "Vehicle": ("geometry.vehicle", "Vehicle"),
    "estimate": ("assembly", "estimate"),
    "EstimateOptions": ("assembly", "EstimateOptions"),
    "load_model": ("modelfile", "load_model"),
    "solve_limits": ("limits", "solve_limits"),
    "export_model": ("export", "export_model"),
    "write_export": ("export", "write_export"),
}

__all__ = ["InputError", "StripcoefError", "UnreachableError", "__version__", *_LAZY]


def __dir__():
    return sorted(__all__)


def __getattr__(name):
    try:
        module, attr = _LAZY[name]
    except KeyError:
        raise AttributeError(f"module 'stripcoef' has no attribute {name!r}") from None
    return getattr(import_module(f"stripcoef.{module}"), attr)
