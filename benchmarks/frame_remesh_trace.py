"""Why a remesh family can be worse than the input's own levels on a frame of thin members: the
levels of each remesh mode of :mod:`stripcoef.hull.remesh` at a list of panel counts, what each
keeps of the surface and what each solves to, against the stored Capytaine reference (issue 32).

For a vehicle file (default geometry/bluerov2_heavy.yaml) the surface the panel method solves on
(:func:`stripcoef.assembly.added_mass.panel_surface`, the default 1600 panels) is cut on its
mirror plane y through the reference point and capped (:func:`stripcoef.hull.mirror_panels.
capped_part`), as :func:`stripcoef.hull.panels.panel_added_mass` does, and remeshed at the edges
of ``--counts`` panels (:func:`stripcoef.hull.remesh.edge_for_panels` of the whole surface's
area) in each mode: creases above 30 deg with edge flips (the isotropic remesh of Botsch &
Kobbelt), above 10 deg with flips, and the thin-member mode (30 deg, no flips, the remesh within
``KNIFE_DISTANCE``).  Each remesh: its panels (the whole mirrored panelling), its area and volume
change against the capped part, its new folds (:func:`stripcoef.hull.remesh.folds`), or why it
was refused; its one-level diagonal added mass (image panels, :func:`stripcoef.hull.mirror_panels.
solve_mirrored`) against the reference of reference_tables/bem/panels_vehicles.csv (Capytaine on
remeshes of the same parts united, 64 sides a circle).  Then the default estimate's levels and
what each extrapolation order makes of them.

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame_remesh_trace [FILE]
        [--counts 400 800 1600 3200 6400] [--write]

``--write`` writes benchmarks/data/frame_remesh_trace.md.  Needs the ``remesh`` extra.  About a
minute of CPU for the default counts.
"""

from __future__ import annotations

import argparse
import csv
import os
import time
import warnings
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
REFS = ROOT / "reference_tables" / "bem" / "panels_vehicles.csv"
OUT = ROOT / "benchmarks" / "data" / "frame_remesh_trace.md"
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
RHO = 1000.0


def reference(path: str) -> np.ndarray:
    """The stored Capytaine reference's diagonal [kg, kg m^2] of ``path``."""
    with open(REFS, newline="") as fh:
        rows = [r for r in csv.DictReader(x for x in fh if not x.startswith("#"))
                if r["file"] == path and r["install"] == "base"]
    if len(rows) != 6:
        raise SystemExit(f"{REFS}: no reference rows for {path}")
    return np.array([float(next(r for r in rows if r["dof"] == d)["bem"]) for d in DOFS])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("file", nargs="?", default="geometry/bluerov2_heavy.yaml")
    ap.add_argument("--counts", type=int, nargs="+", default=(400, 800, 1600, 3200, 6400),
                    help="panel counts of the whole surface whose edges are remeshed")
    ap.add_argument("--write", action="store_true", help=f"write {OUT.relative_to(ROOT)}")
    args = ap.parse_args(argv)

    from stripcoef.assembly import estimate
    from stripcoef.assembly.added_mass import panel_surface
    from stripcoef.geometry.vehicle import load_vehicle
    from stripcoef.hull import remesh
    from stripcoef.hull.bisection import enclosed_volume, surface_area
    from stripcoef.hull.convergence import richardson
    from stripcoef.hull.mirror_panels import capped_part, drop_caps, solve_mirrored
    from stripcoef.hull.panels import DEFAULT_PANELS, member_thickness, panel_added_mass

    ref = reference(args.file)
    veh = load_vehicle(ROOT / args.file)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0 = time.process_time()
        about = tuple(float(x) for x in estimate(veh).reference_point)
        cpu = time.process_time() - t0           # the whole default estimate
        body = panel_surface(veh, DEFAULT_PANELS)
        # (its levels, solved once per process: stripcoef.hull.panels._solved_level)
        m_a, info = panel_added_mass(body, rho=RHO, about=about, panels=DEFAULT_PANELS,
                                     mirrors=("y",))
    v, f = np.asarray(body.vertices, float), np.asarray(body.faces, np.int64)
    area = surface_area(v, f)
    part = capped_part(v, f, ("y",), about)
    pa, pv = surface_area(*part), enclosed_volume(*part)
    lines = [f"# Remesh modes on {args.file} (y-mirrored part, {len(f)}-face panel surface, "
             f"thinnest member {1000 * member_thickness(v, f):.1f} mm)", "",
             f"`OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame_remesh_trace {args.file} "
             f"--counts {' '.join(map(str, args.counts))}`; reference: {REFS.relative_to(ROOT)}."
             " One-level diagonal errors against it [%].", "",
             "| mode | asked | panels | area | volume | new folds | " + " | ".join(DOFS)
             + " | CPU [s] |", "|---" * (12) + "|"]
    modes = (("flips, 30 deg", remesh.MODES[0]), ("flips, 10 deg", remesh.MODES[1]),
             ("no flips (thin members)", remesh.MODES[2]))
    for name, mode in modes:
        for n in args.counts:
            c0 = time.process_time()
            out = remesh.remesh_isotropic(*part, remesh.edge_for_panels(area, n),
                                          feature_angle=mode)
            if out is None:
                lines.append(f"| {name} | {n} | refused | | | | " + " | " * 5 + " |")
                continue
            rv, rf = out
            hv, hf = drop_caps(rv, rf, ("y",), about)
            a = solve_mirrored(hv[hf], ("y",), rho=RHO, about=np.array(about))
            err = 100 * (np.diag(a) / ref - 1)
            lines.append(f"| {name} | {n} | {2 * len(hf)} | "
                         f"{100 * (surface_area(rv, rf) / pa - 1):+.2f} % | "
                         f"{100 * (enclosed_volume(rv, rf) / pv - 1):+.2f} % | "
                         f"{remesh.folds(rv, rf) - remesh.folds(*part)} | "
                         + " | ".join(f"{e:+.1f}" for e in err)
                         + f" | {time.process_time() - c0:.1f} |")
            print(lines[-1], flush=True)
    levels, counts = info["levels"], info["panels"]
    lines += ["", f"Default levels (`panel_added_mass`, {DEFAULT_PANELS} panels, mirror y): "
              f"{info['family']}, formal order {info['formal_order']:.2f}; the whole default estimate "
              f"{cpu:.1f} s of CPU.", "",
              "| value | " + " | ".join(DOFS) + " |", "|---" * 7 + "|",
              "| reported | " + " | ".join(f"{e:+.1f}" for e in
                                          100 * (np.diag(m_a) / ref - 1)) + " |"]
    for k, m in zip(counts, levels):
        lines.append(f"| level {k} | " + " | ".join(
            f"{e:+.1f}" for e in 100 * (np.diag(m) / ref - 1)) + " |")
    for p in (1.0, 4.0 / 3.0, 2.0):
        r = richardson(levels[-2], levels[-1], counts[-2], counts[-1], order=p)
        lines.append(f"| Richardson, last two, order {p:.2f} | " + " | ".join(
            f"{e:+.1f}" for e in 100 * (np.diag(r) / ref - 1)) + " |")
    text = "\n".join(lines) + "\n"
    print(text)
    if args.write:
        OUT.write_text(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
