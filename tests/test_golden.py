"""Regression snapshot: ``coefficients --json`` of every shipped vehicle.

The golden files were written by ``tests/golden/make_golden.py`` before the code was
reorganised; a layout change must leave every number as it was. A change of the
physics regenerates them in a commit that says why.

Strings, integers and structure must match exactly. Floats must match to 1e-12 of
the largest magnitude in their own array (a matrix, a vector, or the scalar itself):
bit for bit on one machine, with room for another CPU's BLAS kernels to round the
last bits of a ~1e-9 coupling differently. ``STRIPCOEF_GOLDEN_EXACT=1`` asks for
bit-for-bit equality.
"""

import json
import math
import os
import sys
import tempfile
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "golden"))
import make_golden  # noqa: E402

GOLDEN = Path(__file__).resolve().parent / "golden"
RTOL = 0.0 if os.environ.get("STRIPCOEF_GOLDEN_EXACT") == "1" else 1e-12


def _scale(value) -> float:
    if isinstance(value, list):
        return max((_scale(v) for v in value), default=0.0)
    return abs(value) if isinstance(value, float) else 0.0


def _compare(got, want, path: str, scale: float):
    if isinstance(want, dict):
        assert isinstance(got, dict) and got.keys() == want.keys(), path
        for k in want:
            _compare(got[k], want[k], f"{path}.{k}", _scale(want[k]) if isinstance(want[k], (list, float)) else 0.0)
    elif isinstance(want, list):
        assert isinstance(got, list) and len(got) == len(want), path
        for i, (g, w) in enumerate(zip(got, want)):
            _compare(g, w, f"{path}[{i}]", scale)
    elif isinstance(want, float) and not isinstance(got, bool):
        if math.isnan(want):
            assert math.isnan(got), path
        else:
            assert abs(got - want) <= RTOL * max(scale, abs(want)), f"{path}: {got!r} != {want!r}"
    else:
        assert got == want, f"{path}: {got!r} != {want!r}"


_TMP = Path(tempfile.mkdtemp(prefix="stripcoef-golden-"))


@pytest.mark.parametrize("name,argv", make_golden.cases(_TMP), ids=lambda v: v if isinstance(v, str) else "")
def test_coefficients_json_unchanged(name, argv):
    expected = json.loads((GOLDEN / f"{name}.json").read_text())
    _compare(make_golden.run(argv), expected, name, 0.0)
