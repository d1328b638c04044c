"""Regression snapshot: ``coefficients --json`` of every shipped vehicle.

The golden files were written by ``tests/golden/make_golden.py`` before the code was
reorganised; a layout change must leave every number as it was. A change of the
physics regenerates them in a commit that says why.

Keys, strings, integers and structure must match exactly. A float must match to 1e-9
(``conftest.RTOL``) of the largest magnitude of the array it belongs to (a matrix, a vector,
the scalar itself), and a derivative of ``coefficients`` (``Y_rdot``) to 1e-9 of the largest
entry of its matrix (M_A): another CPU's BLAS or another numpy/scipy release rounds the last
bits differently (measured: 1.1e-11 of the box mesh's M_A; a coupling that is zero up to
round-off, 7.99e-9 beside 41 kg, has no digits of its own), while a change of the physics
moves a matrix by far more than 1e-9 of its scale. The panel levels' estimated errors come
from a minimiser (Eça & Hoekstra's free-order fit) and match to 1e-6 of their scale
(``conftest.ESTIMATE_RTOL``: measured 1.8e-8 between two machines whose M_A agreed to
5e-16). ``STRIPCOEF_GOLDEN_EXACT=1`` asks for
bit-for-bit equality (on the machine that wrote the files).
"""

import json
import os

import pytest

from conftest import RTOL, ROOT, assert_same_tree, coefficients_json, load_module

GOLDEN = ROOT / "tests" / "golden"
make_golden = load_module(GOLDEN / "make_golden.py", "make_golden", cache=True)
TOLERANCE = 0.0 if os.environ.get("STRIPCOEF_GOLDEN_EXACT") == "1" else RTOL
NAMES = [name for name, _ in make_golden.cases(None)]


@pytest.fixture(scope="module")
def cases(tmp_path_factory):
    return dict(make_golden.cases(tmp_path_factory.mktemp("golden")))


# the BlueROV2 Heavy vehicle file is panelled (about 8 s of CPU each): in the slow set
@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow)
                                  if n.startswith("bluerov2_heavy") else n for n in NAMES])
def test_coefficients_json_unchanged(name, cases, run_once):
    """(The output of a shipped vehicle file is computed once per run and shared with the
    tests that read the same command's output: conftest.coefficients_json.)"""
    expected = json.loads((GOLDEN / f"{name}.json").read_text())
    got = coefficients_json(run_once, *cases[name])
    if _remeshed_panels(got, expected):
        got = _panel_terms_within_their_error(got, expected, name)
    assert_same_tree(got, expected, name, rtol=TOLERANCE)


#: The keys of ``conditions`` that describe the panel family and its levels (they name the
#: family, its panel counts and whether it converged: another family, other values).
PANEL_CONDITIONS = ("added_mass_method", "added_mass_panels", "added_mass_panel_levels",
                    "added_mass_converged", "added_mass_error_max")


def _remeshed_panels(got, want) -> bool:
    """Whether ``got`` is a panelled case whose levels are the remesher's (the ``remesh`` extra,
    pymeshlab, installed) where the golden file holds the base install's family (the input's
    faces refined or coarsened): the golden files are written by the base install, as CI
    runs. Without the remesher a change of family is a change, compared as one."""
    from stripcoef.hull import remesh

    method = want.get("conditions", {}).get("added_mass_method", "")
    return (remesh.available() and "refined/coarsened input" in method
            and got.get("conditions", {}).get("added_mass_method") != method)


def _panel_terms_within_their_error(got, want, name):
    r"""``got`` (the remesher's panel family) checked against the golden file's family where the
    two families differ, and returned with those parts replaced by the golden values, so that
    everything else is compared to 1e-9 as for every case.

    Each term of M_A: :math:`|A^{remesh}_{ij} - A^{input}_{ij}| \le E^{remesh}_{ij} +
    E^{input}_{ij}`, the sum of the two families' estimated errors (``added_mass_error``,
    :func:`stripcoef.hull.panels.estimated_error`: each bounds its own family's distance to the
    converged matrix, so their difference is bounded by the sum; measured: 0.44 of it on the
    VideoRay, 0.12 on the box).  A coupling zero in either (forbidden by a mirror plane) is
    exactly zero in both.  The M_A derivatives (``X_udot`` = -M_A[0, 0]) are read from that
    matrix; their 95 % bands move with the value: within the same bound times the band's
    size relative to the value (measured 0.47 of it)."""
    import copy

    import numpy as np

    from stripcoef.conventions import added_mass_name

    a_got, a_want = np.asarray(got["added_mass"]), np.asarray(want["added_mass"])
    bound = np.asarray(got["added_mass_error"]) + np.asarray(want["added_mass_error"])
    slack = TOLERANCE * np.abs(a_want).max()
    for i, j in zip(*np.nonzero(np.abs(a_got - a_want) > bound + slack)):
        raise AssertionError(f"{name}.added_mass[{i}][{j}]: {a_got[i, j]} != {a_want[i, j]} "
                             f"beyond the two panel families' estimated errors {bound[i, j]:.3g}")
    assert np.array_equal(a_got == 0.0, a_want == 0.0), \
        f"{name}: the couplings forbidden by symmetry differ between the panel families"
    out = copy.deepcopy(got)
    out["added_mass"], out["added_mass_error"] = want["added_mass"], want["added_mass_error"]
    for k in PANEL_CONDITIONS:
        if k in want["conditions"]:
            out["conditions"][k] = want["conditions"][k]
    for i, j in np.ndindex(6, 6):
        c = added_mass_name(i, j)
        if c in want["coefficients"]:
            assert got["coefficients"][c] == pytest.approx(-a_got[i, j], rel=TOLERANCE,
                                                           abs=slack), c
            out["coefficients"][c] = want["coefficients"][c]
        if c in want.get("coefficient_bands", {}):
            band_got, band_want = (np.asarray(b, float) for b in
                                   (got["coefficient_bands"][c], want["coefficient_bands"][c]))
            value = abs(float(a_want[i, j]))
            size = np.abs(band_want).max() / value if value > 0 else 1.0
            assert np.all(np.abs(band_got - band_want) <= bound[i, j] * max(1.0, size) + slack), \
                f"{name}.coefficient_bands.{c}: {band_got} != {band_want}"
            out["coefficient_bands"][c] = want["coefficient_bands"][c]
    return out


def test_the_comparison_scales_by_the_matrix():
    """A zero coupling's round-off passes against its matrix; a real change does not."""
    want = {"added_mass": [[41.0, 8e-9], [8e-9, 5.8]], "linear_damping": [[1.0, 0.0], [0.0, 0.2]],
            "quadratic_damping": [[0.0]], "lift": [[0.0]], "control_surfaces": [],
            "coefficients": {"Y_rdot": -8e-9, "Y_v": -1.0}}
    got = json.loads(json.dumps(want))
    got["coefficients"]["Y_rdot"] = -8.2e-9            # 2e-10 off: 5e-12 of M_A's 41 kg
    got["added_mass"][0][1] = 8.2e-9
    assert_same_tree(got, want)
    got["coefficients"]["Y_v"] = -1.0 - 2e-9          # 2e-9 of D_L: a change
    with pytest.raises(AssertionError, match="Y_v"):
        assert_same_tree(got, want)
    with pytest.raises(AssertionError, match="added_mass"):
        assert_same_tree({**want, "added_mass": [[41.0 + 1e-7, 8e-9], [8e-9, 5.8]]}, want)


def test_a_band_bound_scales_by_its_matrix_times_its_factor():
    """A lognormal band's bound is the value times exp(z sd): the value's round-off (here 1e-10
    of M_A's 79 kg, as measured between two CPUs on the box mesh's K_pdot) is multiplied by the
    bound's factor (129) and passes; a band 1e-6 wider (another sd: a change) does not."""
    want = {"added_mass": [[79.4, 0.0], [0.0, 1.19]], "linear_damping": [[0.0]],
            "quadratic_damping": [[0.0]], "lift": [[0.0]], "control_surfaces": [],
            "coefficients": {"K_pdot": -1.19, "Y_rdot": 1.5e-9},
            "coefficient_bands": {"K_pdot": [-154.19, -0.0092], "Y_rdot": [1.52e-9, 1.7e-9]}}
    got = json.loads(json.dumps(want))
    got["coefficients"]["K_pdot"] = -1.19 * (1 + 7e-9)           # 1e-10 of 79.4 kg
    got["coefficient_bands"]["K_pdot"][0] = -154.19 * (1 + 7e-9)
    got["coefficient_bands"]["Y_rdot"][0] = 1.52e-9 * (1 + 2.4e-7)  # a zero coupling's round-off
    assert_same_tree(got, want)
    got["coefficient_bands"]["K_pdot"][1] = -0.0092 * (1 + 1e-6) - 5e-6
    with pytest.raises(AssertionError, match="coefficient_bands.K_pdot"):
        assert_same_tree(got, want)


def test_an_estimated_error_is_compared_to_its_own_precision():
    """An estimated error's last digits (a minimiser's, sqrt(eps)) pass; a changed estimate,
    or the same deviation in the matrix it estimates, does not."""
    from conftest import ESTIMATE_RTOL

    want = {"added_mass": [[2.0, 0.0], [0.0, 1.0]], "added_mass_error": [[0.3125, 0.0], [0.0, 0.1]],
            "conditions": {"added_mass_error_max": 0.0894}}
    got = json.loads(json.dumps(want))
    got["added_mass_error"][0][0] *= 1 + 2e-8
    got["conditions"]["added_mass_error_max"] *= 1 + 2e-8
    assert_same_tree(got, want, "case")
    got["added_mass_error"][0][0] = 0.3125 * (1 + 10 * ESTIMATE_RTOL)
    with pytest.raises(AssertionError, match="added_mass_error"):
        assert_same_tree(got, want, "case")
    got = json.loads(json.dumps(want))
    got["added_mass"][0][0] *= 1 + 2e-8
    with pytest.raises(AssertionError, match="added_mass"):
        assert_same_tree(got, want, "case")
    with pytest.raises(AssertionError):           # bit-for-bit asked for
        bad = json.loads(json.dumps(want))
        bad["added_mass_error"][0][0] *= 1 + 2e-8
        assert_same_tree(bad, want, "case", rtol=0.0)
