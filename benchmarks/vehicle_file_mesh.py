"""A vehicle file against the mesh of the same parts: the default panel estimate of each, term
by term, with the panel levels, the estimated error and the CPU time (issue 32).

The shipped BlueROV2 Heavy (geometry/bluerov2_heavy.yaml and .stl, written from one list of
parts by scripts/make_bluerov2_heavy.py: the .stl is the surface the vehicle file is panelled
on) by ``stripcoef.assembly.estimate`` with ``added_mass_method`` ``auto`` (the panel method,
1600 panels), about the parts' common origin, rho of the file.  Each term's difference is over
the diagonal scale sqrt(M_ii M_jj) (validation/vehicle_surface.py's measure).  With the
``remesh`` extra the levels are isotropic remeshes (stripcoef.hull.remesh); ``--base`` runs
without the remesher (the refined surface, as a base install has it).

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.vehicle_file_mesh [--base]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--base", action="store_true",
                    help="without the remesher (pymeshlab not imported), as a base install")
    args = ap.parse_args(argv)
    if args.base:
        sys.modules["pymeshlab"] = None          # the import fails: remesh.available() False
    from stripcoef.assembly import estimate
    from stripcoef.errors import ModelWarning
    from stripcoef.geometry.vehicle import Vehicle, load_vehicle
    from validation import ROOT
    from validation.vehicle_surface import term_errors

    models, notes = [], []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ModelWarning)
        rov = load_vehicle(ROOT / "geometry" / "bluerov2_heavy.yaml")
        t = time.process_time()
        models.append(("vehicle file", estimate(rov, reference_point=np.zeros(3)),
                       time.process_time() - t))
        mesh = Vehicle.from_mesh(ROOT / "geometry" / "bluerov2_heavy.stl",
                                 origin=(0.0, 0.0, 0.0), fluid=rov.fluid)
        t = time.process_time()
        models.append(("mesh", estimate(mesh), time.process_time() - t))
    notes = [str(w.message) for w in caught if "not converged" in str(w.message)]
    print(f"BlueROV2 Heavy, {'base install' if args.base else 'remesh extra'}:")
    print("| model | panel levels | estimated error max | CPU [s] | "
          + " | ".join(DOFS) + " |")
    print("|---" * (4 + len(DOFS)) + "|")
    for name, m, cpu in models:
        c = m.conditions
        print(f"| {name} | {'/'.join(str(n) for n in c['added_mass_panel_levels'])} | "
              f"{100 * c['added_mass_error_max']:.1f} % | {cpu:.2f} | "
              + " | ".join(f"{x:.5g}" for x in np.diag(m.added_mass)) + " |")
    err = term_errors(models[0][1].added_mass, models[1][1].added_mass)
    print("| difference over sqrt(M_ii M_jj) | | | | "
          + " | ".join(f"{100 * x:.2f} %" for x in np.diag(err)) + " |")
    i, j = np.unravel_index(int(np.argmax(err)), err.shape)
    print(f"largest term difference: {100 * err.max():.2f} % (M_A[{DOFS[i]}, {DOFS[j]}])")
    for n in notes:
        print("warning: " + n)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
