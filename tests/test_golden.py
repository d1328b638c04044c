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
moves a matrix by far more than 1e-9 of its scale. ``STRIPCOEF_GOLDEN_EXACT=1`` asks for
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
    assert_same_tree(got, expected, name, rtol=TOLERANCE)


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
