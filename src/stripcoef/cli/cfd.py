"""``stripcoef cfd MESH|VEHICLE``: the body's damping by OpenFOAM (steady RANS), with its mesh spread."""

from __future__ import annotations

import sys
from pathlib import Path

from stripcoef.conventions import DOF as DOF_NAMES
from stripcoef.errors import InputError


def add_parser(sub):
    p = sub.add_parser("cfd", help="damping by OpenFOAM (steady RANS, k-omega SST)",
                       description="The body's drag and rotational damping by OpenFOAM "
                                   "(Debian package openfoam): snappyHexMesh around the mesh, "
                                   "steady simpleFoam with k-omega SST; translations by an "
                                   "inflow, rotations by an MRF zone in a still tank. Two "
                                   "mesh levels give the mesh-convergence estimate, two "
                                   "speeds the linear term too. Each run is a case folder "
                                   "under --case-dir with an Allrun script (docs/cfd.md).")
    p.add_argument("mesh", metavar="MESH|VEHICLE",
                   help="closed body: STL, OBJ, PLY or GLB file, or a vehicle file (its parts "
                        "united into one closed surface)")
    p.add_argument("--dofs", default="surge", metavar="DOF[,DOF...]",
                   help="any of surge, sway, heave, roll, pitch, yaw, or all (default surge)")
    p.add_argument("--speeds", metavar="U[,U...]",
                   help="speeds [m/s] (default a vehicle file's reference speed, else 1 "
                        "m/s); two give d_L")
    p.add_argument("--rates", metavar="R[,R...]",
                   help="rotation rates [rad/s] (default 2 U / L: tip speed U)")
    p.add_argument("--levels", default=None, metavar="COARSE,FINE",
                   help="surface cells size/2^level (default 3,4 for surge, sway, heave and "
                        "4,5 for roll, pitch, yaw; one level: no mesh estimate)")
    p.add_argument("--iterations", type=int, default=1000, metavar="N",
                   help="most simpleFoam iterations per run (default 1000; a run stops "
                        "earlier once its force settles)")
    p.add_argument("--ranks", type=int, metavar="N",
                   help="MPI ranks (default: the cores available); the case is decomposed "
                        "for them (hierarchical) and runs unchanged on a cluster")
    p.add_argument("--case-dir", default=None, metavar="DIR",
                   help="folder of the cases, kept (default cfd-<mesh name>)")
    p.add_argument("--write-only", action="store_true",
                   help="write the cases (each with its Allrun) and stop")
    p.add_argument("--compare", action="store_true",
                   help="put the default model's damping (stripcoef coefficients, same water "
                        "and speed, moments about the same origin) beside the CFD's per DOF")
    p.add_argument("--result", metavar="FILE.json",
                   help="read an earlier --json result (a stored reference) instead of "
                        "running OpenFOAM; with --compare, compare it")
    p.add_argument("--json", action="store_true", help="the result as JSON")
    p.add_argument("-o", "--output", metavar="FILE", help="write the output to FILE")
    m = p.add_argument_group("mesh input")
    m.add_argument("--axis", choices=("x", "y", "z"), default="x",
                   help="mesh axis along the body (default x)")
    m.add_argument("--length-unit", choices=("m", "mm", "in"), default="m",
                   help="length unit of the mesh file")
    m.add_argument("--z-up", action="store_true",
                   help="the file is z-up (ROS REP 103, most CAD): turned 180 deg about x")
    from stripcoef.cli.options import add_fluid_arguments
    add_fluid_arguments(p, "water")
    p.set_defaults(func=run)
    return p


def _numbers(text, key):
    if text is None:
        return None
    try:
        vals = [float(v) for v in str(text).split(",")]
    except ValueError:
        vals = []
    if not vals or not all(v > 0 and v < 1e6 for v in vals):
        raise InputError("not a list of positive numbers", key=key, value=text,
                         expected="numbers > 0 separated by commas")
    return vals


def _dofs(text):
    names = [v.strip() for v in str(text).split(",") if v.strip()]
    if names == ["all"]:
        return DOF_NAMES
    bad = [n for n in names if n not in DOF_NAMES]
    if bad or not names:
        raise InputError("unknown degree of freedom", key="--dofs", value=text,
                         expected="names from surge, sway, heave, roll, pitch, yaw (or all)")
    return tuple(dict.fromkeys(names))


def _levels(text):
    try:
        vals = [int(v) for v in str(text).split(",")]
    except ValueError:
        vals = []
    if not 1 <= len(vals) <= 2 or not all(1 <= v <= 8 for v in vals):
        raise InputError("invalid mesh levels", key="--levels", value=text,
                         expected="one or two integers from 1 to 8 (COARSE,FINE)")
    return vals


def _progress_printer():
    from stripcoef import progress

    if not progress.enabled():
        return None
    shown = {}

    def show(label, state, force, moment):
        if label in shown and state.iteration < shown[label] + 25:
            return
        shown[label] = state.iteration
        res = ", ".join(f"{k} {v:.1e}" for k, v in state.residuals.items() if k in
                        ("Ux", "Uy", "Uz", "p"))
        f = "" if force is None else \
            f"; F ({force[0]:.4g}, {force[1]:.4g}, {force[2]:.4g}) N"
        mom = "" if moment is None or not label.split()[0] in ("roll", "pitch", "yaw") else \
            f"; M ({moment[0]:.4g}, {moment[1]:.4g}, {moment[2]:.4g}) N m"
        print(f"cfd {label}: iteration {state.iteration} (residuals {res}){f}{mom}",
              file=sys.stderr, flush=True)
    return show


def run(args) -> int:
    from stripcoef.cfd.drag import drag_by_cfd
    from stripcoef.cli.options import fluid_from_args
    from stripcoef.files import OutputSet, json_text
    from stripcoef.geometry.mesh import MESH_EXTENSIONS, load_mesh
    from stripcoef.geometry.surface import vehicle_surface
    from stripcoef.geometry.vehicle import DEFAULT_SPEED, load_vehicle

    path = Path(args.mesh)
    vehicle = None
    if path.suffix.lower() not in MESH_EXTENSIONS:
        # a vehicle file: its parts united into one closed surface (the panel method's union),
        # its reference speed and water the defaults
        vehicle = load_vehicle(path)
    dofs = _dofs(args.dofs)
    speeds = _numbers(args.speeds, "--speeds") or \
        [vehicle.reference_speed if vehicle is not None else DEFAULT_SPEED]
    rates = _numbers(args.rates, "--rates")
    levels = None if args.levels is None else _levels(args.levels)
    if args.ranks is not None and args.ranks < 1:
        raise InputError("must be positive", key="--ranks", value=args.ranks,
                         expected="an integer >= 1")
    if args.iterations < 10:
        raise InputError("too few iterations", key="--iterations", value=args.iterations,
                         expected="an integer >= 10")
    if args.result:
        result = _stored(args.result)
    else:
        if vehicle is not None:
            surface = vehicle_surface(vehicle)
            fluid = fluid_from_args(args, vehicle.fluid) or vehicle.fluid
        else:
            surface = load_mesh(path, axis=args.axis, length_unit=args.length_unit,
                                z_up=args.z_up).mesh
            fluid = fluid_from_args(args, None)
        case_dir = args.case_dir or f"cfd-{path.stem}"
        result = drag_by_cfd(surface, dofs=dofs, speeds=speeds, rates=rates, levels=levels,
                             ranks=args.ranks, case_dir=case_dir, iterations=args.iterations,
                             fluid=fluid, write_only=args.write_only,
                             source=str(path), on_progress=_progress_printer())
    if args.compare and result.dofs:
        from stripcoef.cfd.compare import with_comparison
        from stripcoef.fluid import Fluid

        if vehicle is None:
            vehicle = load_vehicle(path, axis=args.axis, length_unit=args.length_unit,
                                   origin="centroid", z_up=args.z_up)
        water = Fluid(density=result.density, kinematic_viscosity=result.viscosity,
                      source="the CFD's water")
        result = with_comparison(result, vehicle, fluid=water)
    text = json_text(result.to_dict()) if args.json else result.text()
    if args.output:
        with OutputSet() as outs:
            outs.path(args.output, key="--output").write_text(text)
    else:
        print(text, end="")
    if result.dofs and not result.converged:
        print("stripcoef cfd: warning: a run did not converge; its numbers are marked "
              "NOT CONVERGED and are not a reference", file=sys.stderr)
    return 0


def _stored(path):
    """A stored ``--json`` result, or a one-line error naming the file."""
    import json

    from stripcoef.cfd.result import CfdResult

    try:
        data = json.loads(Path(path).read_text())
        return CfdResult.from_dict(data)
    except OSError as exc:
        raise InputError(f"cannot read it ({exc.strerror or exc})", key="--result",
                         value=str(path), expected="a file written by stripcoef cfd --json") \
            from None
    except (ValueError, KeyError, TypeError, AttributeError) as exc:
        raise InputError(f"not a stripcoef cfd result ({type(exc).__name__}: {exc})",
                         key="--result", value=str(path),
                         expected="a file written by stripcoef cfd --json") from None
