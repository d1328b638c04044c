"""Direct (Green's identity) against source (indirect) formulation of the 3D panel method.

Run:  OPENBLAS_NUM_THREADS=1 python -m benchmarks.panels_formulations

Same panels, same collocation points, same exact near-field integrals: the direct method of
stripcoef.hull.panels.solve_added_mass, and the source method

    (-1/2 I + K) sigma = N,   Phi = S sigma,   A = -rho N^T diag(a) Phi

(Hess & Smith 1967; Katz & Plotkin 2001, sec. 9.3), K_kl = n_k . grad_x of the source integral
of panel l, exact within 2 diameters (in-plane part -sum_edges u_e ln((R+ + s+)/(R- + s-)) by the
divergence theorem on the panel, normal part the solid angle; Wilton et al. 1984), one point
beyond.  Single resolutions (no extrapolation) against Lamb's exact values (sphere, triaxial
ellipsoid) and the stored Richardson BEM (a box), at two panel counts each.
"""

from __future__ import annotations

import os
import sys

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
import scipy.linalg
import trimesh



def source_gradient(points, tri, normal):
    """(k, 3) gradient at ``points`` of (1/4 pi) int_T dS / |x - xi| over flat triangles."""
    R = tri - points[:, None, :]
    r = np.linalg.norm(R, axis=2)
    num = np.einsum("ij,ij->i", R[:, 0], np.cross(R[:, 1], R[:, 2]))
    den = (r[:, 0] * r[:, 1] * r[:, 2] + np.einsum("ij,ij->i", R[:, 0], R[:, 1]) * r[:, 2]
           + np.einsum("ij,ij->i", R[:, 0], R[:, 2]) * r[:, 1]
           + np.einsum("ij,ij->i", R[:, 1], R[:, 2]) * r[:, 0])
    omega = 2.0 * np.arctan2(num, den)
    h = -np.einsum("ij,ij->i", R[:, 0], normal)
    g = np.zeros_like(points)
    for k in range(3):
        a, b = R[:, k], R[:, (k + 1) % 3]
        edge = b - a
        ln = np.linalg.norm(edge, axis=1)
        lt = edge / ln[:, None]
        u = np.cross(lt, normal)
        t0 = np.einsum("ij,ij->i", a, u)
        sm = np.einsum("ij,ij->i", a, lt)
        r0 = np.sqrt(t0 * t0 + h * h)
        ok = r0 > 1e-12 * ln
        r0 = np.where(ok, r0, 1.0)
        fe = np.where(ok, np.arcsinh((sm + ln) / r0) - np.arcsinh(sm / r0), 0.0)
        g -= u * fe[:, None]
    g += normal * omega[:, None]
    return g / (4.0 * np.pi)


def source_added_mass(tri, rho, near_factor=2.0):
    from stripcoef.hull.panels import _frames, generalised_normals, influence_matrices

    c, n, area, diam = _frames(tri)
    s, _ = influence_matrices(tri)
    d = c[:, None, :] - c[None, :, :]
    r2 = np.einsum("klm,klm->kl", d, d)
    np.fill_diagonal(r2, 1.0)
    # far: grad of A/(4 pi r) = -A (x - c) / (4 pi r^3), projected on n_k
    kmat = -np.einsum("klm,km->kl", d, n) * r2 ** -1.5 * (area / (4 * np.pi))[None, :]
    near = r2 < (near_factor * diam[None, :]) ** 2
    np.fill_diagonal(near, False)
    k, l = np.nonzero(near)
    g = source_gradient(c[k], tri[l], n[l])
    kmat[k, l] = np.einsum("ij,ij->i", g, n[k])
    np.fill_diagonal(kmat, 0.0)
    nrm = generalised_normals(c, n)
    lhs = kmat
    lhs[np.diag_indices_from(lhs)] -= 0.5
    sigma = scipy.linalg.solve(lhs, nrm)
    return -rho * (nrm * area[:, None]).T @ (s @ sigma)


def _richardson(pairs):
    (n1, a1), (n2, a2) = pairs
    return (n2 * a2 - n1 * a1) / (n2 - n1)


def main():
    from benchmarks import bluff_shapes as B

    from stripcoef.hull.lamb import ellipsoid_added_mass
    from stripcoef.hull.panels import refine, solve_added_mass, split_in_four

    rho = 1000.0
    refs = B.read_references()
    print("| body | panels | direct: worst diagonal error | source: worst diagonal error |")
    print("|---|---|---|---|")
    for name, axes in (("sphere", (0.15, 0.15, 0.15)), ("triaxial_long", (0.3, 0.15, 0.08))):
        exact = ellipsoid_added_mass(*axes, rho=rho)
        on = exact > 1e-9 * exact.max()
        mats = {}
        for sub in (3, 4):
            m = trimesh.creation.icosphere(subdivisions=sub)
            m.apply_scale(axes)
            out = []
            for fn in (solve_added_mass, source_added_mass):
                a = fn(m.triangles, rho=rho)
                mats.setdefault(fn.__name__, []).append((len(m.faces), a))
                out.append(np.max(np.abs(np.diag(a)[on] / exact[on] - 1.0)))
            print(f"| {name} (Lamb) | {len(m.faces)} | {100 * out[0]:.2f} % | {100 * out[1]:.2f} % |")
        out = [np.max(np.abs(np.diag(_richardson(mats[k]))[on] / exact[on] - 1.0))
               for k in ("solve_added_mass", "source_added_mass")]
        print(f"| {name} (Lamb) | Richardson 1/N | {100 * out[0]:.2f} % | {100 * out[1]:.2f} % |")
    box = trimesh.creation.box([0.46, 0.58, 0.25])
    ref = np.diag(refs["box_bluerov"])
    v, f = refine(np.asarray(box.vertices), np.asarray(box.faces), 400)
    mats = {}
    for vv, ff in ((v, f), split_in_four(v, f)):
        out = []
        for fn in (solve_added_mass, source_added_mass):
            a = fn(vv[ff], rho=rho)
            mats.setdefault(fn.__name__, []).append((len(ff), a))
            out.append(np.max(np.abs(np.diag(a) / ref - 1.0)))
        print(f"| box 0.46 x 0.58 x 0.25 (BEM) | {len(ff)} | {100 * out[0]:.2f} % | "
              f"{100 * out[1]:.2f} % |")
    out = [np.max(np.abs(np.diag(_richardson(mats[k])) / ref - 1.0))
           for k in ("solve_added_mass", "source_added_mass")]
    print(f"| box 0.46 x 0.58 x 0.25 (BEM) | Richardson 1/N | {100 * out[0]:.2f} % | "
          f"{100 * out[1]:.2f} % |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
