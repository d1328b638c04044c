"""Published reference tables: well-formed files, the loader's errors, and the papers'
internal (in)consistencies asserted numerically.

A known mismatch inside a paper is a strict xfail whose reason says what the paper prints
and what its own numbers give; a check the paper passes is a plain assertion.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import pytest

import stripcoef.data
from validation import reference as ref
from stripcoef.errors import InputError

ROOT = ref.reference_dir()
DATA = Path(stripcoef.data.__file__).resolve().parent   # the runtime curves (src/stripcoef/data)
SOURCES = ("videoray_pro3", "romeo", "rov2", "mares", "dnv_rp_c205", "hoerner", "capytaine_anchor",
           "prestero2001", "body_drag_3d", "roddy1990_suboff", "flat_plate_lift", "annular_wing")


def val(source, name):
    return ref.reference_value(source, name)["value"]


def agrees(source, printed, computed_value):
    """computed_value equals the printed row to the row's tolerance (printed precision)."""
    return ref.agrees(ref.reference_value(source, printed), computed_value)


ALL_TABLES = [(s, t) for s in SOURCES for t in ref.tables(s)]
ALL_ROWS = [(s, r["name"]) for s, t in ALL_TABLES for r in ref.load_table(s, t)]
COMPUTED = [(s, n) for s, n in ALL_ROWS if ref.reference_value(s, n)["provenance"] == "computed"]


# ---------------------------------------------------------------------------
# Well-formed files
# ---------------------------------------------------------------------------

def test_every_source_has_its_folder_readme_and_tables():
    assert set(SOURCES) <= set(ref.sources())
    for source in SOURCES:
        readme = ROOT / source / "README.md"
        assert readme.is_file(), readme
        text = readme.read_text()
        assert "Citation" in text and "Inconsistencies" in text, readme
        assert ref.tables(source), source


@pytest.mark.parametrize("source,table", ALL_TABLES)
def test_table_is_well_formed(source, table):
    caption = ref.table_caption(source, table)
    assert caption, "a table starts with its caption and citation"
    rows = ref.load_table(source, table)
    assert rows
    for row in rows:
        assert row["unit"] and row["provenance"] in ref.PROVENANCE and math.isfinite(row["value"])
        assert row["sign_convention"], row["name"]
        if row["provenance"] == "read":
            assert row["source"], row["name"]
        if row["atol"] is not None or row["rtol"] is not None:
            assert row["tolerance_reason"], row["name"]
        if row["tolerance_reason"].startswith("printed precision"):
            # the stated tolerance is exactly half a unit in the last printed digit
            assert row["atol"] == pytest.approx(ref.printed_precision(row["value_text"]), rel=1e-12), row["name"]


@pytest.mark.parametrize("source", SOURCES)
def test_row_names_unique_within_source(source):
    seen = {}
    for table in ref.tables(source):
        for row in ref.load_table(source, table):
            assert row["name"] not in seen, f"{row['name']} in {table} and {seen.get(row['name'])}"
            seen[row["name"]] = table


@pytest.mark.parametrize("source,name", COMPUTED)
def test_computed_row_reproduces_its_formula(source, name):
    row = ref.reference_value(source, name)
    value = ref.recompute(source, name)
    # stored with 6 significant digits
    assert row["value"] == pytest.approx(value, rel=1e-5, abs=1e-12), row["formula"]


@pytest.mark.parametrize("check", [
    pytest.param(c, id=f"{c.source}:{c.computed}",
                 marks=pytest.mark.xfail(strict=True, reason=f"{c.source}: {c.mismatch}") if c.mismatch else ())
    for c in ref.CHECKS])
def test_paper_internal_consistency(check):
    """A number the paper prints equals what the paper's own inputs give (to printed precision)."""
    assert ref.agrees(ref.reference_value(check.source, check.printed), ref.recompute(check.source, check.computed))


def test_check_results_report_every_check():
    results = ref.check_results()
    assert len(results) == len(ref.CHECKS)
    for r in results:
        assert r["agrees"] == (r["check"].mismatch is None), r["check"]


def test_printed_precision():
    assert ref.printed_precision("21.42") == pytest.approx(0.005)
    assert ref.printed_precision("0.5800") == pytest.approx(5e-5)
    assert ref.printed_precision("2.5939e-4") == pytest.approx(5e-9)
    assert ref.printed_precision("228") == pytest.approx(0.5)


# ---------------------------------------------------------------------------
# Loader errors: a missing file or row names what exists
# ---------------------------------------------------------------------------

def test_unknown_source_lists_sources():
    with pytest.raises(InputError, match="unknown reference source.*videoray_pro3"):
        ref.load_table("no_such_paper", "table1")


def test_unknown_table_lists_tables():
    with pytest.raises(InputError, match="unknown reference table.*table1_added_mass"):
        ref.load_table("videoray_pro3", "table9")


def test_unknown_row_lists_closest_names():
    with pytest.raises(InputError, match=r"unknown reference value.*N_rr\.experimental"):
        ref.reference_value("videoray_pro3", "N_rr.experimentl")


def test_missing_folder_is_an_input_error(tmp_path):
    with pytest.raises(InputError, match="reference tables folder not found"):
        ref.sources(root=tmp_path / "nowhere")


def _write(tmp_path, text, source="paper", table="t1"):
    folder = tmp_path / source
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{table}.csv").write_text(text)
    return tmp_path


HEADER = ",".join(ref.COLUMNS)


@pytest.mark.parametrize("line,match", [
    ("a,1.0,,s,read,Table 1,,,,,", "missing unit"),
    ("a,x,kg,s,read,Table 1,,,,,", "not a number"),
    ("a,nan,kg,s,read,Table 1,,,,,", "not a finite number"),
    ("a,1.0,kg,s,guessed,Table 1,,,,,", "unknown provenance"),
    ("a,1.0,kg,s,computed,Table 1,,,,,", "computed row without formula"),
    ("a,1.0,kg,s,read,,,,,,", "read row without source"),
    ("a,1.0,kg,s,assumed,,,,,,", "assumed row without reason"),
    ("a,1.0,kg,s,read,Table 1,,0.1,,,", "tolerance without reason"),
    ("a,1.0,kg,s,read,Table 1,,-0.1,,why,", "negative tolerance"),
    ("a,1.0,kg", "wrong number of fields"),
])
def test_malformed_rows_are_rejected(tmp_path, line, match):
    root = _write(tmp_path, f"# caption\n{HEADER}\n{line}\n")
    with pytest.raises(InputError, match=match) as info:
        ref.load_table("paper", "t1", root=root)
    assert "t1.csv" in str(info.value) and "line 3" in str(info.value)


def test_wrong_header_is_rejected(tmp_path):
    root = _write(tmp_path, "# caption\nname,value\na,1\n")
    with pytest.raises(InputError, match="wrong header row"):
        ref.load_table("paper", "t1", root=root)


def test_duplicate_names_across_tables_are_rejected(tmp_path):
    row = "a,1.0,kg,s,read,Table 1,,,,,"
    root = _write(tmp_path, f"# c\n{HEADER}\n{row}\n", table="t1")
    _write(tmp_path, f"# c\n{HEADER}\n{row}\n", table="t2")
    with pytest.raises(InputError, match="duplicate row name"):
        ref.reference_value("paper", "a", root=root)


def test_formula_evaluation_and_its_errors(tmp_path):
    root = _write(tmp_path, f"# c\n{HEADER}\na,2.0,m,s,read,T1,,,,,\n"
                            "b,4.0,m^2,s,computed,T1,{a}**2,,,,\n")
    assert ref.recompute("paper", "b", root=root) == pytest.approx(4.0)
    assert ref.evaluate("paper", "sqrt({a}) + abs(-1)", root=root) == pytest.approx(math.sqrt(2) + 1)
    with pytest.raises(InputError, match="unsupported formula syntax"):
        ref.evaluate("paper", "__import__('os')", root=root)
    with pytest.raises(InputError, match="unknown reference value"):
        ref.evaluate("paper", "{c} * 2", root=root)
    with pytest.raises(InputError, match="row is not computed"):
        ref.recompute("paper", "a", root=root)


# ---------------------------------------------------------------------------
# VideoRay Pro III (Wang & Clark 2006): Table I vs the yaw identification of sec. III.C
# ---------------------------------------------------------------------------

V = "videoray_pro3"


def test_videoray_beta_over_gamma_is_0_0416():
    """N_r|r| = beta/gamma from the identified yaw model (eq. 8)."""
    value = val(V, "yaw.beta") / val(V, "yaw.gamma")
    assert float(f"{value:.3g}") == 0.0416


def test_videoray_gamma_is_about_z():
    """1/gamma - I_zz reproduces N_rdot; the text's 'about y-axis' (I_yy) does not (a CHECKS mismatch)."""
    assert agrees(V, "N_rdot.experimental", ref.recompute(V, "N_rdot.from_yaw_fit"))
    assert not agrees(V, "N_rdot.experimental", ref.recompute(V, "N_rdot.from_yaw_fit_with_I_yy"))


def test_videoray_table1_is_positive_magnitudes():
    for table in ("table1_added_mass", "table1_linear_drag", "table1_quadratic_drag"):
        for row in ref.load_table(V, table):
            assert row["value"] > 0 and "SNAME" in row["sign_convention"], row["name"]


# ---------------------------------------------------------------------------
# ROV II (Eng et al. 2009): Table II averages, scaling to Tables III/IV, the in-air text
# ---------------------------------------------------------------------------

R = "rov2"


def test_rov2_every_rederivable_table3_4_entry_is_checked():
    """Every surge 'Experiment' entry of Tables III/IV (the only direction with model-scale data in
    Table II; sway/heave/yaw were 'not shown') is compared in SCALED."""
    surge_rows = {r["name"] for t in ("table3_added_mass", "table4_drag") for r in ref.load_table(R, t)
                  if r["name"].startswith("surge.") and r["name"].endswith("experiment")}
    checked = {c.printed for c in ref.CHECKS if c.source == R}
    assert surge_rows and surge_rows <= checked


def test_rov2_in_air_measured_length_matches_fitted():
    assert agrees(R, "air.r_measured", val(R, "air.r_from_alpha"))


@pytest.mark.xfail(strict=True, reason="ROV II in-air text: beta & K_L imply M = 0.304 kg, gamma & K_Q imply 0.046 kg")
def test_rov2_in_air_implied_masses_agree():
    a, b = ref.recompute(R, "air.M_implied_by_K_L"), ref.recompute(R, "air.M_implied_by_K_Q")
    assert a == pytest.approx(b, rel=0.05)


@pytest.mark.xfail(strict=True, reason="ROV II: eq. (4) defines beta = K_L/(M+m_a) (same sign as K_L); the in-air "
                   "text prints beta = +0.0260 with K_L = -0.0079 (sign flipped)")
def test_rov2_in_air_beta_has_the_sign_of_K_L():
    assert math.copysign(1, val(R, "air.beta")) == math.copysign(1, val(R, "air.K_L"))


@pytest.mark.xfail(strict=True, reason="ROV II: eq. (4) defines gamma = K_Q r/(M+m_a) (same sign as K_Q); the in-air "
                   "text prints gamma = -0.0481 with K_Q = +0.0057 (sign flipped)")
def test_rov2_in_air_gamma_has_the_sign_of_K_Q():
    assert math.copysign(1, val(R, "air.gamma")) == math.copysign(1, val(R, "air.K_Q"))


# ---------------------------------------------------------------------------
# ROMEO (Indiveri 1998): eq. 4.17 vs Table I, and the yaw tables' degrees of freedom
# ---------------------------------------------------------------------------

M = "romeo"
HEAVE = [("eta", "k_w"), ("eta", "k_ww"), ("eta", "eta"), ("eta_md", "k_w"), ("eta_md", "k_ww"),
         ("eta_md", "eta"), ("eta_md", "alpha"), ("standard", "k_w"), ("standard", "k_ww")]


@pytest.mark.parametrize("model,p", HEAVE)
def test_romeo_eq4_17_relative_errors_within_table1_range(model, p):
    rel = ref.recompute(M, f"{model}.{p}.relerr")
    lo = ref.reference_value(M, f"{model}.{p}.relerr_min")
    hi = ref.reference_value(M, f"{model}.{p}.relerr_max")
    assert lo["value"] - lo["atol"] <= rel <= hi["value"] + hi["atol"]


@pytest.mark.xfail(strict=True, reason="ROMEO text after Table I quotes 'eta_md = 0.57'; eq. (4.17) gives 0.57 for "
                   "the eta model and 0.54 for the eta-md model")
def test_romeo_text_eta_md_matches_eq4_17():
    assert agrees(M, "heave.efficiency_loss_text", val(M, "eta_md.eta"))


def test_romeo_heave_efficiency_loss_over_40_percent():
    """'the loss of efficiency ... is more then 40%' holds for both eta estimates."""
    assert 1 - val(M, "eta.eta") > 0.40 and 1 - val(M, "eta_md.eta") > 0.40


YAW = ["A_watson", "A_kvh", "B_watson", "B_kvh"]


def _models(label):
    rows = ref.load_table(M, "yaw_" + label)
    return sorted({r["name"].split(".")[1] for r in rows})


def _npoints(label, model):
    return ref.recompute(M, f"{label}.{model}.n_points")


@pytest.mark.parametrize("label", YAW + [s.replace("_", "_pm_", 1) for s in YAW])
def test_romeo_yaw_dof_consistent_within_table(label):
    """dof = N - n_params: every model fitted to the same data has the same N."""
    models = _models(label)
    for direction in ("+", "-", ""):
        ns = {_npoints(label, m) for m in models if (m[-1] == direction if direction else m[-1] not in "+-")}
        assert len(ns) <= 1, (label, direction, ns)


@pytest.mark.parametrize("exp,sensor", [(e, s) for e in "AB" for s in ("watson", "kvh")])
def test_romeo_yaw_split_counts_add_up(exp, sensor):
    pm = f"{exp}_pm_{sensor}"
    n_plus = _npoints(pm, "LB+")
    n_minus = _npoints(pm, "LB-")
    assert n_plus + n_minus == _npoints(f"{exp}_{sensor}", "LB")


@pytest.mark.parametrize("exp,sensor", [(e, s) for e in "AB" for s in ("watson", "kvh")])
def test_romeo_yaw_least_squares_costs_are_ordered(exp, sensor):
    """Nested models: more parameters never fit worse; one model for both directions never fits
    better than separate fits per direction."""
    j = lambda label, m: val(M, f"{label}.{m}.J_LS")  # noqa: E731
    c, pm = f"{exp}_{sensor}", f"{exp}_pm_{sensor}"
    assert j(c, "LQB") <= j(c, "LQNB") <= j(c, "LNB")
    assert j(c, "LQB") <= j(c, "LB") <= j(c, "LNB")
    for model in ("LQB", "LB"):
        assert j(c, model) >= j(pm, model + "+") + j(pm, model + "-")
    for d in "+-":
        assert j(pm, "LQB" + d) <= j(pm, "LB" + d)
    if exp == "A":
        assert j(c, "LNB") >= j(pm, "LNB+") + j(pm, "LNB-")
        for d in "+-":
            assert j(pm, "LB" + d) <= j(pm, "LNB" + d)


def _relerr_rows():
    out = []
    for table in ref.tables(M):
        if table.startswith("yaw_"):
            out += [r["name"] for r in ref.load_table(M, table) if ".relerr_" in r["name"]]
    return out


@pytest.mark.parametrize("name", [
    pytest.param(n, marks=pytest.mark.xfail(strict=True, reason="ROMEO Exp. B +/- Watson table prints "
                                            "100 sd/|b| = -67 % for LQB-: a relative error cannot be negative"))
    if n == "B_pm_watson.LQB-.relerr_b" else n for n in _relerr_rows()])
def test_romeo_yaw_relative_errors_non_negative(name):
    assert val(M, name) >= 0


# ---------------------------------------------------------------------------
# DNV / Hoerner curves and the data files the section code interpolates
# ---------------------------------------------------------------------------

D = "dnv_rp_c205"


@pytest.mark.parametrize("lb", ["2", "5", "10", "40"])
def test_dnv_subcritical_length_factor_against_data_book(lb):
    row = ref.reference_value(D, f"databook.l_over_d_{lb}.kappa")
    assert ref.agrees(row, val(D, f"L_over_B_{lb}.kappa_subcritical"))


def test_dnv_cylinder_curve_shape():
    """Subcritical plateau ~1.2, drag crisis minimum ~0.28 near Re = 6.4e5, recovery above."""
    pts = sorted((val(D, f"point{i:02d}.Re"), val(D, f"point{i:02d}.Cd")) for i in range(1, 29))
    res, cds = zip(*pts)
    assert all(1.19 < c < 1.22 for r, c in pts if r < 2.2e5)
    i_min = cds.index(min(cds))
    assert 6e5 < res[i_min] < 7e5 and 0.28 < cds[i_min] < 0.29
    assert cds[-1] > 0.6


def _data_csv(name):
    path = DATA / name
    if not path.is_file():
        pytest.skip(f"{path.name} is not in this checkout (the lead adds src/stripcoef/data/*.csv)")
    with path.open() as fh:
        return list(csv.DictReader(line for line in fh if not line.startswith("#")))


def test_data_cylinder_drag_matches_reference():
    rows = _data_csv("cylinder_drag_dnv.csv")
    assert len(rows) == 28
    for i, row in enumerate(rows, start=1):
        assert float(row["Re"]) == pytest.approx(val(D, f"point{i:02d}.Re"), rel=5e-3)
        assert float(row["Cd"]) == pytest.approx(val(D, f"point{i:02d}.Cd"), abs=5e-4 + 1e-12)


def test_data_cylinder_length_factor_matches_reference():
    rows = _data_csv("cylinder_length_factor.csv")
    assert [r["L_over_B"] for r in rows] == ["2", "5", "10", "20", "40", "50", "100"]
    for r in rows:
        lb = r["L_over_B"]
        assert float(r["kappa_subcritical"]) == val(D, f"L_over_B_{lb}.kappa_subcritical")
        assert float(r["kappa_supercritical"]) == val(D, f"L_over_B_{lb}.kappa_supercritical")


def test_data_rectangle_added_mass_matches_reference():
    rows = _data_csv("rectangle_added_mass_dnv.csv")
    for r in rows:
        key = f"{float(r['a_over_b']):g}"
        assert float(r["C_A"]) == val(D, f"rectangle.a_over_b_{key}.C_A")
        assert float(r["beta"]) == val(D, f"rectangle.a_over_b_{key}.beta")
    assert {f"{float(r['a_over_b']):g}" for r in rows} == {"0.1", "0.2", "0.5", "1", "2", "5", "10"}


def test_data_plate_added_mass_matches_reference():
    # src/stripcoef/data/plate_added_mass_dnv.csv is Table A-2 by a/b = 1 / (printed b/a)
    rows = _data_csv("plate_added_mass_dnv.csv")
    printed = ["1.0", "1.25", "1.50", "1.59", "2.0", "2.5", "3.0", "3.17", "4.0", "5.0", "6.25",
               "8.0", "10.0"]
    inner = [r for r in rows if float(r["a_over_b"]) > 0]
    assert len(inner) == len(printed)
    for r, ba in zip(sorted(inner, key=lambda r: -float(r["a_over_b"])), printed):
        assert float(r["a_over_b"]) == pytest.approx(1 / float(ba), abs=5e-5)
        assert float(r["lambda"]) == val(D, f"plate.b_over_a_{float(ba):g}.lambda")
    assert [float(r["lambda"]) for r in rows if float(r["a_over_b"]) == 0] == [1.0]


def test_hoerner_curve_is_monotone_decreasing():
    pts = [(val("hoerner", f"point{i:02d}.B_over_2T"), val("hoerner", f"point{i:02d}.Cd")) for i in range(1, 21)]
    assert all(a[0] < b[0] and a[1] >= b[1] for a, b in zip(pts, pts[1:]))


# ---------------------------------------------------------------------------
# DNV Table A-1 (rectangle) against 2D potential flow, computed here independently
# ---------------------------------------------------------------------------

def _rectangle_nodes(half_x, half_y, n_total):
    """Counter-clockwise panel nodes on a 2 half_x x 2 half_y rectangle, cosine-clustered at the
    corners, panel count per side proportional to its length."""
    import numpy as np
    corners = np.array([[-half_x, -half_y], [half_x, -half_y], [half_x, half_y], [-half_x, half_y],
                        [-half_x, -half_y]])
    per = 4.0 * (half_x + half_y)
    pts = []
    for k in range(4):
        side = float(np.hypot(*(corners[k + 1] - corners[k])))
        m = max(20, int(round(n_total * side / per)))
        s = 0.5 * (1.0 - np.cos(np.linspace(0.0, np.pi, m + 1)))[:-1]
        pts.append(corners[k] + s[:, None] * (corners[k + 1] - corners[k]))
    return np.vstack(pts)


def _added_mass_2d(nodes):
    r"""2D added-mass matrix (x, y, rotation about the origin) per unit length and unit density of a
    closed polygon, by constant-strength source panels.

    Neumann condition d(phi)/dn = n_x, n_y, x n_y - y n_x at the panel midpoints; sources of
    potential ln(r)/(2 pi) integrated exactly over each panel (Katz & Plotkin, Low-Speed
    Aerodynamics, 2nd ed., sec. 10.2.1); m_ij = -\oint phi_i n_j ds (Newman 1977, sec. 4.13).
    Test-only independent check of the tabulated coefficients.
    """
    import numpy as np
    p1 = nodes
    d = np.roll(nodes, -1, axis=0) - p1
    length = np.hypot(d[:, 0], d[:, 1])
    t = d / length[:, None]
    n = np.column_stack([t[:, 1], -t[:, 0]])          # outward for counter-clockwise nodes
    mid = p1 + 0.5 * d
    rel = mid[:, None, :] - p1[None, :, :]
    x = np.einsum("ijk,jk->ij", rel, t)
    y = np.einsum("ijk,jk->ij", rel, n)
    L = length[None, :]
    r1, r2 = x**2 + y**2, (x - L) ** 2 + y**2
    dth = np.arctan2(y, x - L) - np.arctan2(y, x)
    np.fill_diagonal(dth, np.pi)                         # self-induced normal velocity 1/2
    u, v = np.log(r1 / r2) / (4 * np.pi), dth / (2 * np.pi)
    a = (u * t[None, :, 0] + v * n[None, :, 0]) * n[:, None, 0] + (u * t[None, :, 1] + v * n[None, :, 1]) * n[:, None, 1]
    b = (0.5 * x * np.log(r1) - 0.5 * (x - L) * np.log(r2) - L + y * dth) / (2 * np.pi)
    bc = np.column_stack([n[:, 0], n[:, 1], mid[:, 0] * n[:, 1] - mid[:, 1] * n[:, 0]])
    phi = b @ np.linalg.solve(a, bc)
    return -(phi * length[:, None]).T @ bc


_PANELS = 600


def test_panel_method_circle_and_plate_limits():
    import numpy as np
    th = np.linspace(0.0, 2 * np.pi, _PANELS, endpoint=False)
    m = _added_mass_2d(np.column_stack([np.cos(th), np.sin(th)]))
    assert m[0, 0] == pytest.approx(np.pi, rel=3e-3) and m[1, 1] == pytest.approx(np.pi, rel=3e-3)
    assert abs(m[2, 2]) < 1e-9 and abs(m[0, 1]) < 1e-9
    plate = _added_mass_2d(_rectangle_nodes(1e-3, 1.0, _PANELS))   # thin plate normal to x
    assert plate[0, 0] / np.pi == pytest.approx(1.0, rel=0.01)       # C_A -> 1
    assert plate[2, 2] / np.pi == pytest.approx(0.125, rel=0.01)     # beta -> 1/8


RATIOS = ["10", "5", "2", "1", "0.5", "0.2", "0.1"]


@pytest.fixture(scope="module")
def rectangle_potential_flow():
    out = {}
    for r in RATIOS:
        a = 1.0                     # half-side normal to the motion (y)
        b = a / float(r)            # half-side along the motion (x)
        m = _added_mass_2d(_rectangle_nodes(b, a, _PANELS))
        out[r] = (m[0, 0] / (math.pi * a**2), m[2, 2] / (math.pi * max(a, b) ** 4))
    return out


@pytest.mark.parametrize("r", RATIOS)
def test_dnv_rectangle_C_A_against_potential_flow(r, rectangle_potential_flow):
    row = ref.reference_value(D, f"rectangle.a_over_b_{r}.C_A")
    assert ref.agrees(row, rectangle_potential_flow[r][0])


@pytest.mark.parametrize("r", [
    pytest.param(r, marks=pytest.mark.xfail(strict=True, reason="DNV Table A-1 (as copied in public code) gives "
                                            "beta = 0.125 at a/b = 10, the flat-plate limit; 2D potential flow gives "
                                            "0.1436, and the table's own a/b = 0.1 entry (same rectangle turned) is 0.147"))
    if r == "10" else r for r in RATIOS])
def test_dnv_rectangle_beta_against_potential_flow(r, rectangle_potential_flow):
    row = ref.reference_value(D, f"rectangle.a_over_b_{r}.beta")
    assert ref.agrees(row, rectangle_potential_flow[r][1])


def test_data_rectangle_drag_against_published_points():
    """The recalled White/Hoerner curve: flat plate ~2.0 (data book 1.98), peak ~2.6 near d/h = 2/3."""
    import numpy as np
    rows = _data_csv("rectangle_drag.csv")
    d = np.array([float(r["d_over_h"]) for r in rows])
    cd = np.array([float(r["Cd"]) for r in rows])
    h = "hoerner"
    assert cd[d == 0.0][0] == pytest.approx(val(h, "long_plate_normal.Cd"), abs=0.05)
    i = int(np.argmax(cd))
    assert abs(d[i] - val(h, "rect_drag.peak.d_over_h")) < 0.1
    assert cd[i] == pytest.approx(val(h, "rect_drag.peak.Cd"), abs=0.15)


def test_data_rectangle_drag_square_within_published_range():
    import numpy as np
    rows = _data_csv("rectangle_drag.csv")
    cd_square = np.interp(1.0, [float(r["d_over_h"]) for r in rows], [float(r["Cd"]) for r in rows])
    assert val("hoerner", "square.Cd_min") <= cd_square <= val("hoerner", "square.Cd_max")


def test_data_plate_aspect_ratio_drag_ends_at_the_published_2d_plate():
    """The recalled plate-vs-aspect-ratio curve (data/plate_drag_aspect_ratio.csv) tends to the
    long plate normal to the flow (data book 1.98) and stays below it (tip vortices)."""
    rows = _data_csv("plate_drag_aspect_ratio.csv")
    cd = {float(r["h_over_b"]): float(r["Cd"]) for r in rows}
    assert cd[0.0] == pytest.approx(val("hoerner", "long_plate_normal.Cd"), abs=0.05)
    assert all(v < val("hoerner", "long_plate_normal.Cd") for k, v in cd.items() if k > 0)


# ---------------------------------------------------------------------------
# Measured 3D body drag (reference_tables/body_drag_3d): the rows the method's drag band is
# measured on, and the rows that check the method's own recalled curves instead
# ---------------------------------------------------------------------------

#: the rows scripts/make_method_uncertainty.py measures the translational drag on
BODY_DRAG_USED = ("sphere.Cd", "cube.face_on.Cd", "cube.edge_on.Cd", "cone.apex60.Cd",
                  "cone.apex30.Cd", "hemisphere_solid.Cd_dome", "hemisphere_solid.Cd_high",
                  "ellipsoid_2to1.Cd")


def test_body_drag_rows_used_are_read_or_computed_from_read():
    """No recalled value measures a band: every used row is read, or computed from read rows."""
    for name in BODY_DRAG_USED:
        row = ref.reference_value("body_drag_3d", name)
        assert row["provenance"] in ("read", "computed"), name
        assert 0.1 < row["value"] < 2.5, name
    sphere = [val("body_drag_3d", f"sphere.Cd.{k}") for k in ("diracdelta", "check_pack",
                                                              "hoerner_digitised")]
    assert val("body_drag_3d", "sphere.Cd") == pytest.approx(sum(sphere) / 3, rel=1e-5)
    assert max(abs(v / val("body_drag_3d", "sphere.Cd") - 1) for v in sphere) <= \
        ref.reference_value("body_drag_3d", "sphere.Cd")["rtol"]


@pytest.mark.parametrize("ld,printed", [(1, 0.91), (2, 0.85), (4, 0.87), pytest.param(
    7, 0.99, marks=pytest.mark.xfail(strict=True, reason="the method puts 0.99 at L/D = 8, "
                                     "not 7: 0.96 at 7 (reference_tables/body_drag_3d remark 4)"))])
def test_axial_blunt_cylinder_curve_against_the_data_book(ld, printed):
    """The method's recalled axial curve of flat-ended cylinders (blunt_cylinder_axial_cd, Hoerner
    fig. 3-33) against the data book's Fig. 5.13(b) (which is why those rows measure nothing)."""
    from stripcoef.sections.drag import blunt_cylinder_axial_cd
    row = ref.reference_value("body_drag_3d", f"cylinder_axial.l_over_d_{ld}.Cd")
    assert row["value"] == printed
    assert float(blunt_cylinder_axial_cd(ld)) == pytest.approx(printed, abs=row["atol"] + 0.01)


def test_data_square_plate_drag_against_the_data_book():
    rows = _data_csv("plate_drag_aspect_ratio.csv")
    cd = {float(r["h_over_b"]): float(r["Cd"]) for r in rows}
    assert cd[1.0] == pytest.approx(val("body_drag_3d", "square_plate.Cd"), abs=0.015)


@pytest.mark.parametrize("ld", ["0.5", "1", "2", "4"])
def test_axial_blunt_cylinder_curve_against_munson(ld):
    """The method's recalled blunt-end curve against a second public copy of Hoerner's rods
    along the flow (Munson Fig. 9.20, reference_tables/body_drag_3d remark 8), l/D 0.5 included."""
    from stripcoef.sections.drag import blunt_cylinder_axial_cd
    row = ref.reference_value("body_drag_3d", f"cylinder_axial.l_over_d_{ld}.Cd.munson")
    assert float(blunt_cylinder_axial_cd(float(ld))) == pytest.approx(row["value"], abs=0.05)


def test_munson_cones_confirm_the_apex_angle_reading():
    """Munson's theta is the half-angle: its 30 deg is the data book's 60 deg apex cone
    (remark 7), within 10 %; and its cones rise to a disc's drag at 90 deg."""
    half30 = val("body_drag_3d", "cone.half_angle30.Cd.munson")
    assert half30 == pytest.approx(val("body_drag_3d", "cone.apex60.Cd"), rel=0.10)
    assert val("body_drag_3d", "cone.half_angle10.Cd.munson") < val("body_drag_3d", "cone.apex30.Cd") \
        < half30
