"""Which remesher makes the panel method's levels: pymeshlab, gmsh or the input refined.

The shapes are the first ``--count`` of the stored CAD-style run (reference_tables/bem/
cad_shapes.csv: seed 874081318, regenerated from its seed by benchmarks.cad_shapes), whose
Capytaine references are stored there.  For each shape and each way of making the panellings:

- ``pymeshlab``: stripcoef.hull.remesh (MeshLab's explicit isotropic remeshing, creases kept);
- ``gmsh``: the STL surface classified into patches at 40 degrees, reparametrised and meshed
  with Frontal-Delaunay at the target size (gmsh's documented way of remeshing an STL, its
  tutorial t13, ``classifySurfaces`` + ``createGeometry``);
- ``input``: the input refined by longest-edge bisection (stripcoef.hull.panels.refine, the
  fallback without a remesher);

three levels at about 400, 800 and 1600 panels are solved by the panel method
(stripcoef.hull.panels.solve_added_mass), the two finest Richardson-extrapolated, and the
error estimate is the grid convergence index (stripcoef.hull.convergence).  Per method: the
panel counts reached against the asked, the remeshing time, the worst diagonal error against
the stored reference, and the coverage of the estimate.  Usage:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.remesh_choice [--count 12]

``--knife`` instead remeshes the wings of benchmarks.thin_members' stored seed (NACA 00xx
sections, a knife-edge trailing edge) in each of :data:`KNIFE_SETTINGS` and tabulates the
changes of area, volume and trailing-edge area: the measurement behind the thin-member modes
of stripcoef.hull.remesh.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
import trimesh  # noqa: E402

from benchmarks import cad_shapes as C  # noqa: E402

STORED = Path("reference_tables/bem/cad_shapes.csv")
SEED = 874081318
TARGETS = (400, 800, 1600)


def gmsh_remesh(v, f, h):
    """gmsh: classify the STL's triangles into patches (40 degrees), rebuild a geometry on
    them and mesh it at size ``h`` [m].  Returns (vertices, faces) or None."""
    import gmsh

    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("m")
        with tempfile.TemporaryDirectory() as t:
            p = os.path.join(t, "m.stl")
            trimesh.Trimesh(v, f, process=False).export(p)
            gmsh.merge(p)
        gmsh.model.mesh.classifySurfaces(40 * np.pi / 180, True, True, np.pi)
        gmsh.model.mesh.createGeometry()
        gmsh.model.geo.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeMax", h)
        gmsh.option.setNumber("Mesh.MeshSizeMin", 0.3 * h)
        gmsh.model.mesh.generate(2)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        et, _, nodes = gmsh.model.mesh.getElements(2)
    except Exception:
        return None
    finally:
        gmsh.finalize()
    idx = np.full(int(tags.max()) + 1, -1)
    idx[tags.astype(int)] = np.arange(len(tags))
    tri = np.concatenate([n for e, n in zip(et, nodes) if e == 2]).astype(int)
    m = trimesh.Trimesh(xyz.reshape(-1, 3), idx[tri].reshape(-1, 3), process=True)
    if not m.is_watertight:
        return None
    trimesh.repair.fix_normals(m)
    return np.asarray(m.vertices), np.asarray(m.faces)


def levels(method, v, f):
    from stripcoef.hull import panels as P
    from stripcoef.hull import remesh as R

    area = P._area(v, f)
    if method == "pymeshlab":
        out = R.remesh_family(v, f, [R.edge_for_panels(area, n) for n in TARGETS])
        return None if out is None else out[0]
    if method == "gmsh":
        lv = [gmsh_remesh(v, f, R.edge_for_panels(area, n)) for n in TARGETS]
        return None if any(x is None for x in lv) else lv
    return [P.refine(v, f, n) for n in TARGETS]


#: The thin members' seed of the stored run of benchmarks.thin_members (docs/validation.md).
THIN_SEED = 1473826805
#: The remesh settings compared on knife edges (``--knife``): name, crease angle [deg], edge
#: flips, surface-distance bound [fraction of the bounding box's diagonal].
KNIFE_SETTINGS = (("flips, creases 30 deg (MeshLab's defaults)", 30.0, True, 0.01),
                  ("flips, creases 10 deg", 10.0, True, 0.01),
                  ("flips, distance 0.0005", 30.0, True, 0.0005),
                  ("no flips, distance 0.01", 30.0, False, 0.01),
                  ("no flips, distance 0.002", 30.0, False, 0.002))


def trailing_edge_area(vertices, faces, chord):
    """Area [m^2] of a wing's sides (not its flat tips) over the aft tenth of the chord (the
    wing of benchmarks.thin_members: chord along x, trailing edge at +chord/2)."""
    t = np.asarray(vertices, float)[np.asarray(faces)]
    n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    side = np.abs(n[:, 2]) < 0.9 * np.linalg.norm(n, axis=1)
    return 0.5 * float(np.linalg.norm(n[side & (t.mean(axis=1)[:, 0] > 0.4 * chord)],
                                      axis=1).sum())


def knife_edges(panels=(400, 1600, 3200)) -> int:
    """The wings of benchmarks.thin_members' stored seed remeshed in each of
    :data:`KNIFE_SETTINGS` at ``panels``: the changes of area, volume and the aft tenth of
    the chord's area, and the faces reached (why stripcoef.hull.remesh's thin-member modes
    have no flips and a 0.002 distance bound)."""
    from benchmarks.thin_members import make_member
    from stripcoef.hull import remesh as R

    rng = np.random.default_rng(THIN_SEED)
    members = [make_member(("plate", "wing")[k % 2], rng) for k in range(6)]
    print(f"    python -m benchmarks.remesh_choice --knife (seed {THIN_SEED})\n")
    print("| wing | panels asked | setting | faces | area | volume | aft tenth of chord |")
    print("|---|---|---|---|---|---|---|")
    for mesh, what, _ in members[1::2]:
        v, f = np.asarray(mesh.vertices, float), np.asarray(mesh.faces)
        chord = float(np.ptp(v[:, 0]))
        a0, v0, te0 = R._area(v, f), R._volume(v, f), trailing_edge_area(v, f, chord)
        for n in panels:
            for name, angle, flips, dist in KNIFE_SETTINGS:
                out, change = R._remesh_checked(v, f, R.edge_for_panels(a0, n),
                                                R.Mode(angle, flips, dist), R.ITERATIONS)
                if out is None and change is None:
                    print(f"| {what} | {n} | {name} | not closed | | | |")
                    continue
                if out is None:                  # refused: its changes
                    print(f"| {what} | {n} | {name} | refused | {100 * change[0]:+.1f} % | "
                          f"{100 * change[1]:+.1f} % | |")
                    continue
                rv, rf = out
                print(f"| {what} | {n} | {name} | {len(rf)} | "
                      f"{100 * (R._area(rv, rf) / a0 - 1):+.1f} % | "
                      f"{100 * (R._volume(rv, rf) / v0 - 1):+.1f} % | "
                      f"{100 * (trailing_edge_area(rv, rf, chord) / te0 - 1):+.1f} % |",
                      flush=True)
    return 0


def main(argv=None) -> int:
    from stripcoef.hull import panels as P
    from stripcoef.hull.convergence import grid_convergence_index, richardson

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--count", type=int, default=12)
    ap.add_argument("--knife", action="store_true",
                    help="instead: the remesh settings on the thin members' knife edges")
    args = ap.parse_args(argv)
    if args.knife:
        return knife_edges()
    refs = C.stored_references(STORED)
    rng = np.random.default_rng(SEED)
    stats = {m: dict(err=[], cov=[], t=[], ratio=[], failed=0) for m in
             ("pymeshlab", "gmsh", "input")}
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(args.count):
            family = C.FAMILIES[int(rng.integers(0, len(C.FAMILIES)))]
            parts, what = C.make_shape(family, rng)
            C.write_as_user(parts, Path(tmp) / "x", rng)           # the same draws
            if k not in refs:
                continue
            ref = refs[k][0]
            surf = C.clean_surface(parts)
            v, f = np.asarray(surf.vertices, float), np.asarray(surf.faces)
            # the stored references are about the model's reference point: the volume
            # centroid of the loaded mesh (origin 0,0,0 given), i.e. the origin here
            line = [f"{k:2d} {family:12s}"]
            for method, st in stats.items():
                t0 = time.perf_counter()
                lv = levels(method, v, f)
                dt = time.perf_counter() - t0
                if lv is None:
                    st["failed"] += 1
                    line.append(f"{method} refused")
                    continue
                counts, mats = [], []
                for pv, pf in lv:
                    counts.append(len(pf))
                    mats.append(P.solve_added_mass(pv[pf], rho=C.RHO))
                a = richardson(mats[-2], mats[-1], counts[-2], counts[-1])
                gci, _, _ = grid_convergence_index(mats, counts)
                est = P.estimated_error(mats[-1], a, gci)
                d = np.abs(np.diag(ref))
                err = np.abs(np.diag(a) - np.diag(ref)) / d
                st["err"].append(err.max())
                st["cov"] += list(np.abs(np.diag(a) - np.diag(ref)) <= np.diag(est))
                st["t"].append(dt)
                st["ratio"] += [c / n for c, n in zip(counts, TARGETS)]
                line.append(f"{method} {'/'.join(map(str, counts))} {dt:.2f} s "
                            f"worst {100 * err.max():.1f} %")
            print("  ".join(line), flush=True)
    print()
    for method, st in stats.items():
        if not st["err"]:
            print(f"{method}: refused on every shape")
            continue
        r = np.array(st["ratio"])
        print(f"{method}: {len(st['err'])} shapes ({st['failed']} refused); panels / asked "
              f"{r.min():.2f}..{r.max():.2f}; making the three levels median "
              f"{np.median(st['t']):.2f} s (max {max(st['t']):.2f} s); worst diagonal error "
              f"median {100 * np.median(st['err']):.1f} %, max {100 * max(st['err']):.1f} %; "
              f"diagonal terms covered by the GCI estimate {100 * np.mean(st['cov']):.0f} %")
    return 0


if __name__ == "__main__":
    sys.exit(main())
