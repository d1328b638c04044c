"""The observed order of convergence on the BlueROV2 Heavy vehicle file's levels (issue 32):
the panel method's own levels and the graded Capytaine reference's, measured, not assumed.

The estimate extrapolates its two finest levels at the formal order of the body's sharpest
convex edge (:func:`stripcoef.hull.panels.edge_order`: 1 in h at a knife edge or a member
thinner than the panels, 4/3 at a right-angled edge, 2 on a smooth body), the largest order
the grid convergence index may use (Oberkampf & Roy 2010, sec. 8.6.3.2).  On the vehicle file
with the remesh extra its levels are the input's faces bisected (1712/3966/9120 panels, the
y mirror plane), and at order 1 its surge, sway and yaw are 6.8-10 % below the graded reference
(reference_tables/bem/graded_frames.csv).  This benchmark measures, per diagonal term:

- the panel method's levels (the default three and, with ``--extra N``, the refinement forced
  on to N panels, ``tolerance=0``): each level's value against the graded reference, the
  observed order of each three consecutive levels (Celik et al. 2008, eqs. 3-5:
  :func:`stripcoef.hull.convergence.observed_order`) and, over four levels or more, Eça &
  Hoekstra's (2014, J. Comput. Phys. 262, 104-130) least-squares order and limit phi_0 with
  their bounds (the free order used only within [0.5, 2], else the best of the fixed orders
  1, 2 and 1 & 2: :func:`stripcoef.hull.convergence.eca_hoekstra`);
- the two finest levels Richardson-extrapolated at orders 1, 4/3 and 2 against the reference
  (what each candidate order would report);
- the graded reference's six levels (5,974-18,210 faces): the same observed orders.

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame_order [--extra 12000] [--write]

``--extra 12000`` adds a fourth level (21,212 panels: the part's face limit ``MAX_FACES`` raised
to 12,000 for the call; 49 s user + 19 s sys, 8.2 GB peak on the 2-core machine).

``--write`` writes benchmarks/data/frame_order.md (the base install's levels, ``--family input``
or no remesher: frame_order_base.md).  The remesh extra makes the default levels
(without it the base install's ladder is measured).
"""

from __future__ import annotations

import argparse
import os
import time
import warnings
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from stripcoef.conventions import DOF as DOFS  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "data" / "frame_order.md"
FILE = "geometry/bluerov2_heavy.yaml"
RHO = 1000.0


def panel_levels(extra: int | None, family: str = "auto"):
    """(counts, diagonal levels (k, 6), formal order, family, the default estimate's counts,
    the reference point, CPU [s]) of the vehicle file's panel levels, about the estimate's
    reference point, rho = :data:`RHO`; ``family`` as :func:`stripcoef.hull.panels.
    panel_added_mass` takes it ("input": the base install's levels, whatever is installed)."""
    from stripcoef.assembly import estimate
    from stripcoef.assembly.added_mass import panel_surface
    from stripcoef.geometry.vehicle import load_vehicle
    from stripcoef.hull import panels as P
    from stripcoef.hull import remesh as R
    from stripcoef.hull.panels import DEFAULT_PANELS, panel_added_mass

    veh = load_vehicle(ROOT / FILE)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = estimate(veh)
        about = tuple(float(x) for x in model.reference_point)
        kw = {} if extra is None else dict(tolerance=0.0, max_panels=2 * int(extra))
        # the forced refinement's levels beyond the library's limit on a remeshed or bisected
        # level (MAX_FACES faces of the part solved, here the y >= 0 half): raised to
        # ``extra`` for this call, then restored (raising MAX_PANELS too changes the default
        # levels: the whole body is then solved without its mirror plane)
        saved = (P.MAX_PANELS, R.MAX_FACES)
        if extra is not None:
            R.MAX_FACES = int(extra)
        try:
            cpu = time.process_time()
            _, info = panel_added_mass(panel_surface(veh, DEFAULT_PANELS), rho=RHO,
                                       about=about, panels=DEFAULT_PANELS, mirrors=("y",),
                                       family=family, **kw)
            cpu = time.process_time() - cpu
        finally:
            P.MAX_PANELS, R.MAX_FACES = saved
    default = tuple(model.conditions.get("added_mass_panel_levels", ()))
    return (list(info["panels"]), np.array([np.diag(m) for m in info["levels"]]),
            float(info["formal_order"]), str(info["family"]), default, np.array(about), cpu)


def graded_levels(point):
    """(counts, diagonal levels (k, 6)) of the graded reference's levels about ``point``, and
    its Eça & Hoekstra reference's diagonal about it."""
    from stripcoef.conventions import transform_matrix
    from validation.graded_bodies import read, references
    from validation.graded_frames import LEVELS, NAME

    _, counts, mats = read(LEVELS)[NAME]
    ref = references(LEVELS)[NAME][0]
    diag = np.array([np.diag(transform_matrix(m, from_point=(0, 0, 0), to_point=point))
                     for m in mats])
    return (list(counts), diag,
            np.diag(transform_matrix(ref, from_point=(0, 0, 0), to_point=point)))


def orders(counts, levels):
    """Per term: the observed order of every three consecutive levels (Celik et al. 2008;
    NaN: oscillating) and, with four levels or more, Eça & Hoekstra's result
    (:class:`stripcoef.hull.convergence.GridUncertainty`) over all of them."""
    from stripcoef.hull.convergence import EH_MIN_LEVELS, eca_hoekstra, observed_order

    h = np.asarray(counts, float) ** -0.5
    trip = []
    for k in range(len(counts) - 2):
        trip.append(observed_order(levels[k + 2], levels[k + 1], levels[k],
                                   h[k + 1] / h[k + 2], h[k] / h[k + 1]))
    eh = ([eca_hoekstra(counts, levels[:, i]) for i in range(levels.shape[1])]
          if len(counts) >= EH_MIN_LEVELS else None)
    return np.array(trip), eh


def _pct(x):
    return f"{100 * x:+.1f} %"


def table(title, counts, levels, ref, eh_ref_levels=True):
    """Markdown lines: each level against ``ref``, the observed orders, Eça & Hoekstra."""
    trip, eh = orders(counts, levels)
    lines = [f"### {title}", "", "| | " + " | ".join(DOFS) + " |", "|---" * 7 + "|"]
    for n, lv in zip(counts, levels):
        lines.append(f"| level {n} | " + " | ".join(_pct(x / r - 1) for x, r in zip(lv, ref))
                     + " |")
    for k, p in enumerate(trip):
        lines.append(f"| observed order, {counts[k]}/{counts[k + 1]}/{counts[k + 2]} | "
                     + " | ".join("osc." if not np.isfinite(x) else f"{x:.2f}" for x in p)
                     + " |")
    if eh is not None:
        lines.append("| Eça & Hoekstra: free order p (fit used) | " + " | ".join(
            f"{g.order:.2f} ({g.fit}{', w' if g.weighted else ''})" for g in eh) + " |")
        lines.append("| Eça & Hoekstra: phi_0 against the reference | " + " | ".join(
            _pct(g.extrapolated / r - 1) for g, r in zip(eh, ref)) + " |")
        lines.append("| Eça & Hoekstra: U of the finest level / its value | " + " | ".join(
            f"{100 * g.uncertainty / abs(lv):.1f} %" for g, lv in zip(eh, levels[-1])) + " |")
    return lines, trip, eh


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--extra", type=int, default=None,
                    help="force the refinement on (tolerance 0), a level of at most this many "
                         "faces of the half solved")
    ap.add_argument("--family", default="auto", choices=("auto", "input"),
                    help="the panel levels: auto (the install's), input (the base install's)")
    ap.add_argument("--write", action="store_true",
                    help=f"write {OUT.relative_to(ROOT)} (the base install's levels: "
                         "frame_order_base.md)")
    args = ap.parse_args(argv)

    from stripcoef.hull import remesh
    from stripcoef.hull.convergence import richardson

    counts, levels, formal, family, default, point, cpu = panel_levels(args.extra, args.family)
    g_counts, g_levels, g_ref = graded_levels(point)
    cmd = ("OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame_order"
           + ("" if args.extra is None else f" --extra {args.extra}")
           + ("" if args.family == "auto" else f" --family {args.family}"))
    lines = [f"# The observed order on the BlueROV2 Heavy vehicle file's levels ({FILE})", "",
             f"`{cmd}` ({'base install levels' if args.family == 'input' else 'remesh extra' if remesh.available() else 'base install'}). "
             f"Panel levels: {family}, formal order {formal:.2f}, the default estimate's "
             f"levels {'/'.join(map(str, default))}; {cpu:.1f} s of CPU for the levels. "
             "Every value is a diagonal term about the estimate's reference point "
             f"{np.round(point, 5).tolist()} m against the graded Capytaine reference "
             "(reference_tables/bem/graded_frames.csv, Eça & Hoekstra over its six levels).",
             ""]
    part, _, _ = table("The panel method's levels", counts, levels, g_ref)
    lines += part
    for p in (1.0, 4.0 / 3.0, 2.0):
        r = richardson(levels[-2], levels[-1], counts[-2], counts[-1], order=p)
        lines.append(f"| Richardson of {counts[-2]}/{counts[-1]} at order {p:.2f} | "
                     + " | ".join(_pct(x / y - 1) for x, y in zip(r, g_ref)) + " |")
    from benchmarks.cad_value_order import observed_value

    for k in range(3, len(counts) + 1):
        r = observed_value(counts[:k], list(levels[:k]))
        lines.append(f"| Richardson of {counts[k - 2]}/{counts[k - 1]} at each term's observed "
                     f"order of {counts[k - 3]}/{counts[k - 2]}/{counts[k - 1]}, in [0.5, 2] | "
                     + " | ".join(_pct(x / y - 1) for x, y in zip(r, g_ref)) + " |")
    if len(counts) > 3:
        k = len(default) if default else 3
        for p in (1.0, 4.0 / 3.0, 2.0):
            r = richardson(levels[k - 2], levels[k - 1], counts[k - 2], counts[k - 1], order=p)
            lines.append(f"| Richardson of {counts[k - 2]}/{counts[k - 1]} at order {p:.2f} | "
                         + " | ".join(_pct(x / y - 1) for x, y in zip(r, g_ref)) + " |")
    lines.append("")
    part, _, _ = table("The graded reference's levels (Capytaine, gmsh graded, mirror y)",
                       g_counts, g_levels, g_ref)
    lines += part
    text = "\n".join(lines) + "\n"
    print(text)
    if args.write:
        base = args.family == "input" or not remesh.available()
        (OUT.with_name("frame_order_base.md") if base else OUT).write_text(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
