"""JSON export: :meth:`stripcoef.model.HydroModel.to_dict` of the model about the chosen point.

Readable back with ``HydroModel.from_dict(json.load(f))``.  The HydroModel contract is
FRD body axes, so FRD is the only axes this format is written in.  Infinite thrust limits
are written as ``Infinity`` (what Python's json module reads and writes).
"""

from __future__ import annotations

import json

from stripcoef.export._common import ExportFormat, ExportView, plain

NAME = "json"


def render(view: ExportView) -> str:
    return json.dumps(plain(view.model.to_dict()), indent=2) + "\n"


#: This format's entry of the registry :data:`stripcoef.export.FORMATS`.
FORMAT = ExportFormat(
    name=NAME,
    description="HydroModel.to_dict() as JSON (FRD; read back with HydroModel.from_dict)",
    suffix=".json",
    render=render,
    axes_allowed=("FRD",),
    holds_effects=True)
