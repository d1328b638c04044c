"""Rotational (and sway/heave) drag of bluff bodies by OpenFOAM: the stored CFD references.

Five bluff shapes (body axes FRD, metres, written to ``reference_tables/cfd/*.stl`` by
``--shapes``): the 1 m cube (already stored), a 2:1:1 box, a short cylinder (L/D 1), a
plate-like box and an open frame of square bars (a box frame, 12 members united). Each
(shape, DOF) is one ``stripcoef cfd`` command, run at one MPI rank and two mesh levels, its
``--json`` result written to ``reference_tables/cfd/<shape>_<dof>.json``::

    python -m benchmarks.cfd_rotation --shapes           # write the STL files (manifold3d)
    nice -n 19 python -m benchmarks.cfd_rotation --run box2 roll   # one stored reference
    python -m benchmarks.cfd_rotation --list             # the commands of every reference
    python -m benchmarks.cfd_rotation --rotational       # the model's rotations against them

A DOF left out by the shape's symmetry is named in :data:`SYMMETRIC` (the cube's roll and
pitch equal its yaw, a body of revolution's pitch its yaw, ...). The tests and
docs/validation.md read the stored files; nothing here runs during the tests.
"""

from __future__ import annotations

import argparse
import shlex
import sys
from pathlib import Path, PurePosixPath

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
FOLDER = "reference_tables/cfd"

#: shape -> (STL file, description)
SHAPES = {
    "cube": ("cube_1m.stl", "cube 1 m"),
    "box2": ("box_2x1x1.stl", "box 1.0 x 0.5 x 0.5 m (2:1:1)"),
    "cylinder": ("cylinder_ld1.stl", "cylinder along x, D 0.5 m, L 0.5 m (L/D 1), 64 sides"),
    "plate": ("plate_box.stl", "plate-like box 0.6 x 0.4 x 0.1 m"),
    "frame": ("open_frame.stl", "open box frame 0.6 x 0.4 x 0.3 m of 0.08 m square bars"),
    "bluerov2": ("../../geometry/bluerov2_heavy.yaml",
                 "BlueROV2 Heavy vehicle file (its parts united), 0.5 m/s"),
}
#: (shape, DOF) -> levels, in order of value (rotations first).
RUNS = {
    ("cube", "yaw"): "4,5",
    ("box2", "roll"): "4,5",
    ("box2", "yaw"): "4,5",
    ("cylinder", "yaw"): "4,5",
    ("plate", "roll"): "4,5",
    ("plate", "pitch"): "4,5",
    ("plate", "yaw"): "4,5",
    ("frame", "yaw"): "4,5",
    ("frame", "roll"): "4,5",
    ("frame", "pitch"): "4,5",
    ("cylinder", "roll"): "4,5",
    ("box2", "sway"): "3,4",
    ("cylinder", "sway"): "3,4",
    ("plate", "heave"): "3,4",
    ("plate", "sway"): "4,5",
    ("frame", "heave"): "4,5",
    ("frame", "sway"): "4,5",
    ("bluerov2", "surge"): "3,4",
    ("bluerov2", "sway"): "3,4",
    ("bluerov2", "heave"): "3,4",
    ("bluerov2", "yaw"): "3,4",
    ("bluerov2", "surge45"): "4,5",
    ("bluerov2", "yaw45"): "4,5",
}
#: DOFs not run because a symmetry of the shape gives them: DOF -> the DOF it equals.
SYMMETRIC = {"cube": {"roll": "yaw", "pitch": "yaw", "sway": "surge", "heave": "surge"},
             "box2": {"pitch": "yaw", "heave": "sway"},
             "cylinder": {"pitch": "yaw", "heave": "sway"}}


def frame_parts(length=0.6, width=0.4, height=0.3, bar=0.08):
    """The open frame's 12 square bars (trimesh boxes): 4 along x at the corners of the
    y-z section, 4 along y and 4 along z at the two ends."""
    import trimesh

    hx, hy, hz = (0.5 * (v - bar) for v in (length, width, height))
    parts = []
    for y in (-hy, hy):
        for z in (-hz, hz):
            parts.append(trimesh.creation.box([length, bar, bar],
                                              trimesh.transformations.translation_matrix([0, y, z])))
    for x in (-hx, hx):
        for z in (-hz, hz):
            parts.append(trimesh.creation.box([bar, width, bar],
                                              trimesh.transformations.translation_matrix([x, 0, z])))
        for y in (-hy, hy):
            parts.append(trimesh.creation.box([bar, bar, height],
                                              trimesh.transformations.translation_matrix([x, y, 0])))
    return parts


def make_shapes() -> list[Path]:
    """Write the STL files of the shapes (centred on their volume centroid)."""
    import trimesh

    meshes = {
        "box2": trimesh.creation.box([1.0, 0.5, 0.5]),
        "cylinder": trimesh.creation.cylinder(radius=0.25, height=0.5, sections=64,
                                              transform=trimesh.transformations.rotation_matrix(
                                                  np.pi / 2, [0, 1, 0])),
        "plate": trimesh.creation.box([0.6, 0.4, 0.1]),
        "frame": trimesh.boolean.union(frame_parts(), engine="manifold"),
    }
    out = []
    for name, mesh in meshes.items():
        assert mesh.is_watertight, name
        mesh.apply_translation(-mesh.center_mass)
        path = ROOT / FOLDER / SHAPES[name][0]
        mesh.export(path, file_type="stl_ascii")
        out.append(path)
    return out


def command(shape: str, dof: str) -> list[str]:
    """The ``stripcoef cfd`` arguments of one stored reference (from the repository root)."""
    stl, _ = SHAPES[shape]
    source = str(PurePosixPath(FOLDER, stl)).replace("reference_tables/cfd/../../", "")
    return ["cfd", source, "--dofs", dof.rstrip("0123456789"), "--levels", RUNS[(shape, dof)],
            "--ranks", "1", "--case-dir", f"build/cfd/{shape}_{dof}", "--json",
            "-o", f"{FOLDER}/{shape}_{dof}.json"]


def table() -> str:
    """Every stored result in reference_tables/cfd as a markdown table: mesh, iterations,
    the value and its mesh spread, y+ and the cost of each DOF."""
    import json

    from stripcoef.cfd.result import NAMES, CfdResult

    head = ("| file | DOF | levels | cells (fine / coarse) | iterations | SNAME d_Q (fine) | "
            "mesh spread (GCI) | y+ fine: mean (min-max) | CPU-min | wall-min | status |")
    lines = [head, "|" + "|".join("---" for _ in range(head.count("|") - 1)) + "|"]
    for path in sorted((ROOT / FOLDER).glob("*.json")):
        res = CfdResult.from_dict(json.loads(path.read_text()))
        for d in res.dofs:
            fine, runs = d.runs[0], d.runs
            yp = "-" if fine.y_plus is None else \
                f"{fine.y_plus[2]:.0f} ({fine.y_plus[0]:.2g}-{fine.y_plus[1]:.0f})"
            gci = "-" if d.gci is None else f"{100 * d.gci:.1f} %"
            lines.append(
                f"| `{path.name}` | {d.dof} | {'/'.join(str(r.level) for r in runs)} | "
                f"{' / '.join(f'{r.cells:,}' for r in runs)} | "
                f"{' / '.join(str(r.iterations) for r in runs)} | "
                f"{NAMES[d.dof][1]} {-d.d_quadratic:.4g} | {gci} | {yp} | "
                f"{sum(r.cpu_seconds for r in runs) / 60:.1f} | "
                f"{sum(r.wall_seconds for r in runs) / 60:.1f} | "
                f"{'converged' if d.converged else 'NOT CONVERGED'} |")
    return "\n".join(lines)


def rotational() -> str:
    """The rotational damping of the default model against every stored CFD rotation, per
    shape: the strips' cross-flow at a lever arm (before) and the surface pressure drag of
    :func:`stripcoef.assembly.damping.rotational_pressure_drag` (after), each as model/CFD of
    the damping moment at the CFD's rate, and the summary over the rows docs/validation.md
    counts (converged, mesh spread within its limit, finest levels, not friction-only)."""
    from validation.cfd import rows, summary_rows

    rs = [r for r in rows() if r["rotation"]]
    counted = {id(r) for r in summary_rows(rs)}
    head = ("| body | DOF | CFD d_Q [kg m^2] | GCI | strips/CFD (before) | surface/CFD (after) "
            "| counted |")
    lines = [head, "|" + "|".join("---" for _ in range(head.count("|") - 1)) + "|"]
    for r in rs:
        lines.append(f"| {r['body']} | {r['dof']} | {-r['cfd_dq']:.4g} | "
                     f"{100 * r['gci']:.1f} % | {r['strips_ratio']:.3f} | {r['ratio']:.3f} | "
                     f"{'yes' if id(r) in counted else 'no'} |")
    use = summary_rows(rs)
    for key, label in (("strips_ratio", "before (strips)"), ("ratio", "after (surface)")):
        ln = np.log([r[key] for r in use])
        lines.append(f"\n{label}: {len(use)} rows, model/CFD {np.exp(ln.min()):.3g} to "
                     f"{np.exp(ln.max()):.3g}, geometric mean {np.exp(ln.mean()):.3g}, rms "
                     f"|ln| {np.sqrt(np.mean(ln ** 2)):.2f}, sd(ln) {np.std(ln, ddof=1):.2f}")
    return "\n".join(lines)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m benchmarks.cfd_rotation", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--shapes", action="store_true", help="write the shapes' STL files")
    p.add_argument("--list", action="store_true", help="print every reference's command")
    p.add_argument("--run", nargs=2, metavar=("SHAPE", "DOF"), help="run one reference")
    p.add_argument("--table", action="store_true",
                   help="print the stored results as markdown (cells, y+, cost)")
    p.add_argument("--rotational", action="store_true",
                   help="the model's rotational damping against every stored CFD rotation, "
                        "before (strips) and after (surface pressure drag)")
    args = p.parse_args(argv)
    if args.rotational:
        print(rotational())
    if args.table:
        print(table())
    if args.shapes:
        for path in make_shapes():
            print(path.relative_to(ROOT))
    if args.list:
        for shape, dof in RUNS:
            print("stripcoef " + shlex.join(command(shape, dof)))
    if args.run:
        import os

        from stripcoef.cli.app import main as cli

        key = tuple(args.run)
        if key not in RUNS:
            p.error(f"no reference {key}; expected one of {sorted(RUNS)}")
        os.chdir(ROOT)
        return cli(command(*key))
    return 0


if __name__ == "__main__":
    sys.exit(main())
