"""Read a VEHICLE argument: a vehicle file (geometry, estimated by strip theory) or a
model file (a :meth:`HydroModel.to_dict` dump in JSON or YAML, e.g. a calibrated model
written by ``stripcoef diagnose --out``).

One loader for every command that takes a vehicle (simulate, diagnose; limits and export
can use it too), so that a calibrated model file is accepted wherever a vehicle is.
"""

from __future__ import annotations

import json
from pathlib import Path

import yaml

from .errors import InputError
from .io import write_text
from .model import HydroModel

#: Keys that mark a model file (HydroModel.to_dict) rather than a vehicle file.
MODEL_KEYS = ("rigid_body_mass", "added_mass", "linear_damping", "quadratic_damping")


def is_model_dict(data) -> bool:
    return isinstance(data, dict) and all(k in data for k in MODEL_KEYS)


def load_model(path) -> HydroModel:
    """A HydroModel from a model file (JSON/YAML) or a vehicle file (YAML, strip theory).

    Raises
    ------
    InputError
        Missing or unreadable file, not a mapping, a model file with a bad matrix.
    """
    path = Path(path)
    name = str(path)
    try:
        text = path.read_text()
    except FileNotFoundError:
        raise InputError("file not found", file=name,
                         expected="a vehicle file (YAML) or a model file (JSON/YAML)") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read ({exc.__class__.__name__})", file=name,
                         expected="a readable vehicle or model file") from None
    try:
        data = json.loads(text) if path.suffix.lower() == ".json" else yaml.safe_load(text)
    except (ValueError, yaml.YAMLError) as exc:
        first = str(exc).splitlines()[0] if str(exc) else exc.__class__.__name__
        raise InputError(f"not valid {'JSON' if path.suffix.lower() == '.json' else 'YAML'} "
                         f"({first})", file=name, expected="a vehicle or model file") from None
    if not isinstance(data, dict):
        raise InputError("not a mapping", file=name, value=type(data).__name__,
                         expected="a vehicle file or a model file (HydroModel.to_dict)")
    if is_model_dict(data):
        return model_from_dict(data, file=name)
    try:
        from .assemble import estimate
        from .geometry.vehicle import load_vehicle
    except ImportError:  # the strip-theory core is not installed in this build
        raise InputError("this is a vehicle file but strip-theory estimation is unavailable",
                         file=name, expected="a model file with " + ", ".join(MODEL_KEYS)) \
            from None
    return estimate(load_vehicle(path))


def model_from_dict(data: dict, *, file: str | None = None) -> HydroModel:
    """HydroModel.from_dict with one-line errors naming the key."""
    import numpy as np

    for key in MODEL_KEYS + ("rigid_body_mass",):
        try:
            m = np.asarray(data[key], dtype=float)
        except (KeyError, TypeError, ValueError):
            raise InputError("missing or non-numeric matrix", file=file, key=key,
                             expected="a 6 x 6 list of numbers") from None
        if m.shape != (6, 6) or not np.all(np.isfinite(m)):
            raise InputError("bad matrix", file=file, key=key, value=list(m.shape),
                             expected="6 x 6 finite numbers")
    for key in ("reference_point", "center_of_gravity", "center_of_buoyancy"):
        try:
            p = np.asarray(data[key], dtype=float)
        except (KeyError, TypeError, ValueError):
            raise InputError("missing or non-numeric point", file=file, key=key,
                             expected="[x, y, z] in metres") from None
        if p.shape != (3,):
            raise InputError("not a point", file=file, key=key, value=data[key],
                             expected="[x, y, z] in metres")
    for key in ("mass", "volume", "density"):
        if not isinstance(data.get(key), (int, float)) or not data[key] > 0:
            raise InputError("missing or non-positive", file=file, key=key,
                             value=data.get(key), expected="a positive number (SI units)")
    try:
        return HydroModel.from_dict(data)
    except (KeyError, TypeError, ValueError) as exc:
        raise InputError(f"bad model file ({exc.__class__.__name__}: {exc})", file=file,
                         expected="a HydroModel.to_dict() mapping") from None


def save_model(model: HydroModel, path) -> None:
    """Write ``model.to_dict()`` atomically as YAML (``.yaml``/``.yml``) or JSON."""
    path = Path(path)
    data = model.to_dict()
    if path.suffix.lower() == ".json":
        text = json.dumps(data, indent=1)
    else:
        text = yaml.safe_dump(_plain(data), sort_keys=False)
    write_text(path, text, key="model")


def _plain(obj):
    """Plain Python types for YAML (numpy scalars/arrays, tuples, infinities kept)."""
    import numpy as np

    if isinstance(obj, dict):
        return {str(k): _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_plain(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _plain(obj.tolist())
    if isinstance(obj, np.generic):
        return obj.item()
    return obj
