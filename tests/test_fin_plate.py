"""Fins' 3D added mass: the rectangular plate's factor (DNV-RP-H103 table A-2) against
Capytaine on thin plates, and finned Myring hulls against their converged BEM
(benchmarks/finned_bodies.py, benchmarks/plate_added_mass.py)."""

import importlib

import numpy as np
import pytest

from stripcoef.errors import InputError
from stripcoef.sections.added_mass import plate_chordwise_factor
from validation import finned


def _bench(name):
    """benchmarks/<name>.py."""
    return importlib.import_module(f"benchmarks.{name}")


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
    bench = finned
    from stripcoef.data import load_table
    table = load_table("plate_added_mass_dnv")
    both = {r: lv for r, lv in bench.load_plates().items() if 0.01 in lv}
    assert set(both) >= {1.0, 2.0}
    for ratio, lv in both.items():
        zero = 2 * lv[0.01] - lv[0.02]
        assert zero == pytest.approx(table.interp(1.0 / ratio, "lambda"), rel=0.03), ratio
    # a thick level alone (b/a = 4: the thin level did not run) lies above the thin plate, as
    # the thickness and the panel error do at b/a = 1 and 2 (+3..+6 %)
    for ratio, lv in bench.load_plates().items():
        assert 1.0 < lv[0.02] / table.interp(1.0 / ratio, "lambda") < 1.06, ratio


# --- finned hulls against the BEM -----------------------------------------------------------

#: tolerances [%] per term of benchmarks/finned_bodies.py COMPARED against the Richardson BEM
#: (two finest of three meshes): every term 3 % (the issue's target), on all six bodies.  The
#: fins' share of sway, heave, pitch and yaw and of roll is the 3D thin-sheet solution with
#: their thickness as an equivalent planform (hull.finsheet), chosen for roll after all six
#: bodies had been run, and taken unchanged for the other modes (no factor fitted).  Measured:
#: every term within 1.3 % but roll (+2.5, +2.9, +1.6, +2.5, +2.5, +1.3 %) and the couplings
#: below
TOLERANCE = {(0, 0): 3.0, (1, 1): 3.0, (2, 2): 3.0, (3, 3): 3.0, (4, 4): 3.0, (5, 5): 3.0,
             (1, 5): 3.0, (2, 4): 3.0}
#: the couplings of large_tail about mid-length are a 23 % difference of the hull's share
#: (1.86 kg m) and the fins' (-1.45 kg m): 1 % of the fins' share is 3.5 % of the coupling.
#: The stored three-level BEM is not converged there (Richardson spread 7.4 % and 2.0 %); the
#: study with the fins refined alone and the hull's error removed
#: (benchmarks/fin_bem_refinement.py) is the reference for them: its coupling still grows with
#: each refinement, and the model is -3.5 % off its finest mesh
KNOWN = {("large_tail", (1, 5)), ("large_tail", (2, 4))}
#: wide_tail's couplings about mid-length are zero within the BEM's spread (0.00044 and
#: -0.011 kg m, spread 779 % and 69 %; the hull's and the fins' shares cancel): compared relative
#: to sqrt(M_ii M_jj) instead (measured -0.09 %)
CANCELLING = {("wide_tail", (1, 5)), ("wide_tail", (2, 4))}


def _fb():
    return finned


@pytest.mark.slow
@pytest.mark.parametrize("case", ["remus_tail", "large_tail", "midbody", "small_tail",
                                  "forward_fins", "wide_tail"])
def test_finned_hulls_against_bem(case):
    fb = _fb()
    ref = fb.load_references()[case]["richardson"]
    m = fb.strip_model(case)
    for (i, j), tol in TOLERANCE.items():
        if (case, (i, j)) in KNOWN:
            continue
        scale = np.sqrt(ref[i, i] * ref[j, j]) if (case, (i, j)) in CANCELLING else abs(ref[i, j])
        err = 100 * (m[i, j] - ref[i, j]) / scale
        assert abs(err) < tol, (case, (i, j), round(err, 2))


def test_large_tail_couplings_against_the_fin_refined_bem():
    # the refined BEM's coupling (the mean of M[1,5] and -M[2,4], equal by symmetry) grows with
    # every refinement, so its finest mesh bounds the converged value from below; the model is
    # within 4 % of that mesh (measured -3.5 %: a regression bound, not the 3 % the issue asks)
    fr = finned
    study = fr.load_refinement()
    mean = [fr.mean_coupling(a) for _, _, a in study]
    assert mean == sorted(mean)
    m = _fb().strip_model("large_tail")
    assert abs(fr.mean_coupling(m) / mean[-1] - 1) < 0.04


@pytest.mark.xfail(strict=True, reason="large_tail's coupling about mid-length: -3.5 % against "
                   "the finest fin-refined BEM (M[1,5] -3.4 %, M[2,4] -3.6 %), whose value still "
                   "grows")
def test_large_tail_couplings_within_3_percent():
    fr = finned
    fine = fr.load_refinement()[-1][2]
    m = _fb().strip_model("large_tail")
    assert abs(fr.mean_coupling(m) / fr.mean_coupling(fine) - 1) < 0.03


@pytest.mark.slow
def test_fins_shares_against_bem():
    # the fins' share (finned minus bare hull) of sway, yaw and their coupling on all six bodies
    # within 5 % plus the BEM's own spread on that term, which a share (a 3-10 % difference of
    # two sways) carries whole (validation.finned.richardson_spread).  Measured with the thin sheet:
    # sway -0.7, +1.7, -3.5, -4.9, -5.7, -1.2 %; yaw -0.2, +2.2, +3.8, -2.5, -4.8, -0.2 %;
    # coupling -0.3, +1.5, -3.7, -0.8, -5.6, +0.6 %.  Before it (the plates' 3D factor on the
    # strip shares): sway -4.8, +4.2, -0.7, -15.2, -3.1, -7.3 %, yaw off by up to 76 %
    from validation.fins import fin_shares
    fb = _fb()
    refs = fb.load_references()
    for case, (_, share, bem) in fin_shares().items():
        for i, j in ((1, 1), (5, 5), (1, 5)):
            spread = fb.richardson_spread(refs[case], i, j) / 100 * abs(refs[case]["richardson"][i, j])
            assert abs(share[i, j] - bem[i, j]) <= 0.05 * abs(bem[i, j]) + spread, (case, i, j)


def test_fin_thickness_factor_against_the_panel_method():
    # a thick fin pair's share of the finned circle's normal added mass over the thin one's:
    # the 2D panel method of the section (circle + 4 fins of thickness t) against C_A(s/(t/2))
    # of the exposed pair (DNV table A-1 rectangle); within 1.5 % for the BEM bodies' fins
    from validation.finned import finned_section as _section
    from stripcoef.assembly.added_mass import _fin_thickness_factor
    from stripcoef.sections import added_mass as am
    from stripcoef.sections.panel import added_mass_contours
    assert _fin_thickness_factor(0.1, 0.0) == 1.0
    for r, a, t in ((0.0955, 0.16, 0.012), (0.059, 0.1425, 0.012)):
        m = added_mass_contours(_section(r, a, 4, t), rho=1000.0, panels=1600)
        circle = am.circle(r, rho=1000.0)
        panel = (m[1, 1] - circle) / (am.circle_with_fins(r, a, rho=1000.0)[0] - circle)
        assert _fin_thickness_factor(a - r, t / 2) == pytest.approx(panel, rel=0.015), (r, a)


@pytest.mark.slow
def test_fin_share_corrected_converges_like_the_bare_hull():
    # Y_rdot of the REMUS-like finned hull with the 3D corrections: within 0.1 % of its
    # 4000-strip value from 250 strips on (the bare hull's: 0.03 %), no spread from the fin edges
    fb = _fb()

    def coupling(n):
        # validation.finned.strip_model: the same estimate, once per process (1000 strips:
        # the model test_finned_hulls_against_bem[remus_tail] reads)
        return fb.strip_model("remus_tail", n)[1, 5]

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


def test_fin_box_is_a_closed_box_with_its_nodes():
    fr = _bench("fin_bem_refinement")
    xs, ys, zs = fr.cosine_nodes(0.0, 0.3, 5), fr.cosine_nodes(-0.01, 0.01, 2), np.linspace(0, 1, 4)
    box = fr.fin_box(xs, ys, zs)
    assert box.is_watertight
    assert box.volume == pytest.approx(0.3 * 0.02 * 1.0, rel=1e-12)
    # two triangles per panel on the six faces
    assert len(box.faces) == 4 * (5 * 2 + 5 * 3 + 3 * 2)
    assert np.allclose(np.unique(np.round(box.vertices[:, 0], 12)), np.round(xs, 12))


@pytest.mark.parametrize("case", ["large_tail", "remus_tail", "small_tail"])
def test_fin_refinement_study_is_symmetric_and_its_hull_correction_small(case):
    # benchmarks/fin_bem_refinement.py: M[1,5] = -M[2,4] on the cruciform, so their difference
    # on each stored mesh is the BEM's own scatter; the hull correction (the bare hull's BEM
    # error on the study's hull mesh) is a small part of the coupling
    fr = fb = finned
    assert case in fr.stored_cases()
    study = fr.load_refinement(case)
    assert [name for name, _, _ in study] == [",".join(map(str, s)) for s in fr.REFINEMENT]
    for name, _, a in study:
        assert abs(a[1, 5] + a[2, 4]) < 0.02 * a[1, 5], name
    exact = fb.bare_hull_exact()
    correction = fr.hull_correction(case)
    for i, j in fr.COUPLINGS:
        assert abs(correction[i, j]) < 0.005 * abs(exact[i, j]), (i, j)


def test_other_couplings_and_the_rolls_against_the_fin_refined_bem():
    # remus_tail's and small_tail's couplings within 3 % of the refined BEM's finest mesh
    # (measured -0.04 %, +0.47 %); the roll of every studied body within 3 % of it and above it
    # (measured +2.73 %, +2.86 %, +2.30 %, with the BEM's roll falling at each refinement:
    # docs/validation.md)
    fr = fb = finned
    for case in ("remus_tail", "small_tail"):
        fine = fr.load_refinement(case)[-1][2]
        m = fb.strip_model(case)
        assert abs(fr.mean_coupling(m) / fr.mean_coupling(fine) - 1) < 0.03, case
    for case in ("large_tail", "remus_tail", "small_tail"):
        study = fr.load_refinement(case)
        roll = [a[3, 3] for _, _, a in study]
        assert roll == sorted(roll, reverse=True), case
        assert 0.0 < fb.strip_model(case)[3, 3] / roll[-1] - 1 < 0.03, case


@pytest.mark.slow
def test_validation_doc_fins_section_is_current():
    """docs/validation.md's section of these bodies is what the code writes now
    (tests/test_validation_doc.py), checked here beside the tests that compute the same strip
    models (``validation.finned.strip_model``, cached in the process)."""
    from test_validation_doc import assert_section_is_current

    assert_section_is_current("fins")
