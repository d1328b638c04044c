"""The low-polygon ellipsoid 21 of seed 1795948662 (160 faces), whose roll the model puts
+10 % above its edge-graded reference (issue 32, branch roll32g; benchmarks/data/
roll32g_trace.md): the default estimate's isotropic levels at N = 1600, 3000, 6000, and the
panel method on the references' own graded panelling (``benchmarks.graded_polyhedra.
polyhedron_mesh``, each quadrilateral split in two, solved whole) at m = 3 ... 6, against
``reference_tables/bem/graded_cad_1795948662.csv`` (Eça & Hoekstra).  Usage:

    python -m benchmarks.roll32g_ellipsoid
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import trimesh  # noqa: E402

from benchmarks.graded_polyhedra import coarse_of_seed, mirror_axes, polyhedron_mesh  # noqa: E402
from stripcoef.hull import panels as P  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def _triangles(pv, pf):
    """Triangles (n, 3, 3) of quadrilaterals whose degenerate ones repeat their third vertex."""
    out = []
    for q in pf:
        u = list(dict.fromkeys(q.tolist()))
        out += [u[:3]] if len(u) == 3 else [[u[0], u[1], u[2]], [u[0], u[2], u[3]]]
    return pv[np.array(out)]


def main(argv=None) -> int:
    from validation.cad_shapes import fine_reference
    from validation.graded_bodies import read

    what, v, f = coarse_of_seed(1795948662, 40, [21])[21]
    _, n, mats = read(ROOT / "reference_tables" / "bem" / "graded_cad_1795948662.csv")[21]
    ref = fine_reference(n, mats)[0][3, 3]
    planes = tuple("xyz"[a] for a in mirror_axes(v))
    print(f"{what}, mirror planes {planes}; roll reference {ref:.5g} kg m^2 (graded, "
          f"{'/'.join(map(str, n))} faces)")
    mesh = trimesh.Trimesh(v, f, process=False)
    for panels in (1600, 3000, 6000):
        P._solved_level.cache_clear()
        c0 = time.process_time()
        a, info = P.panel_added_mass(mesh, rho=1000.0, panels=panels, mirrors=planes)
        print(f"isotropic, N {panels}: levels " + ", ".join(
            f"{c}: {m[3, 3]:.4g}" for c, m in zip(info["panels"], info["levels"]))
            + f"; extrapolated {a[3, 3]:.4g} ({100 * (a[3, 3] / ref - 1):+.1f} %), CPU "
            f"{time.process_time() - c0:.2f} s", flush=True)
    rot = np.eye(3)
    scale = float(np.ptp(v, axis=0).max())
    for m in (3, 4, 5, 6):
        pv, pf = polyhedron_mesh(v, f, m, rot, ())
        tri = _triangles(pv, pf)
        c0 = time.process_time()
        nn, a = P._solve_level(tri.reshape(-1, 3), np.arange(3 * len(tri)).reshape(-1, 3),
                               scale, 1000.0, (0.0, 0.0, 0.0), P.NEAR_FACTOR, ())
        print(f"graded (the references' panelling), m {m}: {nn} triangles, roll {a[3, 3]:.4g} "
              f"({100 * (a[3, 3] / ref - 1):+.1f} %), CPU {time.process_time() - c0:.2f} s",
              flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
