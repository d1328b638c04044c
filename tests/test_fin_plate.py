"""Fins' 3D added mass: the rectangular plate's factor (DNV-RP-H103 table A-2) against
Capytaine on thin plates, and finned Myring hulls against their converged BEM
(benchmarks/finned_bodies.py, benchmarks/plate_added_mass.py)."""

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from stripcoef.errors import InputError
from stripcoef.sections.added_mass import plate_chordwise_factor
from conftest import load_module

ROOT = Path(__file__).resolve().parent.parent


def _bench(name):
    """benchmarks/<name>.py (benchmarks/ is not a package), loaded once."""
    return load_module(ROOT / "benchmarks" / f"{name}.py", cache=True)


# --- the plate factor ------------------------------------------------------------------------

def test_plate_factor_limits():
    assert plate_chordwise_factor(1.0, 1.0) == pytest.approx(0.579)       # the square, as printed
    assert plate_chordwise_factor(1.0, 1e6) == pytest.approx(1.0, abs=1e-5)  # strip theory's limit
    # a wide plate: the 3D value is the strips across the chord, lambda = 1 -> kappa = c / w
    assert plate_chordwise_factor(1e4, 1.0) == pytest.approx(1e-4, rel=1e-3)


@pytest.mark.parametrize("w, c", [(0.3, 1.0), (2.0, 1.0), (5.0, 0.7), (1.0, 1.25)])
def test_plate_factor_is_one_plate_whichever_way_it_is_cut(w, c):
    # kappa(w, c) rho pi (w/2)^2 c and kappa(c, w) rho pi (c/2)^2 w are the same 3D added mass
    a = plate_chordwise_factor(w, c) * np.pi * (w / 2) ** 2 * c
    b = plate_chordwise_factor(c, w) * np.pi * (c / 2) ** 2 * w
    assert a == pytest.approx(b, rel=1e-12)


@pytest.mark.parametrize("w, c", [(0.0, 1.0), (1.0, -1.0), (np.nan, 1.0)])
def test_plate_factor_rejects_bad_dimensions(w, c):
    with pytest.raises(InputError, match="span|chord"):
        plate_chordwise_factor(w, c)


def test_plate_table_against_capytaine():
    # The DNV table is read from a secondary source; Capytaine on thin plates (t/a = 0.02 and
    # 0.01, extrapolated linearly to t = 0) checks it.  Tolerance 3 %: the extrapolation's own
    # spread (the two levels differ by 1-3 % and the thickness and panel errors of a plate's
    # edge are only roughly first order) plus the table's 3 printed digits.
    bench = _bench("plate_added_mass")
    from stripcoef.data import load_table
    table = load_table("plate_added_mass_dnv")
    both = {r: lv for r, lv in bench.load().items() if 0.01 in lv}
    assert set(both) >= {1.0, 2.0}
    for ratio, lv in both.items():
        zero = 2 * lv[0.01] - lv[0.02]
        assert zero == pytest.approx(table.interp(1.0 / ratio, "lambda"), rel=0.03), ratio
    # a thick level alone (b/a = 4: the thin level did not run) lies above the thin plate, as
    # the thickness and the panel error do at b/a = 1 and 2 (+3..+6 %)
    for ratio, lv in bench.load().items():
        assert 1.0 < lv[0.02] / table.interp(1.0 / ratio, "lambda") < 1.06, ratio


# --- finned hulls against the BEM -----------------------------------------------------------

#: tolerances [%] per term of benchmarks/finned_bodies.py COMPARED against the Richardson BEM
#: (two finest of three meshes): every term 3 % (the issue's target).  Roll is the fins' 3D
#: thin-sheet solution with their thickness as an equivalent planform (hull.finsheet): measured
#: +2.5, +2.9, +1.6 % here (before it, the exact 2D roll with the equivalent-body relief:
#: +5.9, +6.3, -1.1 %)
TOLERANCE = {(0, 0): 3.0, (1, 1): 3.0, (2, 2): 3.0, (3, 3): 3.0, (4, 4): 3.0, (5, 5): 3.0,
             (1, 5): 3.0, (2, 4): 3.0}
#: the couplings of large_tail about mid-length are a 21 % difference of the hull's share
#: (1.86 kg m) and the fins' (-1.47 kg m): the fins' share's centroid must be right to 3 mm for
#: 3 % of the coupling; the model's is about 10 mm aft of the BEM's (-19.0 %, -18.0 %; the BEM
#: itself is not converged there: its Richardson values from the two finest and the two
#: coarsest meshes differ by 7.4 % and 2.0 %, and its M[1,5] and -M[2,4], equal on this body,
#: by 1.2 %)
KNOWN = {("large_tail", (1, 5)), ("large_tail", (2, 4))}


def _fb():
    return _bench("finned_bodies")


@pytest.mark.parametrize("case", ["remus_tail", "large_tail", "midbody"])
def test_finned_hulls_against_bem(case):
    fb = _fb()
    ref = fb.load_references()[case]["richardson"]
    m = fb.strip_model(case)
    for (i, j), tol in TOLERANCE.items():
        if (case, (i, j)) in KNOWN:
            continue
        err = 100 * (m[i, j] - ref[i, j]) / abs(ref[i, j])
        assert abs(err) < tol, (case, (i, j), round(err, 2))


@pytest.mark.xfail(strict=True, reason="large_tail's couplings about mid-length: -19.0 % and "
                   "-18.0 % (the fins' share's centroid about 10 mm aft of the BEM's; KNOWN)")
def test_large_tail_couplings_within_3_percent():
    fb = _fb()
    ref = fb.load_references()["large_tail"]["richardson"]
    m = fb.strip_model("large_tail")
    for i, j in ((1, 5), (2, 4)):
        assert abs(m[i, j] - ref[i, j]) < 0.03 * abs(ref[i, j]), (i, j)


@pytest.mark.parametrize("case", ["small_tail", "forward_fins", "wide_tail"])
def test_held_out_roll_against_bem(case):
    # roll of the three bodies added for the uncertainty calibration, within 3 %: measured +2.5,
    # +2.5, +1.3 % (with the equivalent-body relief: +6.3, -1.6, +10.2 %).  The thin-sheet
    # method was chosen among four thickness treatments (none, chord only, tip only, both) on
    # physical grounds, exact in both 2D limits, after all six bodies had been run.
    fb = _fb()
    ref = fb.load_references()[case]["richardson"]
    m = fb.strip_model(case)
    assert abs(m[3, 3] - ref[3, 3]) < 0.03 * ref[3, 3], round(100 * (m[3, 3] / ref[3, 3] - 1), 2)


def _fins_share_of_sway(cases):
    """(strip, BEM, BEM spread) fins' share of sway per case (validation.fins.fin_shares: finned
    minus bare hull, the BEM's bare hull from the axisymmetric solution, exact to 0.02 %); the
    spread [kg] is how far the BEM's sway is from converged (finned_bodies.richardson_spread),
    which the share, a 3-10 % difference of two sways, carries whole."""
    from validation.fins import fin_shares
    fb = _fb()
    out = {}
    for case, (_, share, bem) in fin_shares(cases).items():
        ref = fb.load_references()[case]
        out[case] = (share[1, 1], bem[1, 1],
                     fb.richardson_spread(ref, 1, 1) / 100.0 * ref["richardson"][1, 1])
    return out


#: The bodies the fins' plate treatment was developed on, and the three added afterwards
#: (chosen before their errors were known, for the out-of-sample band check).
DEVELOPED_ON = ("remus_tail", "large_tail", "midbody")
HELD_OUT = ("small_tail", "forward_fins", "wide_tail")


def test_fins_share_of_sway_against_bem():
    # within 3 % plus the BEM's own spread on the bodies it was developed on (measured -4.8 %,
    # +4.2 %, -0.7 %, spreads 2.1 %, 3.3 %, 0.6 % of the share; before the plate factor and the
    # thickness: +25 %, +1.8 %, -8.3 %); within 10 % plus the spread on the held-out ones
    # (measured -15.2 %, -3.1 %, -7.3 %, spreads 7.2 %, 10.8 %, 2.9 %)
    for case, (share, bem, spread) in _fins_share_of_sway(DEVELOPED_ON).items():
        assert abs(share - bem) <= 0.03 * bem + spread, case
    for case, (share, bem, spread) in _fins_share_of_sway(HELD_OUT).items():
        assert abs(share - bem) <= 0.10 * bem + spread, case


@pytest.mark.xfail(strict=True, reason="held-out finned hulls: the fins' share of sway is "
                   "-15.2 % (small_tail) and -7.3 % (wide_tail) off the BEM; KNOWN")
def test_fins_share_of_sway_within_3_percent_on_held_out_bodies():
    for case, (share, bem, spread) in _fins_share_of_sway(HELD_OUT).items():
        assert abs(share - bem) <= 0.03 * bem + spread, case


def test_fin_thickness_factor_against_the_panel_method():
    # a thick fin pair's share of the finned circle's normal added mass over the thin one's:
    # the 2D panel method of the section (circle + 4 fins of thickness t) against C_A(s/(t/2))
    # of the exposed pair (DNV table A-1 rectangle); within 1.5 % for the BEM bodies' fins
    sys.path.insert(0, str(ROOT / "tests"))
    from test_fin_sections import _section
    from stripcoef.assembly.added_mass import _fin_thickness_factor
    from stripcoef.sections import added_mass as am
    from stripcoef.sections.panel import added_mass_contours
    assert _fin_thickness_factor(0.1, 0.0) == 1.0
    for r, a, t in ((0.0955, 0.16, 0.012), (0.059, 0.1425, 0.012)):
        m = added_mass_contours(_section(r, a, 4, t), rho=1000.0, panels=1600)
        circle = am.circle(r, rho=1000.0)
        panel = (m[1, 1] - circle) / (am.circle_with_fins(r, a, rho=1000.0)[0] - circle)
        assert _fin_thickness_factor(a - r, t / 2) == pytest.approx(panel, rel=0.015), (r, a)


def test_fin_share_corrected_converges_like_the_bare_hull():
    # Y_rdot of the REMUS-like finned hull with the 3D corrections: within 0.1 % of its
    # 4000-strip value from 250 strips on (the bare hull's: 0.03 %), no spread from the fin edges
    fb = _fb()
    from stripcoef.assembly.estimate import estimate
    from stripcoef.geometry.vehicle import parse_vehicle

    def coupling(n):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return estimate(parse_vehicle(fb.vehicle_dict("remus_tail", n), file="<c>")).added_mass[1, 5]

    ref = coupling(4000)
    for n in (250, 500, 1000):
        assert coupling(n) == pytest.approx(ref, rel=1e-3), n


# --- fins in surge ---------------------------------------------------------------------------

def test_fin_edgewise_is_the_dnv_rectangle_along_its_long_side():
    from stripcoef.sections.added_mass import fin_edgewise, rectangle_coefficient
    # c x t rectangle moving along c: C_A(t/c) rho pi (t/2)^2 (DNV-RP-C205 table A-1)
    t, c = 0.012, 0.08
    ca = rectangle_coefficient(np.array([t / c]))[0]
    assert fin_edgewise(t, c, rho=1000.0) == pytest.approx(ca * 1000.0 * np.pi * 0.006 ** 2)
    # a plate in its own plane displaces no water: m ~ t^2 in the thin limit (t/c < 0.1)
    assert fin_edgewise(0.002, 0.1) / fin_edgewise(0.004, 0.1) == pytest.approx(0.25)
    # the table's square (C_A = 1.51, Newman 1977 table 4.2)
    assert fin_edgewise(0.1, 0.1, rho=1.0) == pytest.approx(1.51 * np.pi * 0.05 ** 2, rel=0.01)


def _fin_on_cylinder(root, span=0.1, chord=0.2, radius=0.1):
    """Strips of a cylinder of ``radius`` (length 2 m) with one vertical fin of ``span`` whose root
    is at ``root`` from the axis (below the surface: part of it runs inside the hull)."""
    from stripcoef.geometry.vehicle import parse_vehicle
    d = {"name": "fin", "strips": 400,
         "hull": {"profile": [{"type": "cylinder", "x": [-1.0, 1.0], "radius": radius}]},
         "appendages": [{"name": "top", "type": "fin", "center": [0.0, 0.0, -(root + span / 2)],
                         "span_axis": "z", "span": span, "chord": chord, "thickness": 0.01}]}
    return parse_vehicle(d, file="<fin>").cut(400)


def test_fin_exposed_area_leaves_out_the_part_inside_the_hull():
    from stripcoef.hull.corrections import fin_exposed_area
    for root, exposed in ((0.1, 0.1), (0.06, 0.06), (0.03, 0.03)):
        strips = _fin_on_cylinder(root)
        fin = next(p for p in strips.parts if p.role == "fin")
        assert fin_exposed_area(strips, fin) == pytest.approx(0.2 * exposed, rel=1e-9), root


@pytest.mark.parametrize("case", ["remus_tail", "large_tail", "midbody", "small_tail",
                                  "forward_fins", "wide_tail"])
def test_finned_hull_surge_against_bem(case):
    # surge of the six finned hulls (three held out of the fins' plate treatment) within 3 %
    # of the BEM; the fins' section moving along the chord over their exposed span (measured:
    # within 1.3 %; the equal-area spindle it replaced gave up to +5.0 %)
    fb = _fb()
    ref = fb.load_references()[case]["richardson"][0, 0]
    assert fb.strip_model(case)[0, 0] == pytest.approx(ref, rel=0.03)
