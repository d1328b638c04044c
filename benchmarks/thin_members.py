"""Thin plates and wings against converged Capytaine, a fresh seed per run (issue 32).

Draws thin members from two families, the shapes where a panel larger than the member's
thickness could go wrong:

- **plate**: a rectangular plate a x b x t, a from 0.1 to 0.4 m, b/a from 1 to 4, t/a from
  0.01 to 0.05 (a box: sharp 90-degree rims);
- **wing**: a NACA 00xx section (Abbott & von Doenhoff 1959, "Theory of Wing Sections",
  eq. 6.2, the closed-trailing-edge coefficient -0.1036) of chord c from 0.1 to 0.3 m and
  thickness t/c from 0.01 to 0.05, extruded to a span of 1.5 to 5 chords with flat tips (a
  knife-edge trailing edge and a leading-edge radius of 1.1 (t/c)^2 c).

Each is run through :func:`stripcoef.hull.panels.panel_added_mass` as the tool runs a mesh
(default panels, the isotropic remesh family of :mod:`stripcoef.hull.remesh`, refined while a
term's estimated error exceeds 5 %) about the volume centroid, against Capytaine (direct
method, no free surface) on isotropic remeshes at ``--bem-faces`` (coarse to fine), the two
finest Richardson-extrapolated with their own grid convergence index (:func:`bem_reference`).  Per term: the error of a diagonal term over
itself (a term below 1 % of the largest of its block -- a plate's in-plane surge -- over that
1 %, the panel method's own scale), of a coupling over sqrt(A_ii A_jj).  Usage:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.thin_members [--seed S] [--count N]
        [--bem-faces 1000 2000 4000] [--out benchmarks/data/thin_members.md]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

RHO = 1000.0
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
TOLERANCE = 0.05
SIGNIFICANT = 0.01


def naca_section(thickness: float, chord: float, points: int = 48) -> np.ndarray:
    r"""Closed NACA 00xx section [m], counter-clockwise from the trailing edge, cosine-spaced:
    :math:`y_t = 5 \tau c\,(0.2969\sqrt{x} - 0.1260 x - 0.3516 x^2 + 0.2843 x^3 - 0.1036 x^4)`,
    x = X/c (Abbott & von Doenhoff 1959, eq. 6.2, with the closed trailing edge's last
    coefficient)."""
    beta = np.linspace(0.0, np.pi, points)
    x = 0.5 * (1.0 - np.cos(beta))[::-1]                      # 1 -> 0 (TE to LE)
    yt = 5.0 * thickness * (0.2969 * np.sqrt(x) - 0.1260 * x - 0.3516 * x ** 2
                            + 0.2843 * x ** 3 - 0.1036 * x ** 4)
    upper = np.column_stack([x, yt])
    lower = np.column_stack([x[::-1], -yt[::-1]])[1:-1]       # LE -> TE, ends shared
    return np.vstack([upper, lower]) * chord


def wing_panels(thickness: float, chord: float, span: float, faces: int):
    """A structured panelling of the wing (trimesh.Trimesh, about ``faces`` triangles): the
    section at cosine-spaced points (dense at the leading and trailing edges, as wing panel
    methods place them: Katz & Plotkin 2001, sec. 11.1), span stations about as far apart as
    the mean chordwise spacing, flat tips fanned from their centroids."""
    import trimesh

    m = max(12, int(round(np.sqrt(faces * chord / span))))
    sec = naca_section(thickness, chord, m // 2 + 1)
    n = len(sec)
    ns = max(2, int(round(span * n / (2.0 * chord))))
    z = np.linspace(-0.5 * span, 0.5 * span, ns + 1)
    verts = [np.column_stack([sec[:, 0] - 0.5 * chord, sec[:, 1], np.full(n, zj)]) for zj in z]
    verts += [[[-0.5 * chord + sec[:, 0].mean(), 0.0, z[0]]],
              [[-0.5 * chord + sec[:, 0].mean(), 0.0, z[-1]]]]
    v = np.vstack(verts)
    i = np.arange(n)
    f = []
    for j in range(ns):
        a, b = j * n + i, j * n + (i + 1) % n
        f += [np.column_stack([a, b, b + n]), np.column_stack([a, b + n, a + n])]
    c0, c1 = (ns + 1) * n, (ns + 1) * n + 1
    f += [np.column_stack([np.full(n, c0), (i + 1) % n, i]),
          np.column_stack([np.full(n, c1), ns * n + i, ns * n + (i + 1) % n])]
    mesh = trimesh.Trimesh(v, np.vstack(f), process=True)
    trimesh.repair.fix_normals(mesh)
    return mesh


def make_member(kind: str, rng):
    """(trimesh.Trimesh, description, the reference's panelling: a function of the face
    count, or None for the remesh family) of one drawn thin member, centred at the origin."""
    import trimesh
    from shapely.geometry import Polygon

    if kind == "plate":
        a = rng.uniform(0.1, 0.4)
        b, t = a * rng.uniform(1.0, 4.0), a * rng.uniform(0.01, 0.05)
        return (trimesh.creation.box([a, b, t]),
                f"plate {a:.3f} x {b:.3f} x {1000 * t:.1f} mm (t/a {t / a:.3f})", None)
    c = rng.uniform(0.1, 0.3)
    tau, span = rng.uniform(0.01, 0.05), c * rng.uniform(1.5, 5.0)
    sec = naca_section(tau, c)
    m = trimesh.creation.extrude_polygon(Polygon(sec).buffer(0), span)
    m.apply_translation([-0.5 * c, 0.0, -0.5 * span])
    return (m, f"wing NACA 00xx t/c {tau:.3f} chord {c:.3f} span {span:.3f} m",
            lambda faces: wing_panels(tau, c, span, faces))


def bem_reference(mesh, bem_faces, about, max_faces: int = 6000, panelling=None):
    """Capytaine on panellings of ``mesh`` at about ``bem_faces`` faces -- ``panelling(n)``
    where given (a wing's structured panels), else one isotropic remesh family
    (:func:`stripcoef.hull.remesh.remesh_family`), else the member's faces bisected -- the two
    finest Richardson-extrapolated as 1/N, and its own grid convergence index plus the
    extrapolation's step (Roache 1998).  Returns (reference, face counts, its estimated
    error)."""
    from stripcoef.bem import bem_added_mass
    from stripcoef.hull.convergence import grid_convergence_index, richardson
    from stripcoef.hull.panels import estimated_error
    from stripcoef.hull.remesh import edge_for_panels, remesh_family

    import trimesh

    from benchmarks.bluff_shapes import refine

    v, f = np.asarray(mesh.vertices, float), np.asarray(mesh.faces)
    family = None if panelling is not None else remesh_family(
        v, f, [edge_for_panels(float(mesh.area), n) for n in bem_faces], max_faces=max_faces)
    if panelling is not None:                   # a wing: its structured panellings
        meshes = [panelling(n) for n in bem_faces]
    elif family is not None:
        meshes = [trimesh.Trimesh(rv, rf, process=False) for rv, rf in family[0]]
    else:
        meshes = [refine(mesh, n) for n in bem_faces]
    mats, counts = [], []
    for m in meshes:
        mats.append(bem_added_mass(m, rho=RHO, reference_point=about, max_faces=max_faces))
        counts.append(len(m.faces))
    ref = richardson(mats[-2], mats[-1], counts[-2], counts[-1])
    gci, _, _ = grid_convergence_index(mats, counts)
    return ref, counts, estimated_error(mats[-1], ref, gci)


def run_one(kind, rng, bem_faces):
    from stripcoef.hull.panels import NEGLIGIBLE, panel_added_mass

    mesh, what, panelling = make_member(kind, rng)
    about = np.asarray(mesh.center_mass)
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ours, info = panel_added_mass(mesh, rho=RHO, about=about)
    t_model = time.perf_counter() - t0
    t0 = time.perf_counter()
    ref, counts, ref_err = bem_reference(mesh, bem_faces, about, panelling=panelling)
    ref = 0.5 * (ref + ref.T)
    t_bem = time.perf_counter() - t0
    dg = np.abs(np.diag(ref)).copy()
    for block in (slice(0, 3), slice(3, 6)):
        dg[block] = np.maximum(dg[block], NEGLIGIBLE * dg[block].max())
    scale = np.sqrt(np.outer(dg, dg))
    err = (ours - ref) / scale
    est = np.asarray(info["error"]) / scale
    sig = np.eye(6, dtype=bool) | (np.abs(ref) >= SIGNIFICANT * scale)
    iu = np.triu_indices(6)
    diag_err = np.diag(err)
    coup = [(abs(err[i, j]), i, j) for i, j in zip(*iu) if i != j and sig[i, j]]
    return dict(kind=kind, what=what, levels=info["panels"], counts=counts,
                diag=diag_err, est=np.diag(est), worst_coupling=max(coup) if coup else None,
                covered=int(sum(abs(err[i, j]) <= est[i, j] for i, j in zip(*iu)
                                if sig[i, j])),
                terms=int(sum(sig[i, j] for i, j in zip(*iu))),
                bem_est=float(np.max(np.diag(np.asarray(ref_err) / scale))),
                t_model=t_model, t_bem=t_bem, converged=info["converged"])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=None, help="default: a fresh one")
    ap.add_argument("--count", type=int, default=8, help="members (plates and wings alike)")
    ap.add_argument("--bem-faces", type=int, nargs="+", default=(1000, 2000, 4000))
    ap.add_argument("--out", default=None, help="write the table (markdown) here")
    args = ap.parse_args(argv)
    seed = args.seed if args.seed is not None else int(np.random.SeedSequence().entropy
                                                         % 2 ** 32)
    rng = np.random.default_rng(seed)
    cmd = (f"python -m benchmarks.thin_members --seed {seed} --count {args.count} "
           f"--bem-faces {' '.join(map(str, args.bem_faces))}")
    print(cmd, flush=True)
    rows = []
    for k in range(args.count):
        kind = ("plate", "wing")[k % 2]
        try:
            r = run_one(kind, rng, args.bem_faces)
        except Exception as exc:                # a failure is a result: say it, go on
            print(f"{k} {kind}: FAILED: {type(exc).__name__}: {exc}", flush=True)
            continue
        rows.append(r)
        w = int(np.argmax(np.abs(r["diag"])))
        print(f"{k} {r['what']}: panels {'/'.join(map(str, r['levels']))}, worst diagonal "
              f"{DOFS[w]} {100 * r['diag'][w]:+.1f} % (est. {100 * r['est'][w]:.1f} %), "
              f"BEM {'/'.join(map(str, r['counts']))} (its est. {100 * r['bem_est']:.1f} %); "
              f"{r['t_model']:.1f} s vs {r['t_bem']:.1f} s", flush=True)
    ok = sum(int(np.sum(np.abs(r["diag"]) <= TOLERANCE)) for r in rows)
    cov = sum(r["covered"] for r in rows)
    nt = sum(r["terms"] for r in rows)
    lines = [f"    {cmd}", "",
             f"{len(rows)} members: diagonal terms within 5 % of Capytaine: {ok} of "
             f"{6 * len(rows)}; the estimated error covers the actual error in {cov} of {nt} "
             "terms (diagonal and significant couplings).", "",
             "| # | member | panel levels | " + " | ".join(DOFS)
             + " | worst coupling (of scale) | est. covers | BEM faces | BEM est. max | "
             "time model / BEM [s] |",
             "|---" * 13 + "|"]
    for k, r in enumerate(rows):
        wc = r["worst_coupling"]
        lines.append(
            f"| {k} | {r['what']} | {'/'.join(map(str, r['levels']))} | "
            + " | ".join(f"{100 * e:+.1f} %" for e in r["diag"]) + " | "
            + (f"{DOFS[wc[1]]}-{DOFS[wc[2]]} {100 * wc[0]:.1f} %" if wc else "-")
            + f" | {r['covered']}/{r['terms']} | {'/'.join(map(str, r['counts']))} | "
            f"{100 * r['bem_est']:.1f} % | {r['t_model']:.1f} / {r['t_bem']:.1f} |")
    text = "\n".join(lines) + "\n"
    print(text)
    if args.out:
        with open(args.out, "w") as fh:
            fh.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
