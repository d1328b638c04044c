"""Edge-graded panel levels for the frames (issue 32): do they make the panel method's ladder
asymptotic at a modest cost?  Measured, not adopted (benchmarks/data/frame_graded_ladder.md).

The default levels of the BlueROV2 Heavy vehicle file (geometry/bluerov2_heavy.yaml: 9.5-12.7 mm
plates, 5.6 mm duct walls) are the input's faces bisected, 1712/3966/9120 panels on the y
mirror plane; their values converge from above at an observed order 1.1-1.3 (surge, yaw) that
rises with refinement, and the order-1 extrapolation the knife-edge rule prescribes lands
6.8-10 % below the graded reference (benchmarks/data/frame_order.md).  Constant panels at a
convex edge of angle omega converge as h^(2 pi / omega) on uniform meshes; panels graded
towards the edges restore the smooth body's rate (von Petersdorff & Stephan 1990, Math. Methods
Appl. Sci. 12, 229-249).  Two graded panellings of the body's y >= 0 half, each solved by this
project's own panel method on its xOz mirror plane
(:func:`stripcoef.hull.mirror_panels.solve_mirrored`), at a few largest panels H [m]:

- ``bisect``: the base install's own means, the vehicle file's surface (its y >= 0 part closed by
  a cap, :func:`stripcoef.hull.mirror_panels.capped_part`) bisected along longest edges
  (Rivara 1984, :func:`stripcoef.hull.bisection.bisect_graded`) to the references' sizing
  h(d) = min(H, H/4 + d/4) at a distance d from the nearest convex edge sharper than 30 deg
  (the graded reference mesher's rule, :mod:`benchmarks.graded_mesher`), its cap dropped;
- ``uniform``: the comparator, the same capped half bisected uniformly (longest edge at most
  H/3), the default levels' kind;
- ``gmsh``: the graded references' own mesher (:func:`benchmarks.graded_mesher.graded_mesh`,
  gmsh Frontal-Delaunay at the same sizing; the ``graded`` extra).

Per level: panels, CPU of the mesh and of the solve [s], and each diagonal term against the
graded reference (reference_tables/bem/graded_frames.csv, Eça & Hoekstra over its six levels,
moved to the estimate's reference point); each consecutive pair Richardson-extrapolated at
orders 1, 4/3 and 2; the process's peak resident memory.  ``--shape SEED:K`` measures shape K
of a stored CAD seed (its user file as ``benchmarks.cad_shapes`` writes it, mirrored in y
through the model's reference point) against that seed's stored reference
(reference_tables/bem/cad_shapes_SEED.csv) instead.

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame_graded_ladder [--mesher bisect gmsh]
        [--H 0.4 0.256 0.181 0.128] [--shape 1795919297:22] [--write]
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame_graded_ladder --volumes --H 0.4 ... 0.045
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame_graded_ladder --trial --shape SEED:K ...

``gmsh`` needs the ``graded`` extra (``pip install -e '.[graded]'``).  ``--volumes``: the gmsh
halves' volume against the surface, no solve.  ``--trial``: each shape's whole estimate as it
is and with thin members' levels bisected instead of remeshed without flips
(:func:`bisected_thin_family`), against the seed's most resolved references.
"""

from __future__ import annotations

import argparse
import os
import resource
import tempfile
import time
import warnings
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from stripcoef.conventions import DOF as DOFS  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "data" / "frame_graded_ladder.md"
FILE = "geometry/bluerov2_heavy.yaml"
RHO = 1000.0
#: largest panel H [m] of each level (the graded references' rule H/4 at an edge)
LEVELS = (0.4, 0.256, 0.181, 0.128)
#: the uniform comparator's longest edge is H over this [-] (a count near the graded level's)
UNIFORM_DIVISOR = 3.0
#: dihedral [deg] beyond which a convex edge is graded towards (as benchmarks.graded_mesher)
ANGLE = 30.0


def convex_sharp_edges(v, f, angle: float = ANGLE) -> np.ndarray:
    """(k, 2, 3) [m] the edges of a closed mesh whose dihedral exceeds ``angle`` [deg] and
    that are convex (the other face's centroid behind the first face's plane): where the flow
    is singular (Newman 1977 sec. 4.4)."""
    t = v[f]
    n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    c = t.mean(axis=1)
    a = f.reshape(-1)
    b = np.roll(f, -1, axis=1).reshape(-1)
    key = np.minimum(a, b) * len(v) + np.maximum(a, b)
    order = np.argsort(key, kind="stable")
    ks = key[order]
    pair = np.flatnonzero(ks[1:] == ks[:-1])
    f1, f2 = order[pair] // 3, order[pair + 1] // 3
    sharp = np.einsum("ij,ij->i", n[f1], n[f2]) < np.cos(np.radians(angle))
    convex = np.einsum("ij,ij->i", c[f2] - c[f1], n[f1]) < 0.0
    e = order[pair][sharp & convex]
    return np.stack([v[a[e]], v[b[e]]], axis=1)


def heavy():
    """(closed surface (v, f) [m], reference point [m], reference diagonal, its label)."""
    from benchmarks.frame_order import graded_levels
    from stripcoef.assembly import estimate
    from stripcoef.assembly.added_mass import panel_surface
    from stripcoef.geometry.vehicle import load_vehicle
    from stripcoef.hull.panels import DEFAULT_PANELS

    veh = load_vehicle(ROOT / FILE)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = estimate(veh)
    about = np.asarray(model.reference_point, float)
    surf = panel_surface(veh, DEFAULT_PANELS)
    _, _, ref = graded_levels(about)
    return ((np.asarray(surf.vertices, float), np.asarray(surf.faces, np.int64)), about, ref,
            f"{FILE} against the graded reference (reference_tables/bem/graded_frames.csv)",
            np.diag(np.asarray(model.added_mass)) * RHO / model.density)


def cad_shape(seed: int, k: int):
    """As :func:`heavy` for shape ``k`` of a stored CAD seed (its stored reference)."""
    from benchmarks.cad_shapes import user_files
    from stripcoef.assembly import estimate
    from stripcoef.geometry.vehicle import load_vehicle
    from validation.cad_shapes import best_references

    path = ROOT / "reference_tables" / "bem" / f"cad_shapes_{seed}.csv"
    best = best_references(path)
    ref = np.array([best[(k, i, i)][0] for i in range(6)])
    with tempfile.TemporaryDirectory() as tmp:
        (_, _, file, unit), = list(user_files(seed, k + 1, tmp, only={k}))
        veh = load_vehicle(file, length_unit=unit, origin=(0.0, 0.0, 0.0))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            model = estimate(veh, added_mass_method="panels")
    from stripcoef.assembly.added_mass import panel_surface
    from stripcoef.hull.panels import DEFAULT_PANELS

    surf = panel_surface(veh, DEFAULT_PANELS)
    body = surf.united() if hasattr(surf, "united") else getattr(surf, "mesh", surf)
    return ((np.asarray(body.vertices, float), np.asarray(body.faces, np.int64)),
            np.asarray(model.reference_point, float), ref,
            f"shape {k} of seed {seed} against its most resolved reference ({path.name}, "
            "validation.cad_shapes.best_references)",
            np.diag(np.asarray(model.added_mass)) * RHO / model.density)


def bisect_half(v, f, about, H):
    """The y >= 0 half of the closed surface bisected to the graded sizing (module docstring):
    (triangles (n, 3, 3) [m] of the open half, CPU [s])."""
    from stripcoef.hull.bisection import bisect_graded
    from stripcoef.hull.mirror_panels import capped_part, drop_caps
    from stripcoef.hull.remesh import distance_to_segments

    t0 = time.process_time()
    seg = convex_sharp_edges(v, f)
    part = capped_part(v, f, ("y",), about)
    pv, pf = bisect_graded(*part, lambda c: np.minimum(
        H, H / 4.0 + 0.25 * distance_to_segments(c, seg)))
    pv, pf = drop_caps(pv, pf, ("y",), about)
    return pv[pf], time.process_time() - t0


def uniform_half(v, f, about, H):
    """The comparator of :func:`bisect_half`: the same capped half bisected uniformly, longest
    edge at most H / :data:`UNIFORM_DIVISOR` (no grading)."""
    from stripcoef.hull.bisection import bisect_longest
    from stripcoef.hull.mirror_panels import capped_part, drop_caps

    t0 = time.process_time()
    pv, pf = bisect_longest(*capped_part(v, f, ("y",), about), H / UNIFORM_DIVISOR)
    pv, pf = drop_caps(pv, pf, ("y",), about)
    return pv[pf], time.process_time() - t0


def gmsh_half(v, f, about, H):
    """The y >= 0 half remeshed by the graded references' mesher (about at the origin)."""
    import trimesh

    from benchmarks.graded_mesher import graded_mesh

    t0 = time.process_time()
    tm = trimesh.Trimesh(v - about, f, process=True)
    gv, gf = graded_mesh(tm, H, mirror=True)
    return gv[gf] + about, time.process_time() - t0


def volume_change(tri, about, surface) -> float:
    """Relative volume change [-] of the half ``tri`` with its image against the surface's."""
    from stripcoef.hull.bisection import enclosed_volume
    from stripcoef.hull.mirror_panels import mirror_full

    v, f = tri.reshape(-1, 3), np.arange(3 * len(tri)).reshape(-1, 3)
    return enclosed_volume(*mirror_full(v, f, ("y",), about)) / enclosed_volume(*surface) - 1.0


def levels(surface, about, mesher: str, hs):
    """[(panels of the whole body, diagonal (6,), mesh CPU [s], solve CPU [s], H [m],
    volume change [-])]."""
    from stripcoef.hull.mirror_panels import solve_mirrored

    make = {"bisect": bisect_half, "uniform": uniform_half, "gmsh": gmsh_half}[mesher]
    out = []
    for H in hs:
        tri, cpu_mesh = make(*surface, about, H)
        t0 = time.process_time()
        a = solve_mirrored(tri, ("y",), rho=RHO, about=about)
        out.append((2 * len(tri), np.diag(a), cpu_mesh, time.process_time() - t0, H,
                    volume_change(tri, about, surface)))
        print(f"{mesher} H {H}: {2 * len(tri)} panels, mesh {cpu_mesh:.1f} s, solve "
              f"{out[-1][3]:.1f} s", flush=True)
    return out


def _pct(x):
    return f"{100 * x:+.1f} %"


def table(mesher, rows, ref) -> list:
    from stripcoef.hull.convergence import richardson

    lines = [f"### {mesher}", "", "| level | H [m] | panels | volume | CPU mesh + solve [s] | "
             + " | ".join(DOFS) + " |", "|---" * 11 + "|"]
    for k, (n, d, cm, cs, H, dv) in enumerate(rows):
        lines.append(f"| {k} | {H:g} | {n} | {100 * dv:+.2f} % | {cm:.1f} + {cs:.1f} | "
                     + " | ".join(_pct(x / r - 1) for x, r in zip(d, ref)) + " |")
    for p in (1.0, 4.0 / 3.0, 2.0):
        for k in range(1, len(rows)):
            (n1, d1, *_), (n2, d2, *_) = rows[k - 1], rows[k]
            if n2 <= n1:
                continue
            r = richardson(d1, d2, n1, n2, order=p)
            lines.append(f"| Richardson {n1}/{n2}, order {p:.2f} | | | | | "
                         + " | ".join(_pct(x / y - 1) for x, y in zip(r, ref)) + " |")
    return lines + [""]


def volumes(hs, write: bool) -> int:
    """The graded references' mesher on the vehicle file's y >= 0 half at each H: faces of the
    whole, volume change against the surface, CPU of the mesh (no solve)."""
    surface, about, *_ = heavy()
    lines = ["`OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame_graded_ladder --volumes --H "
             + " ".join(f"{h:g}" for h in hs) + "`", "",
             "| H [m] | faces | volume | CPU mesh [s] |", "|---|---|---|---|"]
    for H in hs:
        tri, cpu = gmsh_half(*surface, about, H)
        lines.append(f"| {H:g} | {2 * len(tri)} | "
                     f"{100 * volume_change(tri, about, surface):+.2f} % | {cpu:.1f} |")
        print(lines[-1], flush=True)
    if write:
        with open(OUT, "a") as fh:
            fh.write("\n".join(lines) + "\n\n")
    return 0


def bisected_thin_family(original):
    """A stand-in for :func:`stripcoef.hull.panels._family` for the trial of ``--trial``: where
    the family it finds is a no-flip remesh (the thin-member modes), the input's faces bisected
    instead (the last mode of :data:`stripcoef.hull.remesh.MODES`)."""
    from stripcoef.hull.remesh import MODES

    def family(vertices, faces, edges, modes):
        out = original(vertices, faces, edges, modes)
        if out is not None and not out[1].flips and not out[1].bisect:
            return original(vertices, faces, edges, tuple(m for m in MODES if m.bisect))
        return out
    return family


def trial(shapes, write: bool) -> int:
    """Each of ``shapes`` (SEED:K) estimated as ``benchmarks.cad_shapes`` does, as it is and with
    :func:`bisected_thin_family` in place: the levels, each diagonal term against the most
    resolved reference, the largest estimated error over the term, CPU."""
    from benchmarks.cad_shapes import patched_estimates
    from stripcoef.hull import panels as P
    from validation.cad_shapes import best_references

    lines = ["`OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame_graded_ladder --trial "
             + " ".join(shapes) + "`", "",
             "| shape | family | levels | " + " | ".join(DOFS)
             + " | worst estimate / error | CPU [s] |", "|---" * 11 + "|"]
    for what in shapes:
        seed, k = (int(x) for x in what.split(":"))
        best = best_references(ROOT / "reference_tables" / "bem" / f"cad_shapes_{seed}.csv")
        ref = np.array([best[(k, i, i)][0] for i in range(6)])
        for name, patches in (("as is", {}),
                              ("thin: bisected", {(P, "_family"): bisected_thin_family(
                                  P._family)})):
            for _, _, model, cpu in patched_estimates(seed, k + 1, patches, only={k}):
                d = np.diag(np.asarray(model.added_mass)) * RHO / model.density
                est = np.diag(np.asarray(model.added_mass_error)) * RHO / model.density
                err = d / ref - 1.0
                cover = float(np.min(est / np.maximum(np.abs(d - ref), 1e-300)))
                lines.append(f"| {what} | {name} | "
                             + "/".join(map(str, model.conditions["added_mass_panel_levels"]))
                             + " | " + " | ".join(_pct(x) for x in err)
                             + f" | {cover:.2f} | {cpu:.1f} |")
                print(lines[-1], flush=True)
    if write:
        with open(OUT, "a") as fh:
            fh.write("\n".join(lines) + "\n\n")
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesher", nargs="+", default=["bisect", "gmsh"],
                    choices=("bisect", "uniform", "gmsh"))
    ap.add_argument("--H", type=float, nargs="+", default=list(LEVELS))
    ap.add_argument("--shape", nargs="+", default=None, metavar="SEED:K",
                    help="shapes K of stored CAD seeds instead of the vehicle file")
    ap.add_argument("--volumes", action="store_true",
                    help="the vehicle file's gmsh halves at --H meshed only: faces, volume, CPU")
    ap.add_argument("--trial", action="store_true",
                    help="the --shape shapes' whole estimate as is and with thin members' "
                         "levels bisected (bisected_thin_family)")
    ap.add_argument("--write", action="store_true", help=f"append to {OUT.relative_to(ROOT)}")
    args = ap.parse_args(argv)
    if args.volumes:
        return volumes(args.H, args.write)
    if args.trial:
        return trial(args.shape, args.write)
    cmd = ("OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame_graded_ladder --mesher "
           + " ".join(args.mesher) + " --H " + " ".join(f"{h:g}" for h in args.H)
           + (" --shape " + " ".join(args.shape) if args.shape else ""))
    lines = [f"`{cmd}`", ""]
    for what in args.shape or [None]:
        if what:
            seed, k = (int(x) for x in what.split(":"))
            surface, about, ref, label, model = cad_shape(seed, k)
        else:
            surface, about, ref, label, model = heavy()
        head = len(lines)
        lines += [f"## {label}", "", f"About {np.round(about, 5).tolist()} m; the default "
                  "estimate (this install): " + ", ".join(
                      f"{d} {_pct(x / r - 1)}" for d, x, r in zip(DOFS, model, ref)) + ".", ""]
        for mesher in args.mesher:
            lines += table(mesher, levels(surface, about, mesher, args.H), ref)
        print("\n".join(lines[head:]), flush=True)
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6
    lines.append(f"Peak resident memory of the run: {peak:.2f} GB.")
    text = "\n".join(lines) + "\n"
    print(lines[-1])
    if args.write:
        with open(OUT, "a") as fh:
            fh.write(text + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
