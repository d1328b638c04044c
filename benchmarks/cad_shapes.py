"""A benchmark you cannot tune to: seeded CAD-style bluff shapes against Capytaine on the fly.

Every run draws a fresh seed (printed; ``--seed S`` repeats a run) and from it ``--count``
shapes from families of what CAD tools and simulators export (issue 32):

- ``extrusion``: a random convex polygon (5-9 corners) extruded along a random axis, its caps
  fan-triangulated from one corner as CAD exporters write them (sliver triangles);
- ``chamfer_box`` / ``fillet_box``: boxes with chamfered edges, or rounded corners of a coarse
  sphere, as the convex hull of their corners;
- ``frame``: two side plates and two to four cross tubes, overlapping parts (no union);
- ``plate``: a thin plate (thickness 2-5 % of its span);
- ``coarse``: a cylinder of 8-12 facets or a low-polygon ellipsoid;
- ``pod``: a box hull with a cylinder pod pushed into it (overlapping parts, asymmetric).

Each shape is then written as a user would have it: in millimetres (half of them, read with
``length_unit="mm"``) and as an OBJ with its vertices split at every face (half of them), else
as an STL.  The model is ``estimate(load_vehicle(FILE, origin=(0, 0, 0)),
added_mass_method="panels")`` -- the whole of ``stripcoef coefficients FILE
--added-mass-method panels --origin 0,0,0`` but the printing -- timed on one thread.  The
reference is Capytaine (direct method, no free surface, :func:`stripcoef.bem.bem_added_mass`)
on the shape's clean closed surface (the manifold union of its parts) at two resolutions
(``--bem-faces``, at most 3000 faces, one solve at a time), Richardson-extrapolated as
1/N, about the same point.

Per shape: each diagonal term's error [%], each coupling's error over the diagonal scale
sqrt(A_ii A_jj) [%], and whether the model's estimated error (``added_mass_error``) covers
its actual error (every diagonal term and every coupling whose reference is at least 1 % of
the scale).  Usage:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.cad_shapes [--seed S] [--count N]
                                                            [--csv out/cad_shapes.csv]

``--references CSV`` re-runs the model alone on the seed of a stored run against that run's
references (after a change of the panel method: minutes instead of the BEM's quarter hour);
the references keep their own grid convergence index, Richardson step and solve time as the
stored run wrote them (what it does not hold is written empty: unknown, never 0), and the
first line names the references' command and the re-run.  The stored run,
reference_tables/bem/cad_shapes.csv (docs/validation.md), names both on its first line (seed
1375923287, 40 shapes, BEM 750/1500/3000 faces, run as two ``--shard`` processes and merged).
"""

from __future__ import annotations

import argparse
import csv
import os
import secrets
import sys
import tempfile
import time
import warnings
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
import trimesh  # noqa: E402

from benchmarks.bluff_shapes import refine  # noqa: E402  (the BEM meshes refined alike)

RHO = 1000.0
FAMILIES = ("extrusion", "chamfer_box", "fillet_box", "frame", "plate", "coarse", "pod")
# the DOFs' names and the coupling rule (a coupling is compared when the reference is at least
# SIGNIFICANT of sqrt(A_ii A_jj)) are the validation's, which counts the stored draws alike
from validation.cad_draws import DOFS, SIGNIFICANT  # noqa: E402


def _T(xyz):
    return trimesh.transformations.translation_matrix(xyz)


def _cyl(d, length, center, axis, sections):
    c = trimesh.creation.cylinder(radius=0.5 * d, height=length, sections=sections)
    c.apply_transform(trimesh.geometry.align_vectors([0, 0, 1], np.asarray(axis, float)))
    c.apply_translation(center)
    return c


def _fan_prism(poly, height, axis):
    """A convex polygon (k, 2) extruded by ``height`` along ``axis`` (0, 1, 2), caps fanned
    from corner 0 (the CAD way), sides two triangles each; outward normals."""
    k = len(poly)
    lo = np.column_stack([poly, np.full(k, -0.5 * height)])
    hi = np.column_stack([poly, np.full(k, 0.5 * height)])
    v = np.vstack([lo, hi])
    faces = [[0, i + 1, i] for i in range(1, k - 1)]                  # bottom, facing -z
    faces += [[k, k + i, k + i + 1] for i in range(1, k - 1)]         # top, facing +z
    for i in range(k):
        j = (i + 1) % k
        faces += [[i, j, k + j], [i, k + j, k + i]]
    m = trimesh.Trimesh(v, faces, process=False)
    if m.volume < 0:
        m.invert()
    perm = {2: [0, 1, 2], 0: [2, 0, 1], 1: [1, 2, 0]}[axis]
    return trimesh.Trimesh(np.asarray(m.vertices)[:, perm], m.faces, process=False)


def make_shape(family, rng):
    """(parts: list of closed meshes [m] centred near the origin, description)."""
    u = rng.uniform
    if family == "extrusion":
        k = int(rng.integers(5, 10))
        ang = np.sort(u(0, 2 * np.pi, k))
        a, b = u(0.1, 0.3), u(0.1, 0.3)
        poly = np.column_stack([a * np.cos(ang), b * np.sin(ang)])
        h, axis = u(0.1, 0.5), int(rng.integers(0, 3))
        m = _fan_prism(poly, h, axis)
        return [m], f"{k}-gon {2 * a:.2f}x{2 * b:.2f} extruded {h:.2f} m along {'xyz'[axis]}"
    if family in ("chamfer_box", "fillet_box"):
        size = u(0.15, 0.6, 3)
        r = u(0.1, 0.3) * size.min()
        corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
        inner = corners * (0.5 * size - r)
        if family == "chamfer_box":
            pts = np.vstack([inner + np.eye(3)[i] * corners * r for i in range(3)])
        else:
            ball = trimesh.creation.icosphere(subdivisions=1, radius=r).vertices
            pts = (inner[:, None, :] + ball[None, :, :]).reshape(-1, 3)
        m = trimesh.convex.convex_hull(pts)
        return [m], f"box {size.round(2).tolist()} with {r:.3f} m {family.split('_')[0]}s"
    if family == "frame":
        length, width, height = u(0.3, 0.6), u(0.25, 0.5), u(0.2, 0.4)
        t = u(0.01, 0.03)
        parts = [trimesh.creation.box([length, t, height], transform=_T([0, s * 0.5 * width, 0]))
                 for s in (-1, 1)]
        n = int(rng.integers(2, 5))
        for _ in range(n):
            d = u(0.03, 0.08)
            x = u(-0.5, 0.5) * (length - d)
            z = u(-0.5, 0.5) * (height - d)
            parts.append(_cyl(d, width + t, [x, 0, z], [0, 1, 0], 16))
        return parts, (f"frame {length:.2f}x{width:.2f}x{height:.2f}, plates {1000 * t:.0f} mm, "
                       f"{n} tubes")
    if family == "plate":
        span, chord = u(0.2, 0.6), u(0.15, 0.4)
        t = u(0.02, 0.05) * span
        m = trimesh.creation.box([chord, span, t])
        return [m], f"plate {chord:.2f}x{span:.2f}x{t:.3f} m"
    if family == "coarse":
        if rng.uniform() < 0.5:
            k = int(rng.integers(8, 13))
            d, length = u(0.1, 0.4), u(0.1, 0.5)
            axis = np.eye(3)[int(rng.integers(0, 3))]
            m = _cyl(d, length, [0, 0, 0], axis, k)
            return [m], f"{k}-facet cylinder D {d:.2f} L {length:.2f}"
        n = int(rng.integers(4, 7))
        s = trimesh.creation.uv_sphere(radius=1.0, count=[n, 2 * n])
        ax = u(0.08, 0.3, 3)
        s.apply_scale(ax)
        return [s], f"low-polygon ellipsoid {(2 * ax).round(2).tolist()} ({len(s.faces)} faces)"
    if family == "pod":
        size = u(0.2, 0.5, 3)
        hull = trimesh.creation.box(size)
        d = u(0.3, 0.6) * min(size[1], size[2])
        pod = _cyl(d, u(0.5, 1.0) * size[0], [u(-0.2, 0.2) * size[0], 0.0,
                                               -0.5 * size[2]], [1, 0, 0], 16)
        return [hull, pod], f"box {size.round(2).tolist()} with a pod D {d:.2f} on top"
    raise ValueError(family)


def clean_surface(parts):
    """The true closed surface: the parts' manifold union (one part: itself)."""
    if len(parts) == 1:
        return parts[0]
    return trimesh.boolean.union(parts, engine="manifold")


def drawn_shapes(seed: int, count: int):
    """``(k, family, parts, what)`` of the first ``count`` shapes of ``seed``, drawn exactly
    as :func:`main` draws them: each shape's :func:`make_shape` draws, then
    :func:`write_as_user`'s two (its file is not written), so that shape k is the stored
    run's shape k."""
    rng = np.random.default_rng(seed)
    for k in range(count):
        family = FAMILIES[int(rng.integers(0, len(FAMILIES)))]
        parts, what = make_shape(family, rng)
        rng.uniform(), rng.uniform()                 # write_as_user's two draws
        yield k, family, parts, what


def user_files(seed: int, count: int, directory, only=None):
    """``(k, family, path, length_unit)`` of the first ``count`` shapes of ``seed`` written as a
    user has them (:func:`write_as_user`, in ``directory``), drawn exactly as :func:`main`
    draws them; a shape not in ``only`` is drawn (its :func:`write_as_user` draws too) but not
    written, so that shape k is the stored run's shape k."""
    rng = np.random.default_rng(seed)
    for k in range(count):
        family = FAMILIES[int(rng.integers(0, len(FAMILIES)))]
        parts, _ = make_shape(family, rng)
        if only is not None and k not in only:
            rng.uniform(), rng.uniform()                # write_as_user's two draws
            continue
        path, unit, _ = write_as_user(parts, Path(directory) / family, rng)
        yield k, family, path, unit


def patched_estimates(seed: int, count: int, patches: dict, only=None, before=None,
                      **estimate_kw):
    """Yield ``(k, family, model, cpu)``: each of the seed's shapes as a user has it
    (:func:`user_files`) through ``estimate(load_vehicle(FILE), added_mass_method="panels",
    **estimate_kw)``, with ``patches`` (``{(module, name): replacement}``: the spies and
    forced settings of the estimate-rule benchmarks) in place for that call only and its
    warnings silenced; ``before()`` is called before each estimate (a spy's record cleared),
    ``cpu`` is the estimate's process time [s]. A shape the estimate refuses is printed and
    skipped: a refusal is a result."""
    from stripcoef.assembly import estimate
    from stripcoef.geometry.vehicle import load_vehicle

    real = {key: getattr(*key) for key in patches}
    with tempfile.TemporaryDirectory() as tmp:
        for k, family, path, unit in user_files(seed, count, tmp, only):
            if before is not None:
                before()
            c0 = time.process_time()
            try:
                for (module, name), new in patches.items():
                    setattr(module, name, new)
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    model = estimate(load_vehicle(path, length_unit=unit, origin=(0, 0, 0)),
                                     added_mass_method="panels", **estimate_kw)
            except Exception as exc:            # a refusal is a result: say it, go on
                print(f"{k:3d} {family}: FAILED {type(exc).__name__}: {exc}", flush=True)
                continue
            finally:
                for (module, name), old in real.items():
                    setattr(module, name, old)
            yield k, family, model, time.process_time() - c0


def write_as_user(parts, path_stem, rng):
    """The shape as a user has it: mm or m, OBJ with split vertices or STL. Returns (path,
    length_unit, description)."""
    mm = rng.uniform() < 0.5
    split = rng.uniform() < 0.5
    scale = 1000.0 if mm else 1.0
    mesh = trimesh.util.concatenate([p.copy() for p in parts])
    v = np.asarray(mesh.vertices) * scale
    if split:
        path = Path(f"{path_stem}.obj")
        tri = v[np.asarray(mesh.faces)].reshape(-1, 3)
        lines = ["v %.9g %.9g %.9g" % tuple(p) for p in tri]
        lines += [f"f {3 * k + 1} {3 * k + 2} {3 * k + 3}" for k in range(len(mesh.faces))]
        path.write_text("\n".join(lines) + "\n")
    else:
        path = Path(f"{path_stem}.stl")
        trimesh.Trimesh(v, mesh.faces, process=False).export(path)
    return path, ("mm" if mm else "m"), ("mm" if mm else "m") + (", split OBJ" if split else ", STL")


#: the CSV's columns (one row per upper-triangle term of a shape)
HEADER = ["shape", "family", "what", "how", "panels", "bem_faces", "mirrors", "warned",
          "t_model_s", "t_bem_s", "i", "j", "model", "bem", "error_rel", "covered",
          "significant", "bem_richardson_step_rel", "estimated_error_rel", "bem_gci_rel",
          "covered_with_bem_gci", "cpu_model_s"]


def _cell(x, fmt):
    """A number's CSV cell; an unknown one (NaN) is an empty cell, never 0."""
    return "" if x is None or not np.isfinite(x) else format(x, fmt)


def _number(cell) -> float:
    """A CSV cell back to a number; an empty or missing cell is unknown (NaN)."""
    return float(cell) if cell not in (None, "") else float("nan")


def stored_references(path):
    """The references of a stored run's CSV (``--csv``, :data:`HEADER`): ``{shape index:
    dict(ref=6x6 reference, counts=(faces, ...), gci=its grid convergence index, step=the
    Richardson step |extrapolated - finest level|, t_bem=its solves' wall time [s])}``, the
    matrices in [kg, kg m, kg m^2], the bands recovered from ``bem_gci_rel`` and
    ``bem_richardson_step_rel`` times the comparison's scale sqrt(|A_ii A_jj|) (on the
    diagonal |A_ii|: :func:`compare_terms`).  What the file does not hold is unknown (NaN),
    never 0: an empty or missing cell, and the all-zero bands a re-run wrote before the
    references' own uncertainty was carried through (no three-level solve gives a diagonal
    term a zero index)."""
    refs = {}
    with open(path, newline="") as fh:
        fh.readline()
        for r in csv.DictReader(fh):
            if r["what"].startswith("FAILED"):
                continue
            k = int(r["shape"])
            if k not in refs:
                refs[k] = dict(ref=np.zeros((6, 6)), gci=np.zeros((6, 6)),
                               step=np.zeros((6, 6)),
                               counts=tuple(map(int, r["bem_faces"].split("/"))),
                               t_bem=_number(r.get("t_bem_s")))
            i, j = int(r["i"]), int(r["j"])
            x = refs[k]
            x["ref"][i, j] = x["ref"][j, i] = float(r["bem"])
            x["gci"][i, j] = x["gci"][j, i] = _number(r.get("bem_gci_rel"))
            x["step"][i, j] = x["step"][j, i] = _number(r.get("bem_richardson_step_rel"))
    for x in refs.values():
        d = np.sqrt(np.abs(np.diag(x["ref"])))
        scale = np.outer(d, d)
        for band in ("gci", "step"):
            if not np.any(np.diag(x[band])):      # a re-run's lost band: unknown
                x[band][:] = np.nan
            x[band] *= scale
        if not x["t_bem"]:                        # likewise a re-run's 0 s
            x["t_bem"] = float("nan")
    return refs


def compare_terms(ours, est, ref, ref_gci, ref_step):
    """Per upper-triangle term (i, j) of the model ``ours`` with its estimated error ``est``
    against the reference ``ref`` with its grid convergence index ``ref_gci`` and Richardson
    step ``ref_step`` (all 6x6 [kg, kg m, kg m^2]; an unknown band is NaN): the error and the
    bands relative to the scale sqrt(|A_ii A_jj|) of the reference (on the diagonal |A_ii|),
    whether the model's estimate covers the error, and whether the validation band of both
    numerical uncertainties does, root-sum-square (ASME V&V 20-2009, sec. 2-4:
    u_val = sqrt(u_num,model^2 + u_num,ref^2); None where the reference's is unknown)."""
    d = np.sqrt(np.abs(np.diag(ref)))
    scale = np.outer(d, d)
    err = ours - ref
    rows = []
    for i in range(6):
        for j in range(i, 6):
            significant = i == j or abs(ref[i, j]) >= SIGNIFICANT * scale[i, j]
            vv = np.hypot(est[i, j], ref_gci[i, j])
            rows.append(dict(i=i, j=j, ours=ours[i, j], ref=ref[i, j],
                             est=est[i, j] / scale[i, j], rel=err[i, j] / scale[i, j],
                             covered=bool(abs(err[i, j]) <= est[i, j]),
                             ref_gci=ref_gci[i, j] / scale[i, j],
                             covered_vv=bool(abs(err[i, j]) <= vv) if np.isfinite(vv)
                             else None,
                             significant=significant, bem_step=ref_step[i, j] / scale[i, j]))
    return rows


def csv_rows(r) -> list[list]:
    """The CSV rows (:data:`HEADER`) of one shape's result (:func:`run_one`)."""
    k = r["k"]
    if "failed" in r:
        return [[k, r["family"], "FAILED: " + r["failed"]] + [""] * (len(HEADER) - 3)]
    head = [k, r["family"], r["what"], r["how"], r["panels"],
            "/".join(map(str, r["bem_faces"])), r["mirrors"], int(r["unconverged"]),
            f"{r['t_model']:.3f}", _cell(r["t_bem"], ".3f")]
    return [head + [x["i"], x["j"], f"{x['ours']:.6g}", f"{x['ref']:.6g}",
                    f"{x['rel']:.4g}", int(x["covered"]), int(x["significant"]),
                    _cell(x["bem_step"], ".3g"), f"{x['est']:.3g}",
                    _cell(x["ref_gci"], ".3g"),
                    "" if x["covered_vv"] is None else int(x["covered_vv"]),
                    f"{r['c_model']:.3f}"] for x in r["rows"]]


def bem_reference(surface, bem_faces, ref_point):
    """Capytaine on isotropic remeshes of the clean surface at the ``bem_faces`` (coarse to
    fine; stripcoef.hull.remesh, the same remesher as the panel method's levels), the two
    finest Richardson-extrapolated as 1/N, and the reference's own grid convergence index
    (three levels: Fs 1.25 and the observed order; Roache 1998).  Returns (reference,
    counts, its GCI + extrapolation step, the levels' matrices)."""
    from stripcoef.bem import bem_added_mass
    from stripcoef.hull.convergence import grid_convergence_index, richardson
    from stripcoef.hull.panels import estimated_error
    from stripcoef.hull.remesh import edge_for_panels, remesh_family

    v, f = np.asarray(surface.vertices, float), np.asarray(surface.faces)
    # one remesh family (one crease angle, each level 1.25x the faces of the one before),
    # else the surface's edges bisected at every level (a family that refines)
    family = remesh_family(v, f, [edge_for_panels(float(surface.area), n) for n in bem_faces])
    meshes = ([trimesh.Trimesh(*lv, process=False) for lv in family[0]] if family is not None
              else [refine(surface, n) for n in bem_faces])
    # the remesher lands within about 1.5x of a level's target on thin frames (4120-4532 faces
    # for 3,000: benchmarks/data/frame32d_trace.md), so the cap is twice the finest target
    # (56 n^2 bytes: 2 GB at 6,000 faces), not a fixed 4,000 that dropped those frames
    cap = 2 * max(bem_faces)
    mats, counts = [], []
    for m in meshes:
        mats.append(bem_added_mass(m, rho=RHO, reference_point=ref_point, max_faces=cap))
        counts.append(len(m.faces))
    ref = richardson(mats[-2], mats[-1], counts[-2], counts[-1])
    gci, _, _ = grid_convergence_index(mats, counts)
    return ref, counts, estimated_error(mats[-1], ref, gci), mats


def run_one(family, rng, tmp, bem_faces, stored=None):
    from stripcoef.assembly import estimate
    from stripcoef.geometry.vehicle import load_vehicle

    parts, what = make_shape(family, rng)
    path, unit, how = write_as_user(parts, Path(tmp) / family, rng)
    t0, c0 = time.perf_counter(), time.process_time()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        veh = load_vehicle(path, length_unit=unit, origin=(0.0, 0.0, 0.0))
        model = estimate(veh, added_mass_method="panels")
    t_model = time.perf_counter() - t0
    c_model = time.process_time() - c0          # CPU of this process (one BLAS thread)
    unconverged = any("has not converged" in str(w.message) for w in caught)
    ref_point = np.asarray(model.reference_point)
    t0 = time.perf_counter()
    if stored is not None:              # the same seed's references, read back with their
        ref, counts = stored["ref"], stored["counts"]    # own bands and solve time
        ref_gci, ref_step, t_bem = stored["gci"], stored["step"], stored["t_bem"]
    else:
        ref, counts, ref_gci, mats = bem_reference(clean_surface(parts), bem_faces, ref_point)
        ref_step = np.abs(ref - mats[-1])
        t_bem = time.perf_counter() - t0
    ours = np.asarray(model.added_mass) * RHO / model.density
    est = np.asarray(model.added_mass_error) * RHO / model.density
    rows = compare_terms(ours, est, ref, ref_gci, ref_step)
    return dict(family=family, what=what, how=how, rows=rows, t_model=t_model, t_bem=t_bem,
                c_model=c_model,
                panels="/".join(map(str, model.conditions["added_mass_panel_levels"])), bem_faces=tuple(counts),
                unconverged=unconverged, mirrors=model.conditions["mirror_planes"],
                est_max=model.conditions["added_mass_error_max"])


def vv_count(terms) -> str:
    """How many ``terms`` the root-sum-square band covers, of how many, the terms whose
    reference band is unknown named apart (never counted as covered or missed)."""
    known = [x["covered_vv"] for x in terms if x["covered_vv"] is not None]
    out = (f"{sum(known)} of {len(known)} ({100 * np.mean(known):.0f} %)" if known
           else "unknown")
    return out + (f"; {len(terms) - len(known)} terms' reference band unknown"
                  if len(known) < len(terms) else "")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=None, help="repeat a run (default: a fresh one)")
    ap.add_argument("--count", type=int, default=10, help="shapes to draw (default 10)")
    ap.add_argument("--bem-faces", type=int, nargs="+", default=(750, 1500, 3000),
                    help="faces of the BEM resolutions, coarse to fine (default three)")
    ap.add_argument("--csv", default=None, help="write every term's row to this CSV")
    ap.add_argument("--shard", default=None, metavar="I/N",
                    help="solve only the shapes k with k %% N == I (the others are drawn and "
                         "skipped, so that N processes share one seed; merge their CSVs)")
    ap.add_argument("--references", default=None, metavar="CSV",
                    help="take the BEM references from a stored run of the same --seed "
                         "(re-evaluate the model only; the references' bands and solve "
                         "times are the stored run's, unknown where it has none)")
    args = ap.parse_args(argv)
    stored = stored_references(args.references) if args.references else {}
    seed = args.seed if args.seed is not None else secrets.randbits(32)
    print(f"seed {seed}  (repeat: python -m benchmarks.cad_shapes --seed {seed} "
          f"--count {args.count})", flush=True)
    rng = np.random.default_rng(seed)
    shard = tuple(int(x) for x in args.shard.split("/")) if args.shard else None
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(args.count):
            family = FAMILIES[int(rng.integers(0, len(FAMILIES)))]
            # a shape skipped (another shard's, or one without a stored reference: its BEM
            # failed in the stored run) still takes its draws, so that the shapes after it
            # are the stored run's
            if (shard and k % shard[1] != shard[0]) or (args.references and k not in stored):
                make_shape(family, rng)                 # the draws of a skipped shape
                rng.uniform(), rng.uniform()            # write_as_user's two draws
                results.append(dict(family=family, skipped=True))
                continue
            try:
                r = run_one(family, rng, tmp, args.bem_faces, stored.get(k))
            except Exception as exc:          # a refusal is a result too: say it, go on
                print(f"{k:3d} {family:12s} FAILED: {type(exc).__name__}: {exc}", flush=True)
                results.append(dict(family=family, failed=str(exc), k=k))
                continue
            r["k"] = k
            results.append(r)
            diag = [x for x in r["rows"] if x["i"] == x["j"]]
            coup = [x for x in r["rows"] if x["i"] != x["j"] and x["significant"]]
            worst_d = max(diag, key=lambda x: abs(x["rel"]))
            worst_c = max(coup, key=lambda x: abs(x["rel"])) if coup else None
            sig = diag + coup
            cov = sum(x["covered"] for x in sig)
            print(f"{k:3d} {family:12s} {r['what']} [{r['how']}]\n"
                  f"    panels {r['panels']}, mirrors {r['mirrors']}, BEM {r['bem_faces']}: "
                  f"worst diagonal {DOFS[worst_d['i']]} {100 * worst_d['rel']:+.1f} %, "
                  + (f"worst coupling {DOFS[worst_c['i']]}-{DOFS[worst_c['j']]} "
                     f"{100 * worst_c['rel']:+.1f} % of scale, " if worst_c else "")
                  + f"estimate covers {cov}/{len(sig)} terms (est. max "
                  f"{100 * r['est_max']:.1f} %{', WARNED' if r['unconverged'] else ''}); "
                  f"model {r['t_model']:.1f} s, BEM "
                  + (f"{r['t_bem']:.1f} s" if np.isfinite(r["t_bem"]) else "time unknown")
                  + (" (stored)" if args.references else ""), flush=True)
    results = [r for r in results if "skipped" not in r]
    ok = [r for r in results if "failed" not in r]
    sig = [x for r in ok for x in r["rows"] if x["significant"]]
    diag = [x for r in ok for x in r["rows"] if x["i"] == x["j"]]
    coup = [x for r in ok for x in r["rows"] if x["i"] != x["j"] and x["significant"]]
    print(f"\nseed {seed}: {len(ok)} of {len(results)} shapes solved")
    if ok:
        print(f"  diagonal terms within 5 %: {sum(abs(x['rel']) <= 0.05 for x in diag)} of "
              f"{len(diag)}; couplings within 5 % of the scale: "
              f"{sum(abs(x['rel']) <= 0.05 for x in coup)} of {len(coup)}")
        print(f"  shapes with every term within 5 %: "
              f"{sum(all(abs(x['rel']) <= 0.05 for x in r['rows'] if x['significant']) for r in ok)}"
              f" of {len(ok)}")
        print(f"  estimated error covers the actual error: {sum(x['covered'] for x in sig)} of "
              f"{len(sig)} terms ({100 * np.mean([x['covered'] for x in sig]):.0f} %); with the "
              f"reference's own GCI (root-sum-square, ASME V&V 20): "
              + vv_count(sig))
        print(f"  a warning where some term is off by more than 5 %: "
              f"{sum(r['unconverged'] for r in ok if any(abs(x['rel']) > 0.05 for x in r['rows'] if x['significant']))}"
              f" of {sum(any(abs(x['rel']) > 0.05 for x in r['rows'] if x['significant']) for r in ok)}")
        t = np.array([r["t_model"] for r in ok])
        tb = np.array([r["t_bem"] for r in ok if np.isfinite(r["t_bem"])])
        c = np.array([r["c_model"] for r in ok])
        print(f"  whole-estimate CPU time (one thread): median {np.median(c):.2f} s (max "
              f"{c.max():.2f} s)")
        print(f"  whole-estimate time: median {np.median(t):.2f} s (max {t.max():.2f} s); "
              f"BEM reference (all resolutions"
              + (", the stored run's" if args.references else "") + "): "
              + (f"median {np.median(tb):.2f} s" if len(tb) else "unknown")
              + (f" ({len(ok) - len(tb)} shapes unknown)" if 0 < len(tb) < len(ok) else ""))
    if args.csv:
        Path(args.csv).parent.mkdir(parents=True, exist_ok=True)
        with open(args.csv, "w", newline="") as fh:
            w = csv.writer(fh)
            first = f"benchmarks/cad_shapes.py --seed {seed} --count {args.count}"
            if args.references:    # the references' own command, then this re-run's
                with open(args.references) as ref_fh:
                    origin = ref_fh.readline().lstrip("# ").strip().split("; model rows")[0]
                first = (f"{origin}; model rows re-run by {first} --references "
                         f"{args.references}")
            else:
                first += f" --bem-faces {' '.join(map(str, args.bem_faces))}"
            fh.write(f"# {first}\n")
            w.writerow(HEADER)
            for r in results:
                w.writerows(csv_rows(r))
    return 0


if __name__ == "__main__":
    sys.exit(main())
