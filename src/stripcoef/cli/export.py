"""``stripcoef export VEHICLE --to FORMAT [-o FILE]``: the model in a simulator's format.

VEHICLE is a vehicle file (YAML, estimated by strip theory) or a model file
(``HydroModel.to_dict()`` as JSON or YAML, e.g. from ``stripcoef export --to json``).
Without ``-o`` the export is printed (``npz`` is binary and needs ``-o``).
"""

from __future__ import annotations

import sys

from stripcoef.errors import InputError


def add_parser(subparsers):
    from stripcoef.export import FORMATS
    p = subparsers.add_parser(
        "export", help="export the model to a simulator or data format",
        description="Export a vehicle's hydrodynamic model to a simulator or data format. "
                    "Formats: " + "; ".join(f"{k}: {f.description}" for k, f in FORMATS.items()))
    p.add_argument("vehicle", metavar="VEHICLE",
                   help="vehicle file (YAML) or model file (JSON/YAML from HydroModel.to_dict)")
    p.add_argument("--to", required=True, metavar="FORMAT",
                   help="one of " + ", ".join(FORMATS))
    p.add_argument("-o", "--output", metavar="FILE", help="output file (default: stdout)")
    p.add_argument("--point", metavar="CO|CG|CB|origin|X,Y,Z",
                   help="reference point of the exported matrices: CO (the model's), CG, CB, "
                        "origin or x,y,z in m, FRD body coordinates of the vehicle file (write "
                        "--point=-0.1,0,0 for a negative x); default: the format's (CG for "
                        "uuv, else CO)")
    p.add_argument("--axes", metavar="FRD|FLU",
                   help="axes of the exported matrices (gazebo, uuv: of the link frame); "
                        "default FLU for gazebo and uuv, FRD otherwise")
    p.add_argument("--link", dest="link_name", metavar="NAME", help="link name (gazebo, uuv; default base_link)")
    p.add_argument("--legacy-added-mass", action="store_true",
                   help="gazebo: write the plugin's <xDotU> added-mass tags (Bullet, MuJoCo) "
                        "instead of <fluid_added_mass> (DART)")
    p.add_argument("--fortress", action="store_true",
                   help="gazebo: a file for Ignition Gazebo Fortress (SDF 1.9, whose sdformat 12 "
                        "drops <fluid_added_mass>; ignition plugin names; legacy added mass)")
    p.add_argument("--lumped-added-mass", dest="lumped_added_mass", action="store_true",
                   default=None,
                   help="gazebo: carry part of the added mass in the link's own mass and "
                        "inertia so that the explicit legacy tags stay stable (default with "
                        "--fortress)")
    p.add_argument("--no-lumped-added-mass", dest="lumped_added_mass", action="store_false",
                   help="gazebo: the whole added mass in the explicit legacy tags")
    p.add_argument("--no-thrusters", dest="thrusters", action="store_false", default=None,
                   help="gazebo: no Thruster systems (default: one per thruster)")
    p.add_argument("--world", action="store_true",
                   help="gazebo: a world file around the model (physics, buoyancy)")
    p.add_argument("--no-buoyancy-volume", dest="buoyancy_volume", action="store_false",
                   default=None,
                   help="gazebo: no displaced-volume box (the link's own collisions give the "
                        "buoyancy; gz-sim sums every collision of a link)")
    p.set_defaults(func=run)
    return p


def run(args) -> int:
    from stripcoef.export import export_model, get_format, write_export
    from stripcoef.modelfile import load_model

    spec = get_format(args.to)                 # unknown format: fail before any work
    if spec.binary and not args.output:
        raise InputError(f"format {args.to} is binary and is not printed", key="output",
                         expected="-o FILE")
    model = load_model(args.vehicle)
    if str(model.provenance.get("method", "")).startswith("strip theory") and not model.bands:
        # estimated from a vehicle file here (its added mass by strip theory or, for a bluff
        # one, the panel method): its method bands go into the files' comments
        from stripcoef.geometry.vehicle import load_vehicle
        from stripcoef.study.bands import with_bands
        model = with_bands(model, load_vehicle(args.vehicle))
    options = dict(point=args.point, axes=args.axes, link_name=args.link_name,
                   legacy_added_mass=args.legacy_added_mass, fortress=args.fortress,
                   buoyancy_volume=args.buoyancy_volume,
                   lumped_added_mass=args.lumped_added_mass, thrusters=args.thrusters,
                   world=args.world)
    if args.output:
        path = write_export(model, args.to, args.output, **options)
        print(f"wrote {path}", file=sys.stderr)
    else:
        sys.stdout.write(export_model(model, args.to, **options))
    return 0
