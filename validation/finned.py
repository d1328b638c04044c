"""Finned Myring hulls and their stored Capytaine references: the bodies, the readers of the
stored BEM matrices and the Richardson arithmetic, shared by validation/fins.py, the tests and
the benchmarks that compute the references (benchmarks/finned_bodies.py,
benchmarks/fin_bem_refinement.py, benchmarks/plate_added_mass.py).

Bodies (all along x, metres, origin at mid-length): the REMUS-like Myring hull of
benchmarks/mesh_shapes.py (Prestero 2001, table 2.1: a = 0.191, b = 0.654, c = 0.541,
d = 0.191 m, n = 2, tail half-angle 25 deg; untruncated, L = 1.386 m) with a cruciform of four
flat rectangular fins (thickness 0.012 m) on it, in six sizes and places (:data:`CASES`).

Stored references (reference_tables/bem/, README there):

- ``bem_finned_bodies.csv``: one row per case and mesh, plus the Richardson row of the two
  finest meshes (:func:`load_references`);
- ``bem_fin_refinement.csv``: the fins refined alone on one hull mesh, raw BEM matrices, the
  hull correction applied on loading (:func:`load_refinement`);
- ``bem_plates.csv``: thin rectangular plates, lambda = A_33 / (rho pi/4 a^2 b)
  (:func:`load_plates`).
"""

from __future__ import annotations

import csv
import functools
import warnings

import numpy as np

from validation import ROOT

#: the stored BEM references (reference_tables/bem/README.md)
BEM_DIR = ROOT / "reference_tables" / "bem"
DATA = BEM_DIR / "bem_finned_bodies.csv"
REFINEMENT_DATA = BEM_DIR / "bem_fin_refinement.csv"
PLATES_DATA = BEM_DIR / "bem_plates.csv"

RHO = 1025.0
MYRING = {"a": 0.191, "b": 0.654, "c": 0.541, "d": 0.191, "n": 2.0, "theta_deg": 25.0}
LENGTH = MYRING["a"] + MYRING["b"] + MYRING["c"]
X0 = -0.5 * LENGTH
THICKNESS = 0.012
#: name -> (fin mid-chord x [m], chord [m], tip radius [m])
CASES = {
    "remus_tail": (X0 + 0.17, 0.08, 0.1425),      # the fin size of benchmarks/mesh_shapes.py
    "large_tail": (X0 + 0.25, 0.12, 0.17),
    "midbody": (0.10, 0.14, 0.16),
    # added for the uncertainty calibration (scripts/make_method_uncertainty.py), chosen to span
    # fin size and place before their errors were known: small aft fins, forward fins on the
    # parallel middle body, and aft fins of twice the hull radius in span
    "small_tail": (X0 + 0.12, 0.06, 0.125),
    "forward_fins": (0.40, 0.08, 0.15),
    "wide_tail": (X0 + 0.20, 0.10, 0.22),
}
TERMS = [(i, j) for i in range(6) for j in range(i, 6)]
DOF = ("surge", "sway", "heave", "roll", "pitch", "yaw")
#: mesh levels: (meridian panels, sections round the axis, fin chord / largest fin edge); the
#: panel size shrinks by about sqrt(2) from one level to the next (faces about x 2)
MESH_LEVELS = ((38, 28, 5.7), (54, 40, 8.0), (76, 56, 11.3))
#: the terms compared (every non-zero one of a cruciform-finned body of revolution)
COMPARED = [(0, 0), (1, 1), (2, 2), (3, 3), (4, 4), (5, 5), (1, 5), (2, 4)]


def hull_radius(x):
    """The Myring hull's radius at ``x`` [m] (:data:`MYRING`, Myring 1976 via Prestero 2001)."""
    from stripcoef.geometry.profiles import myring_nose, myring_tail
    p = MYRING
    tail_end, mid_end = X0 + p["c"], X0 + p["c"] + p["b"]
    x = np.asarray(x, float)
    return np.where(x < tail_end, myring_tail(x, X0, tail_end, 0.5 * p["d"], np.radians(p["theta_deg"])),
                    np.where(x > mid_end, myring_nose(x, mid_end, X0 + LENGTH, 0.5 * p["d"], p["n"]),
                             0.5 * p["d"]))


def vehicle_dict(case: str, strips: int = 1000) -> dict:
    """The vehicle file (as a mapping) of a finned hull: Myring profile and four fins whose
    root is the hull surface at the fin's aft edge (the smallest hull radius under the fin)."""
    xc, chord, tip = CASES[case]
    p = MYRING
    r_root = float(hull_radius(xc - 0.5 * chord))
    span = tip - r_root
    mid = r_root + 0.5 * span
    fins = []
    for name, axis, c in (("top", "z", [xc, 0.0, -mid]), ("bottom", "z", [xc, 0.0, mid]),
                          ("port", "y", [xc, -mid, 0.0]), ("starboard", "y", [xc, mid, 0.0])):
        fins.append({"name": name, "type": "fin", "center": c, "span_axis": axis, "span": span,
                     "chord": chord, "thickness": THICKNESS})
    tail_end, mid_end = X0 + p["c"], X0 + p["c"] + p["b"]
    return {"name": case, "strips": strips, "reference_point": [0.0, 0.0, 0.0],
            "hull": {"profile": [
                {"type": "myring_tail", "x": [X0, tail_end], "radius": 0.5 * p["d"],
                 "theta_deg": p["theta_deg"]},
                {"type": "cylinder", "x": [tail_end, mid_end], "radius": 0.5 * p["d"]},
                {"type": "myring_nose", "x": [mid_end, X0 + LENGTH], "radius": 0.5 * p["d"],
                 "n": p["n"]}]},
            "appendages": fins}


def hull_profile(points: int):
    """(x, r) of the hull at ``points`` stations clustered at the ends by cosine spacing, the
    radius zero at both ends [m]."""
    x = X0 + LENGTH * 0.5 * (1.0 - np.cos(np.linspace(0.0, np.pi, points)))
    r = hull_radius(x)
    r[0] = r[-1] = 0.0
    return x, r


def bare_hull_exact():
    """The bare hull's 6x6 added mass about the origin from the axisymmetric panel method
    (stripcoef.hull.axisymmetric, 400 panels on an 801-point profile: exact to 0.02 %)
    [kg, kg m, kg m^2]: a fresh copy of a result solved once per process (0.35 s)."""
    return _bare_hull_exact().copy()


@functools.lru_cache(maxsize=1)
def _bare_hull_exact():
    from stripcoef.hull.axisymmetric import body_of_revolution_added_mass
    x, r = hull_profile(801)
    return body_of_revolution_added_mass(x, r, rho=RHO, x_ref=0.0, panels=400, modes=(0, 1))


def strip_model(case: str, strips: int = 1000):
    """The strip model's 6x6 added mass of ``case`` about the origin [kg, kg m, kg m^2]: a
    fresh copy of a result computed once per process (the tests and the docs ask for the same
    case several times)."""
    return _strip_model(case, strips).copy()


@functools.lru_cache(maxsize=None)
def _strip_model(case: str, strips: int):
    from stripcoef.assembly.estimate import estimate
    from stripcoef.geometry.vehicle import parse_vehicle
    veh = parse_vehicle(vehicle_dict(case, strips), file=f"<{case}>")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return np.asarray(estimate(veh).added_mass)


# --- the stored BEM matrices and their convergence --------------------------------------------

def read_rows(path) -> list:
    """The rows (dicts) of a stored BEM csv, its '#' comment lines skipped."""
    with open(path) as fh:
        return list(csv.DictReader(ln for ln in fh if not ln.startswith("#")))


def row_matrix(row) -> np.ndarray:
    """The symmetric 6x6 matrix of a stored row's m{i}{j} columns (:data:`TERMS`)."""
    a = np.zeros((6, 6))
    for i, j in TERMS:
        a[i, j] = a[j, i] = float(row[f"m{i}{j}"])
    return a


def load_references() -> dict:
    """case -> {faces or 'richardson': 6x6 array} from the stored csv (:data:`DATA`)."""
    out: dict = {}
    for row in read_rows(DATA):
        out.setdefault(row["case"], {})[row["faces"]] = row_matrix(row)
    return out


def richardson(coarse, fine):
    """Richardson value of two meshes, each (faces N, value A): error ~ 1/N (second order in the
    panel size h ~ N^(-1/2)), so A_inf = A_2 + (A_2 - A_1) N_1 / (N_2 - N_1).

    Richardson, Phil. Trans. R. Soc. A 210 (1911); Roache, Verification and Validation in
    Computational Science and Engineering (1998), ch. 5."""
    (n1, a1), (n2, a2) = coarse, fine
    return a2 + (a2 - a1) * n1 / (n2 - n1)


def meshes(levels: dict) -> list:
    """The face counts of one case's stored meshes (:func:`load_references`), smallest first."""
    return sorted(int(k) for k in levels if k != "richardson")


def observed_order(n, a) -> float:
    """Convergence order q of a BEM value on three meshes of n = (N_1, N_2, N_3) faces with values
    a = (A_1, A_2, A_3), from error ~ N^-q: the root of
    (A_2 - A_1)/(A_3 - A_2) = (N_1^-q - N_2^-q)/(N_2^-q - N_3^-q); q = 1 is second order in the
    panel size h ~ N^(-1/2) (the Richardson rows assume it).  NaN when the differences change
    sign (not in the asymptotic range) [-] (Roache 1998, ch. 5)."""
    from scipy.optimize import brentq
    n1, n2, n3 = (float(v) for v in n)
    d12, d23 = a[1] - a[0], a[2] - a[1]
    if d12 == 0 or d23 == 0 or d12 * d23 < 0:
        return float("nan")
    ratio = d12 / d23

    def g(q):
        return (n1 ** -q - n2 ** -q) / (n2 ** -q - n3 ** -q) - ratio
    try:
        return float(brentq(g, 0.05, 5.0))
    except ValueError:
        return float("nan")


def richardson_spread(levels: dict, i: int, j: int) -> float:
    """How far the reference itself is from converged on term (i, j) [%]: the Richardson values
    of the two finest and of the two coarsest of three meshes, their difference over the first
    (NaN with fewer than three meshes).  The meshes are built afresh at each level (not nested),
    so the BEM's convergence is not monotone on every term (benchmarks/finned_bodies.py
    ``--order``)."""
    ns = meshes(levels)
    if len(ns) < 3:
        return float("nan")
    coarse = richardson(*[(n, levels[str(n)][i, j]) for n in ns[-3:-1]])
    fine = levels["richardson"][i, j]
    return 100.0 * abs(fine - coarse) / abs(fine)


# --- the fin-refined study (benchmarks/fin_bem_refinement.py) ----------------------------------

#: the study's default case
CASE = "large_tail"
#: hull mesh level (:data:`MESH_LEVELS`): its own error cancels in the correction
HULL_LEVEL = 1
#: (chord, thickness, span) panel counts of each fin box, cosine-spaced; the thickness count is
#: even so that the quarter's symmetry planes fall on panel edges
REFINEMENT = ((16, 4, 16), (24, 4, 24), (32, 4, 32), (32, 6, 40))
#: the two coupling terms (sway-yaw, heave-pitch) and the diagonal terms reported
COUPLINGS = ((1, 5), (2, 4))
DIAGONAL = ((1, 1), (3, 3), (5, 5))
#: the meshes refined in the fin's plane only (chord and span panels together, the thickness
#: panels fixed): the sequence :func:`in_plane_order` reads
IN_PLANE = ((16, 4, 16), (24, 4, 24), (32, 4, 32))


def stored_cases() -> list:
    """The cases stored in :data:`REFINEMENT_DATA`, in file order."""
    return list(dict.fromkeys(r["case"] for r in read_rows(REFINEMENT_DATA)))


def load_raw(case: str = CASE) -> dict:
    """mesh name -> (faces, raw BEM 6x6 matrix) of the stored study ('bare' = the hull alone)."""
    return {r["mesh"]: (int(r["faces"]), row_matrix(r))
            for r in read_rows(REFINEMENT_DATA) if r["case"] == case}


def hull_correction(case: str = CASE, raw: dict | None = None) -> np.ndarray:
    """The bare hull's exact added mass minus its BEM value on the study's hull mesh [kg, kg m,
    kg m^2]: added to every finned result.  ``raw``: the case's :func:`load_raw`, if read."""
    return bare_hull_exact() - (raw or load_raw(case))["bare"][1]


def load_refinement(case: str = CASE) -> list:
    """[(mesh, faces, hull-corrected 6x6 matrix), ...] of the stored study, coarsest first:
    A_BEM(finned) - A_BEM(bare) + :func:`bare_hull_exact`."""
    raw = load_raw(case)
    correction = hull_correction(case, raw)
    return sorted(((name, n, a + correction) for name, (n, a) in raw.items() if name != "bare"),
                  key=lambda item: item[1])


def mean_coupling(a) -> float:
    """The coupling of a cruciform-finned body of revolution, (M[1,5] - M[2,4]) / 2 [kg m]:
    the two are equal by symmetry, so their mean is the estimate and their difference the
    BEM's scatter."""
    return 0.5 * (a[1, 5] - a[2, 4])


def in_plane_order(study: list, i: int, j: int) -> float:
    """Observed convergence order q of term (i, j) over the :data:`IN_PLANE` meshes of
    ``study`` (:func:`load_refinement`): error ~ N^-q with N the chord x span panels of a fin
    face (:func:`observed_order`), so q = 1 is second order in the panel size, what the
    direct method reaches on smooth bodies.  NaN when the differences grow (not in the
    asymptotic range).  Measured 0.16-0.32 and NaN: no extrapolation is trusted."""
    named = {name: a for name, _, a in study}
    n = [spec[0] * spec[2] for spec in IN_PLANE]
    return observed_order(n, [named[",".join(map(str, spec))][i, j] for spec in IN_PLANE])


# --- thin plates (benchmarks/plate_added_mass.py) ----------------------------------------------

def load_plates() -> dict:
    """b/a -> {t/a: lambda} from the stored csv (:data:`PLATES_DATA`)."""
    out: dict = {}
    for row in read_rows(PLATES_DATA):
        out.setdefault(float(row["b_over_a"]), {})[float(row["t_over_a"])] = float(row["lambda"])
    return out


# --- finned-circle sections (tests/test_fin_sections.py) ---------------------------------------

def finned_section(r, a, fins, t):
    """Circle of radius r with 2 or 4 fins of thickness t to tip radius a (one outer ring) [m]:
    the contour the 2D panel method solves."""
    from shapely.geometry import Point, box
    from shapely.ops import unary_union
    g = [Point(0, 0).buffer(r, 256)] if r > 0 else []
    g.append(box(-a, -t / 2, a, t / 2))
    if fins == 4:
        g.append(box(-t / 2, -a, t / 2, a))
    return [np.asarray(unary_union(g).exterior.coords)[:-1]]
