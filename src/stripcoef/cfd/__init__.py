"""Damping by OpenFOAM: steady RANS around a closed body, run by run (docs/cfd.md).

OpenFOAM is a system dependency (Debian's package ``openfoam``), run as a subprocess; the
case files are written by :mod:`stripcoef.cfd.foamdict` (the OpenFOAM Python helpers are GPL,
stripcoef is MIT). :func:`drag_by_cfd` is the entry point; :class:`CfdResult` its result.
"""

from stripcoef.cfd.drag import drag_by_cfd
from stripcoef.cfd.result import CfdResult, DofResult, RunResult, fit_damping

__all__ = ["drag_by_cfd", "CfdResult", "DofResult", "RunResult", "fit_damping"]
