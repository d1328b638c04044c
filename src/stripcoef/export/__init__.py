r"""Exports of a :class:`~stripcoef.model.HydroModel` to the formats simulators read.

One module per target format; :data:`FORMATS` is the registry, name -> :class:`ExportFormat`.
Each format module has a ``render(view, **options)`` function and its registry entry
``FORMAT = ExportFormat(...)``: its defaults and limits (``default_point``, ``default_axes``,
``axes_allowed``, ``points_allowed``, ``options``, ``holds_effects``).

Every conversion goes through one transform: the model is moved to the reference point
with :meth:`HydroModel.about` and its matrices are expressed in the target axes with
:func:`stripcoef.conventions.transform_matrix` (see :class:`ExportView`).

Formats (see docs/export/ for each):

- ``gazebo``: gz-sim Hydrodynamics plugin + SDF ``<fluid_added_mass>``
- ``uuv``: UUV Simulator / DAVE classic ``hydrodynamic_model`` type ``fossen``
- ``mss``: MATLAB/Octave function file in the style of Fossen's MSS models
- ``python``: importable module with numpy arrays
- ``json``, ``yaml``: ``HydroModel.to_dict()``; ``csv``: a plain table; ``npz``: numpy arrays
"""

from __future__ import annotations

from pathlib import Path

from stripcoef.errors import InputError, unknown_name
from stripcoef.files import write_bytes, write_text
from stripcoef.model import HydroModel
from stripcoef.export import csvtable, gazebo, jsondata, mss, npzarrays, pymodule, uuv, yamldata
from stripcoef.export._common import (POINT_NAMES, ExportFormat, ExportView, SimulatorTrapWarning,
                                      check_axes, resolve_point, trap)

#: The registry of export formats: name -> :class:`ExportFormat` (each module's ``FORMAT``).
FORMATS = {m.FORMAT.name: m.FORMAT for m in (gazebo, uuv, mss, pymodule, jsondata, yamldata,
                                              csvtable, npzarrays)}

__all__ = ["FORMATS", "ExportFormat", "ExportView", "SimulatorTrapWarning", "export_model",
           "get_format", "resolve_point", "write_export"]


def get_format(fmt: str) -> ExportFormat:
    """The :class:`ExportFormat` of ``fmt``; an unknown name is an error listing the valid ones."""
    try:
        return FORMATS[fmt]
    except (KeyError, TypeError):
        raise unknown_name("export format", fmt, FORMATS, key="to") from None


def _check_link_name(name) -> str:
    text = str(name)
    if not text or any(ch.isspace() or ch in '<>&"\'' for ch in text):
        raise InputError("not a link name", key="link", value=name,
                         expected="a non-empty name without spaces or < > & \" '")
    return text


def export_model(model: HydroModel, fmt: str, *, point=None, axes: str | None = None,
                 link_name: str | None = None, legacy_added_mass: bool = False,
                 function_name: str | None = None, fortress: bool = False,
                 buoyancy_volume: bool | None = None, lumped_added_mass: bool | None = None,
                 thrusters: bool | None = None, world: bool = False) -> str | bytes:
    """Export a model to a simulator or data format.

    Parameters
    ----------
    model : HydroModel
        Matrices about ``model.reference_point`` in FRD body axes
    fmt : str
        One of :data:`FORMATS`
    point : "CO", "CG", "CB", "origin", (x, y, z) or "x,y,z", optional
        Reference point of the exported matrices (FRD body coordinates of the model [m];
        see :func:`resolve_point` for the long names);
        default: the format's own (``CO`` = the model's reference point; ``CG`` for ``uuv``,
        which applies forces at the CoG)
    axes : "FRD" or "FLU", optional
        Axes of the exported matrices (for ``gazebo``/``uuv``: of the link frame);
        default: the format's own (FLU for gazebo and uuv, else FRD)
    link_name : str, optional
        Link name for ``gazebo`` and ``uuv`` (default ``base_link``)
    legacy_added_mass : bool
        ``gazebo`` only: write the plugin's ``<xDotU>`` tags instead of ``<fluid_added_mass>``
    function_name : str, optional
        ``mss`` only: the MATLAB function name (defaults to the model name)
    fortress : bool
        ``gazebo`` only: a file for Ignition Gazebo Fortress (SDF 1.9, sdformat 12, the
        ``ignition-gazebo-hydrodynamics-system`` plugin, legacy added-mass tags)
    buoyancy_volume : bool, optional
        ``gazebo`` only: write the non-colliding box of the displaced volume for gz-sim's
        Buoyancy system (default True; False when the link's own collisions carry the volume)
    lumped_added_mass : bool, optional
        ``gazebo`` only: carry part of M_A in the link's mass and inertia so that the explicit
        legacy form stays stable (default: with ``fortress``;
        :func:`stripcoef.export.gazebo.lumped_added_mass_split`)
    thrusters : bool, optional
        ``gazebo`` only: a propeller joint and a Thruster system per thruster (default True)
    world : bool
        ``gazebo`` only: a world file (physics, buoyancy, the model inside) instead of a model

    Returns
    -------
    str, or bytes for binary formats (``npz``)

    Warns
    -----
    SimulatorTrapWarning
        For known simulator traps and terms a format cannot hold.
    """
    spec = get_format(fmt)
    given = {"link_name": link_name, "legacy_added_mass": legacy_added_mass or None,
             "function_name": function_name, "fortress": fortress or None,
             "buoyancy_volume": buoyancy_volume, "lumped_added_mass": lumped_added_mass,
             "thrusters": thrusters, "world": world or None}
    options = {}
    for key, value in given.items():
        if value is None:
            continue
        if key not in spec.options:
            valid = [f for f, m in FORMATS.items() if key in m.options]
            raise InputError(f"option {key} does not apply to format {fmt}",
                             key=key, value=value, expected="a format among " + ", ".join(valid))
        options[key] = _check_link_name(value) if key == "link_name" else value
    axes = check_axes(spec.default_axes if axes is None else axes, spec.axes_allowed,
                      fmt_name=fmt)
    point = spec.default_point if point is None else point
    if spec.points_allowed is not None:
        _, label = resolve_point(model, point)
        if label not in spec.points_allowed:
            raise InputError(f"format {fmt} must be expressed about "
                             + " or ".join(spec.points_allowed), key="point", value=point,
                             expected=" or ".join(spec.points_allowed)
                             + (" (the UUV plugin applies forces at the link's CoG)"
                                if fmt == "uuv" else ""))
    view = ExportView.of(model, point, axes)
    if model.effects and not spec.holds_effects:
        names = ", ".join(str(e.get("effect", e.get("name", "?"))) if isinstance(e, dict)
                          else str(e) for e in model.effects)
        trap(f"{fmt}: the model's calibrated effects ({names}) cannot be written in this "
             "format and are left out; json, yaml and npz keep them")
    return spec.render(view, **options)


def write_export(model: HydroModel, fmt: str, path, **kwargs) -> Path:
    """Export a model and write it to ``path`` atomically (an existing file is replaced
    only by a complete new one).  For ``mss`` the function name is the file's stem.

    Keyword arguments are those of :func:`export_model`.  Returns the path written.
    """
    spec = get_format(fmt)
    path = Path(path)
    if path.is_dir():
        raise InputError("output is a folder", key="output", value=str(path),
                         expected="a file path")
    if "function_name" in spec.options and kwargs.get("function_name") is None:
        kwargs["function_name"] = mss.check_function_name(path.stem)
    data = export_model(model, fmt, **kwargs)
    try:
        if isinstance(data, bytes):
            write_bytes(path, data)
        else:
            write_text(path, data)
    except OSError as exc:
        raise InputError(f"cannot write ({exc.strerror})", key="output", value=str(path),
                         expected="a writable file path") from None
    return path


# re-exported for callers that need to name a point
POINTS = POINT_NAMES
