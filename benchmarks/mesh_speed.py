"""Speed of the mesh pipeline, and strip theory vs the BEM at equal accuracy, in one run.

Run:  .venv/bin/python benchmarks/mesh_speed.py             (about 1-2 minutes, ~3 GB peak)

1. A ~100k-face Myring (REMUS) hull as an STL file -> full matrices (M_A, D_L, D_Q, M_RB):
   wall time of each stage (read + repair, slicing into 200 strips, 2D panel method,
   axisymmetric 3D corrections given the 2D sections, the whole stripcoef.assemble.estimate) --
   best of 3; the total re-solves the 2D sections for the corrections (until they are wired
   into assemble, which has them already).
2. Prolate spheroid L/D = 7.5 as a triangle mesh (as from CAD, no symmetry used): strip theory
   with the axisymmetric corrections vs Capytaine (direct, no free surface) at 1.5k, 3k and
   6k faces, every diagonal term against Lamb's exact values.  The speed ratio is taken against
   the smallest BEM mesh that is at least as accurate as strip theory, or, when none of the
   measured ones is, against the largest (a lower bound on the ratio).
"""

from __future__ import annotations

import os

# many small dense solves: a multi-threaded BLAS spins on a loaded 2-core machine (measured:
# a 160x160 solve takes 19 ms with OpenBLAS threads, 0.14 ms with one); set before numpy loads
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mesh_accuracy import FLUID, RHO, lamb, strip_variants  # noqa: E402
from mesh_shapes import body_of_revolution, myring_profile, spheroid_profile  # noqa: E402

from stripcoef.assemble import displaced_volume, estimate  # noqa: E402
from stripcoef.bem import bem_added_mass  # noqa: E402
from stripcoef.corrections import hull_corrections, strip_section_added_mass  # noqa: E402
from stripcoef.geometry.mesh import load_mesh, mesh_body  # noqa: E402
from stripcoef.geometry.vehicle import MassSpec, Vehicle  # noqa: E402
from stripcoef.sections.panel import added_mass_sections  # noqa: E402


def best(fn, n=3):
    out, times = None, []
    for _ in range(n):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return out, min(times)


def pipeline(path, strips=200):
    with tempfile.TemporaryDirectory():
        body, t_load = best(lambda: load_mesh(path))
        x = np.linspace(*body.x_extent(), strips + 1)
        xc, dx = 0.5 * (x[1:] + x[:-1]), np.diff(x)
        parts, t_slice = best(lambda: body.parts(xc, dx))
        _, t_panel = best(lambda: added_mass_sections(parts[0].contours, rho=RHO, about=None))
        v = Vehicle(name="myring", source=str(path), fluid=FLUID, hull=None, bodies=[body],
                    holes=[], mass=MassSpec(), thrusters=[], reference="center_of_buoyancy")
        st = v.cut(strips)
        _, cb = displaced_volume(st)
        m2d = strip_section_added_mass(st, RHO)
        _, t_corr = best(lambda: hull_corrections(st, rho=RHO, center=cb, section_added_mass=m2d))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            _, t_est = best(lambda: estimate(v, strips=strips))

        def total():
            b = load_mesh(path)
            vv = Vehicle(name="myring", source=str(path), fluid=FLUID, hull=None, bodies=[b],
                         holes=[], mass=MassSpec(), thrusters=[], reference="center_of_buoyancy")
            s = vv.cut(strips)
            _, c = displaced_volume(s)
            hull_corrections(s, rho=RHO, center=c, section_added_mass=strip_section_added_mass(s, RHO))
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                return estimate(vv, strips=strips)
        _, t_total = best(total)
    return {"faces": len(body.mesh.faces), "load": t_load, "slice": t_slice, "panel": t_panel,
            "corrections": t_corr, "estimate": t_est, "total": t_total}


def main():
    print("## 1. 100k-face mesh to full matrices (best of 3, 200 strips)")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "myring.stl"
        mesh = body_of_revolution(myring_profile(400), 128)
        mesh.export(path)
        r = pipeline(path)
    print(f"faces {r['faces']}: read+repair {r['load']:.3f} s, slice {r['slice']:.3f} s, "
          f"2D panel (200 sections) {r['panel']:.3f} s, axisym corrections {r['corrections']:.3f} s, "
          f"assemble.estimate (slice + sections + damping) {r['estimate']:.3f} s; "
          f"file -> matrices incl. corrections (2D sections solved twice) {r['total']:.3f} s")

    print("\n## 2. Spheroid L/D = 7.5 (triangle meshes): strip theory vs Capytaine at equal accuracy")
    ref = np.diag(lamb(1.5, 0.2))
    nz = [0, 1, 2, 4, 5]
    fine = body_of_revolution(spheroid_profile(1.5, 0.2, 400), 256)       # ~100k faces
    (var, ref_pt, body, times), t_strip = best(lambda: strip_variants(fine), n=1)
    err_strip = max(abs(var["axisym"][i, i] / ref[i] - 1) for i in nz) * 100
    # time of the pipeline that produced those numbers: estimate + corrections
    t_s = times["estimate_s"] + times["corrections_s"]
    print(f"strip theory ({len(body.mesh.faces)} faces, 200 strips): max diagonal error "
          f"{err_strip:.3f} %, {t_s:.3f} s (assemble.estimate {times['estimate_s']:.3f} s + "
          f"corrections {times['corrections_s']:.3f} s)")
    rows = []
    for n_ax, n_circ in ((30, 26), (40, 38), (60, 50)):
        m = mesh_body(body_of_revolution(spheroid_profile(1.5, 0.2, n_ax), n_circ), origin="file")
        t0 = time.perf_counter()
        a = bem_added_mass(m, rho=RHO, max_faces=20000)
        t_b = time.perf_counter() - t0
        err = max(abs(a[i, i] / ref[i] - 1) for i in nz) * 100
        rows.append((len(m.mesh.faces), t_b, err))
        print(f"Capytaine {len(m.mesh.faces)} faces: max diagonal error {err:.3f} %, {t_b:.2f} s")
    ok = [r for r in rows if r[2] <= err_strip]
    pick = ok[0] if ok else rows[-1]
    word = "at equal accuracy" if ok else "lower bound (the BEM is still less accurate)"
    print(f"ratio {word}: {pick[1] / t_s:.0f}x ({pick[0]} faces, {pick[1]:.2f} s vs {t_s:.3f} s)")


if __name__ == "__main__":
    main()
