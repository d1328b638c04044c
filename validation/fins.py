"""Validation section: fins (the finned-circle sections and finned Myring hulls against the BEM).

Generated from the same computations the tests assert (tests/test_fin_sections.py) and from the
Capytaine references stored in benchmarks/data/bem_finned_bodies.csv
(benchmarks/finned_bodies.py).
"""

from __future__ import annotations

import sys

import numpy as np

from validation import ROOT, markdown_table

RHO = 1000.0


def _section_rows():
    from stripcoef.sections.added_mass import circle_with_fins, finned_circle_roll
    from stripcoef.sections.panel import added_mass_contours
    sys.path.insert(0, str(ROOT / "tests"))
    from test_fin_sections import _section
    rows = []
    for r, fins in ((0.0, 2), (0.0, 4), (0.42, 2), (0.42, 4), (0.6, 4)):
        roll = finned_circle_roll(r, 1.0, fins=fins, rho=RHO)
        normal = circle_with_fins(r, 1.0, fins=fins, rho=RHO)[0]
        bare = np.pi / 8 if fins == 2 else 2 / np.pi
        e_roll, e_norm = [], []
        for t in (0.02, 0.01, 0.005):
            m = added_mass_contours(_section(r, 1.0, fins, t), rho=RHO, panels=1200)
            e_roll.append(m[2, 2] / roll - 1)
            e_norm.append(m[1, 1] / normal - 1)

        def aitken(e):
            d1, d2 = e[1] - e[0], e[2] - e[1]
            return e[2] - d2 * d2 / (d2 - d1)

        rows.append([f"{fins} fins, R/a = {r}", f"{roll / (RHO * bare):.5f}",
                     f"{100 * e_roll[-1]:+.2f}", f"{100 * aitken(e_roll):+.2f}",
                     f"{100 * aitken(e_norm):+.2f}"])
    return rows


def _bem_rows():
    sys.path.insert(0, str(ROOT / "benchmarks"))
    import finned_bodies as fb
    refs = fb.load_references()
    rows = []
    names = {(0, 0): "surge", (1, 1): "sway", (2, 2): "heave", (3, 3): "roll", (4, 4): "pitch",
             (5, 5): "yaw", (1, 5): "sway-yaw M[1,5]", (2, 4): "heave-pitch M[2,4]"}
    for case in fb.CASES:
        conv = refs[case]["richardson"]
        fine = refs[case][max((k for k in refs[case] if k != "richardson"), key=int)]
        m = fb.strip_model(case)
        scale = np.sqrt(np.outer(np.diag(conv), np.diag(conv)))
        for (i, j), name in names.items():
            rows.append([case if (i, j) == (0, 0) else "", name, f"{fine[i, j]:.5g}",
                         f"{conv[i, j]:.5g}", f"{m[i, j]:.5g}",
                         f"{100 * (m[i, j] - conv[i, j]) / abs(conv[i, j]):+.2f}",
                         f"{100 * (m[i, j] - conv[i, j]) / scale[i, j]:+.2f}" if i != j else ""])
    return rows


def section() -> str:
    parts = ["## Fins\n",
             "### Finned-circle sections: exact roll (conformal mapping) against the 2D panel method\n",
             "Roll m44 of a circle of radius R with two or four thin fins to tip radius a, on the bare "
             "fins' value (pi/8 rho a^4 for a pair, 2/pi rho a^4 for a cruciform); the panel method "
             "solves fins of thickness t = 0.02, 0.01, 0.005 a (1200 panels), extrapolated to t = 0 "
             "(Aitken); the normal term's extrapolation against its exact value "
             "rho pi (a^2 - R^2 + R^4/a^2) shows the extrapolation's own error "
             "(`stripcoef.sections.added_mass.finned_circle_roll`, tests/test_fin_sections.py).\n",
             markdown_table(["section", "m44 / bare fins", "panel t = 0.005a, error %",
                             "panel t -> 0, error %", "normal term t -> 0, error %"],
                            _section_rows()),
             "\n### Finned Myring hulls against Capytaine (vehicle file, 1000 strips, default 3D "
             "corrections)\n",
             "REMUS-like Myring hull (L = 1.386 m, D = 0.191 m) with a cruciform of flat fins "
             "(benchmarks/finned_bodies.py CASES); BEM: quarter meshes with two reflection symmetries, "
             "two refinements, Richardson (benchmarks/data/bem_finned_bodies.csv); M_A about the "
             "origin (mid-length) [kg, kg m, kg m^2]. Couplings also relative to "
             "sqrt(M_ii M_jj), since about mid-length they are differences of the hull's and the "
             "fins' shares.\n",
             markdown_table(["body", "term", "BEM finest", "BEM Richardson", "strip", "error %",
                             "error % of sqrt(M_ii M_jj)"], _bem_rows())]
    return "\n".join(parts)
