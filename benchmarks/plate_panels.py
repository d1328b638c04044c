"""The panel method on a CAD seed's plates against their edge-graded references (issue 32).

Each plate of ``--seed`` of :mod:`benchmarks.cad_shapes` (drawn, written as a user has it and
estimated exactly as that benchmark does: :func:`benchmarks.cad_shapes.run_one`) is compared,
diagonal term by term, with Capytaine on structured panels graded towards every edge
(:mod:`benchmarks.plate_graded`'s levels, Eça & Hoekstra's least squares over them,
:func:`validation.cad_shapes.fine_reference`), twice: with the library's panels (a box or a
plate: panels graded towards its edges, :mod:`stripcoef.hull.graded_panels`) and with the
isotropic remesh the library used before (``--remesh``: the box rule switched off for the
run).  Usage:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.plate_panels --seed S --graded CSV [--md FILE]
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.plate_panels --boxes [--md FILE]

``CSV``: ``python -m benchmarks.plate_graded --seed S --count 40 --csv CSV`` (the seed's
plates' graded levels; seed 1375923287's are reference_tables/bem/cad_plates_graded.csv).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


def graded_refs(path) -> dict:
    """{shape: (6x6 diagonal reference, 6x6 diagonal band) [kg, kg m^2]} of a graded plates
    CSV."""
    from validation.cad_shapes import fine_reference, read_graded

    out = {}
    for k, (_, _, _, faces, terms) in read_graded(path).items():
        ref, band = np.zeros((6, 6)), np.zeros((6, 6))
        for i in range(6):
            r, b, _ = fine_reference(faces, [np.array([[x]]) for x in terms[i]])
            ref[i, i], band[i, i] = r[0, 0], b[0, 0]
        out[k] = (ref, band, faces)
    return out


def run(seed: int, count: int, refs: dict, remesh: bool) -> dict:
    """{shape: run_one's result} of the seed's plates with references, the library's panels
    (``remesh``: the box rule switched off, the isotropic remesh of before)."""
    import benchmarks.cad_shapes as CS
    import stripcoef.hull.panels as P

    saved = P.box_faces
    if remesh:
        P.box_faces = lambda v, f: None
    out = {}
    try:
        rng = np.random.default_rng(seed)
        with tempfile.TemporaryDirectory() as tmp:
            for k in range(count):
                family = CS.FAMILIES[int(rng.integers(0, len(CS.FAMILIES)))]
                if family != "plate" or k not in refs:
                    CS.make_shape(family, rng)
                    rng.uniform(), rng.uniform()
                    continue
                ref, band, faces = refs[k]
                stored = dict(ref=ref, counts=(faces[-1],), gci=band, step=np.full((6, 6), np.nan),
                              t_bem=float("nan"))
                out[k] = CS.run_one(family, rng, tmp, (), stored)
    finally:
        P.box_faces = saved
    return out


def table(seed, graded_path, new, old) -> str:
    lines = [f"`python -m benchmarks.plate_panels --seed {seed} --graded {graded_path}`", "",
             "Diagonal terms' error against the edge-graded reference [%]: the library's panels "
             "(graded towards the box's edges) / the isotropic remesh before; the estimate "
             "(graded) covers the error where marked.", "",
             "| # | plate | panels (graded / remesh) | " + " | ".join(DOFS) + " | CPU graded / "
             "remesh [s] |", "|---" * 10 + "|"]
    worst = {"new": 0.0, "old": 0.0}
    inside = {"new": 0, "old": 0}
    covered = 0
    total = 0
    for k in sorted(new):
        a, b = new[k], old[k]
        cells = []
        for i in range(6):
            x = next(r for r in a["rows"] if r["i"] == i and r["j"] == i)
            y = next(r for r in b["rows"] if r["i"] == i and r["j"] == i)
            worst["new"] = max(worst["new"], abs(x["rel"]))
            worst["old"] = max(worst["old"], abs(y["rel"]))
            inside["new"] += abs(x["rel"]) <= 0.05
            inside["old"] += abs(y["rel"]) <= 0.05
            covered += bool(x["covered"])
            total += 1
            cells.append(f"{100 * x['rel']:+.1f}{'' if x['covered'] else ' (n.c.)'} / "
                         f"{100 * y['rel']:+.1f}")
        lines.append(f"| {k} | {a['what']} [{a['how']}] | {a['panels']} / {b['panels']} | "
                     + " | ".join(cells) + f" | {a['c_model']:.2f} / {b['c_model']:.2f} |")
    lines += ["", f"Within 5 %: graded {inside['new']} of {total}, remesh {inside['old']} of "
              f"{total}; largest error graded {100 * worst['new']:.1f} %, remesh "
              f"{100 * worst['old']:.1f} %; the graded estimate covers {covered} of {total}."]
    return "\n".join(lines) + "\n"


def boxes_table() -> str:
    """The bluff set's eight boxes (:mod:`benchmarks.bluff_shapes`, about their centre, their
    three mirror planes) against the edge-graded references
    (``reference_tables/bem/graded_boxes.csv``): diagonal errors [%], graded / remesh."""
    import stripcoef.hull.panels as P
    from benchmarks.bluff_shapes import SHAPES
    from validation.graded_bodies import box_references

    lines = ["`python -m benchmarks.plate_panels --boxes`", "",
             "| box | panels (graded / remesh) | " + " | ".join(DOFS) + " |", "|---" * 8 + "|"]
    saved = P.box_faces
    worst = [0.0, 0.0]
    for name, (ref, _) in box_references().items():
        m = SHAPES[name][0](None)
        m.apply_translation(-m.center_mass)
        out = []
        for off in (False, True):
            P.box_faces = (lambda v, f: None) if off else saved
            try:
                a, info = P.panel_added_mass(m, rho=1000.0, mirrors=("x", "y", "z"))
            finally:
                P.box_faces = saved
            out.append((np.diag(a) / ref - 1.0, info["panels"]))
        worst = [max(worst[0], np.abs(out[0][0]).max()), max(worst[1], np.abs(out[1][0]).max())]
        lines.append(f"| {name} | {'/'.join(map(str, out[0][1]))} / "
                     f"{'/'.join(map(str, out[1][1]))} | "
                     + " | ".join(f"{100 * x:+.2f} / {100 * y:+.2f}"
                                  for x, y in zip(out[0][0], out[1][0])) + " |")
    lines += ["", f"Largest error: graded {100 * worst[0]:.2f} %, remesh {100 * worst[1]:.2f} %."]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--boxes", action="store_true",
                    help="the bluff set's boxes against graded_boxes.csv instead")
    ap.add_argument("--count", type=int, default=40)
    ap.add_argument("--graded", default=None, help="the seed's graded plate levels (CSV)")
    ap.add_argument("--md", default=None, help="append the table to this file")
    args = ap.parse_args(argv)
    if args.boxes:
        text = boxes_table()
        print(text)
        if args.md:
            with open(args.md, "a") as fh:
                fh.write("\n## The bluff set's boxes\n\n" + text)
        return 0
    if args.seed is None or args.graded is None:
        ap.error("--seed and --graded (or --boxes)")
    refs = graded_refs(args.graded)
    new = run(args.seed, args.count, refs, remesh=False)
    old = run(args.seed, args.count, refs, remesh=True)
    text = table(args.seed, args.graded, new, old)
    print(text)
    if args.md:
        with open(args.md, "a") as fh:
            fh.write(f"\n## Seed {args.seed}\n\n" + text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
