"""A mesh made by revolving a shipped profile gives the profile's matrices (within 1 %)."""

import warnings
from pathlib import Path

import numpy as np
import pytest

from stripcoef.assembly.estimate import estimate
from stripcoef.assembly.damping import wetted_perimeter
from stripcoef.geometry.mesh import mesh_body, revolved_mesh
from stripcoef.geometry.vehicle import MassSpec, Vehicle, load_vehicle

GEOMETRY = Path(__file__).resolve().parents[1] / "geometry"


def _pair(name):
    v = load_vehicle(GEOMETRY / f"{name}.yaml")
    hull = v.bodies[0]
    lo, hi = hull.x_extent()
    x = lo + (hi - lo) * 0.5 * (1 - np.cos(np.linspace(0, np.pi, 401)))
    body = mesh_body(revolved_mesh(x, hull.half_breadth(x), sections=256), origin="file",
                     name="hull")
    kw = dict(source="test", fluid=v.fluid, holes=[], mass=MassSpec(), thrusters=[],
              reference="center_of_buoyancy")
    prof = Vehicle(name="profile", hull=hull, bodies=[hull], **kw)
    mesh = Vehicle(name="mesh", hull=None, bodies=[body], **kw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return estimate(prof, strips=200), estimate(mesh, strips=200)


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
