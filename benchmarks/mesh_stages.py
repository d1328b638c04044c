"""Where strip theory's time goes at the 0.2 % rung of benchmarks/mesh_speed.py.

Run:  .venv/bin/python -m benchmarks.mesh_stages [--repeat 15]     (about 10 s)

The configuration is the cheapest one as accurate as the largest BEM that fits the project
machine (docs/performance.md, "Speed"): the prolate spheroid L/D = 7.5 as a 22,848-face
triangle mesh, 75 strips, 64 meridian panels in the 3D corrections, 32 panels per 2D section.
Each stage is timed alone (best of ``--repeat``); the stages inside ``estimate`` are found by
difference, since each call re-cuts the strips:

- mesh checks and repair: ``mesh_body`` on the triangle arrays;
- slicing: ``Vehicle.cut`` (slice_rings, section properties);
- 2D sections: ``added_mass(corrections=False)`` minus slicing;
- 3D corrections: ``added_mass(corrections=True)`` minus ``added_mass(corrections=False)``;
- damping: ``damping_matrices`` minus slicing;
- total: ``strip_model`` of mesh_speed.py (mesh checks + the whole ``estimate``).
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")      # many small solves: one BLAS thread (see mesh_speed)

import argparse  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402

import trimesh  # noqa: E402

from benchmarks.mesh_speed import spheroid_mesh, spheroid_vehicle, strip_model  # noqa: E402

from stripcoef.assembly import added_mass as assembly_added_mass, damping as assembly_damping, mass as assembly_mass  # noqa: E402
from stripcoef.geometry.mesh import mesh_body  # noqa: E402

#: the 0.2 % configuration: (meridian intervals, panels around) of the mesh, strips,
#: correction panels, section panels
MESH, STRIPS, PANELS, SECTION_PANELS = (120, 96), 75, 64, 32
RHO, NU, SPEED = 1025.0, 1.0e-6, 1.0


def best_ms(fn, n):
    """Best wall time of ``n`` calls [ms] (after one warm-up call)."""
    fn()
    times = []
    for _ in range(n):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return 1e3 * min(times)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=15, help="best of N per stage (default 15)")
    n = ap.parse_args(argv).repeat
    warnings.simplefilter("ignore")
    mesh = spheroid_mesh(*MESH)
    v, f = mesh.vertices, mesh.faces
    body = mesh_body(trimesh.Trimesh(v, f, process=False), origin="file", name="spheroid")
    vehicle = spheroid_vehicle(body)
    strips = vehicle.cut(STRIPS)
    volume, cb = assembly_mass.displaced_volume(strips)

    def am(corr):
        return assembly_added_mass.added_mass(vehicle.cut(STRIPS), RHO, about=cb, volume=volume, center=cb,
                                   corrections=corr, correction_panels=PANELS,
                                   section_panels=SECTION_PANELS)

    t_body = best_ms(lambda: mesh_body(trimesh.Trimesh(v, f, process=False), origin="file"), n)
    t_cut = best_ms(lambda: vehicle.cut(STRIPS), n)
    t_pure = best_ms(lambda: am(False), n)
    t_corr = best_ms(lambda: am(True), n)
    t_damp = best_ms(lambda: assembly_damping.damping_matrices(vehicle.cut(STRIPS), vehicle, RHO, NU, SPEED, cb,
                                               "auto"), n)
    t_all = best_ms(lambda: strip_model(v, f, STRIPS, PANELS, SECTION_PANELS), n)
    print(f"{len(f):,} faces, {STRIPS} strips, {PANELS} correction panels, {SECTION_PANELS} "
          f"section panels; best of {n} [ms]")
    print("| stage | time |\n|---|---|")
    for name, t in (("mesh checks and repair (`mesh_body`)", t_body),
                    ("slicing and section properties (`Vehicle.cut`)", t_cut),
                    ("2D sections (panel method)", t_pure - t_cut),
                    ("3D corrections (two axisymmetric solves)", t_corr - t_pure),
                    ("damping (cross-flow drag, friction)", t_damp - t_cut),
                    ("total, `strip_model` of mesh_speed.py", t_all)):
        print(f"| {name} | {t:.1f} ms |")


if __name__ == "__main__":
    main()
