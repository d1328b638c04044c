import os
from pathlib import Path

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")   # small matrices: threads only add contention

import pytest

ROOT = Path(__file__).resolve().parent.parent
GEOMETRY = ROOT / "geometry"


def load_module(path, name=None, *, cache=False):
    """The Python file ``path`` as a module named ``name`` (default its stem): the model files
    the exporters write (benchmarks/ and scripts/ are packages: ``importlib.import_module``).
    ``cache``: load once per session, registered in sys.modules (a second call returns the same
    module)."""
    import importlib.util
    import sys

    name = name or Path(path).stem
    if cache and name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    if cache:
        sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture
def geometry_dir():
    return GEOMETRY


def spheroid_vehicle(length, diameter, *, rho=1000.0, strips=400, **extra):
    """A spheroid vehicle dict (semi-axes a = L/2, b = D/2)."""
    from stripcoef.geometry.vehicle import parse_vehicle

    a, b = 0.5 * length, 0.5 * diameter
    data = {"name": f"spheroid L/D={length / diameter:g}",
            "fluid": {"density": rho, "kinematic_viscosity": 1e-6},
            "strips": strips,
            "hull": {"profile": [
                {"type": "ellipsoid_tail", "x": [-a, 0.0], "radius": b},
                {"type": "ellipsoid_nose", "x": [0.0, a], "radius": b}]}}
    data.update(extra)
    return parse_vehicle(data, file="<spheroid>")


def cylinder_vehicle(length, diameter, *, rho=1000.0, **extra):
    from stripcoef.geometry.vehicle import parse_vehicle

    data = {"name": "cylinder", "fluid": {"density": rho, "kinematic_viscosity": 1e-6},
            "hull": {"profile": [{"type": "cylinder", "x": [-0.5 * length, 0.5 * length],
                                  "radius": 0.5 * diameter}]}}
    data.update(extra)
    return parse_vehicle(data, file="<cylinder>")
