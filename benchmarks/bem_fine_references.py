"""Finer Capytaine references for the CAD-style shapes: five levels up to 24,000 faces.

The CAD-shape benchmark (benchmarks/cad_shapes.py) takes its reference from Capytaine at
750/1500/3000 faces, the two finest Richardson-extrapolated as 1/N; on the shapes with sharp
edges those references carry a grid convergence index of up to 161 % on the terms that
differ from the panel method by more than 5 % (issue 32), so "within 5 % of converged
Capytaine" was not measurable there.  This script computes the same references on the same
surfaces (the shapes of one seed, their manifold union, isotropic remeshes of the same
family: stripcoef.hull.remesh.remesh_family) at 1500, 3000, 6000, 12000 and 24000 faces, where
a dense 24,000-face solve (9 GB per matrix) is beyond this project's two-core machine, in
three steps:

    # 1. the meshes (needs the remesh extra, pymeshlab), a few minutes:
    python -m benchmarks.bem_fine_references prepare --seed 1375923287 --count 40 --out DIR
    # 2. Capytaine on every level (a 16-core machine: the influence matrices by Capytaine's
    #    OpenMP Fortran; the LU factorisation on a GPU through torch where there is one, else
    #    Capytaine's own LAPACK LU), writing one CSV row per matrix term as it goes:
    python -m benchmarks.bem_fine_references solve --meshes DIR --csv levels.csv
    # 3. the estimate from the levels and the comparison with the model rows of a stored
    #    run, by the three finest levels' grid convergence index (before) and by Eça &
    #    Hoekstra's least squares over all the levels (validation.cad_shapes.fine_reference),
    #    in one table; --holdout: the bands tested on a level they did not see:
    python -m benchmarks.bem_fine_references compare --levels levels.csv [more.csv] \\
        --model reference_tables/bem/cad_shapes.csv [--holdout] [--edge-orders Q ...]

The 750-face level of the same remesh family (that of benchmarks.cad_shapes' stored
references, whose 1,500- and 3,000-face levels are the fine levels' two coarsest):

    python -m benchmarks.bem_fine_references prepare --seed 1375923287 --count 40 --out DIR \\
        --levels 750 1500 3000 --cad-shapes-cap
    python -m benchmarks.bem_fine_references solve --meshes DIR --csv levels_750.csv \\
        --max-level 0 --same-family reference_tables/bem/cad_shapes_fine_levels.csv

``prepare --thin --seed S --count N`` writes the thin plates and wings of
benchmarks.thin_members instead (shapes 100 and up).  The stored levels are
reference_tables/bem/cad_shapes_fine_levels.csv; the extrapolation and the comparison are
validation.cad_shapes.fine_reference and fine_comparison (docs/validation.md, "The references
refined to 12,000 faces").
"""

from __future__ import annotations

import argparse
import csv
import sys
import time
from pathlib import Path

import numpy as np

LEVELS = (1500, 3000, 6000, 12000, 24000)
RHO = 1000.0


# ----------------------------------------------------------------------------- prepare
def prepare(seed: int, count: int, out: Path, levels=LEVELS, max_faces: int | None = -1) -> None:
    """Draw the shapes of ``seed`` exactly as benchmarks.cad_shapes does and write each one's
    remesh family (float64 vertices [m], int32 faces) to ``out/shape_KK.npz``; ``max_faces``
    the family's face cap (-1: 1.6 times the finest level's target; None: the remesher's
    default, as benchmarks.cad_shapes.bem_reference calls it)."""
    from benchmarks.cad_shapes import clean_surface, drawn_shapes
    from stripcoef.hull.remesh import edge_for_panels, remesh_family

    out.mkdir(parents=True, exist_ok=True)
    for k, family, parts, what in drawn_shapes(seed, count):
        surface = clean_surface(parts)
        v, f = np.asarray(surface.vertices, float), np.asarray(surface.faces)
        t0 = time.perf_counter()
        fam = remesh_family(v, f, [edge_for_panels(float(surface.area), n) for n in levels],
                            max_faces=int(1.6 * levels[-1]) if max_faces == -1 else max_faces)
        if fam is None:
            print(f"{k:3d} {family:12s} no remesh family: skipped", flush=True)
            continue
        arrays = {}
        for i, (lv, lf) in enumerate(fam[0]):
            arrays[f"v{i}"] = np.asarray(lv, np.float64)
            arrays[f"f{i}"] = np.asarray(lf, np.int32)
        np.savez_compressed(out / f"shape_{k:02d}.npz", family=family, what=what,
                            mode=str(fam[1]), **arrays)
        print(f"{k:3d} {family:12s} {[len(x[1]) for x in fam[0]]} "
              f"({time.perf_counter() - t0:.1f} s)", flush=True)


THIN_LEVELS = (1000, 2000, 4000, 8000, 16000)


def prepare_thin(seed: int, count: int, out: Path, levels=THIN_LEVELS) -> None:
    """The thin plates and wings of ``seed`` as benchmarks.thin_members draws them (the
    model's own draws skipped: it draws nothing), about their volume centroid (moved to the
    origin), at the reference panellings of that benchmark (a wing's structured panels, a
    plate's remesh family) at ``levels`` faces; ``out/shape_{THIN_OFFSET + k}.npz``
    (validation.cad_shapes.THIN_OFFSET)."""
    import trimesh

    from benchmarks.thin_members import make_member
    from validation.cad_shapes import THIN_OFFSET
    from stripcoef.hull.remesh import edge_for_panels, remesh_family

    out.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(seed)
    for k in range(count):
        kind = ("plate", "wing")[k % 2]
        mesh, what, panelling = make_member(kind, rng)
        about = np.asarray(mesh.center_mass)
        if panelling is not None:
            meshes = [panelling(n) for n in levels]
        else:
            fam = remesh_family(np.asarray(mesh.vertices, float), np.asarray(mesh.faces),
                                [edge_for_panels(float(mesh.area), n) for n in levels],
                                max_faces=int(1.6 * levels[-1]))
            meshes = [trimesh.Trimesh(v, f, process=False) for v, f in fam[0]]
        arrays = {}
        for i, m in enumerate(meshes):
            arrays[f"v{i}"] = np.asarray(m.vertices, np.float64) - about
            arrays[f"f{i}"] = np.asarray(m.faces, np.int32)
        np.savez_compressed(out / f"shape_{THIN_OFFSET + k:03d}.npz", family=kind, what=what,
                            about=about, **arrays)
        print(f"{THIN_OFFSET + k:3d} {kind:6s} {what}: {[len(m.faces) for m in meshes]}",
              flush=True)


# ------------------------------------------------------------------------------- solve
class _TorchLU:
    """Capytaine's linear solver on a GPU: A's LU factors (torch.linalg.lu_factor) kept for
    the six radiation problems that share A, then one triangular solve per right-hand side."""

    def __init__(self, torch):
        self.torch, self.a, self.lu, self.piv = torch, None, None, None

    def __call__(self, a, b):
        torch = self.torch
        if self.a is not a:
            self.a, self.lu, self.piv = None, None, None
            torch.cuda.empty_cache()
            self.lu, self.piv = torch.linalg.lu_factor(torch.as_tensor(np.asarray(a),
                                                                       device="cuda"))
            self.a = a
        def one(rhs):
            t = torch.as_tensor(np.ascontiguousarray(rhs), device="cuda",
                                dtype=self.lu.dtype).reshape(-1, 1)
            return torch.linalg.lu_solve(self.lu, self.piv, t).reshape(-1).cpu().numpy()
        if np.iscomplexobj(b) and not self.lu.dtype.is_complex:
            return (one(b.real) + 1j * one(b.imag)).reshape(b.shape)
        return one(b).reshape(b.shape)


def _solver():
    import capytaine as cpt
    try:
        import torch
        gpu = torch.cuda.is_available()
    except ImportError:
        gpu = False
    engine = (cpt.DefaultMatrixEngine(linear_solver=_TorchLU(torch)) if gpu
              else cpt.DefaultMatrixEngine())
    return cpt.BEMSolver(method="direct", engine=engine), ("torch-cuda LU" if gpu else "LAPACK LU")


def added_mass(solver, vertices, faces, rho=RHO):
    """Capytaine's 6x6 added mass [kg, kg m, kg m^2] about the origin, no free surface
    (the same problem as stripcoef.bem.bem_added_mass, set up here because ``solve`` runs
    where neither stripcoef's dependencies (trimesh) are installed nor its solver can take a
    GPU linear solver)."""
    import capytaine as cpt
    names = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
    mesh = cpt.Mesh(vertices=vertices, faces=faces, name="body")
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)),
                            name="body")
    problems = [cpt.RadiationProblem(body=body, radiating_dof=d, free_surface=np.inf,
                                     omega=np.inf, rho=rho) for d in names]
    a = np.zeros((6, 6))
    for j, res in enumerate(solver.solve_all(problems, progress_bar=False)):
        for i, d in enumerate(names):
            a[i, j] = float(np.real(res.added_mass[d]))
    return 0.5 * (a + a.T)


def solve(meshes: Path, csv_path: Path, max_level: int | None = None, order=None,
          min_level: int = 0, same_family: Path | None = None) -> None:
    """Every level of every ``meshes/shape_*.npz``, coarse levels of all shapes first (within
    a level, the shapes listed in ``order`` first), one CSV row per upper-triangle term,
    flushed after every solve (a run cut short keeps what it solved).  ``same_family``: a
    levels CSV; only the shapes whose levels 1 and 2 have the faces of its levels 0 and 1 (one
    remesh family, the remesher being deterministic) are solved."""
    import logging
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    files = sorted(meshes.glob("shape_*.npz"))
    data = {p.stem: np.load(p) for p in files}
    if same_family is not None:
        known: dict = {}
        with open(same_family, newline="") as fh:
            for r in csv.DictReader(fh):
                known.setdefault(int(r["shape"]), {})[int(r["level"])] = int(r["faces"])
        keep = {}
        for name, d in data.items():
            lv = known.get(int(name.split("_")[1]), {})
            faces = [len(d[f"f{i}"]) for i in (1, 2) if f"f{i}" in d.files]
            if faces == [lv.get(0), lv.get(1)]:
                keep[name] = d
            else:
                print(f"{name}: levels {faces} are not {[lv.get(0), lv.get(1)]}: another "
                      "family, skipped", flush=True)
        data = keep
    named = {int(n.split("_")[1]): n for n in data}
    first = [named[k] for k in (order or []) if k in named]
    data = {name: data[name] for name in first + [n for n in data if n not in first]}
    nlev = max(sum(1 for k in d.files if k.startswith("f")) for d in data.values())
    if max_level is not None:
        nlev = min(nlev, max_level + 1)
    solver, how = _solver()
    print(f"{len(files)} shapes, {nlev} levels, linear solver: {how}", flush=True)
    with open(csv_path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["shape", "level", "faces", "seconds", "i", "j", "added_mass"])
        for level in range(min_level, nlev):
            for name, d in data.items():
                if f"f{level}" not in d.files:
                    continue
                v, f = d[f"v{level}"].astype(float), d[f"f{level}"].astype(np.int64)
                t0 = time.perf_counter()
                a = added_mass(solver, v, f)
                dt = time.perf_counter() - t0
                k = int(name.split("_")[1])
                for i in range(6):
                    for j in range(i, 6):
                        w.writerow([k, level, len(f), f"{dt:.2f}", i, j, repr(float(a[i, j]))])
                fh.flush()
                print(f"shape {k:2d} level {level} {len(f):6d} faces {dt:7.1f} s", flush=True)


# ----------------------------------------------------------------------------- compare
def _measures(rows, misses) -> dict:
    """The comparison's counts of ``rows`` (validation.cad_shapes.fine_comparison) as
    {label: text}; ``misses``: the (shape, i) of the diagonal terms off by more than 5 %
    against the references of the first method (the before)."""
    diag = [r for r in rows if r["i"] == r["j"]]
    sig = [r for r in rows if r["significant"]]
    coup = [r for r in sig if r["i"] != r["j"]]
    bands = np.array([r["band"] for r in diag])
    hard = [r for r in diag if (r["shape"], r["i"]) in misses]

    def frac(good, of):
        return f"{good} of {len(of)}"

    out = {"diagonal within 5 %": frac(sum(abs(r["err"]) <= 0.05 for r in diag), diag)}
    for limit in (0.05, 0.02):
        tight = [r for r in diag if r["band"] <= limit]
        out[f"  where the reference's band <= {100 * limit:.0f} %"] = frac(
            sum(abs(r["err"]) <= 0.05 for r in tight), tight)
    out["couplings within 5 % of the scale"] = frac(
        sum(abs(r["err"]) <= 0.05 for r in coup), coup)
    out["the model's estimate covers its error"] = frac(
        sum(abs(r["err"]) <= r["est"] for r in sig), sig)
    out["  with the reference's band, root-sum-square"] = frac(
        sum(abs(r["err"]) <= np.hypot(r["est"], r["band"]) for r in sig), sig)
    out["3,000-face references within 5 % (diagonal)"] = frac(
        sum(abs(r["stored_err"]) <= 0.05 for r in diag), diag)
    out["reference's band, diagonal: median / max"] = (
        f"{100 * np.median(bands):.1f} % / {100 * bands.max():.0f} %")
    out["reference's band over 5 % (diagonal)"] = frac(int((bands > 0.05).sum()), diag)
    out[f"the {len(misses)} terms missed before: band <= 5 %"] = frac(
        sum(r["band"] <= 0.05 for r in hard), hard)
    out[f"the {len(misses)} terms missed before: model within 5 %"] = frac(
        sum(abs(r["err"]) <= 0.05 for r in hard), hard)
    out[f"the {len(misses)} terms missed before: error within band"] = frac(
        sum(abs(r["err"]) <= r["band"] for r in hard), hard)
    return out


def compare(levels_csv, model_csv, edge_orders=()) -> None:
    """The model rows of a stored benchmarks.cad_shapes run against the fine references
    (validation.cad_shapes.fine_comparison: the same numbers as docs/validation.md), by
    each way of estimating the reference from the levels, in one table: the three finest
    levels' grid convergence index (before), Eça & Hoekstra's least squares over all levels,
    and (``edge_orders``) the latter with fixed orders that edge singularities imply among
    its alternative fits."""
    from stripcoef.conventions import DOF as DOFS
    from validation.cad_shapes import fine_comparison

    levels_csv = [levels_csv] if isinstance(levels_csv, (str, Path)) else list(levels_csv)
    methods = [("GCI, 3 finest", levels_csv, "gci", ())]
    if len(levels_csv) > 1:
        methods.append(("E-H, first file only", levels_csv[:1], "eca-hoekstra", ()))
    methods.append(("E-H, all levels", levels_csv, "eca-hoekstra", ()))
    if edge_orders:
        methods.append((f"E-H + orders {'/'.join(f'{q:.3g}' for q in edge_orders)}",
                        levels_csv, "eca-hoekstra", tuple(edge_orders)))
    runs = [(label, fine_comparison(lv, model_csv, m, extra))
            for label, lv, m, extra in methods]
    first = runs[0][1]
    misses = {(r["shape"], r["i"]) for r in first if r["i"] == r["j"] and abs(r["err"]) > 0.05}
    table = [(label, _measures(rows, misses)) for label, rows in runs]
    print(f"{len({r['shape'] for r in first})} shapes, "
          f"{sum(r['i'] == r['j'] for r in first)} diagonal terms")
    width = max(len(k) for k in table[0][1])
    print(" " * width + " | " + " | ".join(f"{label:>22s}" for label, _ in table))
    for key in table[0][1]:
        print(f"{key:{width}s} | " + " | ".join(f"{m[key]:>22s}" for _, m in table))
    by = [{(r["shape"], r["i"]): r for r in rows if r["i"] == r["j"]} for _, rows in runs]
    every = {k for b in by for k, r in b.items() if abs(r["err"]) > 0.05}
    print(f"\nThe {len(every)} diagonal terms off by more than 5 % by any method (model - "
          "reference, the reference's band, the order of its fit in h):")
    for key in sorted(every, key=lambda k: -abs(by[0][k]["err"])):
        r0 = by[0][key]
        cells = [f"{100 * b[key]['err']:+6.1f} % +-{100 * b[key]['band']:5.1f} % "
                 f"p {b[key]['order']:4.2f}" for b in by]
        print(f"  shape {key[0]:2d} {r0['family']:12s} {DOFS[key[1]]:6s} " + " | ".join(cells))


#: The shape classes of the uncovered terms' listing: which of the body's features sets the
#: order of its slowest terms (hull.panels.edge_order)
CLASSES = {"plate": "thin plate", "frame": "thin members", "extrusion": "sharp edges",
           "chamfer_box": "sharp edges", "fillet_box": "sharp edges", "coarse": "sharp edges",
           "pod": "sharp edges"}


def uncovered(levels_csv, model_csv) -> None:
    """The significant terms whose model estimate does not cover the model's error against
    the fine references (Eça & Hoekstra over all levels), by shape class (:data:`CLASSES`):
    the error and the estimate [% of the scale], the reference's band and its fit's order."""
    from stripcoef.conventions import DOF as DOFS
    from validation.cad_shapes import fine_comparison

    rows = [r for r in fine_comparison(list(levels_csv), model_csv) if r["significant"]]
    miss = [r for r in rows if abs(r["err"]) > r["est"]]
    est = [r["est"] for r in rows if r["i"] == r["j"]]
    print(f"the model's estimate covers {len(rows) - len(miss)} of {len(rows)} terms; the "
          f"diagonal estimate's median {100 * np.median(est):.2f} % (90th percentile "
          f"{100 * np.percentile(est, 90):.1f} %); not covered, by shape class:")
    for cls in sorted(set(CLASSES.values())):
        of = [r for r in rows if CLASSES.get(r["family"]) == cls]
        mine = sorted((r for r in miss if CLASSES.get(r["family"]) == cls),
                      key=lambda r: (r["shape"], r["i"], r["j"]))
        print(f"  {cls}: {len(mine)} of {len(of)}")
        for r in mine:
            print(f"    shape {r['shape']:2d} {r['family']:11s} {DOFS[r['i']]}-{DOFS[r['j']]:6s}"
                  f" error {100 * r['err']:+5.1f} %, estimate {100 * r['est']:4.1f} %, "
                  f"reference's band {100 * r['band']:4.1f} % (order {r['order']:.2f})")


def holdout(levels_csv) -> None:
    """The bands tested on a level they did not see (validation.cad_shapes.fine_holdout)."""
    from validation.cad_shapes import fine_holdout

    h = fine_holdout(levels_csv)
    print(f"{h['shapes']} shapes with five levels or more: the finest level's move within the "
          "band estimated without it (significant terms; the diagonal band's median / max)")
    for label, (good, of, bands) in h["seen"].items():
        print(f"  {label:24s} {good} of {of}   {100 * np.median(bands):.1f} % / "
              f"{100 * max(bands):.0f} %")
    print("the diagonal terms' reference of one procedure within another's band:")
    for (b, a), (good, of) in h["inside"].items():
        print(f"  {b:14s} within {a:14s} band: {good} of {of}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("prepare")
    p.add_argument("--seed", type=int, required=True)
    p.add_argument("--count", type=int, default=40)
    p.add_argument("--out", type=Path, required=True)
    p.add_argument("--thin", action="store_true",
                   help="the thin members of benchmarks.thin_members instead of CAD shapes")
    p.add_argument("--levels", type=int, nargs="+", default=None,
                   help=f"target face counts of the CAD shapes' family (default {LEVELS}); "
                   "750 1500 3000 with --cad-shapes-cap: the family of benchmarks.cad_shapes' "
                   "stored references")
    p.add_argument("--cad-shapes-cap", action="store_true",
                   help="the remesher's default face cap, as benchmarks.cad_shapes")
    s = sub.add_parser("solve")
    s.add_argument("--meshes", type=Path, required=True)
    s.add_argument("--csv", type=Path, required=True)
    s.add_argument("--max-level", type=int, default=None)
    s.add_argument("--min-level", type=int, default=0)
    s.add_argument("--same-family", type=Path, default=None,
                   help="a levels CSV: solve only the shapes whose levels 1 and 2 are its 0 and 1")
    s.add_argument("--order", default="", help="shape indices solved first at every level "
                   "(comma-separated)")
    c = sub.add_parser("compare")
    c.add_argument("--levels", type=Path, nargs="+", required=True,
                   help="levels CSVs of the same remesh families, merged per shape")
    c.add_argument("--model", type=Path, required=True)
    c.add_argument("--holdout", action="store_true",
                   help="also the bands tested on the finest level they did not see")
    c.add_argument("--edge-orders", type=float, nargs="*", default=[],
                   help="fixed orders in h added to Eca & Hoekstra's alternative fits (a third "
                   "column)")
    args = ap.parse_args(argv)
    if args.cmd == "prepare":
        if args.thin:
            prepare_thin(args.seed, args.count, args.out)
        else:
            prepare(args.seed, args.count, args.out, tuple(args.levels or LEVELS),
                    None if args.cad_shapes_cap else -1)
    elif args.cmd == "solve":
        solve(args.meshes, args.csv, args.max_level,
              [int(x) for x in args.order.split(",") if x.strip()], args.min_level,
              args.same_family)
    else:
        compare(args.levels, args.model, args.edge_orders)
        print()
        uncovered(args.levels, args.model)
        if args.holdout:
            print()
            holdout(args.levels)
    return 0


if __name__ == "__main__":
    sys.exit(main())
