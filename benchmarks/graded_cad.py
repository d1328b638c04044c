"""Edge-graded Capytaine references of the CAD benchmark's faceted convex shapes on their
three mirror planes (issue 32): the low-polygon ellipsoid 14 and the filleted box 18 of seed
1375923287 (:mod:`benchmarks.cad_shapes`, drawn exactly as it draws them, about the origin as
it takes them).

Both are convex polyhedra whose every facet edge turns the flow (ellipsoid 14: 216 edges of
4.8-36.9 deg; box 18: 168 edges of 11.2-35.2 deg; coplanar triangles aside), so that the
velocity is singular at each (the wedge of fluid of angle pi + theta about an edge turning
the normal by theta: phi ~ r^(pi / (pi + theta)), Newman 1977 sec. 4.4).  The stored
references of these two shapes are uniform remeshes refined to 15,000-16,500 faces whose own
Eça & Hoekstra bands are 4.5-13.7 % (reference_tables/bem/cad_shapes_fine_levels.csv), and the
structured sector panels of :mod:`benchmarks.graded_polyhedra` did not converge monotonically
on them (benchmarks/data/coarse_graded.md).  Here the graded mesher of the frames
(:func:`benchmarks.graded_mesher.graded_mesh`: gmsh, h = min(H, H/4 + 0.25 d), d the distance to
the nearest convex edge) is used with every facet edge graded towards and every facet its own
patch (``ANGLE`` 1 deg for both, where the frames take 30 deg: on these bodies no edge is a
smooth surface's facet joint, the surface the model solves is the faceted one), on the
x, y, z >= 0 eighth (the bodies are mirror-symmetric in the three coordinate planes through
the origin, checked by :func:`benchmarks.frame_references.mirror_planes`), solved by
Capytaine (direct method, no free surface) on the two vertical planes with the z < 0 half
mirrored (:func:`benchmarks.plate_graded.capytaine_eighth`: four LUs of N/4 instead of one of
N, the CPU; the memory stays about the one-plane solve's, :func:`predicted_gb`).  The nodes lie on the facets, so every level is the faceted body exactly
(area and volume checked per level).

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.graded_cad --only 14 18 \\
        --levels 0.08 0.064 0.05 0.04 0.032 --csv reference_tables/bem/graded_cad_1375923287.csv
    python -m benchmarks.graded_cad --compare reference_tables/bem/graded_cad_1375923287.csv

The rows have the columns of ``graded_coarse.csv`` (shape, what, level, m = H [m], faces of
the whole body, i, j, added mass [kg, kg m, kg m^2] about the origin, seconds of CPU of the
solve), read by :func:`validation.cad_shapes.read_graded_levels`.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import csv  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from benchmarks import graded_mesher as GM  # noqa: E402

SEED = 1375923287
COUNT = 40
#: the shapes of :data:`SEED` built here (ellipsoid 14, filleted box 18)
SHAPES = (14, 18)
#: dihedral [deg] beyond which a facet edge is graded towards and bounds a patch: every facet
#: edge of these convex polyhedra (their least dihedral is 4.8 deg), not the coplanar
#: triangles' diagonals (0 deg)
ANGLE = 1.0
#: largest panel H [m] per level, coarse to fine
LEVELS = (0.08, 0.064, 0.05, 0.04, 0.032)
#: the most memory a level's solve may take [GB] (other processes share the machine)
MAX_GB = 8.0
HEADER = ["shape", "what", "level", "m", "faces", "i", "j", "added_mass", "seconds"]


def surface(k: int, seed: int = SEED, count: int = COUNT):
    """(the closed surface [m] of shape ``k`` of ``seed`` about the origin, its description)."""
    from benchmarks.cad_shapes import clean_surface, drawn_shapes

    for i, _, parts, what in drawn_shapes(seed, count):
        if i == k:
            return clean_surface(parts), what
    raise ValueError(f"shape {k}: not among the first {count} shapes of seed {seed}")


def whole(v, f):
    """The closed body's (vertices, triangles) of its x, y, z >= 0 eighth: mirrored in each
    plane in turn, each image's faces reversed (normals outward)."""
    for axis in range(3):
        s = np.ones(3)
        s[axis] = -1.0
        v, f = np.vstack([v, v * s]), np.vstack([f, f[:, ::-1] + len(v)])
    return v, f


def check(v, f, mesh) -> dict:
    """Faces, area and volume of the eighth's whole body relative to ``mesh``'s, and the least
    triangle quality 4 sqrt(3) A / (a^2 + b^2 + c^2)."""
    wv, wf = whole(v, f)
    p = wv[wf]
    cr = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    area = 0.5 * np.linalg.norm(cr, axis=1)
    vol = np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2])).sum() / 6.0
    sq = sum(np.sum((p[:, (k + 1) % 3] - p[:, k]) ** 2, axis=1) for k in range(3))
    return {"faces": len(wf), "area": float(area.sum() / mesh.area - 1.0),
            "volume": float(vol / mesh.volume - 1.0), "quality": float((4 * np.sqrt(3.0) * area
                                                                       / sq).min())}


def predicted_gb(faces: int) -> float:
    """Memory [GB] of the quarter solve of ``faces`` faces (whole body) in a fresh process:
    24 N^2 bytes and 0.5 GB, as the one-plane solve's (:func:`benchmarks.graded_mesher.
    predicted_gb`; measured here: 2.98 GB peak at 10,760 faces, 21.4 N^2 + 0.5 GB; Capytaine
    3.0's nested solve takes no less).  A process that solves several levels peaks higher
    (4.44 GB at its fourth level, 10,504 faces: the memory of the levels before is not all
    returned), so the finest levels are best run one process each (``--first-level``)."""
    return 24.0 * faces ** 2 / 1e9 + 0.5


def run(path, shapes=SHAPES, levels=LEVELS, max_gb: float = MAX_GB, first_level: int = 0):
    """Every level of each shape: mesh, check, solve, rows of :data:`HEADER` appended to
    ``path`` as they come (``first_level``: the first level's index, a finer level appended
    to a shape's rows)."""
    import capytaine

    from benchmarks.frame_references import mirror_planes
    from benchmarks.plate_graded import capytaine_eighth

    new = not Path(path).exists()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with open(path, "a", newline="") as fh:
        if new:
            fh.write(f"# python -m benchmarks.graded_cad {' '.join(sys.argv[1:])}: Capytaine "
                     f"{capytaine.__version__} (direct method, no free surface, rho = 1000 "
                     f"kg/m^3), gmsh triangles graded towards every facet edge (dihedral > "
                     f"{ANGLE:g} deg; h = min(H, H / {GM.RATIO:g} + {GM.GROWTH:g} d); "
                     "benchmarks.graded_cad), the x, y, z >= 0 eighth solved on the xOz and "
                     "yOz planes, z mirrored; m = H [m]; seconds: CPU of the solve; "
                     "upper-triangle 6x6 added mass [kg, kg m, kg m^2] about the origin\n")
            csv.writer(fh).writerow(HEADER)
        w = csv.writer(fh)
        for k in shapes:
            body, what = surface(k)
            sym = mirror_planes(body)
            if not all(sym[a][1] > -1e-6 and sym[a][0] < 1e-6 for a in range(3)):
                raise ValueError(f"shape {k}: not mirror-symmetric in x, y and z ({sym})")
            for lev, H in enumerate(levels, start=first_level):
                v, f = GM.graded_mesh(body, H, angle=ANGLE, patch_angle=ANGLE,
                                      planes=(0, 1, 2), curve_angle=ANGLE)
                c = check(v, f, body)
                if abs(c["volume"]) > 1e-6 or abs(c["area"]) > 1e-6:
                    raise RuntimeError(f"shape {k} at H = {H:g} m: the remesh is not the "
                                       f"body (area {c['area']:+.1e}, volume "
                                       f"{c['volume']:+.1e})")
                if predicted_gb(c["faces"]) > max_gb:
                    print(f"{k}: H {H:g} m, {c['faces']} faces: predicted "
                          f"{predicted_gb(c['faces']):.1f} GB > {max_gb:g} GB, not solved",
                          flush=True)
                    continue
                cpu = time.process_time()
                a, n, _ = capytaine_eighth(v, f)
                cpu = time.process_time() - cpu
                print(f"{k}: H {H:g} m, {n} faces (area {c['area']:+.1e}, volume "
                      f"{c['volume']:+.1e}, least quality {c['quality']:.3f}), {cpu:.1f} s "
                      f"CPU, peak {GM.peak_gb():.2f} GB: "
                      + " ".join(f"{x:.6g}" for x in np.diag(a)), flush=True)
                w.writerows([k, f"{what}, gmsh graded, eighth", lev, f"{H:g}", n, i, j,
                             f"{a[i, j]:.9g}", f"{cpu:.2f}"]
                            for i in range(6) for j in range(i, 6))
                fh.flush()


DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


def compare(levels_csv, model_path=None) -> tuple[list[dict], list[str]]:
    """Per diagonal term of the shapes of ``levels_csv``: the levels, Eça & Hoekstra's
    reference over them (:func:`validation.cad_shapes.fine_reference`: limit, band of the
    finest level, order), the stored run's model (default reference_tables/bem/cad_shapes.csv,
    the remesh extra) and its estimated error, and the uniform fine reference
    (cad_shapes_fine_levels*.csv, :func:`validation.cad_shapes.read_levels`); printed as a
    table, returned as rows and the table's lines."""
    from validation.cad_shapes import (DATA, FINE_ALL, fine_reference, read_graded_levels,
                                       read_levels, read_stored_run)

    graded = read_graded_levels(levels_csv)
    fine = read_levels(*FINE_ALL)
    _, stored = read_stored_run(model_path or DATA)
    model = {(int(t["shape"]), int(t["i"]), int(t["j"])): t for t in stored
             if not t["what"].startswith("FAILED")}
    rows = []
    lines = ["| # | term | graded levels (faces: value) | graded ref. (band, order) | model | "
             "model vs graded | model's estimate | uniform fine ref. (band) vs graded |",
             "|---" * 8 + "|"]
    for k, lv in sorted(graded.items()):
        n = [lv[x][0] for x in sorted(lv)]
        ref, band, order = fine_reference(n, [lv[x][1] for x in sorted(lv)])
        f = fine.get(k, {})
        f_ref, f_band, _ = fine_reference([f[x][0] for x in sorted(f)],
                                          [f[x][1] for x in sorted(f)])
        for i in range(6):
            t = model[(k, i, i)]
            m = float(t["model"])
            row = dict(shape=k, i=i, levels=[(c, lv[x][1][i, i]) for c, x in zip(n, sorted(lv))],
                       ref=ref[i, i], band=band[i, i] / ref[i, i], order=order[i, i],
                       model=m, error=m / ref[i, i] - 1.0,
                       estimate=float(t["estimated_error_rel"]),
                       fine=f_ref[i, i], fine_band=f_band[i, i] / f_ref[i, i],
                       fine_error=f_ref[i, i] / ref[i, i] - 1.0)
            rows.append(row)
            lines.append(f"| {k} | {DOFS[i]} | "
                  + ", ".join(f"{c}: {v:.5g}" for c, v in row["levels"])
                  + f" | {row['ref']:.5g} ({100 * row['band']:.1f} %, {row['order']:.2f}) | "
                  f"{m:.5g} | {100 * row['error']:+.1f} % | {100 * row['estimate']:.1f} % | "
                  f"{row['fine']:.5g} ({100 * row['fine_band']:.1f} %) "
                  f"{100 * row['fine_error']:+.1f} % |")
    print("\n".join(lines))
    return rows, lines


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.graded_cad",
                                 description=__doc__.split("\n\n")[0])
    ap.add_argument("--csv", default=None, help="append the levels here")
    ap.add_argument("--only", type=int, nargs="+", default=list(SHAPES))
    ap.add_argument("--levels", type=float, nargs="+", default=list(LEVELS))
    ap.add_argument("--max-gb", type=float, default=MAX_GB)
    ap.add_argument("--first-level", type=int, default=0,
                    help="index of the first level (levels appended to a shape's rows)")
    ap.add_argument("--compare", default=None, metavar="LEVELS_CSV",
                    help="the stored run's model against the graded levels of this file")
    ap.add_argument("--md", default=None, help="--compare: write the table here")
    ap.add_argument("--faces", action="store_true",
                    help="mesh the levels and print their faces and checks, no solve")
    args = ap.parse_args(argv)
    if args.compare:
        _, lines = compare(args.compare)
        if args.md:
            Path(args.md).write_text(
                "# CAD shapes 14 and 18 against their edge-graded references "
                "(benchmarks.graded_cad)\n\n"
                f"`python -m benchmarks.graded_cad --compare {args.compare} --md {args.md}`. "
                "The model: the stored run reference_tables/bem/cad_shapes.csv (the remesh "
                "extra) and its estimated error; the graded reference: Eça & Hoekstra over the "
                "levels (its band the uncertainty of the finest level, the order its fit's); "
                "the uniform fine reference: cad_shapes_fine_levels*.csv by the same procedure. "
                "Diagonal terms [kg, kg m^2] about the origin.\n\n" + "\n".join(lines) + "\n")
        return 0
    if args.faces:
        for k in args.only:
            body, what = surface(k)
            for H in args.levels:
                v, f = GM.graded_mesh(body, H, angle=ANGLE, patch_angle=ANGLE,
                                      planes=(0, 1, 2), curve_angle=ANGLE)
                c = check(v, f, body)
                print(f"{k} ({what}): H {H:g} m: {c['faces']} faces, area {c['area']:+.1e}, "
                      f"volume {c['volume']:+.1e}, least quality {c['quality']:.3f}, "
                      f"predicted {predicted_gb(c['faces']):.1f} GB", flush=True)
        return 0
    if args.csv is None:
        ap.error("--csv is required (or --faces)")
    run(args.csv, args.only, args.levels, args.max_gb, args.first_level)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
