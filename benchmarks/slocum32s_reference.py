"""A finer Capytaine reference of one public mesh, solved on its mirror planes (issue 32 trace).

The stored references of benchmarks/public_meshes.py stop at about 8,000 faces (the dense
direct method's memory, 56 N^2 bytes: 3.6 GB).  A body with the mirror planes x = 0 and
y = 0 (about the loaded mesh's origin) is solved here as Capytaine's nested
``ReflectionSymmetricMesh`` (Ancellin & Dias 2019; its reflection-symmetric solve splits the
dense problem into 2^k blocks of N/2^k unknowns), so a whole panelling of 16,000 faces costs
about four solves of 4,000: the quarter body on the planes' positive side is cut and capped
(:func:`stripcoef.hull.mirror_panels.capped_part`), isotropically remeshed at the edge of the
whole panelling asked (:func:`stripcoef.hull.remesh.remesh_isotropic`, the stored
references' mode: crease angle 30 degrees, flips; finer remeshes of the Slocum's quarter are
refused as folded or degenerate), its caps dropped
(:func:`~stripcoef.hull.mirror_panels.drop_caps`), refined by longest-edge bisection to each
level and mirrored by Capytaine.  Prints each
level's diagonal about the origin [kg, kg m^2] (direct method, infinite fluid, rho 1000).
Usage::

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.slocum32s_reference --mirror DIR \
        --base 8000 --faces 8000 16000 [--name slocum]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from benchmarks.public_meshes import MESHES, RHO, read_from_mirror


def quarter_level(v, f, faces: int, base: int, area: float):
    """(vertices, faces) of the quarter x >= 0, y >= 0 remeshed for ``base`` faces of the
    whole panelling, caps dropped, then refined by longest-edge bisection to about ``faces``
    faces of the whole panelling (:func:`stripcoef.hull.bisection.refine`: the same flat
    panels split, so the levels of one base are one nested family), or ``None``."""
    from stripcoef.hull.bisection import refine
    from stripcoef.hull.mirror_panels import capped_part, drop_caps
    from stripcoef.hull.remesh import Mode, edge_for_panels, remesh_isotropic

    part = capped_part(v, f, ("x", "y"))
    if part is None:
        return None
    lv = remesh_isotropic(*part, edge_for_panels(area, base), feature_angle=Mode(30.0))
    if lv is None:
        return None
    q = drop_caps(*lv, ("x", "y"))
    return q if q is None else refine(*q, faces // 4)


def symmetric_added_mass(v, f) -> np.ndarray:
    """M_A about the origin [kg, kg m, kg m^2] of the quarter (v, f) mirrored in y = 0 and
    x = 0 by Capytaine (direct method, infinite fluid)."""
    import capytaine as cpt

    from stripcoef.bem import CAPYTAINE_DOFS

    quarter = cpt.Mesh(vertices=v, faces=f, name="quarter")
    mesh = cpt.ReflectionSymmetricMesh(
        half=cpt.ReflectionSymmetricMesh(half=quarter, plane="xOz"), plane="yOz")
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)),
                            name="body")
    problems = [cpt.RadiationProblem(body=body, radiating_dof=d, free_surface=np.inf,
                                     omega=np.inf, rho=RHO) for d in CAPYTAINE_DOFS]
    results = cpt.BEMSolver(method="direct").solve_all(problems, progress_bar=False)
    a = np.zeros((6, 6))
    for j, res in enumerate(results):
        for i, d in enumerate(CAPYTAINE_DOFS):
            a[i, j] = float(np.real(res.added_mass[d]))
    return 0.5 * (a + a.T)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mirror", required=True, type=Path)
    ap.add_argument("--name", default="slocum")
    ap.add_argument("--faces", type=int, nargs="+", default=(8000, 16000))
    ap.add_argument("--base", type=int, default=8000,
                    help="faces of the whole panelling the quarter is remeshed for")
    args = ap.parse_args(argv)
    from stripcoef.geometry.vehicle import load_vehicle

    mesh = next(m for m in MESHES if m.name == args.name)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / (args.name + Path(mesh.path).suffix)
        path.write_bytes(read_from_mirror(args.mirror, mesh))
        body = load_vehicle(path).bodies[0]
        surface = body.united() if hasattr(body, "united") else body.mesh
    v, f = np.asarray(surface.vertices, float), np.asarray(surface.faces, np.int64)
    for n in args.faces:
        t0 = time.process_time()
        q = quarter_level(v, f, n, args.base, float(surface.area))
        if q is None:
            print(f"{n}: the quarter could not be cut or remeshed")
            continue
        a = symmetric_added_mass(*q)
        print(f"{args.name} asked {n} faces: whole {4 * len(q[1])} faces, diagonal "
              + " ".join(f"{x:.5g}" for x in np.diag(a))
              + f" ({time.process_time() - t0:.1f} s CPU)", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
