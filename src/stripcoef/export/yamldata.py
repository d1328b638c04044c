"""YAML export: :meth:`stripcoef.model.HydroModel.to_dict` of the model about the chosen point.

Readable back with ``HydroModel.from_dict(yaml.safe_load(f))``.  FRD body axes only (the
HydroModel contract).
"""

from __future__ import annotations

import yaml

from stripcoef.export._common import ExportFormat, ExportView, header_lines
from stripcoef.model import plain

NAME = "yaml"


def render(view: ExportView) -> str:
    head = "".join(f"# {line}\n" for line in header_lines(view, NAME))
    return head + yaml.safe_dump(plain(view.model.to_dict()), sort_keys=False,
                                 default_flow_style=None, width=120)


#: This format's entry of the registry :data:`stripcoef.export.FORMATS`.
FORMAT = ExportFormat(
    name=NAME,
    description="HydroModel.to_dict() as YAML (FRD; read back with HydroModel.from_dict)",
    suffix=".yaml",
    render=render,
    axes_allowed=("FRD",),
    holds_effects=True)
