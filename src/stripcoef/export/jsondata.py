"""JSON export: :meth:`stripcoef.model.HydroModel.to_dict` of the model about the chosen point.

Readable back with ``HydroModel.from_dict(json.load(f))``.  The HydroModel contract is
FRD body axes, so FRD is the only axes this format is written in.  Infinite thrust limits
are written as ``Infinity`` (what Python's json module reads and writes).
"""

from __future__ import annotations

import json

from stripcoef.export._common import ExportView, plain

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
    return json.dumps(plain(view.model.to_dict()), indent=2) + "\n"
