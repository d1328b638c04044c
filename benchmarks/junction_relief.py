"""3D survival of the 2D added mass of short rings: axisymmetric tubes and a short frame junction.

Run:  .venv/bin/python benchmarks/junction_relief.py tubes     (about 1 minute, < 1 GB)
      .venv/bin/python benchmarks/junction_relief.py frames    (a few minutes, ~3 GB)

tubes:  transverse and axial added mass of short circular tubes (length l, bore r_i, outer r_o)
        from stripcoef.corrections.ring_body_added_mass against Capytaine on a
        RotationSymmetricMesh of the same tube (direct method, no free surface), and the ratio
        to the 2D annulus rho pi (r_o^2 + r_i^2) l.
frames: see main_frames.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import logging
import sys
import time

import numpy as np

from stripcoef.corrections import ring_body_added_mass

RHO = 1000.0


def _profile(l, ri, ro, n_len, n_wall):
    """Closed (r, z) profile of a tube wall, counter-clockwise (Capytaine's outward normals)."""
    def seg(a, b, n):
        t = 0.5 * (1.0 - np.cos(np.pi * np.arange(n) / n))
        return a[None, :] + t[:, None] * (b - a)[None, :]
    c = [np.array(p, float) for p in ((ro, -l / 2), (ro, l / 2), (ri, l / 2), (ri, -l / 2))]
    pts = np.vstack([seg(c[0], c[1], n_len), seg(c[1], c[2], n_wall),
                     seg(c[2], c[3], n_len), seg(c[3], c[0], n_wall), c[0][None, :]])
    return pts


def capytaine_tube(l, ri, ro, n_len=40, n_wall=16, n_circ=64):
    """Capytaine on a tube about its axis (Capytaine's z = our x): our [m11, m22, m66 about the
    centre]."""
    import capytaine as cpt
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    prof = _profile(l, ri, ro, n_len, n_wall)
    pts = np.column_stack([prof[:, 0], np.zeros(len(prof)), prof[:, 1]])
    c, s = np.cos(2 * np.pi / n_circ), np.sin(2 * np.pi / n_circ)
    rot = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    n = len(pts)
    verts = np.concatenate([pts, pts @ rot.T])
    faces = np.array([(i, i + n, i + n + 1, i + 1) for i in range(n - 1)])
    mesh = cpt.RotationSymmetricMesh(wedge=cpt.Mesh(vertices=verts, faces=faces), n=n_circ)
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)))
    dofs = ("Heave", "Surge", "Pitch")
    pbs = [cpt.RadiationProblem(body=body, radiating_dof=d, free_surface=np.inf, omega=np.inf,
                                rho=RHO) for d in dofs]
    res = cpt.BEMSolver(method="direct").solve_all(pbs, progress_bar=False)
    return np.array([res[k].added_mass[d] for k, d in enumerate(dofs)]), (n - 1) * n_circ


def main_tubes():
    ro = 0.3
    print("| r_i/r_o | l/(2 r_i) | ours m22 / 2D | Capytaine m22 / 2D | diff | ours m11 | Capytaine m11 "
          "| ours m66 | Capytaine m66 | faces | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for ri in (0.15, 0.24, 0.27):
        for lr in (0.1, 0.25, 0.5, 1.0, 2.0):
            l = lr * 2 * ri
            ours = ring_body_added_mass([-l / 2, l / 2, l / 2, -l / 2], [ri, ri, ro, ro], rho=RHO)
            t0 = time.perf_counter()
            ref, faces = capytaine_tube(l, ri, ro)
            sec = time.perf_counter() - t0
            m2d = RHO * np.pi * (ro ** 2 + ri ** 2) * l
            print(f"| {ri / ro:.2f} | {lr:.2f} | {ours[1, 1] / m2d:.4f} | {ref[1] / m2d:.4f} | "
                  f"{100 * (ours[1, 1] - ref[1]) / ref[1]:+.2f} % | {ours[0, 0]:.4g} | {ref[0]:.4g} | "
                  f"{ours[5, 5]:.4g} | {ref[2]:.4g} | {faces} | {sec:.1f} |", flush=True)


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else "tubes"
    {"tubes": main_tubes}[what]()
