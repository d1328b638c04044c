"""Options shared by the commands that read a vehicle: fluid, mesh input, points, strips."""

from __future__ import annotations

from pathlib import Path

from stripcoef.errors import InputError


def add_fluid_arguments(parser, title: str):
    """--rho, --nu, --water-temperature, --salinity (shared by the commands that estimate)."""
    g = parser.add_argument_group(title)
    g.add_argument("--rho", type=float, metavar="KG_M3", help="water density [kg/m^3]")
    g.add_argument("--nu", type=float, metavar="M2_S", help="kinematic viscosity [m^2/s]")
    g.add_argument("--water-temperature", type=float, metavar="C", help="temperature [degC]")
    g.add_argument("--salinity", type=float, metavar="PSU", help="salinity [PSU]")
    g.add_argument("--water-equation", choices=("eos80", "teos10"), default=None,
                   help="density from temperature and salinity by EOS-80 (default) or TEOS-10 "
                        "(needs pip install 'stripcoef[seawater]')")
    return g


def add_mesh_arguments(parser):
    """--origin, --axis, --length-unit, --added-mass-method, --added-mass-panels for mesh
    input (shared with ``compare``)."""
    m = parser.add_argument_group("mesh input")
    m.add_argument("--origin", default="centroid", metavar="centroid|X,Y,Z",
                   help="reference point of a mesh: its volume centroid or a point [m]")
    m.add_argument("--axis", choices=("x", "y", "z"), default="x",
                   help="mesh axis along the body (default x)")
    m.add_argument("--length-unit", choices=("m", "mm", "in"), default="m",
                   help="length unit of the mesh file")
    m.add_argument("--z-up", action="store_true",
                   help="the mesh file is z-up (ROS REP 103, most CAD): turned 180 deg about "
                        "x into the body axes (FRD, z down)")
    from stripcoef.assembly.methods import estimate_choices   # the command's own stack

    a = parser.add_argument_group("added mass")
    a.add_argument("--added-mass-method", choices=estimate_choices(), default="auto",
                   help="M_A by the 3D panel method for a vehicle that is neither round nor "
                        "slender (a mesh, or a vehicle file on its parts united into one "
                        "closed surface), by strip theory otherwise (auto, default); always "
                        "by strip theory (strips); always by the panel method (panels)")
    a.add_argument("--added-mass-panels", type=int, metavar="N",
                   help="panels of the panel method's finer resolution (default 1600; may "
                        "exceed the mesh's face count: the mesh is refined)")
    return m


def parse_point(text: str, *, key: str):
    """'X,Y,Z' -> array of 3 floats [m], or an InputError naming the option."""
    import numpy as np

    parts = str(text).split(",")
    try:
        vals = [float(v) for v in parts]
    except ValueError:
        vals = []
    if len(vals) != 3 or not all(np.isfinite(vals)):
        raise InputError("not a point", key=key, value=text, expected="X,Y,Z in metres")
    return np.asarray(vals)


def fluid_from_args(args, default):
    """Fluid from --rho/--nu or --water-temperature/--salinity (None: keep the default)."""
    import numpy as np

    from stripcoef.fluid import Fluid

    ts = args.water_temperature is not None or args.salinity is not None
    dn = args.rho is not None or args.nu is not None
    equation = getattr(args, "water_equation", None)
    if equation is not None and not ts:
        raise InputError("an equation of state needs the water's temperature and salinity",
                         key="--water-equation", value=equation,
                         expected="--water-temperature and --salinity beside it")
    if ts and dn:
        raise InputError("conflicting fluid options", key="--rho/--nu",
                         expected="either --rho/--nu or --water-temperature/--salinity")
    if ts:
        if args.water_temperature is None or args.salinity is None:
            raise InputError("incomplete fluid options", key="--water-temperature/--salinity",
                             expected="both --water-temperature and --salinity")
        try:
            return Fluid.from_temperature_salinity(args.water_temperature, args.salinity,
                                                   equation=equation or "eos80")
        except InputError as exc:
            flag = {"temperature": "water-temperature", "equation": "water-equation"}.get(
                str(exc.key), str(exc.key))
            raise exc.with_key("--" + flag) from None
    if dn:
        base = default or Fluid()
        rho = args.rho if args.rho is not None else base.density
        nu = args.nu if args.nu is not None else base.kinematic_viscosity
        for k, v in (("--rho", rho), ("--nu", nu)):
            if not np.isfinite(v) or v <= 0:
                raise InputError("must be positive", key=k, value=v, expected="a number > 0")
        return Fluid(density=rho, kinematic_viscosity=nu, source="command line")
    return None


def load_any_vehicle(args):
    """A Vehicle from a YAML vehicle file or from a mesh (with the mesh options)."""

    from stripcoef.geometry.vehicle import MESH_SUFFIXES, load_vehicle

    path = Path(args.vehicle)
    if path.suffix.lower() in MESH_SUFFIXES:
        origin = "centroid" if args.origin == "centroid" else parse_point(args.origin, key="--origin")
        return load_vehicle(path, axis=args.axis, length_unit=args.length_unit, origin=origin,
                            z_up=getattr(args, "z_up", False))
    return load_vehicle(path)


def estimate_options(args, vehicle):
    """The :class:`~stripcoef.assembly.EstimateOptions` of the command line (``--strips``,
    ``--no-corrections``, ``--speed``, ``--reference-point``, ``--regime``,
    ``--added-mass-method``, ``--added-mass-panels``, the fluid options; those a command
    lacks keep their defaults)."""
    from stripcoef.assembly import EstimateOptions

    ref = None
    if getattr(args, "reference_point", None) is not None:     # "" is an error, not unset
        rp = args.reference_point
        ref = rp if rp in ("center_of_buoyancy", "center_of_gravity", "origin") else \
            parse_point(rp, key="--reference-point")
    from stripcoef.strips import MAX_STRIPS

    if args.strips is not None and not 4 <= args.strips <= MAX_STRIPS:
        raise InputError("invalid number of strips", key="--strips", value=args.strips,
                         expected=f"an integer from 4 to {MAX_STRIPS}")
    return EstimateOptions(strips=args.strips,
                           corrections=False if args.no_corrections else None,
                           speed=args.speed, reference_point=ref,
                           regime=getattr(args, "regime", "auto"),
                           fluid=fluid_from_args(args, vehicle.fluid),
                           added_mass_method=getattr(args, "added_mass_method", "auto"),
                           added_mass_panels=getattr(args, "added_mass_panels", None))


def estimate_from_args(args):
    """The vehicle and the HydroModel the options ask for (commands that take a VEHICLE)."""
    from stripcoef.assembly import estimate

    vehicle = load_any_vehicle(args)
    return vehicle, estimate(vehicle, estimate_options(args, vehicle))


def add_map_argument(parser):
    """--map: read the log (any CSV, several CSVs, a ROS bag) through a column map."""
    parser.add_argument("--map", metavar="MAP.yaml", default=None,
                        help="column map: read LOG (any CSV, several CSV streams or a ROS "
                             "bag) through it (docs/logs.md)")


def read_log_from_args(path, args, *, required=()):
    """The log at ``path``: the log CSV format, or through ``--map`` a CSV or a ROS bag."""
    from stripcoef.ingest import read_any_log

    return read_any_log(path, column_map=getattr(args, "map", None), required=required)

