"""How far the bluff set's stored order-2 references lie from the edge-graded ones, and the
panel method against both (issue 32).

For every shape of :mod:`benchmarks.bluff_shapes` with edge-graded Capytaine levels
(``validation.graded_bodies.BLUFF_FILES``: the boxes, the chamfered box, the unions of prisms
along x), per diagonal term and per coupling significant in either reference (at least
:data:`benchmarks.bluff_shapes.SIGNIFICANT` of sqrt(A_ii A_jj)):

- the bias: the stored two-level Richardson at order 2 (``reference_tables/bem/
  bem_bluff.csv``) minus the graded reference (Eça & Hoekstra over four or five graded
  levels), relative to the diagonal term (a coupling: to sqrt(A_ii A_jj) of the graded
  matrix), with the graded reference's own band;
- the library's default (``estimate`` with ``auto``: what ``stripcoef coefficients`` and
  ``scripts.make_method_uncertainty --measure`` run on these meshes, the panel method with
  the body's mirror planes; :func:`auto_method` says which method it takes) against the
  stored reference and against the graded one: errors and within-5 % counts.

Usage (about 10 s of CPU; the stored records: ``graded_bias.md`` in the base install, as
the stored accuracy tables and ``method_errors.csv`` were made, ``graded_bias_remesh.md``
with the ``remesh`` extra):

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.graded_bias [--md benchmarks/data/graded_bias.md]
"""

from __future__ import annotations

import argparse
import datetime
import sys
from pathlib import Path

import numpy as np

DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
WITHIN = 0.05


def _terms(a, b, significant):
    """Diagonal terms and the couplings significant in ``a`` or ``b`` (relative to the
    diagonal scale of ``a``)."""
    d = np.abs(np.diag(a))
    out = [(i, i) for i in range(6) if d[i] > 1e-9 * d.max()]
    for i in range(6):
        for j in range(i + 1, 6):
            s = np.sqrt(d[i] * d[j])
            if s > 0 and max(abs(a[i, j]), abs(b[i, j])) >= significant * s:
                out.append((i, j))
    return out


def _rel(x, ref, i, j):
    """(x - ref) at (i, j) relative to ref's diagonal term (i = j) or sqrt(A_ii A_jj)."""
    d = np.abs(np.diag(ref))
    return float((x[i, j] - ref[i, j]) / (ref[i, i] if i == j else np.sqrt(d[i] * d[j])))


def _vehicle(name):
    """The shape's mesh as a vehicle (``benchmarks.bluff_shapes.strip_mesh``, about its volume
    centroid), as ``scripts.make_method_uncertainty`` takes it."""
    from benchmarks import bluff_shapes as bs
    from stripcoef.fluid import Fluid
    from stripcoef.geometry.vehicle import Vehicle

    return Vehicle.from_mesh(bs.strip_mesh(name), name=name,
                             fluid=Fluid(density=bs.RHO, kinematic_viscosity=1e-6,
                                         source="benchmark"))


def auto_method(name) -> str:
    """The added-mass method the library's default (``auto``) takes for the shape's mesh
    (:func:`stripcoef.assembly.methods.choose_method`)."""
    from stripcoef.assembly.methods import choose_method

    veh = _vehicle(name)
    return choose_method("auto", veh, veh.cut(None)).name


def model_matrix(name):
    """M_A [kg, kg m, kg m^2] of the shape by the library's default (``estimate``, ``auto``:
    what ``stripcoef coefficients`` computes for the mesh, mirror planes used), about its
    volume centroid, and the panel counts of its levels."""
    import warnings

    from stripcoef.assembly.estimate import estimate

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = estimate(_vehicle(name))
    return (np.asarray(model.added_mass, float),
            list(model.conditions.get("added_mass_panel_levels", ())))


def rows(names=None):
    """Per shape with a graded reference: its terms' (i, j, stored bias, graded band, panel
    error against the stored reference, against the graded one)."""
    from benchmarks import bluff_shapes as bs
    from validation.graded_bodies import bluff_sources

    graded = bluff_sources()
    stored = bs.read_references()
    out = {}
    for name in names or list(bs.SHAPES):
        if name not in graded:
            continue
        ref, band, path = graded[name]
        old = stored[name]
        a, panels = model_matrix(name)
        terms = _terms(ref, old, bs.SIGNIFICANT)
        d = np.abs(np.diag(ref))
        out[name] = dict(path=path, panels=panels, terms=[
            dict(i=i, j=j, bias=_rel(old, ref, i, j),
                 band=float(band[i, j] / (d[i] if i == j else np.sqrt(d[i] * d[j]))),
                 vs_old=_rel(a, old, i, j), vs_graded=_rel(a, ref, i, j))
            for i, j in terms])
    return out


def table(res) -> str:
    auto = ", ".join(sorted({auto_method(n) for n in res}))
    lines = ["| shape | graded file | diagonal bias: median / max | largest (term) | couplings: "
             "largest bias | graded band (diagonal): max | panels within 5 %: vs stored / vs "
             "graded (diagonal; couplings) | panels' worst: vs stored / vs graded |",
             "|---|---|---|---|---|---|---|---|"]
    for name, r in res.items():
        dg = [t for t in r["terms"] if t["i"] == t["j"]]
        cp = [t for t in r["terms"] if t["i"] != t["j"]]
        b = np.abs([t["bias"] for t in dg])
        w = max(dg, key=lambda t: abs(t["bias"]))
        cb = max((abs(t["bias"]) for t in cp), default=0.0)

        def n_ok(ts, key):
            return sum(abs(t[key]) <= WITHIN for t in ts)
        worst_old = max(r["terms"], key=lambda t: abs(t["vs_old"]))
        worst_new = max(r["terms"], key=lambda t: abs(t["vs_graded"]))
        lines.append(
            f"| {name} | {Path(r['path']).name} | {100 * np.median(b):.2f} / {100 * b.max():.2f} %"
            f" | {DOFS[w['i']]} {100 * w['bias']:+.2f} % | {100 * cb:.2f} % | "
            f"{100 * max(t['band'] for t in dg):.2f} % | "
            f"{n_ok(dg, 'vs_old')}/{len(dg)} / {n_ok(dg, 'vs_graded')}/{len(dg)}; "
            f"{n_ok(cp, 'vs_old')}/{len(cp)} / {n_ok(cp, 'vs_graded')}/{len(cp)} | "
            f"{_name(worst_old)} {100 * worst_old['vs_old']:+.1f} % / "
            f"{_name(worst_new)} {100 * worst_new['vs_graded']:+.1f} % |")
    allt = [t for r in res.values() for t in r["terms"]]
    dg = [t for t in allt if t["i"] == t["j"]]
    cp = [t for t in allt if t["i"] != t["j"]]
    b = np.abs([t["bias"] for t in dg])
    lines += ["", f"All {len(res)} shapes: diagonal bias median {100 * np.median(b):.2f} %, max "
              f"{100 * b.max():.2f} %, within 1 % on {int((b <= 0.01).sum())} of {len(b)}; the "
              f"panel method within 5 % on {sum(abs(t['vs_old']) <= WITHIN for t in dg)} of "
              f"{len(dg)} diagonal terms against the stored references, "
              f"{sum(abs(t['vs_graded']) <= WITHIN for t in dg)} against the graded ones; "
              f"couplings within 5 % of the scale {sum(abs(t['vs_old']) <= WITHIN for t in cp)}"
              f" / {sum(abs(t['vs_graded']) <= WITHIN for t in cp)} of {len(cp)}; median "
              f"|error| of the diagonal {100 * np.median(np.abs([t['vs_old'] for t in dg])):.2f}"
              f" / {100 * np.median(np.abs([t['vs_graded'] for t in dg])):.2f} %."]
    lines += ["", "| shape | term | stored - graded | graded band | panels - stored | panels - "
              "graded |", "|---|---|---|---|---|---|"]
    for name, r in res.items():
        lines += [f"| {name} | {_name(t)} | {100 * t['bias']:+.2f} % | {100 * t['band']:.2f} % | "
                  f"{100 * t['vs_old']:+.2f} % | {100 * t['vs_graded']:+.2f} % |"
                  for t in r["terms"]]
    from stripcoef.hull import remesh

    lines += ["", "(A diagonal term relative to the graded diagonal term, a coupling to "
              "sqrt(A_ii A_jj) of the graded matrix; couplings significant (1 % of the scale) "
              "in either reference. Model: the library's default, `estimate(vehicle)` with "
              "`auto`, as `stripcoef coefficients` runs it on the mesh and "
              "`scripts.make_method_uncertainty --measure` measures it (`auto` takes "
              f"{auto} on every shape here); the remesher "
              f"(pymeshlab, the `remesh` extra) {'installed' if remesh.available() else 'not installed: the base install'}.)"]
    return "\n".join(lines) + "\n"


def _name(t):
    return DOFS[t["i"]] if t["i"] == t["j"] else f"{DOFS[t['i']]}-{DOFS[t['j']]}"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", nargs="+", default=None, help="these shapes only")
    ap.add_argument("--md", default=None, help="also write the tables here")
    args = ap.parse_args(argv)
    text = table(rows(args.only))
    print(text)
    if args.md:
        Path(args.md).write_text(
            "### The bluff set's stored order-2 references against the edge-graded ones, and "
            f"the panel method against both\n\n`OPENBLAS_NUM_THREADS=1 python -m "
            f"benchmarks.graded_bias --md {args.md}` ({datetime.date.today().isoformat()})."
            "\n\n" + text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
