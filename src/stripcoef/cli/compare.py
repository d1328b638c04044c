"""``stripcoef compare``: strip theory and the Capytaine BEM side by side on a mesh."""

from __future__ import annotations

import time

import numpy as np

from stripcoef.conventions import added_mass_name
from stripcoef.errors import InputError
from stripcoef.geometry.vehicle import MESH_SUFFIXES
from stripcoef.files import check_finite_output, json_text, write_text
from stripcoef.cli.coefficients import add_fluid_arguments, add_mesh_arguments


def add_parser(sub):
    p = sub.add_parser("compare", help="strip theory vs the 3D BEM (Capytaine) on a mesh",
                       description="Added mass of a CAD mesh by strip theory and by the "
                                   "Capytaine boundary-element method (needs stripcoef[bem]), "
                                   "with each method's wall time and the % difference per term.")
    p.add_argument("vehicle", metavar="MODEL", help="mesh file (" + " ".join(MESH_SUFFIXES) + ")")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.add_argument("-o", "--output", metavar="FILE", help="write to FILE (atomically)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="draw strip theory vs BEM per DOF (.png/.pdf/.svg; matplotlib)")
    p.add_argument("--strips", type=int, metavar="N", help="number of strips")
    p.add_argument("--speed", type=float, metavar="M_S", help="reference speed [m/s]")
    p.add_argument("--no-corrections", action="store_true",
                   help="pure strip theory (no 3D corrections)")
    p.add_argument("--max-faces", type=int, default=None, metavar="N",
                   help="largest mesh the BEM accepts (default 8000; memory grows as N^2)")
    add_fluid_arguments(p, "fluid (default: sea water)")
    add_mesh_arguments(p)
    p.set_defaults(func=run, reference_point=None, regime="auto", method="strip")
    return p


def compare_rows(strip, bem, *, rel_zero: float = 1e-3):
    """Per added-mass term (upper triangle, non-zero in either method): name, strip, BEM, % diff.

    Each block has a natural scale: the largest translational diagonal term m, the
    largest rotational one I, and sqrt(m I) for the couplings.  A term below
    ``rel_zero`` of its scale in both methods is zero (by symmetry; BEM noise) and is
    not listed; one that is zero only in the BEM gets no % difference (None).
    """
    strip, bem = np.asarray(strip, float), np.asarray(bem, float)
    m = max(np.abs(np.diag(bem)[:3]).max(), np.abs(np.diag(strip)[:3]).max(), 1e-300)
    inertia = max(np.abs(np.diag(bem)[3:]).max(), np.abs(np.diag(strip)[3:]).max(), 1e-300)
    scales = {(0, 0): m, (1, 1): inertia, (0, 1): np.sqrt(m * inertia)}
    rows = []
    for i in range(6):
        for j in range(i, 6):
            scale = scales[(i // 3, j // 3)]
            s, b = strip[i, j], bem[i, j]
            if abs(s) <= rel_zero * scale and abs(b) <= rel_zero * scale:
                continue
            pct = 100.0 * (s - b) / abs(b) if abs(b) > rel_zero * scale else None
            rows.append({"term": added_mass_name(i, j), "i": i, "j": j, "strip": float(s),
                         "bem": float(b), "diff_percent": pct})
    return rows


def run(args) -> int:
    from stripcoef import bem
    from stripcoef.assembly.estimate import estimate
    from stripcoef.geometry.mesh import MeshBody
    from stripcoef.cli.options import estimate_options, load_any_vehicle

    bem._capytaine()                                   # fail early, before any work
    if args.plot:
        from stripcoef.figures import check_plot_path
        check_plot_path(args.plot, key="--plot")
    t0 = time.perf_counter()
    vehicle = load_any_vehicle(args)
    t_load = time.perf_counter() - t0
    if not (len(vehicle.bodies) == 1 and isinstance(vehicle.bodies[0], MeshBody)):
        raise InputError("compare needs a mesh file", file=str(args.vehicle),
                         expected="a mesh file (" + "/".join(MESH_SUFFIXES) + ")")
    body = vehicle.bodies[0]
    options = estimate_options(args, vehicle)
    t0 = time.perf_counter()
    model = estimate(vehicle, options)
    t_strip = time.perf_counter() - t0
    kw = {} if args.max_faces is None else {"max_faces": args.max_faces}
    a_bem, t_bem = bem.timed_bem_added_mass(body, rho=model.density,
                                            reference_point=model.reference_point, **kw)
    quality = bem.panel_quality(body.mesh)
    rows = compare_rows(model.added_mass, a_bem)
    if not quality["trusted"]:          # a bogus BEM gives a bogus difference: say so instead
        for r in rows:
            r["diff_percent"] = None
    if args.plot:
        from stripcoef.figures import save_figure
        save_figure(bem.comparison_figure(model.added_mass, a_bem, name=model.name,
                                          key="--plot"), args.plot, key="--plot")
    data = {
        "name": model.name, "faces": int(len(body.mesh.faces)), "repairs": body.repairs,
        "reference_point": [float(v) for v in model.reference_point],
        "density": model.density, "strips": model.conditions.get("strips"),
        "corrections": model.conditions.get("corrections"),
        # the added mass compared: strip theory, or the 3D panel method (auto's choice for a
        # bluff mesh; the key strip_theory below keeps its name for the JSON contract)
        "added_mass_method": model.conditions.get("added_mass_method") or "strip theory",
        "seconds": {"load": t_load, "strip_theory": t_strip, "bem": t_bem},
        "speedup": t_bem / max(t_strip, 1e-12),
        "strip_theory": [[float(v) for v in r] for r in model.added_mass],
        "bem": [[float(v) for v in r] for r in a_bem],
        "terms": rows,
        "panel_quality": quality,
    }
    check_finite_output(data, what="the comparison", file=str(args.vehicle))
    text = json_text(data) if args.json else format_comparison(data)
    if args.output:
        write_text(args.output, text if text.endswith("\n") else text + "\n", key="--output")
    else:
        print(text, end="" if text.endswith("\n") else "\n")
    return 0


def format_comparison(data) -> str:
    s = data["seconds"]
    out = [f"{data['name']}: {data['faces']} faces, added mass about "
           f"{np.round(data['reference_point'], 4).tolist()} m, rho = {data['density']:.5g} kg/m^3",
           (f"  strip theory ({data['strips']} strips, 3D corrections "
            f"{'on' if data['corrections'] else 'off'}): {s['strip_theory']:.3f} s"
            if data.get("added_mass_method", "strip theory") == "strip theory" else
            f"  stripcoef ({data['added_mass_method']}): {s['strip_theory']:.3f} s"),
           f"  BEM (Capytaine, direct, no free surface):      {s['bem']:.3f} s"
           f"   ({data['speedup']:.3g}x stripcoef's time)",
           f"  mesh loading and repair: {s['load']:.3f} s"]
    for r in data["repairs"]:
        out.append(f"  repaired: {r}")
    q = data["panel_quality"]
    if not q["trusted"]:
        out.append(f"  BEM NOT TRUSTED: {100 * q['area_fraction']:.0f} % of the surface is in panels "
                   f"with aspect ratio > {q['limit']:.0f} (up to {q['max_aspect']:.0f}); no % "
                   f"differences are given. Remesh with panels of similar length and width "
                   f"(e.g. trimesh.remesh.subdivide_to_size, or a finer CAD export).")
    out.append("")
    out.append(f"  {'term':10s} {'strip':>12s} {'BEM':>12s} {'diff %':>8s}")
    for r in data["terms"]:
        pct = ("     n/a" if not q["trusted"] else "   (0)") if r["diff_percent"] is None \
            else f"{r['diff_percent']:+8.2f}"
        # SNAME derivative = -M_A[i, j]
        out.append(f"  {r['term']:10s} {-r['strip']:12.5g} {-r['bem']:12.5g} {pct}")
    out.append("  (values are SNAME derivatives, -M_A[i, j]; units kg, kg m, kg m^2)")
    return "\n".join(out) + "\n"
