"""JSON export: :meth:`stripcoef.model.HydroModel.to_dict` of the model about the chosen point.

Readable back with ``HydroModel.from_dict(json.load(f))``.  The HydroModel contract is
FRD body axes, so FRD is the only axes this format is written in.  Strict JSON: a thruster
without a limit is ``null`` (:func:`stripcoef.files.json_text`, docs/conventions.md).
"""

from __future__ import annotations

from stripcoef.export._common import ExportView
from stripcoef.files import json_text

NAME = "json"
DESCRIPTION = "HydroModel.to_dict() as JSON (FRD; read back with HydroModel.from_dict)"
SUFFIX = ".json"
BINARY = False
AXES_ALLOWED = ("FRD",)
DEFAULT_AXES = "FRD"
DEFAULT_POINT = "CO"
POINTS_ALLOWED = None
#: Whether the model's calibrated ``effects`` fit this format (else a SimulatorTrapWarning).
HOLDS_EFFECTS = True
OPTIONS = ()


def render(view: ExportView) -> str:
    return json_text(view.model.to_dict())
