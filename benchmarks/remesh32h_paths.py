"""The panel method's two families on fine smooth meshes, one process (remesh32h, issue 32).

Why the remesh extra made the panel method slower: :func:`stripcoef.hull.panels.panel_added_mass`
took the isotropic remesh (pymeshlab) whenever it could be imported, and the input family's
coarsened levels (vertex clustering) otherwise.  On a fine smooth mesh the remesher re-reads
the whole input at every level and the remeshed family goes on to four levels of up to
3,000-6,000 panels (the whole body where no mirror plane is passed), where the coarsened input
stops at two.  This benchmark solves each shape with both families in one process (the remesh
extra installed), against exact or stored references, and prints per family the levels, the
worst diagonal and coupling error, whether the estimated error covers each diagonal term, and
the CPU time of the solve; and the verdict of the rule that now decides
(:func:`stripcoef.hull.panels.fine_smooth_input`).

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.remesh32h_paths --bluff sphere oblate triaxial_wide triaxial_long cyl_y
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.remesh32h_paths --ellipsoids 6 --seed S
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.remesh32h_paths --bluff all --families auto

(the last: the bluff table of ``benchmarks.bluff_shapes --method panels`` with each shape's
family, CPU time and whether the estimate covers each diagonal term, in either install).

Shapes: the smooth shapes of benchmarks/bluff_shapes.py (their 19,200-face strip meshes, the
bluff table's panel input; references :func:`benchmarks.bluff_shapes.reference_matrix`), and
seeded triaxial ellipsoids (semi-axes drawn in [0.05, 0.4] m, an icosphere of 5,120 or
20,480 faces or a UV sphere scaled to them, turned by a random rotation so that no mirror
plane lies on the axes) against Lamb's exact matrix turned with them
(:func:`stripcoef.hull.lamb.ellipsoid_added_mass`; the tessellation's own volume deficit, the
same for both families, is part of the error).
"""

from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np
import trimesh

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
RHO = 1000.0


def ellipsoid_draw(seed: int, count: int):
    """``count`` (name, mesh, reference 6x6 [kg, kg m, kg m^2]) of seeded ellipsoids (module
    docstring), centred on the origin."""
    from stripcoef.hull.lamb import ellipsoid_added_mass

    rng = np.random.default_rng(seed)
    out = []
    for k in range(count):
        axes = np.sort(rng.uniform(0.05, 0.4, 3))[::-1]
        kind = ("ico4", "ico5", "uv")[int(rng.integers(3))]
        if kind == "uv":
            m = trimesh.creation.uv_sphere(radius=1.0, count=[40, 80])
        else:
            m = trimesh.creation.icosphere(subdivisions=int(kind[-1]), radius=1.0)
        m.apply_scale(axes)
        rot = trimesh.transformations.random_rotation_matrix(rng.random(3))
        m.apply_transform(rot)
        ref = np.diag(np.asarray(ellipsoid_added_mass(*axes, rho=RHO), float))
        t = np.zeros((6, 6))
        t[:3, :3] = t[3:, 3:] = rot[:3, :3]
        out.append((f"ellipsoid {k} ({kind}, {axes[0]:.3f}/{axes[1]:.3f}/{axes[2]:.3f} m)",
                    m, t @ ref @ t.T))
    return out


def bluff_draw(names):
    """(name, the bluff table's panel input, its reference) of benchmarks.bluff_shapes."""
    from benchmarks.bluff_shapes import read_references, reference_matrix, strip_mesh

    refs = read_references()
    return [(n, strip_mesh(n), reference_matrix(n, refs)) for n in names]


def errors(a, ref):
    """(worst relative diagonal error, worst coupling error over sqrt(A_ii A_jj)) [-] of the
    terms :func:`benchmarks.bluff_shapes.errors` compares (diagonal terms not zero, couplings
    at least 1 % of the scale)."""
    from benchmarks.bluff_shapes import errors as term_errors

    e = term_errors(a, ref)
    diag = [abs(x) for (i, j), x in e.items() if i == j]
    coup = [abs(x) for (i, j), x in e.items() if i != j]
    return max(diag), (max(coup) if coup else 0.0)


def run(shapes, families=("input", "remesh")):
    """Markdown rows: every shape with every family (module docstring)."""
    from stripcoef.geometry.mesh import mesh_body
    from stripcoef.hull.panels import (DEFAULT_PANELS, edge_features, fine_smooth_input,
                                       panel_added_mass)

    rows = ["| shape | faces | fine_smooth_input | family | levels | worst diagonal | worst "
            "coupling (of the scale) | diagonal covered | CPU [s] |", "|---" * 9 + "|"]
    for name, mesh, ref in shapes:
        body = mesh_body(mesh, name=name.split()[0])
        v, f = np.asarray(body.mesh.vertices, float), np.asarray(body.mesh.faces, np.int64)
        t0 = time.process_time()
        rule = fine_smooth_input(v, f, DEFAULT_PANELS, edge_features(v, f))
        t_rule = time.process_time() - t0
        for fam in families:
            t0 = time.process_time()
            try:
                a, info = panel_added_mass(body, rho=RHO, family=fam)
            except Exception as exc:                         # a family that cannot follow it
                rows.append(f"| {name} | {len(f)} | {rule} | {fam} | failed: {exc} | | | | |")
                continue
            cpu = time.process_time() - t0
            wd, wc = errors(a, ref)
            err = info["error"]
            d = np.diag(ref)
            ok = d > 1e-6 * d.max()
            covered = (np.abs(np.diag(a) - d) <= np.diag(err))[ok] if err is not None else None
            cov = "-" if covered is None else f"{int(covered.sum())}/{int(ok.sum())}"
            rows.append(f"| {name} | {len(f)} | {rule} ({t_rule:.2f} s) | {fam}: "
                        f"{info['family']} | {'/'.join(map(str, info['panels']))} | "
                        f"{100 * wd:.2f} % | {100 * wc:.2f} % | {cov} | {cpu:.2f} |")
            print(rows[-1], flush=True)
    return rows


def verdicts(cad=(), mirror=None):
    """Markdown rows: the rule's verdict (:func:`stripcoef.hull.panels.fine_smooth_input`
    at the default panels) on the surfaces the panel method is given: the CAD draws' true
    surfaces (``cad``: (seed, count) pairs, :func:`benchmarks.cad_shapes.clean_surface`, the
    parts united as a user's file is) and the public meshes as read by ``load_mesh`` (its
    defaults; a mesh refused as found is said so), their face counts and sharpest edges."""
    import tempfile
    from pathlib import Path

    from benchmarks.cad_shapes import clean_surface, drawn_shapes
    from stripcoef.hull.panels import DEFAULT_PANELS, edge_features, fine_smooth_input

    def one(label, v, f):
        v, f = np.asarray(v, float), np.asarray(f, np.int64)
        feats = edge_features(v, f)
        ok = fine_smooth_input(v, f, DEFAULT_PANELS, feats)
        return (f"| {label} | {len(f)} | {np.degrees(feats.turning):.0f} | {feats.folds} | "
                f"{ok} |")

    rows = ["| surface | faces | sharpest convex edge [deg] | folds | fine_smooth_input |",
            "|---|---|---|---|---|"]
    for seed, count in cad:
        for k, family, parts, _ in drawn_shapes(seed, count):
            m = clean_surface(parts)
            rows.append(one(f"CAD {seed}:{k} ({family})", m.vertices, m.faces))
    if mirror is not None:
        from benchmarks.public_meshes import MESHES, read_from_mirror
        from stripcoef.geometry.mesh import load_mesh

        with tempfile.TemporaryDirectory() as tmp:
            for mesh in MESHES:
                path = Path(tmp) / Path(mesh.path).name
                try:
                    path.write_bytes(read_from_mirror(Path(mirror), mesh))
                    body = load_mesh(path)
                    u = body.united() if hasattr(body, "united") else body.mesh
                except Exception as exc:                    # refused as found
                    rows.append(f"| {mesh.name} | - | - | - | not read as found: "
                                f"{str(exc)[:60]} |")
                    continue
                rows.append(one(mesh.name, u.vertices, u.faces))
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bluff", nargs="*", default=[],
                    help="shapes of benchmarks.bluff_shapes ('all': the 24)")
    ap.add_argument("--ellipsoids", type=int, default=0, help="seeded ellipsoids to draw")
    ap.add_argument("--seed", type=int, default=None, help="their seed (default: the clock)")
    ap.add_argument("--families", nargs="+", default=["input", "remesh"],
                    choices=("input", "remesh", "auto"))
    ap.add_argument("--verdicts", nargs="*", default=None, metavar="SEED:COUNT",
                    help="only the rule's verdict on these CAD draws (and --mirror's meshes)")
    ap.add_argument("--mirror", default=None, help="the public meshes' mirror (--verdicts)")
    args = ap.parse_args(argv)
    if args.verdicts is not None:
        cad = [tuple(int(x) for x in a.split(":")) for a in args.verdicts]
        print("\n".join(verdicts(cad, args.mirror)))
        return 0
    if args.bluff == ["all"]:
        from benchmarks.bluff_shapes import SHAPES

        args.bluff = list(SHAPES)
    shapes = bluff_draw(args.bluff)
    if args.ellipsoids:
        seed = int(time.time()) if args.seed is None else args.seed
        print(f"ellipsoid seed {seed}", flush=True)
        shapes += ellipsoid_draw(seed, args.ellipsoids)
    rows = run(shapes, tuple(args.families))
    print("\n" + "\n".join(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
