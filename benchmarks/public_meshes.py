"""Public vehicle meshes, run as a user would, against Capytaine on remeshed copies (issue 32).

The meshes are the ROV, AUV and glider meshes that open-source simulators and ROS description
packages publish (:data:`MESHES`: repository, commit, path, license; the table is
reference_tables/public_meshes/README.md).  They are not committed: ``--mirror DIR`` reads
them from local clones, ``DIR/<owner>+<name>`` or ``DIR/<name>`` (a working tree or a bare
git directory: the file is read with ``git show COMMIT:PATH``), so the benchmark runs where
GitHub cannot be reached.  Per mesh:

1. **as found**: ``stripcoef coefficients MESH --rho 1000 --json`` (default ``auto``): exit
   code, the warnings (units, axes, repairs, convergence), the method chosen; a COLLADA file
   (.dae) read directly (its declared unit and up axis);
   a mesh refused as found whose error names ``stripcoef mesh MESH --repair -o OUT`` is
   repaired so -- the fix the error tells a user -- and ``OUT`` is run (run ``repaired``);
2. **panels**: the same with ``--added-mass-method panels`` when ``auto`` chose the strips;
3. **reference**: Capytaine (direct method, no free surface, :func:`stripcoef.bem.bem_added_mass`)
   on isotropic remeshes (:mod:`stripcoef.hull.remesh`) of the closed surface the panel method
   solves (the loaded, repaired and united mesh) at ``--bem-faces`` (coarse to fine, default
   500 1000 2000: each solve under a minute; the stored run: 2000 4000 8000 with
   ``--bem-max-faces 9000``, 3-8 min and 4 GB per mesh), one remesh family for all levels
   (printed with each level's diagonal), the two finest Richardson-extrapolated as 1/N, with
   its own grid convergence index (Roache 1998), moved to each run's reference point.

Per term: the model's error (diagonal: of the term; couplings whose reference is at least 1 %
of sqrt(A_ii A_jj): of that scale; a diagonal term below 1 % of the largest of its block, the
roll of a body of revolution, scaled by that 1 % as the panel method's check does), whether the model's estimated error covers it, and
whether the root-sum-square of both estimated errors does (ASME V&V 20-2009).  Usage:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.public_meshes --mirror DIR
        [--only NAME ...] [--csv reference_tables/public_meshes/public_meshes.csv [--update]]

The stored run (reference_tables/public_meshes/public_meshes.csv, docs/validation.md) names
its command and commit of every mesh on its first lines.  ``--update`` with ``--only``
replaces the rows of the meshes run in an existing CSV and keeps the others (their command
is added to the first line).  ``--points --csv CSV`` writes each stored run's reference point
(``ref_x, ref_y, ref_z`` [m], the run's JSON ``reference_point``) into CSV, recomputed from
the mesh without the BEM (:func:`write_points`).
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from benchmarks.bluff_shapes import refine  # noqa: E402  (the BEM meshes refined alike)
from validation.public_meshes import POINT_COLUMNS, moved_uncertainty  # noqa: E402

RHO = 1000.0
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
SIGNIFICANT = 0.01
TOLERANCE = 0.05


@dataclass(frozen=True)
class PublicMesh:
    name: str          # short name of the row
    vehicle: str
    kind: str          # ROV, AUV, glider
    repo: str          # owner/name on GitHub
    commit: str
    path: str
    license: str
    role: str          # collision or visual mesh


_UUV = "uuvsimulator/"
_DAVE = ("Field-Robotics-Lab/dave", "e54ea16bdaf7d6dbb466cf141846a03f284a44dd")
#: The public meshes (reference_tables/public_meshes/README.md repeats this table).
MESHES = (
    PublicMesh("rexrov", "RexROV (uuv_simulator)", "ROV", _UUV + "uuv_simulator",
               "bfb40cb153684a0703173117b6bbf4258e8e71c5",
               "uuv_descriptions/meshes/RexROV_no_props.stl", "Apache-2.0", "visual"),
    PublicMesh("desistek_saga", "Desistek SAGA", "ROV", _UUV + "desistek_saga",
               "4a1d10f597a6c1c3657f40338682dbbbc7cf72f6",
               "desistek_saga_description/mesh/saga.stl", "Apache-2.0", "collision"),
    PublicMesh("eca_a9", "ECA A9", "AUV", _UUV + "eca_a9",
               "5c7e357253c0873d1441ae10910949871cfb944a",
               "eca_a9_description/mesh/eca_a9.stl", "Apache-2.0", "collision"),
    PublicMesh("lauv", "LAUV (OceanScan)", "AUV", _UUV + "lauv_gazebo",
               "3529e028b2e7fcf33e92db0a319ce71afb3d9ea6",
               "lauv_description/meshes/body.stl", "Apache-2.0", "collision"),
    PublicMesh("slocum", "Slocum glider (DAVE)", "glider", *_DAVE,
               "models/dave_robot_models/models/glider_slocum/mesh/COLLISION-Slocum-Glider.dae",
               "Apache-2.0", "collision"),
    PublicMesh("glider_hybrid_whoi", "WHOI hybrid glider (DAVE)", "glider", *_DAVE,
               "models/dave_robot_models/models/glider_hybrid_whoi/mesh/"
               "glider_hybrid_whoi_collision.dae", "Apache-2.0", "collision"),
    PublicMesh("caldus", "Caldus ROV (DAVE)", "ROV", *_DAVE,
               "urdf/robots/caldus_description/meshes/caldus_collision.dae", "Apache-2.0",
               "collision"),
    PublicMesh("caracara", "Caracara ROV (DAVE)", "ROV", *_DAVE,
               "urdf/robots/caracara_description/meshes/caracara_collision.dae", "Apache-2.0",
               "collision"),
    PublicMesh("smilodon", "Smilodon ROV (DAVE)", "ROV", *_DAVE,
               "urdf/robots/smilodon_description/meshes/smilodon_collision.dae", "Apache-2.0",
               "collision"),
    PublicMesh("erov", "eROV (DAVE)", "ROV", *_DAVE,
               "models/dave_object_models/models/erov/mesh/erov.dae", "Apache-2.0", "visual"),
)


def read_from_mirror(mirror: Path, mesh: PublicMesh) -> bytes:
    """The mesh file's bytes from a local clone under ``mirror`` (module docstring)."""
    owner, name = mesh.repo.split("/")
    for base in (mirror / f"{owner}+{name}", mirror / name, mirror / owner / name):
        for cand in (base / "repo" / ".git", base / "repo", base / ".git", base):
            if not cand.is_dir():
                continue
            probe = subprocess.run(["git", "--git-dir", str(cand), "cat-file", "-e",
                                    f"{mesh.commit}:{mesh.path}"], capture_output=True)
            if probe.returncode == 0:
                return subprocess.run(["git", "--git-dir", str(cand), "show",
                                       f"{mesh.commit}:{mesh.path}"], capture_output=True,
                                      check=True).stdout
        if (base / mesh.path).is_file():            # a plain checkout (commit not checked)
            return (base / mesh.path).read_bytes()
    raise FileNotFoundError(f"{mesh.repo}@{mesh.commit[:10]}:{mesh.path} not under {mirror}")


def run_cli(path: Path, *extra) -> dict:
    """``stripcoef coefficients PATH --rho 1000 --json`` in a subprocess: exit code, warnings,
    the JSON, wall time [s]."""
    cmd = [sys.executable, "-m", "stripcoef", "coefficients", str(path), "--rho", str(RHO),
           "--json", *extra]
    t0 = time.perf_counter()
    out = subprocess.run(cmd, capture_output=True, text=True)
    dt = time.perf_counter() - t0
    data = None
    if out.returncode == 0:
        try:
            data = json.loads(out.stdout)
        except json.JSONDecodeError:
            data = None
    warns = [ln for ln in out.stderr.splitlines() if ln.startswith(("warning", "stripcoef"))]
    return {"rc": out.returncode, "warnings": warns, "json": data, "seconds": dt,
            "command": "stripcoef coefficients " + path.name + " --rho 1000 --json"
                       + "".join(" " + e for e in extra)}


REPAIR = "stripcoef mesh"


def repair_named(run: dict, found: Path, out: Path):
    """When a refusal names ``stripcoef mesh FILE --repair -o OUT``, that command run on the
    file as found (a subprocess): the repaired copy ``out`` and a note, else (None, '')."""
    why = " ".join(run["warnings"])
    if run["rc"] != 2 or f"'{REPAIR} {found.name} --repair" not in why:
        return None, ""
    rep = subprocess.run([sys.executable, "-m", "stripcoef", "mesh", str(found), "--repair",
                          "-o", str(out)], capture_output=True, text=True)
    if rep.returncode != 0 or not out.exists():
        return None, ""
    notes = [ln.strip()[2:] for ln in rep.stdout.splitlines() if ln.strip().startswith("- ")]
    return out, f"{REPAIR} {found.name} --repair -o {out.name}: " + "; ".join(notes)


def axis_named(run: dict):
    """The axis a run's warning tells the user to give (``use --axis y``), or None."""
    import re

    for w in run["warnings"]:
        m = re.search(r"use --axis ([xyz])\b", w)
        if m:
            return m.group(1)
    return None


def frame_rotation(path: Path, axis: str) -> np.ndarray:
    """The rotation R (3x3) from the body axes of ``path`` loaded as found to those with
    ``--axis axis``: v_axis = R v_found, both about the volume centroid (least squares over
    the loaded vertices, which the two loads give in the same order)."""
    import warnings

    from stripcoef.geometry.vehicle import load_vehicle

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        a = np.asarray(load_vehicle(path).bodies[0].mesh.vertices, float)
        b = np.asarray(load_vehicle(path, axis=axis).bodies[0].mesh.vertices, float)
    q, *_ = np.linalg.lstsq(a, b, rcond=None)           # b = a q
    return q.T


def rotate_6(m, rot):
    """A 6x6 matrix about a point in other axes: T M T^T, T = diag(R, R) (a rotation)."""
    t = np.zeros((6, 6))
    t[:3, :3] = t[3:, 3:] = rot
    return t @ np.asarray(m, float) @ t.T


def bem_reference(path: Path, bem_faces, max_faces: int = 4000, levels=None):
    """Capytaine on isotropic remeshes of the closed surface the panel method solves (the
    loaded, repaired, united mesh), about the body origin.  Returns (M_A, its estimated
    error, face counts, seconds); ``levels``, a list, gets (family, faces, M_A) of every
    level appended (``--levels-csv``)."""
    import trimesh

    from stripcoef.bem import bem_added_mass
    from stripcoef.geometry.vehicle import load_vehicle
    from stripcoef.hull.convergence import grid_convergence_index, richardson
    from stripcoef.hull.panels import estimated_error
    from stripcoef.hull.remesh import MAX_FACES, edge_for_panels, remesh_family

    veh = load_vehicle(path)
    body = veh.bodies[0]
    surface = body.united() if hasattr(body, "united") else body.mesh
    v, f = np.asarray(surface.vertices, float), np.asarray(surface.faces)
    t0 = time.perf_counter()
    # one remesh family (one crease angle, each level 1.25x the faces of the one before),
    # else the surface's edges bisected at every level (a family that refines)
    # (a surface whose creases hold the remesh near its own face count -- ECA A9's capped
    # parts: 2354/2910/3860 faces at 10 deg -- refines by 1.2x, not 1.25x, per level)
    # (the remesh's own cap, MAX_FACES 6000, raised to the BEM's limit: a family asked for
    # 8000 faces is a remesh too, not the fallback below)
    edges = [edge_for_panels(float(surface.area), n) for n in bem_faces]
    cap = max(max_faces, MAX_FACES)
    family = (remesh_family(v, f, edges, max_faces=cap)
              or remesh_family(v, f, edges, min_ratio=1.2, max_faces=cap))
    meshes = ([trimesh.Trimesh(*lv, process=False) for lv in family[0]] if family is not None
              else [refine(surface, n) for n in bem_faces])
    print("    BEM levels: " + ("one remesh family, " + repr(family[1]) if family is not None
                               else "the surface's edges bisected (no remesh family)")
          + ": " + "/".join(str(len(m.faces)) for m in meshes) + " faces", flush=True)
    if any(len(b.faces) <= len(a.faces) for a, b in zip(meshes, meshes[1:])):
        raise ValueError("the BEM levels do not refine: "
                         + "/".join(str(len(m.faces)) for m in meshes) + " faces")
    mats, counts = [], []
    for m in meshes:
        mats.append(bem_added_mass(m, rho=RHO, reference_point=np.zeros(3),
                                   max_faces=max_faces))
        counts.append(len(m.faces))
        if levels is not None:
            levels.append((str(family[1]) if family is not None else "bisected input",
                           len(m.faces), mats[-1]))
        print(f"    BEM {len(m.faces)} faces (area {m.area / surface.area - 1:+.2%}, volume "
              f"{m.volume / surface.volume - 1:+.2%} of the surface): diagonal "
              + " ".join(f"{a:.5g}" for a in np.diag(mats[-1])), flush=True)
    ref = richardson(mats[-2], mats[-1], counts[-2], counts[-1])
    gci, _, _ = grid_convergence_index(mats, counts)
    return 0.5 * (ref + ref.T), estimated_error(mats[-1], ref, gci), counts, \
        time.perf_counter() - t0


def compare(run: dict, ref, ref_err) -> list[dict]:
    """Per term of a CLI run: error against the reference moved to the run's reference point."""
    from stripcoef.conventions import transform_matrix

    d = run["json"]
    point = np.asarray(d["reference_point"], float)
    ref_p = transform_matrix(ref, from_point=(0, 0, 0), to_point=point)
    # the error band moves with the matrix, each term's bound through the rigid transfer's
    # coefficients (validation.public_meshes.moved_uncertainty)
    err_p = moved_uncertainty(ref_err, point)
    return compare_at(run, ref_p, err_p)


def compare_at(run: dict, ref_p, err_p) -> list[dict]:
    """Per term of a CLI run: error against the reference ``ref_p`` and its estimated error
    ``err_p``, both already at the run's reference point and in its frame."""
    from stripcoef.hull.panels import NEGLIGIBLE

    d = run["json"]
    ours = np.asarray(d["added_mass"], float)
    est = d.get("added_mass_error")
    est = np.asarray(est, float) if est is not None else np.zeros((6, 6))
    dg = np.abs(np.diag(ref_p)).copy()
    for block in (slice(0, 3), slice(3, 6)):   # the panel method's scale (NEGLIGIBLE floor)
        dg[block] = np.maximum(dg[block], NEGLIGIBLE * dg[block].max())
    diag = np.sqrt(dg)
    scale = np.outer(diag, diag)
    rows = []
    for i in range(6):
        for j in range(i, 6):
            sig = i == j or abs(ref_p[i, j]) >= SIGNIFICANT * scale[i, j]
            s = scale[i, j]
            e = ours[i, j] - ref_p[i, j]
            rows.append(dict(i=i, j=j, model=ours[i, j], bem=ref_p[i, j], rel=e / s,
                             est=est[i, j] / s, bem_err=err_p[i, j] / s, significant=sig,
                             covered=bool(abs(e) <= est[i, j]),
                             covered_vv=bool(abs(e) <= np.hypot(est[i, j], err_p[i, j]))))
    return rows


HEADER = ["mesh", "vehicle", "kind", "repo", "commit", "path", "license", "role", "note", "run",
          "command", "method", "panel_levels", "warned", "seconds", "bem_faces", "bem_seconds",
          "i", "j", "model", "bem", "error_rel", "estimated_error_rel", "bem_error_rel",
          "significant", "covered", "covered_with_bem_error", *POINT_COLUMNS]


def csv_rows(s):
    """The CSV rows of one run of one mesh (:data:`HEADER`)."""
    m, run = s["mesh"], s["run"]
    return [[m.name, m.vehicle, m.kind, m.repo, m.commit, m.path, m.license, m.role, s["note"],
             s["label"], run["command"], method_of(run), s["levels"], int(s["warned"]),
             f"{run['seconds']:.2f}", "/".join(map(str, s["counts"])),
             f"{s['t_bem']:.1f}" if np.isfinite(s["t_bem"]) else "",      # unknown: empty
             t["i"], t["j"], f"{t['model']:.6g}", f"{t['bem']:.6g}", f"{t['rel']:.4g}",
             f"{t['est']:.4g}", f"{t['bem_err']:.4g}", int(t["significant"]),
             int(t["covered"]), int(t["covered_vv"]), *point_cells(run)] for t in s["terms"]]


def point_cells(run) -> list[str]:
    """The run's reference point [m] (its JSON ``reference_point``, the axes of the run) as
    the CSV's :data:`~validation.public_meshes.POINT_COLUMNS` cells."""
    return [repr(float(x)) for x in run["json"]["reference_point"]]


def stored_references(path) -> dict:
    """The references of a stored run (its CSV, :data:`HEADER`): ``{(mesh, run label):
    (reference at the run's point and frame, its estimated error, BEM face counts,
    BEM seconds)}``; the error is recovered from ``bem_error_rel`` times the scale of
    :func:`compare_at`; seconds the file does not hold are unknown (NaN), never 0."""
    from stripcoef.hull.panels import NEGLIGIBLE

    with open(path, newline="") as fh:
        fh.readline()
        rows = [r for r in csv.DictReader(fh) if r.get("i")]
    out = {}
    for r in rows:
        key = (r["mesh"], r["run"])
        if key not in out:
            out[key] = [np.zeros((6, 6)), np.zeros((6, 6)), r["bem_faces"],
                        float(r["bem_seconds"] or "nan")]      # not in the file: unknown
        i, j = int(r["i"]), int(r["j"])
        out[key][0][i, j] = out[key][0][j, i] = float(r["bem"])
        out[key][1][i, j] = out[key][1][j, i] = float(r["bem_error_rel"])
    for ref, rel, _, _ in out.values():
        dg = np.abs(np.diag(ref)).copy()
        for block in (slice(0, 3), slice(3, 6)):
            dg[block] = np.maximum(dg[block], NEGLIGIBLE * dg[block].max())
        rel *= np.sqrt(np.outer(dg, dg))           # in place: the error [kg, kg m, kg m^2]
    return {k: (v[0], v[1], [int(c) for c in v[2].split("/") if c], v[3])
            for k, v in out.items()}


LEVELS_HEADER = ["mesh", "commit", "family", "level", "faces", "i", "j", "added_mass"]


def write_levels(path, mesh: PublicMesh, levels, command: str) -> None:
    """Append the Capytaine levels of one mesh (:func:`bem_reference`'s ``levels``: family,
    faces, M_A about the body origin [kg, kg m, kg m^2], symmetrised) to the CSV ``path``
    (:data:`LEVELS_HEADER`, one row per upper-triangle term), replacing that mesh's earlier
    rows; the first line is the command."""
    rows = []
    if Path(path).exists():
        with open(path, newline="") as fh:
            fh.readline()
            rows = [r for r in list(csv.reader(fh))[1:] if r and r[0] != mesh.name]
    for k, (family, faces, m) in enumerate(levels):
        m = 0.5 * (np.asarray(m, float) + np.asarray(m, float).T)
        rows += [[mesh.name, mesh.commit, family, k, faces, i, j, f"{m[i, j]:.9g}"]
                 for i in range(6) for j in range(i, 6)]
    order = {m.name: k for k, m in enumerate(MESHES)}
    rows.sort(key=lambda r: (order.get(r[0], len(order)), int(r[3])))
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as fh:
        fh.write("# " + command + " --only NAME --levels-csv CSV, for each NAME below (the "
                 "levels of each mesh's Capytaine reference, about the body origin, "
                 "rho = 1000 kg/m^3)\n")
        csv.writer(fh).writerow(LEVELS_HEADER)
        csv.writer(fh).writerows(rows)


def write_points(mirror: Path, path) -> None:
    """Write the reference point of every run stored in the CSV ``path`` into its
    :data:`~validation.public_meshes.POINT_COLUMNS` (added where the CSV has none), without
    the BEM: per mesh and run label, the mesh as the run had it (as found, or the repair its
    refusal names, ``--axis`` as the label says) run through ``stripcoef coefficients ...
    --added-mass-method strips`` (seconds), whose JSON ``reference_point`` is the run's (the
    centre of buoyancy of the loaded mesh, computed before the added-mass method is chosen:
    stripcoef.assembly.estimate); a run refused so is run with its own options."""
    with open(path, newline="") as fh:
        first = fh.readline()
        rows = list(csv.DictReader(fh))
    points: dict = {}
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in MESHES:
            labels = sorted({r["run"] for r in rows if r["mesh"] == mesh.name
                             and r["run"] != "refused"})
            if not labels:
                continue
            raw = read_from_mirror(mirror, mesh)
            found = Path(tmp) / (mesh.name + Path(mesh.path).suffix.lower())
            found.write_bytes(raw)
            repaired = found.with_name(found.stem + "_closed.stl")
            for label in labels:
                src = found
                if label.startswith("repaired"):
                    subprocess.run([sys.executable, "-m", "stripcoef", "mesh", str(found),
                                    "--repair", "-o", str(repaired)], capture_output=True,
                                   check=True)
                    src = repaired
                axis = label.split("--axis ")[1][:1] if "--axis " in label else ""
                extra = ("--axis", axis) if axis else ()
                run = run_cli(src, *extra, "--added-mass-method", "strips")
                if run["rc"] != 0 or run["json"] is None:
                    own = ("--added-mass-method", "panels") if "panels" in label else ()
                    run = run_cli(src, *extra, *own)
                points[(mesh.name, label)] = point_cells(run)
                print(f"{mesh.name} [{label}]: reference point "
                      + ", ".join(f"{float(x):.6g}" for x in points[(mesh.name, label)])
                      + " m", flush=True)
    header = list(rows[0].keys()) if rows else list(HEADER)
    header += [c for c in POINT_COLUMNS if c not in header]
    with open(path, "w", newline="") as fh:
        fh.write(first.rstrip("\n") + "; reference points (" + ", ".join(POINT_COLUMNS)
                 + ") from python -m benchmarks.public_meshes --mirror DIR --points --csv CSV"
                 "\n" if "--points" not in first else first)
        w = csv.DictWriter(fh, fieldnames=header)
        w.writeheader()
        for r in rows:
            cells = points.get((r["mesh"], r["run"]))
            if cells is not None:
                r.update(dict(zip(POINT_COLUMNS, cells)))
            w.writerow({k: r.get(k) or "" for k in header})


def method_of(run):
    c = (run["json"] or {}).get("conditions", {})
    return "panels" if c.get("added_mass_method") else "strips"


def updated_command(first: str, only, command: str) -> str:
    """The first line of a CSV whose rows of the meshes ``only`` come from ``command``: the
    run's own command, then one '; rows of NAMES from COMMAND' clause per update, the meshes
    of ``only`` taken out of the earlier clauses."""
    base, *clauses = first.split("; rows of ")
    out = [base]
    for clause in clauses:
        names, _, cmd = clause.partition(" from ")
        left = [n for n in names.split() if n not in only]
        if left:
            out.append(" ".join(left) + " from " + cmd)
    out.append(" ".join(only) + " from " + command)
    return "; rows of ".join(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mirror", required=True, type=Path,
                    help="folder of local clones (owner+name or name)")
    ap.add_argument("--only", nargs="*", default=None, help="names of MESHES to run")
    ap.add_argument("--bem-faces", type=int, nargs="+", default=(500, 1000, 2000))
    ap.add_argument("--bem-max-faces", type=int, default=4000,
                    help="largest BEM level (Capytaine's dense matrices: ~56 N^2 bytes)")
    ap.add_argument("--csv", default=None, help="write every term's row to this CSV")
    ap.add_argument("--references", default=None, metavar="CSV",
                    help="compare with the Capytaine references of a stored run (its CSV) "
                         "instead of computing them (after a change of the model: minutes "
                         "instead of the BEM's hour)")
    ap.add_argument("--levels-csv", default=None, metavar="CSV",
                    help="append every Capytaine level's matrix (about the body origin, each "
                         "upper-triangle term) to this CSV, to re-extrapolate without the BEM")
    ap.add_argument("--update", action="store_true",
                    help="with --csv and --only: replace those meshes' rows, keep the others")
    ap.add_argument("--points", action="store_true",
                    help="only write each run's reference point into the stored --csv "
                         "(recomputed from the mesh, no BEM)")
    args = ap.parse_args(argv)
    if args.points:
        if not args.csv:
            ap.error("--points needs --csv (the stored run to complete)")
        write_points(args.mirror, args.csv)
        return 0
    summary = []
    command = ("python -m benchmarks.public_meshes --mirror DIR --bem-faces "
               + " ".join(map(str, args.bem_faces))
               + (f" --bem-max-faces {args.bem_max_faces}" if args.bem_max_faces != 4000
                  else ""))
    base_command = command                       # (the levels CSV's first line)
    stored = stored_references(args.references) if args.references else None
    if stored is not None:
        command = ("python -m benchmarks.public_meshes --mirror DIR --references "
                   + args.references)
    if args.csv:                          # written as the meshes finish (a long run)
        Path(args.csv).parent.mkdir(parents=True, exist_ok=True)
        kept = []
        if args.update and args.only and Path(args.csv).exists():
            with open(args.csv, newline="") as fh:
                first = fh.readline().lstrip("# ").strip()
                kept = [r for r in csv.reader(fh)][1:]
            kept = [r for r in kept if r and r[0] not in args.only]
            command = updated_command(first, args.only, command + " --only "
                                      + " ".join(args.only) + " --update")
        with open(args.csv, "w", newline="") as fh:
            fh.write("# " + command + "\n")
            csv.writer(fh).writerow(HEADER)
            csv.writer(fh).writerows(kept)
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in MESHES:
            if args.only and mesh.name not in args.only:
                continue
            try:
                raw = read_from_mirror(args.mirror, mesh)
            except (FileNotFoundError, subprocess.CalledProcessError) as exc:
                print(f"{mesh.name}: SKIPPED ({exc})", flush=True)
                continue
            found = Path(tmp) / (mesh.name + Path(mesh.path).suffix.lower())
            found.write_bytes(raw)
            first = run_cli(found)
            note = "read .dae directly" if found.suffix == ".dae" else ""
            path, label = found, "auto"
            repaired, rnote = repair_named(first, found,
                                           found.with_name(found.stem + "_closed.stl"))
            if repaired is not None:               # the repair the refusal names
                path, label, note = repaired, "repaired", rnote
                print(f"{mesh.name}: refused as found; {rnote[:300]}", flush=True)
            auto = run_cli(path) if path != found else first
            runs = {label: auto}
            if auto["rc"] == 0 and method_of(auto) == "strips":
                runs["panels" if label == "auto" else label + ", panels"] = run_cli(
                    path, "--added-mass-method", "panels")
            axis = axis_named(auto) if auto["rc"] == 0 else None
            if axis:                           # the fix the warning names
                extra = ("--axis", axis)
                runs[f"{label}, --axis {axis}"] = ax = run_cli(path, *extra)
                if ax["rc"] == 0 and method_of(ax) == "strips":
                    runs[f"{label}, --axis {axis}, panels"] = run_cli(
                        path, *extra, "--added-mass-method", "panels")
            print(f"{mesh.name}: as found exit {first['rc']}"
                  + (f" ({first['warnings'][-1][:160]})" if first["rc"] else "")
                  + (f"; {note}" if note else "") + "; auto -> "
                  + (method_of(auto) if auto["rc"] == 0 else f"exit {auto['rc']}")
                  + f" in {auto['seconds']:.1f} s", flush=True)
            for w in auto["warnings"]:
                print("    " + w[:220], flush=True)
            if auto["rc"] != 0:                 # refused as a user runs it: a result too
                why = (auto["warnings"] or ["exit %d" % auto["rc"]])[-1].replace(
                    str(path.parent) + os.sep, "")
                print(f"    refused: {why[:300]}", flush=True)
                if args.csv:
                    with open(args.csv, "a", newline="") as fh:
                        csv.writer(fh).writerow(
                            [mesh.name, mesh.vehicle, mesh.kind, mesh.repo, mesh.commit,
                             mesh.path, mesh.license, mesh.role, why, "refused",
                             auto["command"]] + [""] * (len(HEADER) - 11))
                continue
            try:
                levels = []
                ref, ref_err, counts, t_bem = (bem_reference(path, args.bem_faces,
                                                             args.bem_max_faces, levels)
                                               if stored is None else (None, None, [], 0.0))
            except Exception as exc:            # a refusal is a result: say it, go on
                print(f"    reference FAILED: {type(exc).__name__}: {exc}", flush=True)
                continue
            if args.levels_csv and levels:
                write_levels(args.levels_csv, mesh, levels, base_command)
            for label, run in runs.items():
                if run["rc"] != 0 or run["json"] is None:
                    print(f"    {label}: exit {run['rc']}", flush=True)
                    continue
                if stored is not None:
                    if (mesh.name, label) not in stored:
                        print(f"    {label}: no stored reference", flush=True)
                        continue
                    ref_p, err_p, counts, t_bem = stored[(mesh.name, label)]
                    terms = compare_at(run, ref_p, err_p)
                elif "--axis" in run["command"]:
                    rot = frame_rotation(path, axis)
                    terms = compare(run, rotate_6(ref, rot), np.abs(rotate_6(ref_err,
                                                                             np.abs(rot))))
                else:
                    terms = compare(run, ref, ref_err)
                c = run["json"]["conditions"]
                sig = [t for t in terms if t["significant"]]
                wd = max((t for t in terms if t["i"] == t["j"]), key=lambda t: abs(t["rel"]))
                coup = [t for t in sig if t["i"] != t["j"]]
                wc = max(coup, key=lambda t: abs(t["rel"])) if coup else None
                warned = any("has not converged" in w for w in run["warnings"])
                line = dict(mesh=mesh, label=label, run=run, terms=terms, counts=counts,
                            t_bem=t_bem, warned=warned, note=note,
                            levels="/".join(map(str, c.get("added_mass_panel_levels") or ())))
                summary.append(line)
                if args.csv:
                    with open(args.csv, "a", newline="") as fh:
                        csv.writer(fh).writerows(csv_rows(line))
                print(f"    {label}: worst diagonal {DOFS[wd['i']]} {100 * wd['rel']:+.1f} %"
                      + (f", worst coupling {DOFS[wc['i']]}-{DOFS[wc['j']]} "
                         f"{100 * wc['rel']:+.1f} %" if wc else "")
                      + f"; estimate covers {sum(t['covered'] for t in sig)}/{len(sig)} "
                      f"(with the BEM's: {sum(t['covered_vv'] for t in sig)}); est. max "
                      f"{100 * (c.get('added_mass_error_max') or 0):.1f} %"
                      + (" WARNED" if warned else "") + f"; {run['seconds']:.1f} s; "
                      f"BEM {'/'.join(map(str, counts))} faces "
                      + (f"{t_bem:.1f} s" if np.isfinite(t_bem) else "time unknown"),
                      flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
