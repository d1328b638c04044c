"""JSON export: :meth:`stripcoef.model.HydroModel.to_dict` of the model about the chosen point.

Readable back with ``HydroModel.from_dict(json.load(f))``.  The HydroModel contract is
FRD body axes, so FRD is the only axes this format is written in.  Strict JSON: a thruster
without a limit is ``null`` (:func:`stripcoef.files.json_text`, docs/conventions.md).
"""

from __future__ import annotations

from stripcoef.export._common import ExportFormat, ExportView
from stripcoef.files import json_text

NAME = "json"


def render(view: ExportView) -> str:
    return json_text(view.model.to_dict())


#: This format's entry of the registry :data:`stripcoef.export.FORMATS`.
FORMAT = ExportFormat(
    name=NAME,
    description="HydroModel.to_dict() as JSON (FRD; read back with HydroModel.from_dict)",
    suffix=".json",
    render=render,
    axes_allowed=("FRD",),
    holds_effects=True)
