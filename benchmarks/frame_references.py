"""Graded Capytaine references of the frames on their mirror plane (issue 32): the shipped
BlueROV2 Heavy's surface (geometry/bluerov2_heavy.stl: the vehicle file's parts united at the
tessellation the panel method solves, scripts/make_bluerov2_heavy.py) and the bluff set's two
frames (``open_frame``, ``bluerov2_heavy``: :mod:`benchmarks.bluff_shapes`).

Their 40 mm tubes and 12.7 mm plates need panels of a few millimetres at their edges: the
graded mesher's levels (:func:`benchmarks.graded_mesher.graded_mesh`, h = min(H, H/4 + 0.25 d)
towards the convex edges sharper than 30 deg) are 6,000-40,000 faces, beyond a dense solve of
the whole body on this machine.  Each surface is checked for mirror planes through its volume
centroid (:func:`mirror_planes`: the volume of the body and of its mirror image not shared,
relative to the volume, computed by manifold3d: zero for a mirror-symmetric solid, whatever its
triangulation), its y >= 0 half meshed (the input cut on y = 0, the cut a boundary of gmsh's
patches whose nodes are put on y = 0 exactly, so that the half and its image share them) and
Capytaine (direct method, no free surface) solves the half on its xOz plane
(``cpt.ReflectionSymmetricMesh``: two blocks of (N/2)^2 instead of N^2 for each of S and K,
the LU of two N/2 blocks instead of one N: Ancellin & Dias 2019, sec. 3).  None of the three
surfaces is mirror-symmetric in x or z (thrusters and pods fore-aft and above), so the nested
two-plane solve (``benchmarks.plate_graded.capytaine_eighth``) does not apply.

Memory: S and K of a half solve are N x N/2 complex128 each (Capytaine 3.0 keeps them complex
at infinite frequency), the two blocks of K's LU another N^2/2 (LU in place): 24 N^2 bytes
(measured: 3.68 GB peak at 12,062 faces, 8.05 GB at 18,210: 22.8 N^2 + 0.5 GB).  A level predicted over
``--max-gb`` (8 GB) is not solved, and that is said: the vehicle file's finest stored level
(18,210 faces, H = 0.045 m) peaked at 8.05 GB, which this rule (8.5 GB) now refuses.

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame_references --symmetry
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame_references --proof [--H 0.3]
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame_references --csv CSV
        [--levels 0.128 0.09 0.075 0.064 0.054 0.045] [--max-gb 8.5]
    python -m benchmarks.frame_references --csv reference_tables/bem/graded_frames.csv --compare

The bluff set's frames are written by ``benchmarks.graded_mesher --only open_frame
bluerov2_heavy`` (the same mesher and solve, about the volume centroid) into
reference_tables/bem/graded_meshes.csv, which the bluff benchmark reads.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import csv  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from benchmarks import graded_mesher as GM  # noqa: E402

#: the vehicle file's surface (the panel method's default tessellation of its parts)
STL = Path("geometry") / "bluerov2_heavy.stl"
NAME = "bluerov2_heavy_file"
#: largest panel H [m] of each level, coarse to fine (whole body 5,974-18,210 faces; the
#: stored file's six, the finest over this rule's 8 GB: --max-gb 8.5)
LEVELS = (0.128, 0.09, 0.075, 0.064, 0.054, 0.045)
#: the most memory a level's solve may take [GB]
MAX_GB = 8.0
#: a plane is a mirror plane when the volume not shared with the mirror image is below this
#: fraction of the volume (manifold3d's exact booleans: 1e-7 on the frames' y = 0)
SYMMETRY_TOL = 1e-6
DOFS = GM.DOFS
AXES = ("x (yOz plane)", "y (xOz plane)", "z (xOy plane)")


def vehicle_surface():
    """The shipped BlueROV2 Heavy's surface (geometry/bluerov2_heavy.stl) in its body axes
    about the vehicle file's origin, as a trimesh."""
    import trimesh

    from validation import ROOT

    return trimesh.load(ROOT / STL, process=True)


def asymmetry(mesh, axis: int, at: float) -> float:
    """Volume of ``mesh`` (a closed trimesh) not shared with its mirror image in the plane
    x_axis = ``at`` [m], over its volume [-]: (V + V' - 2 V cap V') / V, by manifold3d."""
    import trimesh

    image = mesh.copy()
    v = np.array(image.vertices, float)
    v[:, axis] = 2.0 * at - v[:, axis]
    image.vertices = v
    image.invert()
    common = trimesh.boolean.intersection([mesh, image], engine="manifold").volume
    return float(2.0 * (mesh.volume - common) / mesh.volume)


def mirror_planes(mesh, tol: float = SYMMETRY_TOL) -> dict:
    """{axis: (plane position [m], asymmetry [-])} of every axis whose plane through the
    volume centroid leaves less than ``tol`` of the volume unshared (:func:`asymmetry`); the
    others' asymmetry is printed by ``--symmetry``."""
    c = np.asarray(mesh.center_mass, float)
    out = {}
    for axis in range(3):
        a = asymmetry(mesh, axis, float(c[axis]))
        if abs(a) < tol:
            out[axis] = (float(c[axis]), a)
    return out


def surfaces() -> dict:
    """{name: closed trimesh} of the three frames: the vehicle file's surface about its origin,
    the bluff set's two frames about their volume centroids (as graded_mesher solves them)."""
    return {NAME: vehicle_surface(), "open_frame": GM.shape_body("open_frame"),
            "bluerov2_heavy": GM.shape_body("bluerov2_heavy")}


def solve_half(v, f, full: bool = False):
    """(6x6 added mass about the origin [kg, kg m, kg m^2], CPU seconds) of the closed body
    whose y >= 0 half is (v, f): Capytaine on ``ReflectionSymmetricMesh`` (plane xOz), or with
    ``full`` on the same panels as one mesh (``merged()``: the check of the symmetric solve); direct
    method, no free surface, rho 1000 kg/m^3, LU in place."""
    import logging

    import capytaine as cpt

    from benchmarks.plate_graded import RHO

    logging.getLogger("capytaine").setLevel(logging.ERROR)
    t0 = time.process_time()
    mesh = cpt.ReflectionSymmetricMesh(
        half=cpt.Mesh(vertices=v, faces=np.column_stack([f, f[:, 2]])), plane="xOz")
    if full:
        mesh = mesh.merged()            # the same panels, the symmetry not used
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)))
    names = list(body.dofs)
    problems = [cpt.RadiationProblem(body=body, radiating_dof=d, free_surface=np.inf,
                                     omega=np.inf, rho=RHO) for d in names]
    engine = cpt.BasicMatrixEngine(linear_solver="lu_decomposition_with_overwrite") \
        if hasattr(cpt, "BasicMatrixEngine") else \
        cpt.bem.engines.DefaultMatrixEngine(linear_solver="lu_decomposition_with_overwrite")
    res = cpt.BEMSolver(engine=engine, method="direct").solve_all(problems, progress_bar=False)
    a = np.zeros((6, 6))
    for j, r in enumerate(res):
        for i, d in enumerate(names):
            a[i, j] = float(np.real(r.added_mass[d]))
    return 0.5 * (a + a.T), time.process_time() - t0


def proof(H: float = 0.3) -> dict:
    """The symmetric solve against the full one on the vehicle file's surface at a coarse
    level H [m]: {faces, largest term difference over sqrt(A_ii A_jj), CPU s of each}."""
    body = vehicle_surface()
    v, f = GM.graded_mesh(body, H, mirror=True)
    half, t_half = solve_half(v, f)
    whole, t_full = solve_half(v, f, full=True)
    d = np.sqrt(np.abs(np.diag(whole)))
    diff = float(np.max(np.abs(half - whole) / np.outer(d, d)))
    out = {"faces": 2 * len(f), "max_diff": diff, "cpu_half": t_half, "cpu_full": t_full}
    print(f"{NAME} at H = {H:g} m, {out['faces']} faces: symmetric solve against the full one, "
          f"largest term difference {diff:.2e} of sqrt(A_ii A_jj); CPU {t_half:.1f} s "
          f"(half) against {t_full:.1f} s (full)")
    return out


def run(path, levels=LEVELS, max_gb: float = MAX_GB):
    """The vehicle file's surface at each level H of ``levels``: graded half, checked
    (:func:`benchmarks.graded_mesher.accepted`), solved on its mirror plane; rows of
    :data:`benchmarks.graded_mesher.HEADER` appended to ``path`` (``m``: H [m], ``seconds``:
    CPU seconds of the solve), about the vehicle file's origin.  A level predicted over
    ``max_gb`` is said and skipped."""
    import capytaine

    body = vehicle_surface()
    planes = mirror_planes(body)
    if 1 not in planes or abs(planes[1][0]) > 1e-9:
        raise RuntimeError(f"{STL}: not mirror-symmetric in y = 0 (planes {planes})")
    new = not Path(path).exists()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with open(path, "a", newline="") as fh:
        if new:
            fh.write(f"# python -m benchmarks.frame_references {' '.join(sys.argv[1:])}: "
                     f"Capytaine {capytaine.__version__} (direct method, no free surface, "
                     "rho = 1000 kg/m^3), gmsh triangles graded towards the convex edges "
                     f"sharper than {GM.ANGLE:g} deg (h = min(H, H / {GM.RATIO:g} + "
                     f"{GM.GROWTH:g} d); benchmarks.graded_mesher), the y >= 0 half solved on "
                     "the xOz mirror plane; m = H [m]; seconds: CPU of the solve; "
                     "upper-triangle 6x6 added mass [kg, kg m, kg m^2] about the vehicle "
                     "file's origin\n")
            csv.writer(fh).writerow(GM.HEADER)
        w = csv.writer(fh)
        for lev, H in enumerate(levels):
            t0 = time.process_time()
            v, f = GM.graded_mesh(body, H, mirror=True)
            c = GM.accepted(GM.check(v, f, body, True), f"{NAME} at H = {H:g} m")
            mesh_s = time.process_time() - t0
            need = GM.predicted_gb(c["faces"])
            if need > max_gb:
                print(f"{NAME}: H {H:g} m, {c['faces']} faces: predicted {need:.1f} GB > "
                      f"{max_gb:g} GB, not solved", flush=True)
                continue
            a, sec = solve_half(v, f)
            print(f"{NAME}: H {H:g} m, {c['faces']} faces (area {c['area']:+.1e}, volume "
                  f"{c['volume']:+.1e}, least quality {c['quality']:.3f}), mesh {mesh_s:.1f} s, "
                  f"solve {sec:.1f} s CPU, peak {GM.peak_gb():.2f} GB (predicted {need:.2f}): "
                  + " ".join(f"{x:.6g}" for x in np.diag(a)), flush=True)
            w.writerows([NAME, f"{STL} remeshed by gmsh, mirror xOz", lev, f"{H:g}",
                         c["faces"], i, j, f"{a[i, j]:.9g}", f"{sec:.2f}"]
                        for i in range(6) for j in range(i, 6))
            fh.flush()


def merge(paths, out, note: str = ""):
    """The level rows of several runs (CSV files of :func:`run`) in one file ``out``: each
    shape's levels ordered by H, coarse to fine, and numbered again; its first line the runs'
    command lines (each file's first line) joined, then ``note``."""
    rows, heads = [], []
    for p in paths:
        with open(p, newline="") as fh:
            heads.append(fh.readline().lstrip("# ").split(":")[0].strip())
            rows += list(csv.DictReader(fh))
    with open(p, newline="") as fh:
        first = fh.readline().rstrip("\n")
    desc = first.split(": ", 1)[1]
    rows.sort(key=lambda r: (r["shape"], -float(r["m"]), int(r["i"]), int(r["j"])))
    level: dict = {}
    for r in rows:
        hs = level.setdefault(r["shape"], [])
        if r["m"] not in hs:
            hs.append(r["m"])
        r["level"] = hs.index(r["m"])
    with open(out, "w", newline="") as fh:
        fh.write(f"# {'; '.join(heads)}{note} (rows merged by benchmarks.frame_references "
                 f"--merge, levels ordered by H): {desc}\n")
        w = csv.DictWriter(fh, fieldnames=GM.HEADER)
        w.writeheader()
        w.writerows(rows)


#: the stored model rows of the vehicle file (benchmarks.panels_vehicles: diagonal terms, both
#: installs) and its golden model (the base install's full matrix and its estimated errors)
PANELS_VEHICLES = Path("reference_tables") / "bem" / "panels_vehicles.csv"
GOLDEN = Path("tests") / "golden" / "bluerov2_heavy.json"


def compare(levels_csv, stored_csv=None, golden=None) -> list:
    """The stored model rows against the vehicle file's graded reference
    (:func:`validation.graded_frames.frame_terms`: the reference moved to the golden model's
    point, each diagonal term of both installs and the golden couplings, the estimate's
    coverage), printed as tables; returns the rows."""
    from validation import ROOT
    from validation.graded_frames import frame_terms, term_name

    t = frame_terms(ROOT / levels_csv, ROOT / (stored_csv or PANELS_VEHICLES),
                    ROOT / (golden or GOLDEN))
    if not t:
        print(f"{levels_csv}: no levels of {NAME}")
        return []
    print(f"{NAME}: graded reference over {'/'.join(map(str, t['faces']))} faces, about "
          f"{np.round(t['point'], 5).tolist()} m")
    print("| faces | " + " | ".join(DOFS) + " |  (each level's diagonal about that point)")
    print("|---" * 7 + "|")
    for n, dg in t["levels"]:
        print(f"| {n} | " + " | ".join(f"{x:.6g}" for x in dg) + " |")
    print()
    print("| install | term | model | graded reference | its band | order | model error | "
          "estimated error | covered | stored uniform reference's error |")
    print("|---" * 10 + "|")
    for row in t["rows"]:
        print(f"| {row['install']} | {term_name(row)} | {row['model']:.6g} | "
              f"{row['graded']:.6g} | {100 * row['band']:.2f} % | {row['order']:.2f} | "
              f"{100 * row['error']:+.1f} % | {100 * row['estimated']:.1f} % | "
              f"{'yes' if row['covered'] else 'no'} | "
              + ("" if np.isnan(row["uniform"]) else f"{100 * row['uniform']:+.2f} %") + " |")
    return t["rows"]


def symmetry_report() -> dict:
    """{name: [asymmetry per axis]} of the three frames about their volume centroids,
    printed."""
    out = {}
    for name, m in surfaces().items():
        c = np.asarray(m.center_mass, float)
        out[name] = [asymmetry(m, k, float(c[k])) for k in range(3)]
        print(f"{name} ({len(m.faces)} faces, centroid {np.round(c, 5).tolist()} m): "
              + "; ".join(f"{AXES[k]}: {out[name][k]:.2e}" for k in range(3))
              + " -> mirror planes: "
              + (", ".join(AXES[k] for k in range(3) if abs(out[name][k]) < SYMMETRY_TOL)
                 or "none"))
    return out


def main(argv=None) -> int:
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--symmetry", action="store_true", help="the frames' mirror planes, then stop")
    ap.add_argument("--proof", action="store_true",
                    help="the symmetric solve against the full one at --H, then stop")
    ap.add_argument("--H", type=float, default=0.3, help="--proof's level H [m]")
    ap.add_argument("--csv", default=None, help="append the vehicle file's levels here")
    ap.add_argument("--levels", type=float, nargs="+", default=list(LEVELS),
                    help="largest panel H [m] of each level")
    ap.add_argument("--max-gb", type=float, default=MAX_GB)
    ap.add_argument("--merge", nargs="+", default=None, metavar="RUN_CSV",
                    help="merge these runs' levels into --csv, then stop")
    ap.add_argument("--note", default="", help="--merge: appended to the runs' command lines")
    ap.add_argument("--compare", action="store_true",
                    help="the stored model rows against the levels of --csv, then stop")
    args = ap.parse_args(argv)
    if args.symmetry:
        symmetry_report()
        return 0
    if args.proof:
        proof(args.H)
        return 0
    if not args.csv:
        ap.error("--csv, --symmetry or --proof")
    if args.merge:
        merge(args.merge, args.csv, args.note)
        return 0
    if args.compare:
        compare(args.csv)
        return 0
    run(args.csv, args.levels, args.max_gb)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
