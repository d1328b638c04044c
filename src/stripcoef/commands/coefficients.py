"""``stripcoef coefficients``: a vehicle file or a mesh in, the hydrodynamic model out."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import yaml

from stripcoef.conventions import DOF
from stripcoef.errors import InputError
from stripcoef.fluid import Fluid, RHO_SEAWATER, NU_SEAWATER
from stripcoef.io import write_text

MESH_SUFFIXES = (".stl", ".obj", ".ply", ".glb", ".gltf", ".off")


def add_parser(sub):
    p = sub.add_parser("coefficients", help="added mass, damping and rigid-body matrices",
                       description="Strip-theory hydrodynamic model of a vehicle file (YAML) "
                                   "or a CAD mesh (STL/OBJ/PLY/GLB).")
    p.add_argument("vehicle", metavar="VEHICLE", help="vehicle file (.yaml) or mesh file")
    fmt = p.add_mutually_exclusive_group()
    fmt.add_argument("--json", action="store_true", help="print the JSON contract")
    fmt.add_argument("--yaml", action="store_true", help="print YAML (same content)")
    p.add_argument("-o", "--output", metavar="FILE", help="write to FILE (atomically)")
    p.add_argument("--strips", type=int, metavar="N", help="number of strips")
    p.add_argument("--speed", type=float, metavar="M_S",
                   help="reference speed for Reynolds numbers and damping [m/s]")
    p.add_argument("--no-corrections", action="store_true",
                   help="pure strip theory (no 3D end corrections)")
    p.add_argument("--reference-point", metavar="POINT",
                   help="center_of_buoyancy, center_of_gravity, origin or X,Y,Z [m]")
    p.add_argument("--regime", choices=("auto", "laminar", "turbulent"), default="auto",
                   help="friction line (default: auto, laminar below Re_L = 5e5)")
    add_fluid_arguments(p, "fluid (override the file; defaults for meshes: sea water)")
    m = add_mesh_arguments(p)
    m.add_argument("--method", choices=("strip", "bem"), default="strip",
                   help="strip theory (default) or the Capytaine BEM (needs stripcoef[bem])")
    p.set_defaults(func=run)
    return p


def add_fluid_arguments(parser, title: str):
    """--rho, --nu, --water-temperature, --salinity (shared by the commands that estimate)."""
    g = parser.add_argument_group(title)
    g.add_argument("--rho", type=float, metavar="KG_M3", help="water density [kg/m^3]")
    g.add_argument("--nu", type=float, metavar="M2_S", help="kinematic viscosity [m^2/s]")
    g.add_argument("--water-temperature", type=float, metavar="C", help="temperature [degC]")
    g.add_argument("--salinity", type=float, metavar="PSU", help="salinity [PSU]")
    return g


def add_mesh_arguments(parser):
    """--origin, --axis, --length-unit for mesh input (shared with ``compare``)."""
    m = parser.add_argument_group("mesh input")
    m.add_argument("--origin", default="centroid", metavar="centroid|X,Y,Z",
                   help="reference point of a mesh: its volume centroid or a point [m]")
    m.add_argument("--axis", choices=("x", "y", "z"), default="x",
                   help="mesh axis along the body (default x)")
    m.add_argument("--length-unit", choices=("m", "mm", "in"), default="m",
                   help="length unit of the mesh file")
    return m


def parse_point(text: str, *, key: str):
    """'X,Y,Z' -> array of 3 floats [m], or an InputError naming the option."""
    parts = str(text).split(",")
    try:
        vals = [float(v) for v in parts]
    except ValueError:
        vals = []
    if len(vals) != 3 or not all(np.isfinite(vals)):
        raise InputError("not a point", key=key, value=text, expected="X,Y,Z in metres")
    return np.asarray(vals)


def fluid_from_args(args, default: Fluid | None) -> Fluid | None:
    """Fluid from --rho/--nu or --water-temperature/--salinity (None: keep the default)."""
    ts = args.water_temperature is not None or args.salinity is not None
    dn = args.rho is not None or args.nu is not None
    if ts and dn:
        raise InputError("conflicting fluid options", key="--rho/--nu",
                         expected="either --rho/--nu or --water-temperature/--salinity")
    if ts:
        if args.water_temperature is None or args.salinity is None:
            raise InputError("incomplete fluid options", key="--water-temperature/--salinity",
                             expected="both --water-temperature and --salinity")
        return Fluid.from_temperature_salinity(args.water_temperature, args.salinity)
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
    from stripcoef.geometry.vehicle import MassSpec, Vehicle, load_vehicle

    path = Path(args.vehicle)
    if path.suffix.lower() in MESH_SUFFIXES:
        try:
            from stripcoef.geometry import mesh as mesh_mod
        except ImportError:
            raise InputError("mesh input is not available in this installation",
                             file=str(path), expected="a vehicle file (.yaml)") from None
        origin = args.origin
        body = mesh_mod.load_mesh(path, axis=args.axis, length_unit=args.length_unit,
                                  origin="centroid" if origin == "centroid" else "file")
        ref = "center_of_buoyancy" if origin == "centroid" else parse_point(origin, key="--origin")
        return Vehicle(name=path.stem, source=str(path),
                       fluid=Fluid(RHO_SEAWATER, NU_SEAWATER, "default sea water"),
                       hull=None, bodies=[body], holes=[], mass=MassSpec(), thrusters=[],
                       reference=ref)
    return load_vehicle(path)


def estimate_from_args(args):
    """The HydroModel the options ask for (shared by the commands that take a VEHICLE)."""
    from stripcoef.assemble import estimate

    vehicle = load_any_vehicle(args)
    fluid = fluid_from_args(args, vehicle.fluid)
    ref = None
    if getattr(args, "reference_point", None):
        rp = args.reference_point
        ref = rp if rp in ("center_of_buoyancy", "center_of_gravity", "origin") else \
            parse_point(rp, key="--reference-point")
    if args.strips is not None and args.strips < 4:
        raise InputError("too few strips", key="--strips", value=args.strips,
                         expected="an integer >= 4")
    return vehicle, estimate(vehicle, strips=args.strips,
                             corrections=False if args.no_corrections else None,
                             speed=args.speed, reference_point=ref, regime=args.regime,
                             fluid=fluid)


def _pt(point) -> list:
    """A point rounded to 0.1 mm for display, without negative zeros [m]."""
    return (np.round(np.asarray(point, dtype=float), 4) + 0.0).tolist()


def format_table(model) -> str:
    """A readable summary: mass properties, the three matrices, conditions."""
    def mat(name, m, unit):
        lines = [f"{name} [{unit}] about {_pt(model.reference_point)} m:"]
        lines.append("        " + "".join(f"{d:>11s}" for d in DOF))
        for d, row in zip(DOF, np.asarray(m)):
            lines.append(f"{d:>7s} " + "".join(f"{v:11.4g}" for v in row))
        return "\n".join(lines)

    c = model.conditions
    out = [f"{model.name}: strip theory ({c.get('strips')} strips, 3D corrections "
           f"{'on' if c.get('corrections') else 'off'})",
           f"  mass {model.mass:.4g} kg, volume {model.volume:.5g} m^3 "
           f"(rho V = {model.density * model.volume:.4g} kg)",
           f"  CG {_pt(model.center_of_gravity)} m, "
           f"CB {_pt(model.center_of_buoyancy)} m",
           f"  fluid: rho = {model.density:.5g} kg/m^3, nu = {model.kinematic_viscosity:.4g} m^2/s",
           "",
           mat("Added mass M_A", model.added_mass, "kg, kg m, kg m^2"),
           "",
           mat("Linear damping D_L", model.linear_damping, "kg/s, kg m/s, kg m^2/s"),
           "",
           mat("Quadratic damping D_Q", model.quadratic_damping, "kg/m, kg, kg m^2"),
           "",
           mat("Rigid-body mass M_RB", model.rigid_body_mass, "kg, kg m, kg m^2"),
           "",
           "Conditions:"]
    keys = ("reference_speed", "reynolds_length", "regime", "cf_laminar", "cf_turbulent",
            "cf_used", "form_factor", "axial_drag_coefficient_frontal", "hull_reynolds_diameter",
            "hull_crossflow_cd_y", "hull_length_factor", "axial_added_mass",
            "end_correction_sway", "end_correction_heave", "end_correction_pitch",
            "end_correction_yaw", "correction_method")
    for k in keys:
        if k in c:
            v = c[k]
            out.append(f"  {k:32s} {v:.4g}" if isinstance(v, float) else f"  {k:32s} {v}")
    return "\n".join(out) + "\n"


def run(args) -> int:
    if args.method == "bem":
        from stripcoef import bem  # optional extra

        vehicle = load_any_vehicle(args)
        data = bem.bem_model_dict(vehicle, args)
        text = json.dumps(data, indent=2)
    else:
        _, model = estimate_from_args(args)
        data = model.to_dict()
        if args.json:
            text = json.dumps(data, indent=2)
        elif args.yaml:
            text = yaml.safe_dump(data, sort_keys=False)
        else:
            text = format_table(model)
    if args.output:
        write_text(args.output, text if text.endswith("\n") else text + "\n", key="--output")
    else:
        print(text, end="" if text.endswith("\n") else "\n")
    return 0
