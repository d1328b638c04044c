"""Which stored bodies the graded prism panels reach (issue 32, branch roll32g): a body's
estimate changes only where :func:`stripcoef.hull.graded_panels.prism_faces` reads its
closed surface as a right prism within the default level cap (2 x 1,600 panels) and
:func:`~stripcoef.hull.graded_panels.box_faces` does not take it first.  Checked on the public
vehicle meshes (``--mirror DIR``, as ``benchmarks.public_meshes`` reads them), the shipped
vehicle files (their united surface) and the bluff set; the CAD draws' prisms are listed by
``benchmarks.roll32g_draws``.  Usage:

    python -m benchmarks.roll32g_reach [--mirror DIR]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def reached(body) -> str:
    """"box", "prism" or "-" for a mesh body (a MeshBody, a Trimesh)."""
    from stripcoef.hull import graded_panels as G
    from stripcoef.hull.panels import DEFAULT_PANELS

    m = body.united() if hasattr(body, "united") else getattr(body, "mesh", body)
    v, f = np.asarray(m.vertices, float), np.asarray(m.faces, np.int64)
    if G.box_faces(v, f) is not None:
        return "box"
    return "prism" if G.prism_faces(v, f, 2 * DEFAULT_PANELS) is not None else "-"


def main(argv=None) -> int:
    from benchmarks.bluff_shapes import SHAPES
    from stripcoef.assembly.added_mass import panel_surface
    from stripcoef.geometry.vehicle import load_vehicle
    from stripcoef.hull.panels import DEFAULT_PANELS

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mirror", default=None, help="the public meshes' clones")
    args = ap.parse_args(argv)
    if args.mirror:
        from benchmarks.public_meshes import MESHES, read_from_mirror

        with tempfile.TemporaryDirectory() as tmp:
            for mesh in MESHES:
                try:
                    raw = read_from_mirror(Path(args.mirror), mesh)
                except FileNotFoundError as exc:
                    print(f"public {mesh.name}: not found ({exc})")
                    continue
                found = Path(tmp) / (mesh.name + Path(mesh.path).suffix.lower())
                found.write_bytes(raw)
                try:
                    body = panel_surface(load_vehicle(found), DEFAULT_PANELS)
                except Exception as exc:     # a mesh refused as found: its repair is another file
                    print(f"public {mesh.name}: refused as found ({type(exc).__name__})")
                    continue
                print(f"public {mesh.name}: {reached(body)}", flush=True)
    for path in sorted((ROOT / "geometry").glob("*.yaml")):
        body = panel_surface(load_vehicle(path), DEFAULT_PANELS)
        print(f"vehicle {path.name}: {reached(body)}", flush=True)
    for name, spec in SHAPES.items():
        try:
            m = spec[0](None)
        except TypeError:
            m = spec[0](2000)          # a resolution [faces] (the round bodies)
        print(f"bluff {name}: {reached(m)}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
