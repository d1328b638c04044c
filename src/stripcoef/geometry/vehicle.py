"""The vehicle file (YAML): schema, validation and the :class:`Vehicle` it describes.

Every key is documented in docs/vehicle-file.md.  Validation is strict: unknown
keys, missing required keys, wrong types, non-finite or non-positive sizes,
gapped or overlapping profile segments, holes outside the hull and appendages
that intersect nothing are refused with an :class:`~stripcoef.errors.InputError`
naming the file, the key path, the value and what was expected.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from stripcoef.errors import InputError
from stripcoef.fluid import EQUATIONS, NU_SEAWATER, Fluid, RHO_FRESHWATER, RHO_SEAWATER
from stripcoef.files import load_yaml, read_text
from stripcoef.strips import MAX_STRIPS, Strips, uniform_stations
from stripcoef.thrusters import Thruster
from stripcoef.geometry.keypaths import nominal
from stripcoef.geometry.bodies import Box, Cylinder, Fin, Hole, Hull
from stripcoef.geometry import mesh as mesh_mod
from stripcoef.geometry.profiles import SEGMENT_TYPES, Segment, check_contiguous, myring_tail
from stripcoef.geometry.shapes import built_from_half_sizes

#: Default number of strips (converged to 0.1 % on the shipped vehicles; docs/vehicle-file.md).
DEFAULT_STRIPS = 1000
#: Default reference speed for Reynolds numbers and the damping split [m/s].
DEFAULT_SPEED = 1.0
REFERENCE_NAMES = ("center_of_buoyancy", "center_of_gravity", "origin")
#: The largest length a vehicle file may give [m]: ten times the largest submarine built
#: (about 175 m); a larger value is a unit or typing error, and the geometry libraries lose
#: their precision long before 1e300 (a one-line error instead of a traceback or a NaN).
MAX_DIMENSION = 2000.0


def _check_dimension(r, key, values, expected="lengths in metres"):
    """Refuse ``values`` [m] (any nesting) whose magnitude exceeds :data:`MAX_DIMENSION`."""
    arr = np.abs(np.asarray(values, dtype=float))
    if arr.size and float(arr.max()) > MAX_DIMENSION:
        raise r.err(key, "too large", float(arr.max()),
                    f"{expected} up to {MAX_DIMENSION:g} m (a unit error?)")


#: File suffixes read as CAD meshes (:mod:`stripcoef.geometry.mesh`); the rest must be YAML.
MESH_SUFFIXES = (".stl", ".obj", ".ply", ".glb", ".gltf", ".off", ".dae")


@dataclass
class DensityZone:
    """A zone of uniform density between two x stations, over some bodies (MARES Table I)."""

    name: str
    x_aft: float
    x_fwd: float
    density: float
    bodies: tuple[str, ...] | None  # None = every body


@dataclass
class MassSpec:
    """Mass properties: given directly, or from density zones, or neutrally buoyant uniform."""

    mass: float | None = None
    center_of_gravity: np.ndarray | None = None
    inertia: np.ndarray | None = None  # 3x3 about the CG
    zones: list[DensityZone] = field(default_factory=list)
    default_density: float | None = None  # density where no zone applies (None: fluid's)


@dataclass
class SurfacePanel:
    """One lifting panel of a control surface: a fin's exposed part (root at the hull).

    ``center`` [m] is mid span and mid chord in body axes, ``span`` root to tip [m],
    ``chord`` [m]; the panel's plane is normal to ``normal`` (y for a rudder, z for an
    elevator).  ``root`` [m] is the hull's half-width at the root's mid chord (the distance of the
    root from the hull axis); ``root_radii`` [m] samples it along the root chord, empty if the
    chord reaches past the hull's ends (the lift model uses them to decide whether the fin
    sits on a cylinder: :func:`stripcoef.hull.lift.cylindrical_root`).
    """

    center: np.ndarray
    span: float
    chord: float
    normal: str
    root: float = 0.0
    root_radii: tuple = ()

    @property
    def area(self) -> float:
        return self.span * self.chord


@dataclass
class ControlSurfaceSpec:
    """A rudder or elevator of the vehicle file: panels deflected together and its limits.

    ``max_deflection`` and ``stall_angle`` in [rad]; ``fins`` names the fin appendages it
    is made of (their lift is then counted once, here).
    """

    name: str
    kind: str
    panels: list
    max_deflection: float
    stall_angle: float
    fins: tuple = ()


@dataclass
class Vehicle:
    """Everything a vehicle file says (validated)."""

    name: str
    source: str
    fluid: Fluid
    hull: Hull | None
    bodies: list  # hull first, then appendages (and mesh bodies)
    holes: list[Hole]
    mass: MassSpec
    thrusters: list[Thruster]
    reference: str | np.ndarray = "center_of_buoyancy"
    reference_speed: float = DEFAULT_SPEED
    n_strips: int = DEFAULT_STRIPS
    corrections: bool = True
    description: str = ""
    control_surfaces: list = field(default_factory=list)
    body_lift: str = "auto"

    @classmethod
    def from_mesh(cls, mesh, *, axis: str = "x", length_unit: str = "m", origin="centroid",
                  fluid: Fluid | None = None, name: str | None = None,
                  z_up: bool = False) -> "Vehicle":
        """A vehicle made of one closed CAD mesh, with default sea water and neutral buoyancy.

        Parameters
        ----------
        mesh : str, Path, MeshBody or trimesh.Trimesh
            A mesh file (STL, OBJ, PLY, GLB, GLTF, OFF), a loaded body or an in-memory mesh.
        axis : {"x", "y", "z"}
            The mesh axis along the body's length (mapped onto body x).
        length_unit : {"m", "mm", "cm", "in", "ft"}
            Unit of the mesh coordinates.
        origin : "centroid" or (x, y, z)
            "centroid": body axes at the volume centroid, matrices about the centre of
            buoyancy; a point: the file's origin is kept and the matrices are about that
            point [m, body axes].
        fluid : Fluid, optional
            Default: sea water (:data:`stripcoef.fluid.RHO_SEAWATER`, ``NU_SEAWATER``).
        name : str, optional
            Default: the file's stem, or "mesh".
        z_up : bool
            The file is z-up (ROS REP 103, most CAD): turned 180 deg about x into FRD.
        """
        if isinstance(origin, str):
            if origin != "centroid":
                raise InputError("unknown mesh origin", key="origin", value=origin,
                                 expected="'centroid' or a point (x, y, z) [m]")
            reference, body_origin = "center_of_buoyancy", "centroid"
        else:
            reference = np.asarray(origin, dtype=float).reshape(-1)
            if reference.shape != (3,) or not np.isfinite(reference).all():
                raise InputError("not a point", key="origin", value=list(reference),
                                 expected="three finite coordinates [m]")
            body_origin = "file"
        kw = dict(axis=axis, length_unit=length_unit, origin=body_origin, z_up=bool(z_up))
        if isinstance(mesh, mesh_mod.MeshBody):
            body, source = mesh, mesh.source
        elif isinstance(mesh, (str, Path)):
            body, source = mesh_mod.load_mesh(mesh, **kw), str(mesh)
        elif hasattr(mesh, "vertices") and hasattr(mesh, "faces"):
            body, source = mesh_mod.mesh_body(mesh, name=name or "mesh", **kw), "<trimesh>"
        else:
            raise InputError("not a mesh", key="mesh", value=type(mesh).__name__,
                             expected="a mesh file path, a MeshBody or a trimesh.Trimesh")
        return cls(name=name or (Path(source).stem if source != "<trimesh>" else "mesh"),
                   source=source,
                   fluid=fluid or Fluid(RHO_SEAWATER, NU_SEAWATER, "default sea water"),
                   hull=None, bodies=[body], holes=[], mass=MassSpec(), thrusters=[],
                   reference=reference)

    def x_extent(self) -> tuple[float, float]:
        lo = min(b.x_extent()[0] for b in self.bodies)
        hi = max(b.x_extent()[1] for b in self.bodies)
        return lo, hi

    @property
    def length(self) -> float:
        lo, hi = self.x_extent()
        return hi - lo

    def cut(self, n: int | None = None) -> Strips:
        """Cut the vehicle into ``n`` equal strips along x (default ``n_strips``)."""
        n = int(n or self.n_strips)
        if n < 4:
            raise InputError("too few strips", key="strips", value=n, expected="at least 4")
        lo, hi = self.x_extent()
        x, dx = uniform_stations(lo, hi, n)
        parts = []
        for body in self.bodies:
            own = body.parts(x, dx)
            if not any(np.size(p.index) for p in own):
                # a body shorter than a strip is invisible to strip theory (and a hull that
                # covers no strip leaves the hull terms without a section)
                blo, bhi = body.x_extent()
                raise InputError(f"body '{body.name}' covers no strip", file=self.source,
                                 key="strips", value=f"{n} strips over {hi - lo:.4g} m",
                                 expected=f"strips shorter than the body's {bhi - blo:.4g} m "
                                          "(more strips, or sizes in metres)")
            parts.extend(own)
        holes = [h.cut(x, dx, self.hull) for h in self.holes] if self.hull is not None else []
        for body in self.bodies:
            if hasattr(body, "holes"):
                holes.extend(body.holes(x, dx))
        return Strips(x=x, dx=dx, parts=parts, holes=holes)


# ---------------------------------------------------------------------------
# Reading and validation
# ---------------------------------------------------------------------------

class _Reader:
    """Typed access to a YAML mapping with error messages naming file and key path."""

    def __init__(self, file: str):
        self.file = file

    def err(self, key, what="", value=InputError._MISSING, expected=None):
        return InputError(what, file=self.file, key=key, value=value, expected=expected)

    def mapping(self, data, key, allowed, required=()):
        if not isinstance(data, dict):
            raise self.err(key, "not a mapping", data, "a mapping of keys to values")
        for k in data:
            if k not in allowed:
                raise self.err(f"{key}.{k}" if key else str(k), "unknown key",
                               expected="one of " + ", ".join(allowed))
        for k in required:
            if k not in data:
                raise self.err(f"{key}.{k}" if key else k, "missing required key",
                               expected="the keys " + ", ".join(required)
                               + " (docs/vehicle-file.md)")
        return data

    def number(self, data, key, path, *, default=None, positive=False, nonneg=False,
               required=False):
        full = f"{path}.{key}" if path else key
        if key not in data:
            if required:
                raise self.err(full, "missing required key", expected="a number")
            return default
        v = data[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise self.err(full, "wrong type", v, "a number")
        v = float(v)
        if not math.isfinite(v):
            raise self.err(full, "not finite", v, "a finite number")
        if positive and v <= 0:
            raise self.err(full, "must be positive", v, "a number > 0")
        if nonneg and v < 0:
            raise self.err(full, "must not be negative", v, "a number >= 0")
        return v

    def vector(self, data, key, path, n=3, *, default=None, required=False):
        full = f"{path}.{key}" if path else key
        if key not in data:
            if required:
                raise self.err(full, "missing required key", expected=f"a list of {n} numbers")
            return None if default is None else np.asarray(default, float)
        v = data[key]
        if (not isinstance(v, (list, tuple)) or len(v) != n
                or any(isinstance(a, bool) or not isinstance(a, (int, float)) for a in v)):
            raise self.err(full, "wrong type", v, f"a list of {n} numbers")
        arr = np.asarray(v, dtype=float)
        if not np.all(np.isfinite(arr)):
            raise self.err(full, "not finite", v, f"a list of {n} finite numbers")
        return arr

    def matrix(self, data, key, path, shape, expected):
        """A nested list of finite numbers of ``shape`` (no ragged rows, no strings)."""
        full = f"{path}.{key}" if path else key
        v = data[key]

        def numbers(x, dims):
            if not dims:
                return (not isinstance(x, bool) and isinstance(x, (int, float))
                        and math.isfinite(x))
            return (isinstance(x, list) and len(x) == dims[0]
                    and all(numbers(y, dims[1:]) for y in x))
        if not numbers(v, shape):
            raise self.err(full, "wrong type", v, expected)
        return np.asarray(v, dtype=float)

    def string(self, data, key, path, *, choices=None, default=None, required=False):
        full = f"{path}.{key}" if path else key
        if key not in data:
            if required:
                raise self.err(full, "missing required key", expected="a string")
            return default
        v = data[key]
        if not isinstance(v, str):
            raise self.err(full, "wrong type", v, "a string")
        if choices is not None and v not in choices:
            raise self.err(full, "invalid value", v, "one of " + ", ".join(choices))
        return v

    def listing(self, data, key, path, *, required=False):
        full = f"{path}.{key}" if path else key
        if key not in data:
            if required:
                raise self.err(full, "missing required key", expected="a list")
            return []
        v = data[key]
        if not isinstance(v, list):
            raise self.err(full, "wrong type", v, "a list")
        return v


#: The typed reader, also used for model files (:mod:`stripcoef.modelfile`).
Reader = _Reader


def _segment(r: _Reader, seg, path) -> Segment:
    r.mapping(seg, path, ("type", "x", "radius", "n", "theta_deg", "points", "length"),
              ("type", "x"))
    kind = r.string(seg, "type", path, choices=SEGMENT_TYPES, required=True)
    x = seg["x"]
    if (not isinstance(x, list) or len(x) != 2
            or any(isinstance(a, bool) or not isinstance(a, (int, float)) for a in x)):
        raise r.err(f"{path}.x", "wrong type", x, "[x_aft, x_fwd] in metres")
    xa, xf = float(x[0]), float(x[1])
    if not (math.isfinite(xa) and math.isfinite(xf)):
        raise r.err(f"{path}.x", "not finite", x, "finite numbers")
    if xf <= xa:
        raise r.err(f"{path}.x", "segment has no length", x, "x_aft < x_fwd")
    _check_dimension(r, f"{path}.x", [xa, xf])
    params = {}
    if kind == "table":
        pts = seg.get("points")
        try:
            arr = np.asarray(pts, dtype=float)
        except (TypeError, ValueError):
            arr = None
        if arr is None or arr.ndim != 2 or arr.shape[1] != 2 or arr.shape[0] < 2:
            raise r.err(f"{path}.points", "wrong type", pts, "a list of [x, r] pairs (>= 2)")
        if not np.all(np.isfinite(arr)):
            raise r.err(f"{path}.points", "not finite", pts, "finite numbers")
        if np.any(np.diff(arr[:, 0]) <= 0):
            raise r.err(f"{path}.points", "x not increasing", pts.__repr__()[:60],
                        "strictly increasing x")
        if np.any(arr[:, 1] < 0):
            raise r.err(f"{path}.points", "negative radius", pts, "radii >= 0")
        if arr[0, 0] > xa + 1e-9 or arr[-1, 0] < xf - 1e-9:
            raise r.err(f"{path}.points", "table does not cover the segment",
                        [float(arr[0, 0]), float(arr[-1, 0])], f"points from {xa} to {xf}")
        _check_dimension(r, f"{path}.points", arr)
        params["points"] = arr
    elif kind == "cone":
        rad = seg.get("radius")
        if (not isinstance(rad, list) or len(rad) != 2
                or any(isinstance(a, bool) or not isinstance(a, (int, float)) for a in rad)):
            raise r.err(f"{path}.radius", "wrong type", rad, "[r_aft, r_fwd] in metres")
        if any((not math.isfinite(a)) or a < 0 for a in rad) or max(rad) <= 0:
            raise r.err(f"{path}.radius", "invalid radii", rad, "radii >= 0, not both zero")
        _check_dimension(r, f"{path}.radius", rad)
        params["radius"] = (float(rad[0]), float(rad[1]))
    else:
        params["radius"] = r.number(seg, "radius", path, positive=True, required=True)
        _check_dimension(r, f"{path}.radius", params["radius"])
        if kind == "myring_nose":
            params["n"] = r.number(seg, "n", path, default=2.0, positive=True)
        if kind == "myring_tail":
            th = r.number(seg, "theta_deg", path, default=25.0, nonneg=True)
            if th >= 90.0:
                raise r.err(f"{path}.theta_deg", "not a tail half-angle", th,
                            "an angle from 0 to < 90 degrees")
            if "length" not in seg:
                # the cubic must stay between the axis and the radius over the tail's length
                rs = myring_tail(np.linspace(xa, xf, 201), xa, xf, params["radius"],
                                 math.radians(th))
                if np.min(rs) < -1e-12 * params["radius"] or \
                        np.max(rs) > params["radius"] * (1 + 1e-9):
                    raise r.err(f"{path}.theta_deg", "the tail leaves [0, radius] with this angle",
                                th, f"a smaller angle for a tail {xf - xa:g} m long of radius "
                                    f"{params['radius']:g} m")
            params["theta_deg"] = th
        if kind in ("myring_nose", "myring_tail"):
            full = r.number(seg, "length", path, positive=True, default=None)
            if full is not None:
                if full < xf - xa - 1e-12:
                    raise r.err(f"{path}.length", "shorter than the segment", full,
                                f"the full Myring length >= x_fwd - x_aft = {xf - xa:g} m "
                                "(a longer one truncates the tip)")
                params["length"] = full
    if "length" in seg and kind not in ("myring_nose", "myring_tail"):
        raise r.err(f"{path}.length", "unexpected key for this segment type",
                    expected="length only on myring_nose and myring_tail segments")
    return Segment(kind, xa, xf, params)


def _profile(r: _Reader, segs, path):
    if not isinstance(segs, list) or not segs:
        raise r.err(path, "wrong type", segs, "a non-empty list of segments")
    segments = [_segment(r, s, f"{path}[{i}]") for i, s in enumerate(segs)]
    return check_contiguous(segments, file=r.file, key=path)


def _hull(r: _Reader, data) -> Hull:
    path = "hull"
    r.mapping(data, path, ("name", "section", "profile", "half_breadth", "half_height", "y", "z"))
    section = r.string(data, "section", path, choices=built_from_half_sizes(),
                       default="ellipse")
    if "profile" in data:
        if "half_breadth" in data or "half_height" in data:
            raise r.err(path, "both profile and half_breadth/half_height given",
                        expected="either profile (circular) or half_breadth + half_height")
        prof = _profile(r, data["profile"], f"{path}.profile")
        hb = hh = prof
    else:
        if "half_breadth" not in data or "half_height" not in data:
            raise r.err(f"{path}.profile", "missing required key",
                        expected="profile, or both half_breadth and half_height")
        hb = _profile(r, data["half_breadth"], f"{path}.half_breadth")
        hh = _profile(r, data["half_height"], f"{path}.half_height")
        if abs(hb.x_aft - hh.x_aft) > 1e-9 or abs(hb.x_fwd - hh.x_fwd) > 1e-9:
            raise r.err(f"{path}.half_height", "profiles cover different x ranges",
                        [hh.x_aft, hh.x_fwd], f"the half_breadth range [{hb.x_aft}, {hb.x_fwd}]")
    return Hull(name=r.string(data, "name", path, default="hull"), half_breadth=hb,
                half_height=hh, section=section, y=r.number(data, "y", path, default=0.0),
                z=r.number(data, "z", path, default=0.0))


def _appendage(r: _Reader, data, path):
    r.mapping(data, path, ("name", "type", "axis", "center", "diameter", "length",
                           "inner_diameter", "size", "span_axis", "span", "chord", "thickness",
                           "mesh", "length_unit", "transform"), ("type",))
    kind = r.string(data, "type", path, choices=("cylinder", "box", "fin", "mesh"), required=True)
    name = r.string(data, "name", path, default=path)
    if kind == "cylinder":
        d = r.number(data, "diameter", path, positive=True, required=True)
        di = r.number(data, "inner_diameter", path, default=0.0, nonneg=True)
        if di >= d:
            raise r.err(f"{path}.inner_diameter", "not smaller than the diameter", di,
                        f"a value < diameter = {d}")
        return Cylinder(name=name, axis=r.string(data, "axis", path, choices=("x", "y", "z"),
                                                 default="x"),
                        center=r.vector(data, "center", path, required=True), diameter=d,
                        length=r.number(data, "length", path, positive=True, required=True),
                        inner_diameter=di)
    if kind == "box":
        size = r.vector(data, "size", path, required=True)
        if np.any(size <= 0):
            raise r.err(f"{path}.size", "must be positive", size.tolist(),
                        "[lx, ly, lz] all > 0")
        center = r.vector(data, "center", path, required=True)
        _check_dimension(r, f"{path}.size", size)
        _check_dimension(r, f"{path}.center", center)
        return Box(name=name, center=center, size=size)
    if kind == "fin":
        return Fin(name=name, center=r.vector(data, "center", path, required=True),
                   span_axis=r.string(data, "span_axis", path, choices=("y", "z"), required=True),
                   span=r.number(data, "span", path, positive=True, required=True),
                   chord=r.number(data, "chord", path, positive=True, required=True),
                   thickness=r.number(data, "thickness", path, positive=True, default=0.01))
    # a mesh appendage (or hull)
    mfile = r.string(data, "mesh", path, required=True)
    mpath = Path(r.file).parent / mfile
    if "transform" in data:
        r.matrix(data, "transform", path, (4, 4), "a 4x4 homogeneous transform (rows of 4 "
                                                  "finite numbers)")
    return mesh_mod.load_mesh(mpath, length_unit=r.string(data, "length_unit", path,
                                                          choices=("m", "mm", "in"), default="m"),
                              origin="file", transform=data.get("transform"), name=name,
                              role="appendage")


def _hole(r: _Reader, data, path) -> Hole:
    r.mapping(data, path, ("name", "axis", "x", "y", "z", "diameter"), ("axis", "x", "diameter"))
    axis = r.string(data, "axis", path, choices=("y", "z"), required=True)
    offset_key = "y" if axis == "z" else "z"
    if ("z" if axis == "z" else "y") in data:
        raise r.err(f"{path}.{'z' if axis == 'z' else 'y'}", "unexpected key for this axis",
                    expected=f"only x and {offset_key} to place a hole along {axis}")
    return Hole(name=r.string(data, "name", path, default=path), axis=axis,
                x=r.number(data, "x", path, required=True),
                offset=r.number(data, offset_key, path, default=0.0),
                diameter=r.number(data, "diameter", path, positive=True, required=True))


def _fluid(r: _Reader, data) -> Fluid:
    if data is None:
        return Fluid()
    path = "fluid"
    r.mapping(data, path, ("water", "density", "kinematic_viscosity", "temperature", "salinity",
                           "equation"))
    water = r.string(data, "water", path, choices=("sea", "fresh"), default="sea")
    if "equation" in data and "temperature" not in data and "salinity" not in data:
        raise r.err(f"{path}.equation", "an equation of state needs temperature and salinity",
                    data["equation"], expected="temperature and salinity beside it")
    if "temperature" in data or "salinity" in data:
        if "density" in data or "kinematic_viscosity" in data:
            raise r.err(path, "both temperature/salinity and density/viscosity given",
                        expected="either temperature + salinity, or density + kinematic_viscosity")
        t = r.number(data, "temperature", path, required=True)
        s = r.number(data, "salinity", path, required=True, nonneg=True)
        equation = r.string(data, "equation", path, choices=EQUATIONS, default="eos80")
        try:
            return Fluid.from_temperature_salinity(t, s, equation=equation)
        except InputError as exc:            # the correlation's error, in the file's terms
            raise r.err(f"{path}.{exc.key}", exc.what, exc.value, exc.expected) from None
    rho = r.number(data, "density", path, positive=True,
                   default=RHO_SEAWATER if water == "sea" else RHO_FRESHWATER)
    nu = r.number(data, "kinematic_viscosity", path, positive=True,
                  default=1.19e-6 if water == "sea" else 1.14e-6)
    return Fluid(density=rho, kinematic_viscosity=nu,
                 source=f"vehicle file ({water} water defaults where not given)")


def _mass(r: _Reader, data) -> MassSpec:
    if data is None:
        return MassSpec()
    path = "mass"
    r.mapping(data, path, ("mass", "center_of_gravity", "inertia", "zones", "default_density"))
    spec = MassSpec(mass=r.number(data, "mass", path, positive=True),
                    center_of_gravity=r.vector(data, "center_of_gravity", path),
                    default_density=r.number(data, "default_density", path, positive=True))
    if spec.mass is not None and spec.default_density is not None:
        raise r.err(f"{path}.default_density", "both mass and default_density given",
                    spec.default_density, "either mass (the body's mass is given) or "
                    "default_density (the mass follows from the volume)")
    if "inertia" in data:
        v = data["inertia"]
        arr = None
        try:
            arr = np.asarray(v, dtype=float)
        except (TypeError, ValueError):
            pass
        if arr is None or arr.shape not in ((3,), (3, 3)) or not np.all(np.isfinite(arr)):
            raise r.err(f"{path}.inertia", "wrong type", v,
                        "[Ixx, Iyy, Izz] or a 3x3 matrix about the CG, kg m^2")
        arr = np.diag(arr) if arr.shape == (3,) else arr
        if not np.allclose(arr, arr.T) or np.any(np.linalg.eigvalsh(0.5 * (arr + arr.T)) <= 0):
            raise r.err(f"{path}.inertia", "not symmetric positive definite", v,
                        "a symmetric positive-definite inertia tensor")
        # principal moments of a real body: I1 + I2 >= I3 for every ordering (the triangle
        # inequality of I_i = int (r^2 - x_i^2) dm; Landau & Lifshitz, Mechanics, sec. 32)
        p1, p2, p3 = np.linalg.eigvalsh(0.5 * (arr + arr.T))
        if p1 + p2 < p3 * (1.0 - 1e-9):
            raise r.err(f"{path}.inertia", "principal moments violate the triangle inequality",
                        v, f"I1 + I2 >= I3 (principal moments {p1:.4g}, {p2:.4g}, {p3:.4g} "
                           "kg m^2)")
        spec.inertia = arr
    for i, z in enumerate(r.listing(data, "zones", path)):
        zp = f"{path}.zones[{i}]"
        r.mapping(z, zp, ("name", "x", "density", "bodies"), ("x", "density"))
        x = z["x"]
        if (not isinstance(x, list) or len(x) != 2
                or any(isinstance(a, bool) or not isinstance(a, (int, float)) for a in x)
                or not all(math.isfinite(a) for a in x) or x[1] <= x[0]):
            raise r.err(f"{zp}.x", "wrong value", x,
                        "[x_aft, x_fwd], finite, with x_aft < x_fwd [m]")
        bodies = z.get("bodies")
        if bodies is not None and (not isinstance(bodies, list)
                                   or not all(isinstance(b, str) for b in bodies)):
            raise r.err(f"{zp}.bodies", "wrong type", bodies, "a list of body names")
        spec.zones.append(DensityZone(name=r.string(z, "name", zp, default=zp), x_aft=float(x[0]),
                                      x_fwd=float(x[1]),
                                      density=r.number(z, "density", zp, nonneg=True,
                                                       required=True),
                                      bodies=tuple(bodies) if bodies else None))
    if spec.zones and spec.mass is not None:
        raise r.err(f"{path}.zones", "both mass and zones given",
                    expected="either mass (+ center_of_gravity, inertia) or density zones")
    if spec.inertia is not None and spec.mass is None:
        raise r.err(f"{path}.mass", "missing required key", expected="mass when inertia is given")
    return spec


def _thruster(r: _Reader, data, path) -> Thruster:
    r.mapping(data, path, ("name", "position", "direction", "ct_forward", "ct_backward", "ct",
                           "max_forward", "max_backward", "max_thrust", "eta_forward",
                           "eta_backward", "deadband", "torque_ratio", "kq"),
              ("name", "position", "direction"))
    name = r.string(data, "name", path, required=True)
    d = r.vector(data, "direction", path, required=True)
    if np.linalg.norm(d) < 1e-12:
        raise r.err(f"{path}.direction", "zero vector", d.tolist(), "a non-zero direction")
    ct = r.number(data, "ct", path, positive=True, default=None)
    mx = r.number(data, "max_thrust", path, nonneg=True, default=None)
    inf = float("inf")
    t = Thruster(
        name=name, position=r.vector(data, "position", path, required=True),
        direction=d / np.linalg.norm(d),
        ct_forward=r.number(data, "ct_forward", path, positive=True, default=ct or 1.0),
        ct_backward=r.number(data, "ct_backward", path, positive=True, default=ct or 1.0),
        max_forward=r.number(data, "max_forward", path, nonneg=True,
                             default=mx if mx is not None else inf),
        max_backward=r.number(data, "max_backward", path, nonneg=True,
                              default=mx if mx is not None else inf),
        eta_forward=r.number(data, "eta_forward", path, positive=True, default=1.0),
        eta_backward=r.number(data, "eta_backward", path, positive=True, default=1.0),
        deadband=r.number(data, "deadband", path, nonneg=True, default=0.0),
        torque_ratio=_torque_ratio(r, data, path, ct),
    )
    return t


def _torque_ratio(r: _Reader, data, path, ct) -> float:
    """k_Q = Q/T [m] from ``torque_ratio`` or from ``kq`` [N m per command^2] and the
    forward thrust coefficient (Q = kq n|n|, T = ct n|n|: k_Q = kq/ct; Prestero 2001,
    sec. 3.8)."""
    if "torque_ratio" in data and "kq" in data:
        raise r.err(f"{path}.kq", "both torque_ratio and kq given",
                    expected="one of torque_ratio [m] or kq [N m per command^2]")
    if "kq" in data:
        kq = r.number(data, "kq", path)
        ctf = r.number(data, "ct_forward", path, positive=True, default=ct)
        if ctf is None:
            raise r.err(f"{path}.kq", "kq without a thrust coefficient",
                        expected="ct or ct_forward beside kq (k_Q = kq / ct)")
        return kq / ctf
    return r.number(data, "torque_ratio", path, default=0.0)


TOP_KEYS = ("name", "description", "fluid", "reference_point", "reference_speed", "strips",
            "corrections", "hull", "holes", "appendages", "mass", "thrusters", "control_surfaces",
            "body_lift")
#: Span axis of the panels of each control surface type (rudder: vertical, elevator: horizontal).
SURFACE_TYPES = {"rudder": "z", "elevator": "y"}


def exposed_panels(hull: Hull, center, span: float, chord: float, span_axis: str, *,
                   path: str, r: "_Reader | None" = None) -> list:
    """The parts of a fin outside the hull, one panel per side (root at the hull surface).

    The hull half-width at the fin's x along its span axis is the root; a fin that does
    not reach the hull surface is refused (InputError naming ``path``; ``r`` adds the file).
    """
    r = r or _Reader(None)
    k = "xyz".index(span_axis)
    off = float(center[k]) - (hull.y if span_axis == "y" else hull.z)
    x = float(center[0])
    lo, hi = hull.x_extent()
    width = float(hull.half_breadth(x) if span_axis == "y" else hull.half_height(x)) \
        if lo <= x <= hi else 0.0
    a, b = off - 0.5 * span, off + 0.5 * span
    tol = 1e-6 * max(1.0, span)
    if width <= 0.0 or (a > width + tol) or (b < -width - tol):
        raise r.err(f"{path}", "control surface does not touch the hull",
                    [float(v) for v in center],
                    f"a panel whose root reaches the hull surface (hull half-width "
                    f"{width:.4g} m along {span_axis} at x = {x:.4g} m)")
    along = np.linspace(x - 0.5 * chord, x + 0.5 * chord, 9)
    half = hull.half_breadth if span_axis == "y" else hull.half_height
    root_radii = tuple(float(half(xi)) for xi in along) if lo <= along[0] and along[-1] <= hi \
        else ()
    panels = []
    for lo_s, hi_s in ((max(a, width), b), (a, min(b, -width))):
        if hi_s - lo_s > tol:
            c = np.array(center, dtype=float)
            c[k] = (hull.y if span_axis == "y" else hull.z) + 0.5 * (lo_s + hi_s)
            panels.append(SurfacePanel(center=c, span=hi_s - lo_s, chord=chord,
                                       normal="y" if span_axis == "z" else "z",
                                       root=width, root_radii=root_radii))
    if not panels:
        raise r.err(f"{path}", "control surface is inside the hull", [float(v) for v in center],
                    "a panel reaching out of the hull")
    return panels


def _control_surface(r: _Reader, data, path, hull: Hull, fins: dict, used: dict):
    r.mapping(data, path, ("name", "type", "fins", "span", "chord", "area", "position", "axis",
                           "max_deflection_deg", "stall_angle_deg"),
              ("name", "type", "max_deflection_deg"))
    name = r.string(data, "name", path, required=True)
    kind = r.string(data, "type", path, choices=tuple(SURFACE_TYPES), required=True)
    span_axis = SURFACE_TYPES[kind]
    axis = r.string(data, "axis", path, choices=("y", "z"), default=span_axis)
    if axis != span_axis:
        raise r.err(f"{path}.axis", "span axis does not fit the type", axis,
                    f"{span_axis} for a {kind} (rudder: vertical, elevator: horizontal)")
    dmax = r.number(data, "max_deflection_deg", path, positive=True, required=True)
    stall = r.number(data, "stall_angle_deg", path, positive=True, default=None)
    if stall is None:
        stall = dmax
    if dmax > stall:
        raise r.err(f"{path}.max_deflection_deg", "deflection beyond the stall angle", dmax,
                    f"at most stall_angle_deg = {stall:g} deg (the linear lift law ends at stall)")
    if dmax >= 90.0:
        raise r.err(f"{path}.max_deflection_deg", "invalid value", dmax, "less than 90 deg")
    panels = []
    names = ()
    if "fins" in data:
        if any(k in data for k in ("span", "chord", "area", "position")):
            raise r.err(f"{path}.fins", "both fins and span/chord/position given",
                        expected="either fins (appendage names) or the surface's own geometry")
        names = data["fins"]
        if not isinstance(names, list) or not names or not all(isinstance(n, str) for n in names):
            raise r.err(f"{path}.fins", "wrong type", names, "a list of fin appendage names")
        for n in names:
            if n not in fins:
                raise r.err(f"{path}.fins", "unknown fin", n,
                            "one of " + (", ".join(sorted(fins)) or "(no fin appendages)"))
            if n in used:
                raise r.err(f"{path}.fins", "fin used by two control surfaces", n,
                            f"each fin in one surface (already in {used[n]!r})")
            fin = fins[n]
            if fin.span_axis != span_axis:
                raise r.err(f"{path}.fins", f"fin {n!r} spans along {fin.span_axis}", n,
                            f"fins spanning along {span_axis} for a {kind}")
            used[n] = name
            panels += exposed_panels(hull, fin.center, fin.span, fin.chord, span_axis, r=r,
                                      path=f"{path}.fins")
        names = tuple(names)
    else:
        pos = r.vector(data, "position", path, required=True)
        span = r.number(data, "span", path, positive=True, required=True)
        chord = r.number(data, "chord", path, positive=True)
        area = r.number(data, "area", path, positive=True)
        if (chord is None) == (area is None):
            raise r.err(f"{path}.chord", "give chord or area", expected="one of chord [m] or "
                        "area [m^2] beside span")
        chord = chord if chord is not None else area / span
        panels = exposed_panels(hull, pos, span, chord, span_axis, r=r, path=f"{path}.position")
    return ControlSurfaceSpec(name=name, kind=kind, panels=panels,
                              max_deflection=math.radians(dmax), stall_angle=math.radians(stall),
                              fins=names)


def parse_vehicle(data, *, file: str = "<vehicle>") -> Vehicle:
    """Validate a parsed vehicle mapping and build the :class:`Vehicle`.

    Values declared uncertain (``{value: V, sd: S}`` or ``{value: V, tol: T}``, see
    :mod:`stripcoef.geometry.keypaths`) take their nominal value ``V``.
    """
    if isinstance(data, dict):
        data = nominal(data, file=file)
    r = _Reader(file)
    r.mapping(data, "", TOP_KEYS, ("hull",))
    name = r.string(data, "name", "", default=Path(file).stem)
    fluid = _fluid(r, data.get("fluid"))
    hull = _hull(r, data["hull"])
    bodies: list = [hull]
    names = {hull.name}
    for i, a in enumerate(r.listing(data, "appendages", "")):
        body = _appendage(r, a, f"appendages[{i}]")
        if body.name in names:
            raise r.err(f"appendages[{i}].name", "duplicated name", body.name, "unique names")
        names.add(body.name)
        bodies.append(body)
    holes = [_hole(r, h, f"holes[{i}]") for i, h in enumerate(r.listing(data, "holes", ""))]
    # geometric consistency
    hlo, hhi = hull.x_extent()
    for i, h in enumerate(holes):
        lo, hi = h.x_extent()
        if lo < hlo or hi > hhi:
            raise r.err(f"holes[{i}].x", "hole outside the hull", h.x,
                        f"the hole within the hull's x range [{hlo}, {hhi}]")
        width = hull.half_breadth(h.x) if h.axis == "z" else hull.half_height(h.x)
        if abs(h.offset) + 0.5 * h.diameter > width + 1e-12:
            raise r.err(f"holes[{i}].diameter", "hole wider than the hull there", h.diameter,
                        f"|offset| + diameter/2 <= {float(width):.4g} m (hull half-width at x)")
    for i, body in enumerate(bodies[1:]):
        if isinstance(body, Fin):
            _check_fin(r, body, hull, f"appendages[{i}]")
    _check_connected(r, bodies)
    mass = _mass(r, data.get("mass"))
    for i, z in enumerate(mass.zones):
        for b in (z.bodies or ()):
            if b not in names:
                raise r.err(f"mass.zones[{i}].bodies", "unknown body", b,
                            "one of " + ", ".join(sorted(names)))
    fins = {b.name: b for b in bodies if isinstance(b, Fin)}
    used: dict = {}
    surfaces = [_control_surface(r, c, f"control_surfaces[{i}]", hull, fins, used)
                for i, c in enumerate(r.listing(data, "control_surfaces", ""))]
    if len({c.name for c in surfaces}) != len(surfaces):
        raise r.err("control_surfaces", "duplicated control surface name",
                    [c.name for c in surfaces], "unique names")
    body_lift = data.get("body_lift", "auto")
    if body_lift is True or body_lift is False:
        body_lift = "on" if body_lift else "off"
    if body_lift not in ("auto", "on", "off", "slender", "datcom", "stratford", "stratford_panel"):
        raise r.err("body_lift", "invalid value", body_lift,
                    "auto, on, off, slender, datcom, stratford or stratford_panel")
    thrusters = [_thruster(r, t, f"thrusters[{i}]")
                 for i, t in enumerate(r.listing(data, "thrusters", ""))]
    if len({t.name for t in thrusters}) != len(thrusters):
        raise r.err("thrusters", "duplicated thruster name", [t.name for t in thrusters],
                    "unique names")
    ref = data.get("reference_point", "center_of_buoyancy")
    if isinstance(ref, str):
        if ref not in REFERENCE_NAMES:
            raise r.err("reference_point", "invalid value", ref,
                        "one of " + ", ".join(REFERENCE_NAMES) + " or [x, y, z]")
    else:
        ref = r.vector(data, "reference_point", "")
    strips = data.get("strips", DEFAULT_STRIPS)
    if isinstance(strips, bool) or not isinstance(strips, int) or not 4 <= strips <= MAX_STRIPS:
        raise r.err("strips", "invalid value", strips, f"an integer from 4 to {MAX_STRIPS}")
    corr = data.get("corrections", True)
    if not isinstance(corr, bool):
        raise r.err("corrections", "wrong type", corr, "true or false")
    return Vehicle(name=name, source=file, fluid=fluid, hull=hull, bodies=bodies, holes=holes,
                   mass=mass, thrusters=thrusters, reference=ref,
                   reference_speed=r.number(data, "reference_speed", "", positive=True,
                                            default=DEFAULT_SPEED),
                   n_strips=strips, corrections=corr,
                   description=str(data.get("description", "")),
                   control_surfaces=surfaces, body_lift=body_lift)


def _bbox(body) -> np.ndarray:
    """Axis-aligned bounding box [[x0, y0, z0], [x1, y1, z1]] of a body [m]."""
    lo, hi = body.x_extent()
    if isinstance(body, Hull):
        xs = np.linspace(lo, hi, 401)
        b, h = float(np.max(body.half_breadth(xs))), float(np.max(body.half_height(xs)))
        return np.array([[lo, body.y - b, body.z - h], [hi, body.y + b, body.z + h]])
    if hasattr(body, "bbox"):
        return np.asarray(body.bbox(), float)
    c = body.center
    if isinstance(body, Cylinder):
        half = np.full(3, 0.5 * body.diameter)
        half["xyz".index(body.axis)] = 0.5 * body.length
    elif isinstance(body, Box):
        half = 0.5 * np.asarray(body.size)
    else:  # Fin
        half = np.array([0.5 * body.chord, 0.5 * body.thickness, 0.5 * body.thickness])
        half["xyz".index(body.span_axis)] = 0.5 * body.span
    return np.array([c - half, c + half])


def _check_fin(r: _Reader, fin: Fin, hull: Hull, path: str) -> None:
    """A radial fin (its span line through the hull's cross-section, e.g. a tail fin) must run
    from the hull surface outward: its root radius (distance of the inner edge from the hull
    axis) between 0 and the hull's half-width under the fin.

    Root radius :math:`r_0 = |c_s - c_{hull}| - s/2` along the span axis (centre c [m], span s
    [m]); the hull's half-height (z fins) or half-breadth (y fins) R(x) over the chord [m].
    ``r_0 < 0``: the fin crosses the hull axis (a pair must be two fins, one each side: the
    finned section of docs/theory.md pairs them); ``r_0 > max R``: the fin does not touch the
    hull.  Fins off the hull's centre plane are left to the bounding-box check.
    """
    k = "xyz".index(fin.span_axis)
    other = 2 if k == 1 else 1
    axis = np.array([0.0, hull.y, hull.z])
    lo, hi = fin.x_extent()
    hlo, hhi = hull.x_extent()
    xs = np.linspace(max(lo, hlo), min(hi, hhi), 65) if hi > hlo and lo < hhi else np.array([])
    prof = hull.half_height if fin.span_axis == "z" else hull.half_breadth
    across = hull.half_breadth if fin.span_axis == "z" else hull.half_height
    reach = float(np.max(prof(xs))) if xs.size else 0.0
    width = float(np.max(across(xs))) if xs.size else 0.0
    if abs(fin.center[other] - axis[other]) > width:      # not on the hull's centre plane
        return
    root = abs(fin.center[k] - axis[k]) - 0.5 * fin.span
    if root < -1e-9:
        raise r.err(f"{path}.span", f"fin '{fin.name}' crosses the hull axis", fin.span,
                    f"a fin from the hull surface outward: span <= 2 |center.{fin.span_axis}| = "
                    f"{2 * abs(fin.center[k] - axis[k]):.4g} m (a fin pair is two fins)")
    if root > reach * (1 + 1e-6) + 1e-9:
        raise r.err(f"{path}.center", f"fin '{fin.name}' does not touch the hull",
                    [float(v) for v in fin.center],
                    f"a root radius |center.{fin.span_axis}| - span/2 = {root:.4g} m <= the hull's "
                    f"half-width under the fin, {reach:.4g} m")


def _check_connected(r: _Reader, bodies) -> None:
    """Every appendage must touch the hull or an appendage that does (bounding boxes)."""
    boxes = [_bbox(b) for b in bodies]
    tol = 1e-6
    connected = {0}
    changed = True
    while changed:
        changed = False
        for i in range(1, len(bodies)):
            if i in connected:
                continue
            for j in connected:
                if np.all(boxes[i][0] <= boxes[j][1] + tol) and np.all(boxes[j][0] <= boxes[i][1] + tol):
                    connected.add(i)
                    changed = True
                    break
    for i in range(1, len(bodies)):
        if i not in connected:
            c = getattr(bodies[i], "center", boxes[i].mean(axis=0))
            raise r.err(f"appendages[{i - 1}]", f"appendage '{bodies[i].name}' intersects nothing",
                        [float(v) for v in c],
                        "an appendage touching the hull or an appendage attached to it")


def load_vehicle(path, **mesh_options) -> Vehicle:
    """Read and validate a vehicle file (YAML, docs/vehicle-file.md) or a mesh file.

    A mesh file (:data:`MESH_SUFFIXES`) becomes a vehicle through :meth:`Vehicle.from_mesh`,
    which takes ``mesh_options`` (axis, length_unit, origin, fluid, name).
    """
    path = Path(path)
    name = str(path)
    if path.suffix.lower() in MESH_SUFFIXES:
        return Vehicle.from_mesh(path, **mesh_options)
    if mesh_options:
        raise InputError("mesh options given for a vehicle file", file=name,
                         key=", ".join(sorted(mesh_options)),
                         expected="options only with a mesh file (" + " ".join(MESH_SUFFIXES) + ")")
    if path.suffix.lower() not in (".yaml", ".yml"):
        raise InputError("unknown vehicle file extension", file=name, value=path.suffix,
                         expected=".yaml or .yml, or a mesh: " + " ".join(MESH_SUFFIXES))
    return parse_vehicle(read_vehicle_data(path), file=name)


def read_vehicle_data(path) -> dict:
    """The raw mapping of a vehicle YAML file (not yet validated: :func:`parse_vehicle`), read
    by the one bounded YAML reader (:func:`stripcoef.files.load_yaml`)."""
    path = Path(path)
    name = str(path)
    data = load_yaml(read_text(path, kind="vehicle file"), file=name)
    if not isinstance(data, dict):
        raise InputError("not a mapping", file=name, value=type(data).__name__,
                         expected="a YAML mapping with at least a 'hull' key")
    return data
