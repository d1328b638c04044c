"""Thin rectangular plates moving normal to themselves: Capytaine against DNV-RP-H103 table A-2.

Run (from the repository root):
  python -m benchmarks.plate_added_mass          # print the stored results against the table
  python -m benchmarks.plate_added_mass --bem    # recompute them (~5 min, ~2 GB)

The plate is a x b (a the shorter side, a = 1 m) of thickness t, meshed as a box with edges
<= h = sqrt(8 a b / N) (N ~ faces of the full plate), solved on its quarter with two
reflection symmetries (Capytaine, direct method, no free surface, rho = 1000 kg/m^3).
lambda = A_33 / (rho pi/4 a^2 b).  Two levels, (t/a, N) = (0.02, 4000) and (0.01, 8000): the
thickness and the panel size both halve; the thin-plate value is extrapolated linearly in t,
lambda_0 = 2 lambda(t/2) - lambda(t) [assumption: both errors first order in t and h, the edge
singularity of a plate makes the panel error ~ h].  The results are stored in
reference_tables/bem/bem_plates.csv (the thin level of b/a = 4, about 32,000 faces, did not finish
on the 2-core, shared development machine: its process ended without output, presumably out of
memory); they check the table behind
stripcoef.sections.added_mass.plate_chordwise_factor (src/stripcoef/data/plate_added_mass_dnv.csv).
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse
import csv

import numpy as np

from validation.finned import PLATES_DATA as DATA
from validation.finned import load_plates
RHO = 1000.0
RATIOS = (1.0, 2.0, 4.0)
LEVELS = ((0.02, 4000), (0.01, 8000))


def quarter_plate(a, b, t, n_full):
    """The x >= 0, y >= 0 quarter of a box plate b (x) x a (y) x t (z), edges <= sqrt(8ab/N)."""
    import trimesh
    h = np.sqrt(8 * a * b / n_full)
    box = trimesh.creation.box([b, a, t])
    v, f = trimesh.remesh.subdivide_to_size(box.vertices, box.faces, max_edge=h)
    m = trimesh.Trimesh(v, f, process=True)
    q = trimesh.intersections.slice_mesh_plane(m, [1, 0, 0], [0, 0, 0], cap=False)
    return trimesh.intersections.slice_mesh_plane(q, [0, 1, 0], [0, 0, 0], cap=False)


def plate_lambda(ratio, t, n_full):
    """(lambda [-], faces of the full plate) for b/a = ``ratio``, a = 1 m, thickness t [m]."""
    import logging

    import capytaine as cpt
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    a, b = 1.0, ratio
    q = quarter_plate(a, b, t, n_full)
    qm = cpt.Mesh(vertices=np.asarray(q.vertices), faces=np.asarray(q.faces))
    mesh = cpt.ReflectionSymmetricMesh(half=cpt.ReflectionSymmetricMesh(half=qm, plane="xOz"),
                                       plane="yOz")
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)))
    pb = cpt.RadiationProblem(body=body, radiating_dof="Heave", free_surface=np.inf,
                              omega=np.inf, rho=RHO)
    res = cpt.BEMSolver(method="direct").solve(pb)
    return float(np.real(res.added_mass["Heave"])) / (RHO * np.pi / 4 * a * a * b), 4 * len(q.faces)


def run_bem():
    """Solve every (b/a, level) and write each row as soon as it is known (the thin level of
    b/a = 4, about 32,000 faces, may run out of memory on a small machine: the rows before it
    are kept and compare() skips a ratio without both levels)."""
    with open(DATA, "w", newline="") as fh:
        fh.write("# Normal added mass of thin rectangular plates a x b (a = 1 m the shorter side), lambda = A_33 / (rho pi/4 a^2 b) [-].\n"
                 "# Source: computed by python -m benchmarks.plate_added_mass --bem (Capytaine, direct method, quarter mesh with two\n"
                 "# reflection symmetries, no free surface); t_over_a = thickness / a [-], faces = full-plate mesh size.\n")
        w = csv.writer(fh)
        w.writerow(["b_over_a", "t_over_a", "faces", "lambda"])
        fh.flush()
        for ratio in RATIOS:
            for t, n in LEVELS:
                lam, faces = plate_lambda(ratio, t, n)
                print(f"b/a = {ratio}, t/a = {t}: {faces} faces, lambda = {lam:.5f}", flush=True)
                w.writerow([ratio, t, faces, f"{lam:.5f}"])
                fh.flush()


def compare():
    from stripcoef.data import load_table
    table = load_table("plate_added_mass_dnv")
    print("| b/a | t/a = 0.02 | t/a = 0.01 | t -> 0 | DNV-RP-H103 | error % |")
    print("|---|---|---|---|---|---|")
    for ratio, lv in sorted(load_plates().items()):
        dnv = table.interp(1.0 / ratio, "lambda")
        if 0.01 not in lv:
            print(f"| {ratio:g} | {lv[0.02]:.4f} | - | - | {dnv:.3f} | - |")
            continue
        thick, thin = lv[0.02], lv[0.01]
        zero = 2 * thin - thick
        print(f"| {ratio:g} | {thick:.4f} | {thin:.4f} | {zero:.4f} | {dnv:.3f} | "
              f"{100 * (zero - dnv) / dnv:+.2f} |")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bem", action="store_true", help="recompute the BEM values")
    if ap.parse_args().bem:
        run_bem()
    compare()


if __name__ == "__main__":
    main()
