"""How the panel method's rotation about a coarse cylinder's axis converges with the panel
count, on the isotropic remesh and on the prism graded towards its edges (issue 32, branch
roll32g; benchmarks/data/roll32g_trace.md).

For one coarse cylinder of a CAD draw (``benchmarks.cad_shapes``; default seed 1795948662,
shape 4: 12 facets, D 0.31 m, L 0.20 m, axis x), about the origin, its three mirror planes
used: each level of the default estimate (``panel_added_mass``) with
:data:`stripcoef.hull.graded_panels.PRISMS` off (isotropic remeshes) at ``--panels`` N (its
levels N/4 ... 2N), and on (the graded prism, whose coarsest level has at least
:data:`~stripcoef.hull.graded_panels.LEAST_NODES` panels on a facet), each level's
axial-rotation term and the extrapolated value with its estimated error, against the
edge-graded Capytaine reference (``reference_tables/bem/graded_coarse_SEED.csv``, Eça &
Hoekstra's least squares).  CPU seconds per estimate (one BLAS thread).  Usage:

    python -m benchmarks.roll32g_ladder [--seed S --shape K] [--panels 800 1600 3000 6000]
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import trimesh  # noqa: E402

from benchmarks.graded_polyhedra import coarse_of_seed, mirror_axes  # noqa: E402
from stripcoef.hull import graded_panels as G  # noqa: E402
from stripcoef.hull import panels as P  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def main(argv=None) -> int:
    from validation.cad_shapes import fine_reference
    from validation.graded_bodies import read

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=1795948662)
    ap.add_argument("--shape", type=int, default=4)
    ap.add_argument("--panels", type=int, nargs="+", default=[800, 1600, 3000, 6000])
    args = ap.parse_args(argv)
    what, v, f = coarse_of_seed(args.seed, 40, [args.shape])[args.shape]
    _, n, mats = read(ROOT / "reference_tables" / "bem" / f"graded_coarse_{args.seed}.csv")[
        args.shape]
    ref, band, _ = fine_reference(n, mats)
    prism = G.prism_faces(v, f)
    i = 3 + int(np.argmax(np.abs(prism.axis)))
    name = "surge sway heave roll pitch yaw".split()[i]
    print(f"seed {args.seed} shape {args.shape}: {what}; its {name} (the axial rotation): "
          f"edge-graded Capytaine {ref[i, i]:.6g} kg m^2 (band {band[i, i]:.2g}, levels "
          f"{'/'.join(map(str, n))} faces)\n")
    planes = tuple("xyz"[a] for a in mirror_axes(v))
    mesh = trimesh.Trimesh(v, f, process=False)
    saved = G.PRISMS
    print("| panelling | N | levels (panels: value) | extrapolated | estimate | error | CPU [s] |")
    print("|---|---|---|---|---|---|---|")
    try:
        for on in (False, True):
            G.PRISMS = on
            for panels in args.panels:
                P._solved_level.cache_clear()          # each estimate solved, not recalled
                c0 = time.process_time()
                a, info = P.panel_added_mass(mesh, rho=1000.0, panels=panels, mirrors=planes)
                cpu = time.process_time() - c0
                lv = ", ".join(f"{c}: {m[i, i]:.4g}" for c, m in zip(info["panels"],
                                                                    info["levels"]))
                print(f"| {'graded prism' if on else 'isotropic remesh'} | {panels} | {lv} | "
                      f"{a[i, i]:.4g} | {100 * info['estimate'][i, i] / a[i, i]:.1f} % | "
                      f"{100 * (a[i, i] / ref[i, i] - 1):+.1f} % | {cpu:.2f} |", flush=True)
    finally:
        G.PRISMS = saved
    return 0


if __name__ == "__main__":
    sys.exit(main())
