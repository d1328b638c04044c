"""Convergence of the Capytaine references of the finned torpedo and the open-frame ROV.

Run:  .venv/bin/python -m benchmarks.mesh_reference_convergence   (about 6 minutes, ~6 GB peak)

The BEM (direct, no free surface) about the strip model's centre of buoyancy:
- finned torpedo: three refinements of its coarse general mesh (the two finest are those of
  benchmarks/mesh_accuracy.py);
- open-frame ROV: four refinements of its quarter mesh with Capytaine's two reflection
  symmetries (ReflectionSymmetricMesh, xOz and yOz: same matrices as the full mesh, a quarter
  of the memory), up to 25k faces.
With face counts N1 < N2 < N3 (the three finest) and a discretisation error ~ N^(-p/2) (p: order
in the panel size h ~ N^(-1/2)), p is fitted per term and the converged value extrapolated
(Richardson).  Then the strip model as shipped (stripcoef.assembly.estimate.estimate, 200 strips) against
the finest BEM and the extrapolated value.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import warnings

import numpy as np
from scipy.optimize import brentq

from benchmarks.mesh_accuracy import DOF, RHO, capytaine_general, strip_variants  # noqa: E402
from benchmarks.mesh_shapes import finned_torpedo, open_frame_rov, open_frame_rov_quarter, refine_to  # noqa: E402

from stripcoef.geometry.mesh import mesh_body  # noqa: E402


def richardson(n, v):
    """Fit v = v_inf + c N^(-q) through three points (q = p/2); returns (v_inf, q) or None."""
    h = np.asarray(n, float)
    d1, d2 = v[1] - v[0], v[2] - v[1]
    if d1 == 0 or d2 / d1 <= 0:
        return None

    def f(q):
        return (h[2] ** -q - h[1] ** -q) / (h[1] ** -q - h[0] ** -q) - d2 / d1

    try:
        q = brentq(f, 0.05, 4.0)
    except ValueError:
        return None
    c = d1 / (h[1] ** -q - h[0] ** -q)
    return v[2] - c * h[2] ** -q, q


def capytaine_quarter(quarter, ref):
    """Capytaine on a quarter mesh with the xOz and yOz reflection symmetries."""
    import logging
    import time

    import capytaine as cpt
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    q = cpt.Mesh(vertices=np.asarray(quarter.vertices, float), faces=np.asarray(quarter.faces, int))
    mesh = cpt.ReflectionSymmetricMesh(half=cpt.ReflectionSymmetricMesh(half=q, plane="xOz"),
                                       plane="yOz")
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=tuple(ref)))
    dofs = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
    pbs = [cpt.RadiationProblem(body=body, radiating_dof=d, free_surface=np.inf, omega=np.inf,
                                rho=RHO) for d in dofs]
    t0 = time.perf_counter()
    res = cpt.BEMSolver(method="direct").solve_all(pbs, progress_bar=False)
    a = np.array([[r.added_mass[d] for d in dofs] for r in res]).T
    return 0.5 * (a + a.T), time.perf_counter() - t0


def main():
    cases = (("finned torpedo", finned_torpedo(), finned_torpedo(n_profile=40, sections=24),
              (1500, 3000, 6000), False),
             ("open-frame ROV", refine_to(open_frame_rov(), 20000), open_frame_rov_quarter(),
              (1000, 2400, 3500, 5000), True))
    for name, fine, coarse, targets, quarter in cases:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            var, ref_pt, _, _ = strip_variants(fine)
        runs = []
        for target in targets:
            if quarter:
                mq = refine_to(coarse, target)
                a, sec = capytaine_quarter(mq, ref_pt)
                faces = 4 * len(mq.faces)
            else:
                mb = mesh_body(refine_to(coarse, target), origin="file")
                a, sec = capytaine_general(mb, ref_pt)
                faces = len(mb.mesh.faces)
            runs.append((faces, np.diag(a), sec))
            print(f"{name}: {faces} faces, {sec:.1f} s, diagonal {np.array2string(runs[-1][1], precision=5)}",
                  flush=True)
        n = [r[0] for r in runs[-3:]]
        ours = np.diag(var["default"])
        print(f"| {name} | term | BEM finest ({runs[-1][0]} faces) | extrapolated | order in h | "
              f"strip default | vs finest | vs extrapolated |")
        for i in range(6):
            v = np.array([r[1][i] for r in runs[-3:]])
            if abs(v[-1]) < 1e-9 * max(abs(r[1]).max() for r in runs):
                continue
            fit = richardson(n, v)
            vinf, q = fit if fit is not None else (float("nan"), float("nan"))
            print(f"| | {DOF[i]} | {v[-1]:.5g} | {vinf:.5g} | {2 * q:.2f} | {ours[i]:.5g} | "
                  f"{100 * (ours[i] - v[-1]) / abs(v[-1]):+.2f} % | {100 * (ours[i] - vinf) / abs(vinf):+.2f} % |")


if __name__ == "__main__":
    main()
