"""YAML export: :meth:`stripcoef.model.HydroModel.to_dict` of the model about the chosen point.

Readable back with ``HydroModel.from_dict(yaml.safe_load(f))``.  FRD body axes only (the
HydroModel contract).
"""

from __future__ import annotations

import yaml

from stripcoef.export._common import ExportView, header_lines, plain

NAME = "yaml"
DESCRIPTION = "HydroModel.to_dict() as YAML (FRD; read back with HydroModel.from_dict)"
SUFFIX = ".yaml"
BINARY = False
AXES_ALLOWED = ("FRD",)
DEFAULT_AXES = "FRD"
DEFAULT_POINT = "CO"
POINTS_ALLOWED = None
#: Whether the model's calibrated ``effects`` fit this format (else a SimulatorTrapWarning).
HOLDS_EFFECTS = True
OPTIONS = ()


def render(view: ExportView) -> str:
    head = "".join(f"# {line}\n" for line in header_lines(view, NAME))
    return head + yaml.safe_dump(plain(view.model.to_dict()), sort_keys=False,
                                 default_flow_style=None, width=120)
