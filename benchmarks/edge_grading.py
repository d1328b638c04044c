"""Panels graded towards sharp edges: do they restore the observed order of convergence?

The Capytaine references of the CAD-style shapes refined to 12,000 faces
(reference_tables/bem/cad_shapes_fine_levels.csv, docs/validation.md "The references refined
to 12,000 faces") converge at an observed order of about 0.5 in h on the sharp-edged shapes'
terms (a thin plate's in-plane sway and yaw, a coarse polyhedron's rotations): uniform
constant panels against a velocity singular at the edges.  This benchmark solves the same
surfaces (seed 1375923287 of benchmarks.cad_shapes, drawn exactly as
benchmarks.bem_fine_references prepare draws them: shapes 10 and 25, thin plates, 9, a box
with a pod, and 14, a low-polygon ellipsoid) on panellings graded towards their edges sharper than 30 degrees
(stripcoef.hull.remesh.graded_for_panels: the isotropic remesh, then longest-edge bisection
to the algebraic grading h(d) = h (d/L)^(1 - 1/beta), beta = 2, L a tenth of the bounding
box's diagonal; von Petersdorff & Stephan 1990), by Capytaine and by stripcoef's own panel
method (stripcoef.hull.panel_kernels.solve_added_mass), next to the uniform remeshes of the
same family, and prints per diagonal term the observed order (Celik et al. 2008) and the grid
convergence index of the finest level (stripcoef.hull.convergence, Oberkampf & Roy's rule)
of the three levels near 1500/3000/6000 faces, and the finest level's difference from the
uniform 4-level Capytaine reference (1500 to 12,000 faces, validation.cad_shapes
.fine_reference).

    python -m benchmarks.edge_grading [--out DIR] [--panel-shapes 10,25] [--beta 2]

Solves are cached in DIR (default /tmp/edge_grading) as .npy files; about 15 minutes on two
loaded cores.  Writes benchmarks/data/edge_grading.md (another beta:
edge_grading_betaB.md).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

SEED = 1375923287
SHAPES = (10, 25, 9, 14)
TARGETS = (1500, 3000, 6000)
#: the crease angle the graded panellings refine towards [deg] (the remesher's creases; the
#: low-polygon ellipsoid's facet edges are 30 to 60 degrees, the plates' rims 90)
ANGLE = 30.0
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
OUTPUT = Path(__file__).parent / "data" / "edge_grading.md"


def draw(seed=SEED, wanted=SHAPES):
    """{shape number: (family, description, vertices [m], faces)} as prepare draws them."""
    from benchmarks.cad_shapes import clean_surface, drawn_shapes

    out = {}
    for k, family, parts, what in drawn_shapes(seed, max(wanted) + 1):
        if k in wanted:
            s = clean_surface(parts)
            out[k] = (family, what, np.asarray(s.vertices, float), np.asarray(s.faces))
    return out


def panellings(v, f, beta):
    """{"uniform": [...], "graded": [...]} lists of (vertices, faces) near TARGETS faces."""
    from benchmarks.bem_fine_references import LEVELS
    from stripcoef.hull.bisection import surface_area
    from stripcoef.hull.remesh import edge_for_panels, graded_for_panels, remesh_family

    area = surface_area(v, f)
    fam = remesh_family(v, f, [edge_for_panels(area, n) for n in LEVELS],
                        max_faces=int(1.6 * LEVELS[-1]))
    uniform = fam[0][:len(TARGETS)]
    graded = [graded_for_panels(v, f, n, beta=beta, angle=ANGLE) for n in TARGETS]
    return {"uniform": uniform, "graded": graded}


def cached(path: Path, compute):
    if path.exists():
        return np.load(path)
    a = compute()
    np.save(path, a)
    return a


def reference(shape):
    """(face counts, the uniform Capytaine levels, the 4-level fine reference) of the stored
    file."""
    from validation.cad_shapes import FINE, fine_reference, read_levels

    lv = read_levels(FINE)[shape]
    n = [lv[x][0] for x in sorted(lv)]
    mats = [lv[x][1] for x in sorted(lv)]
    ref, band, _ = fine_reference(n, mats)
    return n, mats, ref, band


def study(counts, mats):
    """(observed order, GCI of the finest, finest) of the last three levels, per term."""
    from stripcoef.hull.convergence import grid_convergence_index, observed_order

    n = np.asarray(counts[-3:], float)
    h = n ** -0.5
    p = observed_order(mats[-1], mats[-2], mats[-3], h[-2] / h[-1], h[-3] / h[-2])
    gci, _, _ = grid_convergence_index(mats[-3:], counts[-3:])
    return p, gci, mats[-1]


def run(out: Path, panels, beta: float, shapes_wanted=SHAPES) -> str:
    import logging

    from benchmarks.bem_fine_references import _solver, added_mass
    from stripcoef.hull.panel_kernels import solve_added_mass

    logging.getLogger("capytaine").setLevel(logging.ERROR)
    out.mkdir(parents=True, exist_ok=True)
    solver, _ = _solver()
    shapes = draw(wanted=shapes_wanted)
    lines = [f"# Panels graded towards sharp edges (seed {SEED}, shapes "
             f"{', '.join(map(str, shapes_wanted))}, beta {beta:g})", "",
             "`python -m benchmarks.edge_grading`.  Per diagonal term: observed order p in h "
             "(h ~ N^-1/2; formal 2; '-' oscillating) and grid convergence index of the finest "
             "of three levels (Oberkampf & Roy), and the finest level's difference from the "
             "uniform Capytaine reference extrapolated from 1500 to 12,000 faces "
             "(ref. band: its own GCI).", ""]
    capytaine = ("capytaine", lambda v, f: added_mass(solver, v, f))
    own = ("panels", lambda v, f: 0.5 * (lambda a: a + a.T)(solve_added_mass(v[f], rho=1000.0)))
    for k in shapes_wanted:
        engines = [capytaine] + ([own] if k in panels else [])
        family, what, v, f = shapes[k]
        n_ref, mats_ref, ref, band = reference(k)
        fams = panellings(v, f, beta)
        counts = {name: [len(x[1]) for x in lv] for name, lv in fams.items()}
        lines += [f"## Shape {k}: {what}", "",
                  f"uniform faces {counts['uniform']} (stored levels {n_ref}), graded faces "
                  f"{counts['graded']}", ""]
        res = {}
        for ename, solve in engines:
            for fname, lv in fams.items():
                if (ename, fname) == ("capytaine", "uniform") and \
                        counts[fname] == n_ref[:len(counts[fname])]:
                    # the same meshes as the stored levels (remesh_family, the same call as
                    # bem_fine_references prepare): their stored solves
                    res[ename, fname] = study(counts[fname], mats_ref[:len(counts[fname])])
                    continue
                mats = []
                for (pv, pf) in lv:
                    path = out / f"{k}_{ename}_{fname}_{len(pf)}_b{beta:g}.npy"
                    t0 = time.perf_counter()
                    mats.append(cached(path, lambda: solve(np.asarray(pv, float),
                                                           np.asarray(pf, np.int64))))
                    print(f"shape {k} {ename:9s} {fname:7s} {len(pf):5d} faces "
                          f"{time.perf_counter() - t0:6.1f} s", flush=True)
                res[ename, fname] = study(counts[fname], mats)
        head = "| term | ref. | ref. band | uniform 12k vs ref. |"
        rule = "|---|---|---|---|"
        for (ename, fname) in res:
            head += f" {ename} {fname}: p / GCI / finest vs ref. |"
            rule += "---|"
        lines += [head, rule]
        for i in range(6):
            row = (f"| {DOFS[i]} | {ref[i, i]:.5g} | {100 * band[i, i] / abs(ref[i, i]):.1f} % | "
                   f"{100 * (mats_ref[-1][i, i] - ref[i, i]) / abs(ref[i, i]):+.2f} % "
                   f"({n_ref[-1]}) |")
            for (p, gci, fine) in res.values():
                ps = "-" if not np.isfinite(p[i, i]) else f"{p[i, i]:.2f}"
                row += (f" {ps} / {100 * gci[i, i] / abs(ref[i, i]):.1f} % / "
                        f"{100 * (fine[i, i] - ref[i, i]) / abs(ref[i, i]):+.2f} % |")
            lines.append(row)
        lines.append("")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("/tmp/edge_grading"))
    ap.add_argument("--panel-shapes", default="10,25",
                    help="shapes also solved by stripcoef's panel method (comma-separated; "
                    "'' for none)")
    ap.add_argument("--beta", type=float, default=2.0)
    ap.add_argument("--shapes", default=",".join(map(str, SHAPES)),
                    help="the shapes of the seed to study (comma-separated)")
    args = ap.parse_args(argv)
    shapes = tuple(int(x) for x in args.shapes.split(",") if x.strip())
    text = run(args.out, {int(x) for x in args.panel_shapes.split(",") if x.strip()}, args.beta,
               shapes)
    out = OUTPUT if args.beta == 2.0 else OUTPUT.with_name(f"edge_grading_beta{args.beta:g}.md")
    out.write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
