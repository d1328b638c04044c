"""Accuracy of strip theory on meshes against Lamb and converged Capytaine BEM.

Run:  .venv/bin/python -m benchmarks.mesh_accuracy            (about 2-4 minutes, ~3 GB peak)
      .venv/bin/python -m benchmarks.mesh_accuracy --quick    (bodies of revolution only)

For each body: strip theory on a fine mesh (200 strips) in three variants --
``pure`` (no 3D corrections), ``axisym`` (stripcoef.hull.corrections alone: one axisymmetric BEM of
the added-mass-equivalent bodies of revolution of the whole body) and ``default``
(stripcoef.assembly.estimate.estimate as shipped: the same, but per member and junction for a body made
of several members, stripcoef.hull.members) -- against
the reference: Lamb's exact spheroid values, or Capytaine (direct, no free surface).
Prints markdown tables (per cent error of every non-zero diagonal term, and the couplings).
"""

from __future__ import annotations

import os

# many small dense solves: a multi-threaded BLAS spins on a loaded 2-core machine (measured:
# a 160x160 solve takes 19 ms with OpenBLAS threads, 0.14 ms with one); set before numpy loads
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse
import logging
import time
import warnings

import numpy as np

from benchmarks.mesh_shapes import (body_of_revolution, capsule_profile, finned_torpedo,  # noqa: E402
                         myring_profile, open_frame_rov, refine_to, spheroid_profile)

from stripcoef.assembly.estimate import displaced_volume, estimate  # noqa: E402
from stripcoef.assembly.added_mass import entrained_water  # noqa: E402
from stripcoef.assembly.added_mass import section_matrices  # noqa: E402
from stripcoef.strips import strip_added_mass  # noqa: E402
from stripcoef.conventions import transform_matrix  # noqa: E402
from stripcoef.hull.corrections import apply_corrections, hull_corrections, strip_section_added_mass  # noqa: E402
from stripcoef.fluid import Fluid  # noqa: E402
from stripcoef.geometry.mesh import mesh_body  # noqa: E402
from stripcoef.geometry.vehicle import MassSpec, Vehicle  # noqa: E402
from stripcoef.hull.lamb import spheroid_added_mass  # noqa: E402

RHO = 1000.0
FLUID = Fluid(density=RHO, kinematic_viscosity=1e-6, source="benchmark")
DOF = ("surge", "sway", "heave", "roll", "pitch", "yaw")


def lamb(length, diameter):
    """Lamb's exact 6x6 added mass of a spheroid (stripcoef.hull.lamb.spheroid_added_mass)."""
    return np.diag(spheroid_added_mass(0.5 * length, 0.5 * diameter, rho=RHO))

def strip_variants(mesh, strips=200):
    body = mesh_body(mesh, origin="file", name="body")
    v = Vehicle(name="body", source="benchmark", fluid=FLUID, hull=None, bodies=[body], holes=[],
                mass=MassSpec(), thrusters=[], reference="center_of_buoyancy")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0 = time.perf_counter()
        main = estimate(v, strips=strips)
        t_main = time.perf_counter() - t0
        pure = estimate(v, strips=strips, corrections=False)
    st = v.cut(strips)
    _, cb = displaced_volume(st)
    t0 = time.perf_counter()
    m2d = strip_section_added_mass(st, RHO)
    c = hull_corrections(st, rho=RHO, center=cb, section_added_mass=m2d)
    t_corr = time.perf_counter() - t0
    m = apply_corrections(strip_added_mass(st, section_matrices(st, RHO), cb), c)
    axi = transform_matrix(m, from_point=cb, to_point=main.reference_point) + \
        entrained_water(st, RHO, main.reference_point)
    pure_m = pure.added_mass.copy()
    pure_m[0, 0] = 0.0                     # pure strip theory has no axial term
    return {"pure": pure_m, "axisym": 0.5 * (axi + axi.T), "default": main.added_mass}, \
        main.reference_point, body, {"estimate_s": t_main, "corrections_s": t_corr}


def capytaine_symmetric(profile, n_axial=160, n_circ=80, ref=(0.0, 0.0, 0.0)):
    """Capytaine on a RotationSymmetricMesh (axis z there; ours x = its z, y = its x, z = its y)."""
    import capytaine as cpt
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    x, r = profile
    s = np.r_[0.0, np.cumsum(np.hypot(np.diff(x), np.diff(r)))]
    t = np.interp(s[-1] * 0.5 * (1 - np.cos(np.linspace(0, np.pi, n_axial + 1))), s, np.arange(s.size))
    xs, rs = np.interp(t, np.arange(s.size), x), np.interp(t, np.arange(s.size), r)
    pts = np.column_stack([rs, np.zeros_like(rs), xs])
    mesh = cpt.RotationSymmetricMesh.from_profile_points(pts, n=n_circ)
    center = (ref[1], ref[2], ref[0])
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=center))
    dofs = ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"]
    pbs = [cpt.RadiationProblem(body=body, radiating_dof=d, free_surface=np.inf, omega=np.inf,
                                rho=RHO) for d in dofs]
    t0 = time.perf_counter()
    res = cpt.BEMSolver(method="direct").solve_all(pbs, progress_bar=False)
    sec = time.perf_counter() - t0
    a = np.array([[r.added_mass[d] for d in dofs] for r in res]).T
    p = [2, 0, 1, 5, 3, 4]
    a = a[np.ix_(p, p)]
    return 0.5 * (a + a.T), sec


def capytaine_general(mesh, ref):
    from stripcoef.bem import bem_added_mass
    t0 = time.perf_counter()
    a = bem_added_mass(mesh, rho=RHO, reference_point=ref, max_faces=20000)
    return a, time.perf_counter() - t0


def pct(a, b):
    return 100.0 * (a - b) / abs(b) if abs(b) > 0 else float("nan")


def report(name, variants, ref, ref_name, extra=""):
    nonzero = [i for i in range(6) if ref[i, i] > 1e-6 * np.abs(np.diag(ref)).max()]
    rows = []
    for key in ("pure", "axisym", "default"):
        m = variants[key]
        errs = [pct(m[i, i], ref[i, i]) for i in nonzero]
        rows.append(f"| {name} | {key} | " + " | ".join(f"{DOF[i]} {e:+.2f}" for i, e in zip(nonzero, errs))
                    + f" | {max(abs(e) for e in errs):.2f} |")
    print(f"\n{name}: reference {ref_name} {extra}")
    print("reference diagonal:", np.array2string(np.diag(ref), precision=5))
    for r in rows:
        print(r)
    from stripcoef.cli.compare import compare_rows
    for r in compare_rows(variants["default"], ref):
        if r["i"] == r["j"]:
            continue
        i, j = r["i"], r["j"]
        print(f"  coupling M[{i},{j}]: reference {ref[i, j]:.5g}, default {variants['default'][i, j]:.5g}, "
              f"axisym {variants['axisym'][i, j]:.5g}, pure {variants['pure'][i, j]:.5g}")
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="bodies of revolution only")
    args = ap.parse_args()
    print("| body | strip variant | error per diagonal term [%] | max abs [%] |")
    # spheroids vs Lamb
    for ld in (2, 4, 6, 8, 10, 12):
        var, _, body, _ = strip_variants(body_of_revolution(spheroid_profile(1.5, 1.5 / ld), 128))
        report(f"spheroid L/D={ld} ({len(body.mesh.faces)} faces)", var, lamb(1.5, 1.5 / ld), "Lamb (exact)")
    # capsule vs Capytaine (symmetric mesh, 12800 panels)
    prof = capsule_profile()
    var, ref_pt, body, _ = strip_variants(body_of_revolution(prof, 128))
    ref, sec = capytaine_symmetric(prof, ref=ref_pt)
    report(f"capsule L/D=7.5 ({len(body.mesh.faces)} faces)", var, ref,
           f"Capytaine RotationSymmetricMesh 160x80 ({sec:.1f} s)")
    prof = myring_profile()
    var, ref_pt, body, _ = strip_variants(body_of_revolution(prof, 128))
    ref, sec = capytaine_symmetric(prof, ref=ref_pt)
    report(f"Myring (REMUS) ({len(body.mesh.faces)} faces)", var, ref,
           f"Capytaine RotationSymmetricMesh 160x80 ({sec:.1f} s)")
    if args.quick:
        return
    # finned torpedo and open-frame ROV vs Capytaine on general meshes (no symmetry)
    for name, fine, coarse in (("finned torpedo", finned_torpedo(), finned_torpedo(n_profile=40, sections=24)),
                               ("open-frame ROV", refine_to(open_frame_rov(), 20000), open_frame_rov())):
        var, ref_pt, body, _ = strip_variants(fine)
        refs = []
        for n in (3000, 6000):
            mb = mesh_body(refine_to(coarse, n), origin="file")
            a, sec = capytaine_general(mb, ref_pt)
            refs.append((len(mb.mesh.faces), a, sec))
        conv = np.max(np.abs(np.diag(refs[1][1] - refs[0][1])) / np.maximum(np.abs(np.diag(refs[1][1])), 1e-300)) * 100
        report(f"{name} ({len(body.mesh.faces)} faces)", var, refs[1][1],
               f"Capytaine general mesh {refs[1][0]} faces ({refs[1][2]:.1f} s)",
               f"[{refs[0][0]} -> {refs[1][0]} faces changes the diagonal by at most {conv:.2f} %]")


if __name__ == "__main__":
    main()
