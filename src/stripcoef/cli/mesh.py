"""``stripcoef mesh MESH``: what a mesh file holds, what the loader repairs, and a repaired copy."""

from __future__ import annotations

from stripcoef.errors import InputError


def add_parser(sub):
    p = sub.add_parser("mesh", help="check a mesh file, say what is repaired, write a repaired copy",
                       description="Read a mesh as found and as repaired (vertices split at "
                                   "seams merged, zero-area faces flipped or collapsed, holes "
                                   "closed, winding and normals fixed, several bodies united; a "
                                   "mesh still open: each open part capped, the parts united) "
                                   "and say what was changed. --repair -o OUT writes the "
                                   "repaired closed surface (body axes FRD, metres, the file's "
                                   "origin); --plot draws it with the file's open edges in red.")
    p.add_argument("mesh", metavar="MESH", help="STL, OBJ, PLY, GLB or COLLADA (.dae) file")
    p.add_argument("--axis", choices=("x", "y", "z"), default="x",
                   help="mesh axis along the body (default x)")
    p.add_argument("--length-unit", choices=("m", "mm", "in"), default="m",
                   help="length unit of the mesh file")
    p.add_argument("--z-up", action="store_true",
                   help="the file is z-up (ROS REP 103, most CAD): turned 180 deg about x")
    p.add_argument("--repair", action="store_true", help="write the repaired mesh (with -o)")
    p.add_argument("-o", "--output", metavar="OUT", help="repaired mesh file (.stl, .ply, .obj)")
    p.add_argument("--plot", metavar="FILE.png", help="draw the repaired mesh and the open edges")
    p.add_argument("--json", action="store_true", help="the report as JSON")
    p.set_defaults(func=run)
    return p


def run(args) -> int:
    from pathlib import Path

    from stripcoef.files import json_text, write_bytes
    from stripcoef.geometry.meshcheck import check_mesh, mesh_figure

    if args.repair != (args.output is not None):
        raise InputError("--repair and -o go together", key="--output", value=args.output,
                         expected="--repair -o OUT (the repaired mesh file)")
    if args.output is not None and Path(args.output).suffix.lower() not in (".stl", ".ply", ".obj"):
        raise InputError("unknown output mesh format", key="--output", value=args.output,
                         expected="a file name ending in .stl, .ply or .obj")
    report, surface, open_segments = check_mesh(args.mesh, axis=args.axis,
                                                length_unit=args.length_unit, z_up=args.z_up)
    if args.json:
        print(json_text(report.to_dict()))
    else:
        ok = "closed, consistently wound" if report.watertight else "NOT closed"
        print(f"{report.source}:")
        print(f"  found:    {report.faces_found} faces, {report.vertices_found} vertices, "
              f"{report.open_edges_found} open or non-manifold edges")
        print(f"  repaired: {report.faces} faces, {report.vertices} vertices, {ok}; "
              f"{report.bodies} bod{'y' if report.bodies == 1 else 'ies'}")
        ex = report.extent
        print(f"  size {ex[0]:.4g} x {ex[1]:.4g} x {ex[2]:.4g} m (body x, y, z), volume "
              f"{report.volume:.4g} m^3")
        print("  changed:" + (" nothing" if not report.repairs else ""))
        for note in report.repairs:
            print(f"    - {note}")
        print("  body axes FRD (z down): a z-up file (ROS REP 103, most CAD) needs --z-up "
              "(a COLLADA file: its <up_axis> is used)")
        if report.closed_parts:
            print(f"  the file as found is refused (open parts): use the repaired copy, "
                  f"--repair -o {Path(args.mesh).stem}_closed.stl")
    if args.output is not None:
        ext = Path(args.output).suffix.lower()[1:]
        write_bytes(args.output, surface.export(file_type=ext), key="--output")
        if not args.json:
            print(f"wrote {args.output}")
    if args.plot is not None:
        from stripcoef.figures import save_figure

        fig = mesh_figure(surface, open_segments, title=Path(args.mesh).name, key="--plot")
        save_figure(fig, args.plot, key="--plot")
    return 0
