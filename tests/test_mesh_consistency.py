"""A mesh made by revolving a shipped profile gives the profile's matrices (within 1 %)."""

import numpy as np
import pytest

from stripcoef.assembly.damping import wetted_perimeter
from stripcoef.geometry.mesh import mesh_body, revolved_mesh

def _pair(name):
    """(profile model, revolved-mesh model): ``validation.meshes.consistency_pair``, the
    models docs/validation.md's meshes section prints (computed once per process, checked
    below)."""
    from validation.meshes import consistency_pair

    return consistency_pair(name)


@pytest.fixture(scope="module", params=["capsule", "spheroid", "mares"])
def pair(request):
    return _pair(request.param)


def _close(a, b, rtol=1e-2):
    scale = np.abs(a).max()
    np.testing.assert_allclose(b, a, rtol=rtol, atol=1e-6 * scale)


def test_added_mass_matches_profile(pair):
    a, b = pair
    _close(a.added_mass, b.added_mass)
    assert b.volume == pytest.approx(a.volume, rel=1e-3)


def test_linear_damping_matches_profile(pair):
    a, b = pair
    _close(a.linear_damping, b.linear_damping)


def test_crossflow_quadratic_damping_matches_profile(pair):
    a, b = pair
    idx = np.ix_([1, 2, 4, 5], [1, 2, 4, 5])
    _close(a.quadratic_damping[idx], b.quadratic_damping[idx])


def test_friction_terms_match_profile(pair):
    a, b = pair
    assert b.quadratic_damping[0, 0] == pytest.approx(a.quadratic_damping[0, 0], rel=1e-2)
    assert b.quadratic_damping[3, 3] == pytest.approx(a.quadratic_damping[3, 3], rel=1e-2)


def test_polygon_perimeter_of_circle():
    t = np.linspace(0.0, np.pi, 81)[::-1]
    body = mesh_body(revolved_mesh(0.5 * np.cos(t), 0.1 * np.sin(t), sections=256))
    p = body.strips(41).parts[0]
    np.testing.assert_allclose(wetted_perimeter(p)[20], 2 * np.pi * p.half_breadth[20], rtol=1e-4)


@pytest.mark.slow
def test_validation_doc_meshes_section_is_current():
    """docs/validation.md's meshes section is what the code writes now
    (tests/test_validation_doc.py), checked here on the models of the tests above."""
    from test_validation_doc import assert_section_is_current

    assert_section_is_current("meshes")
