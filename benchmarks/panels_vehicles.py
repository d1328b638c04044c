"""The shipped vehicle files' panel added mass against Capytaine on the same closed surface.

For each vehicle file (default: geometry/videoray_pro3.yaml and geometry/bluerov2_heavy.yaml)
the surface the panel method solves on (its parts united, :func:`stripcoef.geometry.surface.
vehicle_surface`, 64 sides a circle) is remeshed isotropically (:mod:`stripcoef.hull.remesh`,
the ``remesh`` extra) at the ``--bem-faces`` targets as one family
(:func:`stripcoef.hull.remesh.remesh_family`: one crease angle and mode for every level, a
level grown until it refines the one before by 1.25x and keeps the area and volume), and on
every remesh both Capytaine (direct method, no free surface;
:func:`stripcoef.bem.bem_added_mass`) and the panel method's one-level solve
(:func:`stripcoef.hull.panels.solve_added_mass`) are run: the same mesh, two codes.  The
reference is the Capytaine levels' Richardson extrapolation (two finest, 1/N) with its grid
convergence index (:mod:`stripcoef.hull.convergence`).  Then the estimate as a user
runs it (``stripcoef coefficients FILE``: ``auto``, the default panels), with the ``remesh``
extra and as a base install has it (the remesher switched off), is compared with it term by
term, with its estimated error (``added_mass_error``), about the vehicle's reference
point, rho = 1000 kg/m^3.

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.panels_vehicles [FILE ...]
        [--bem-faces 1600 3200] [--max-faces 5000] [--csv CSV]
        [--references CSV]

``--references CSV`` re-runs the estimate only, against the Capytaine references stored in
CSV (its ``bem``, ``bem_gci_rel``, ``bem_faces`` and ``same_mesh_max_diff_rel`` columns):
minutes instead of the solves, for a change of the panel method or of its estimated error.

Needs the ``bem`` and ``remesh`` extras.  A surface that no family remeshes within
``--max-faces`` keeping its area and volume (members thinner than the edge collapsed) gets no
reference, and that is said.
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
RHO = 1000.0
RERUN = "; model rows re-run by "


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="*", default=["geometry/videoray_pro3.yaml",
                                                  "geometry/bluerov2_heavy.yaml"])
    ap.add_argument("--bem-faces", type=int, nargs="+", default=(1600, 3200),
                    help="remesh targets [faces], coarse to fine")
    ap.add_argument("--max-faces", type=int, default=5000, help="largest BEM mesh solved")
    ap.add_argument("--csv", default=None,
                    help="write each diagonal term's row to this CSV (validation/vehicle_surface.py "
                         "reads reference_tables/bem/panels_vehicles.csv)")
    ap.add_argument("--update", action="store_true",
                    help="with --csv: replace the rows of FILES in the existing CSV and keep "
                         "the others (the first line then names both commands)")
    ap.add_argument("--references", default=None, metavar="CSV",
                    help="re-run the estimate only, against the Capytaine references stored "
                         "in this CSV (a file without rows there is an error)")
    args = ap.parse_args(argv)
    stored = _stored_references(args.references, args.files) if args.references else None
    rows = []

    import trimesh

    from stripcoef.assembly import estimate
    from stripcoef.bem import bem_added_mass
    from stripcoef.geometry.surface import vehicle_surface
    from stripcoef.geometry.vehicle import load_vehicle
    from stripcoef.hull import remesh
    from stripcoef.hull.convergence import grid_convergence_index, richardson
    from stripcoef.hull.panels import estimated_error, solve_added_mass

    def run(veh, remesher):
        """The default estimate, with the remesher or as a base install has it (no
        ``remesh`` extra: :func:`stripcoef.hull.remesh.available` False)."""
        from unittest import mock

        with warnings.catch_warnings(record=True) as caught, \
                mock.patch.object(remesh, "available", lambda: remesher and real()):
            warnings.simplefilter("always")
            c0 = time.process_time()
            model = estimate(veh)
            cpu = time.process_time() - c0
        warned = [str(w.message) for w in caught if "has not converged" in str(w.message)]
        return model, cpu, warned

    real = remesh.available
    for path in args.files:
        veh = load_vehicle(path)
        runs = {}
        for install, remesher in (("remesh extra", True), ("base", False)):
            if remesher and not real():
                continue
            runs[install] = run(veh, remesher)
        model = next(iter(runs.values()))[0]
        about = np.asarray(model.reference_point, float)
        surf = vehicle_surface(veh)
        v, f = np.asarray(surf.vertices, float), np.asarray(surf.faces)
        print(f"{path}: surface {len(f)} faces, area {surf.area:.4f} m^2, volume "
              f"{surf.volume:.6f} m^3", flush=True)
        for install, (m, cpu, warned) in runs.items():
            print(f"  estimate ({install}): {m.conditions.get('added_mass_method')}, CPU "
                  f"{cpu:.1f} s" + (f"; warned: {warned[0].split(': ', 1)[1][:140]}"
                                    if warned else ""), flush=True)
        if stored is not None:
            ref, ref_err, counts, same = stored[path]
            print(f"  references from {args.references} (Capytaine, {counts} faces)")
            rows += _rows(path, runs, ref, ref_err, counts, same)
            continue
        mats, counts, pairs = [], [], []
        # one remesh family (remesh.remesh_family: one crease angle and mode for every level,
        # each level at least 1.25x the faces of the one before), so that the levels refine
        # one discretisation and Richardson applies; none: the file is skipped and said
        edges = [remesh.edge_for_panels(surf.area, n) for n in args.bem_faces]
        family = remesh.remesh_family(v, f, edges, max_faces=args.max_faces)
        if family is None:
            print(f"  no remesh family at {'/'.join(map(str, args.bem_faces))} faces within "
                  f"--max-faces {args.max_faces} (area or volume changed: members thinner "
                  "than the edge): no reference", flush=True)
            continue
        print(f"  BEM levels: one remesh family, {family[1]}: "
              + "/".join(str(len(lv[1])) for lv in family[0]) + " faces", flush=True)
        for lv in family[0]:
            t0 = time.perf_counter()
            bem = bem_added_mass(trimesh.Trimesh(*lv, process=False), rho=RHO,
                                 reference_point=about, max_faces=args.max_faces)
            t_bem = time.perf_counter() - t0
            t0 = time.perf_counter()
            pan = solve_added_mass(lv[0][lv[1]], rho=RHO, about=about)
            t_pan = time.perf_counter() - t0
            pan = 0.5 * (pan + pan.T)
            mats.append(bem)
            counts.append(len(lv[1]))
            pairs.append((pan, bem))
            print(f"  {len(lv[1])} faces: Capytaine {np.diag(bem).round(4).tolist()} "
                  f"({t_bem:.1f} s); panel method on the same mesh "
                  f"{np.diag(pan).round(4).tolist()} ({t_pan:.1f} s); largest difference "
                  f"{100 * np.max(np.abs(np.diag(pan) / np.diag(bem) - 1)):.2f} %", flush=True)
        if len(mats) < 2:
            print("  fewer than two BEM levels: no reference")
            continue
        ref = richardson(mats[-2], mats[-1], counts[-2], counts[-1])
        gci, _, _ = grid_convergence_index(mats, counts)
        ref_err = estimated_error(mats[-1], ref, gci)
        print(f"  reference (Richardson {counts[-2]}/{counts[-1]}): "
              f"{np.diag(ref).round(4).tolist()}")
        same = max(float(np.max(np.abs(np.diag(p) / np.diag(b) - 1))) for p, b in pairs)
        rows += _rows(path, runs, np.diag(ref), np.diag(ref_err), "/".join(map(str, counts)),
                      f"{same:.3g}")
    if args.csv:
        import csv
        from pathlib import Path

        Path(args.csv).parent.mkdir(parents=True, exist_ok=True)
        command = ("benchmarks/panels_vehicles.py " + " ".join(args.files) + " --bem-faces "
                   + " ".join(map(str, args.bem_faces)) + f" --max-faces {args.max_faces}")
        if args.references:    # the references' own command, then this re-run's
            with open(args.references) as fh:
                first = fh.readline().lstrip("# ").strip().split(RERUN)[0]
            command = (first + RERUN + "benchmarks/panels_vehicles.py " + " ".join(args.files)
                       + f" --references {args.references}")
        kept = []
        if args.update and not args.references and Path(args.csv).exists():
            # the other files' rows and command
            with open(args.csv, newline="") as fh:
                first = fh.readline().lstrip("# ").strip()
                kept = [r for r in list(csv.reader(fh))[1:] if r and r[0] not in args.files]
            base, *clauses = first.split("; rows of ")    # as benchmarks.public_meshes
            out = [base]
            for clause in clauses:
                names, _, cmd = clause.partition(" from ")
                left = [n for n in names.split() if n not in args.files]
                if left:
                    out.append(" ".join(left) + " from " + cmd)
            out.append(" ".join(args.files) + " from " + command + " --csv " + args.csv
                       + " --update")
            command = "; rows of ".join(out)
        with open(args.csv, "w", newline="") as fh:
            fh.write("# " + command + "\n")
            w = csv.writer(fh)
            w.writerow(["file", "install", "dof", "estimate", "bem", "error_rel",
                        "estimated_error_rel", "bem_gci_rel", "panel_levels", "bem_faces",
                        "same_mesh_max_diff_rel", "cpu_estimate_s", "warned"])
            w.writerows(kept + rows)
    return 0


def _rows(path, runs, ref, ref_err, counts, same):
    """One CSV row per diagonal term and install: the estimate against the reference ``ref``
    (its diagonal [kg, kg m, kg m^2]) with the reference's band ``ref_err`` (same units),
    printed as it goes."""
    rows = []
    for install, (m, cpu, warned) in runs.items():
        ours = np.asarray(m.added_mass) * RHO / m.density
        est = np.asarray(m.added_mass_error) * RHO / m.density
        levels = "/".join(map(str, m.conditions.get("added_mass_panel_levels", ())))
        for i in range(6):
            e = ours[i, i] / ref[i] - 1.0
            rows.append([path, install, DOFS[i], f"{ours[i, i]:.6g}", f"{ref[i]:.6g}",
                         f"{e:.4g}", f"{est[i, i] / abs(ref[i]):.4g}",
                         f"{ref_err[i] / abs(ref[i]):.4g}", levels, counts, same,
                         f"{cpu:.2f}", int(bool(warned))])
            print(f"  {install:12s} {DOFS[i]:6s} estimate {ours[i, i]:.5g}  reference "
                  f"{ref[i]:.5g} (+- {100 * ref_err[i] / abs(ref[i]):.1f} %)  "
                  f"error {100 * e:+.1f} %  estimated {100 * est[i, i] / abs(ref[i]):.1f}"
                  f" %  {'covered' if abs(ours[i, i] - ref[i]) <= est[i, i] else 'NOT covered'}",
                  flush=True)
    return rows


def _stored_references(csv_path, files):
    """The Capytaine references of ``files`` in a CSV this script wrote: per file the
    diagonal reference and its band [kg, kg m, kg m^2], the BEM levels' face counts and the
    same-mesh difference, as read (one install's rows; every install shares them)."""
    import csv

    with open(csv_path, newline="") as fh:
        fh.readline()
        table = list(csv.DictReader(fh))
    out = {}
    for path in files:
        rows = {r["dof"]: r for r in table if r["file"] == path}
        if set(rows) != set(DOFS):
            raise SystemExit(f"{csv_path}: no reference rows for {path} (dof column has "
                             f"{sorted(rows)}; expected {list(DOFS)})")
        ref = np.array([float(rows[d]["bem"]) for d in DOFS])
        band = np.array([float(rows[d]["bem_gci_rel"]) for d in DOFS]) * np.abs(ref)
        first = rows[DOFS[0]]
        out[path] = (ref, band, first["bem_faces"], first["same_mesh_max_diff_rel"])
    return out


if __name__ == "__main__":
    sys.exit(main())
