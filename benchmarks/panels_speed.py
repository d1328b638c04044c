"""Speed of the 3D panel method (stripcoef.hull.panels) on ~100k-face meshes, in one run.

Run:  OPENBLAS_NUM_THREADS=1 python -m benchmarks.panels_speed

1. A triaxial ellipsoid (0.30, 0.15, 0.08 m) of ~100k faces (vertex-clustered icosphere):
   panel_added_mass (coarsening + two solves + extrapolation) against Lamb's exact diagonal,
   best of 3; then the full model (stripcoef.assembly.estimate.estimate, M_A by the panels,
   damping and rigid-body terms by the strips) against the strips alone, best of 3.
2. The BlueROV2-Heavy-like frame of benchmarks/bluff_shapes.py (the former
   geometry/bluerov2_heavy.stl) refined to ~100k faces
   (longest-edge bisection: the same surface): panel_added_mass, best of 3, and its diagonal
   against the stored Richardson BEM of reference_tables/bem/bem_bluff.csv -- or the error that
   refuses it (its thin members need more panels than MAX_PANELS allows).
Times exclude start-up (imports) and reading/repairing the mesh (MeshBody in memory).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
import trimesh

ROOT = Path(__file__).resolve().parents[1]
from benchmarks.mesh_speed import best  # noqa: E402  (best of n wall times)


def main():
    from stripcoef.assembly.estimate import estimate
    from stripcoef.fluid import Fluid
    from stripcoef.geometry.mesh import mesh_body
    from stripcoef.geometry.vehicle import Vehicle
    from stripcoef.hull import panels as P
    from stripcoef.hull.lamb import ellipsoid_added_mass

    rho = 1000.0
    axes = (0.30, 0.15, 0.08)
    ico = trimesh.creation.icosphere(subdivisions=7)
    ico.apply_scale(axes)
    v, f = P._cluster(np.asarray(ico.vertices), np.asarray(ico.faces), 0.003)
    body = mesh_body(trimesh.Trimesh(v, f), name="ellipsoid")
    (a, info), dt = best(lambda: P.panel_added_mass(body, rho=rho))
    err = np.diag(a) / ellipsoid_added_mass(*axes, rho=rho) - 1.0
    print(f"ellipsoid {len(body.mesh.faces)} faces: panel_added_mass {dt:.3f} s, panels "
          f"{info['panels']}, diagonal vs Lamb {np.array2string(100 * err, precision=2)} %")
    veh = Vehicle.from_mesh(body, fluid=Fluid(rho, 1e-6, "benchmark"))
    _, tp = best(lambda: estimate(veh, added_mass_method="panels"))
    _, ts = best(lambda: estimate(veh))
    print(f"  full model: estimate(added_mass_method='panels') {tp:.3f} s, strips alone "
          f"{ts:.3f} s")

    from benchmarks import bluff_shapes as B

    stl = B._bluerov2()          # the frame of the stored BEM reference
    base = mesh_body(stl, name="bluerov2").mesh
    base.apply_translation(-base.center_mass)
    rv, rf = P.refine(np.asarray(base.vertices), np.asarray(base.faces), 100_000)
    rov = mesh_body(trimesh.Trimesh(rv, rf), name="bluerov2_100k")
    from stripcoef.errors import InputError

    try:
        (a, info), dt = best(lambda: P.panel_added_mass(rov, rho=rho))
    except InputError as exc:       # thin members: coarsening them changes the volume
        print(f"bluerov2_heavy refined to {len(rov.mesh.faces)} faces: refused: {exc}")
        return 0
    ref = np.diag(B.read_references()["bluerov2_heavy"])
    print(f"bluerov2_heavy refined to {len(rov.mesh.faces)} faces: panel_added_mass {dt:.3f} s, "
          f"panels {info['panels']}, diagonal vs BEM "
          f"{np.array2string(100 * (np.diag(a) / ref - 1), precision=1)} %")
    return 0


if __name__ == "__main__":
    sys.exit(main())
