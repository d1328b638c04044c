"""estimate(correction_panels=): the meridian panels of the axisymmetric 3D corrections."""

import warnings

import numpy as np
import pytest

from stripcoef.assemble import estimate
from stripcoef.corrections import DEFAULT_PANELS
from stripcoef.errors import InputError
from stripcoef.fluid import Fluid
from stripcoef.geometry.mesh import mesh_body, revolved_mesh
from stripcoef.geometry.vehicle import MassSpec, Vehicle
from stripcoef.hull import spheroid_added_mass

RHO = 1000.0


def spheroid_vehicle(length=1.5, diameter=0.2, n=120, sections=64):
    t = np.linspace(0.0, np.pi, n + 1)[::-1]
    mesh = revolved_mesh(0.5 * length * np.cos(t), 0.5 * diameter * np.sin(t), sections=sections)
    body = mesh_body(mesh, origin="file", name="spheroid")
    return Vehicle(name="spheroid", source="test", fluid=Fluid(density=RHO, kinematic_viscosity=1e-6,
                                                              source="test"),
                   hull=None, bodies=[body], holes=[], mass=MassSpec(), thrusters=[],
                   reference="center_of_buoyancy")


def diagonal(vehicle, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = estimate(vehicle, strips=60, **kw)
    return np.diag(m.added_mass), m.conditions


def test_correction_panels_converge_to_the_default():
    v = spheroid_vehicle()
    default, cond = diagonal(v)
    assert cond["correction_panels"] == DEFAULT_PANELS
    same, _ = diagonal(v, correction_panels=DEFAULT_PANELS)
    np.testing.assert_array_equal(same, default)
    nz = [0, 1, 2, 4, 5]
    dev = []
    for panels in (20, 40, 80):
        d, cond = diagonal(v, correction_panels=panels)
        assert cond["correction_panels"] == panels
        dev.append(np.max(np.abs(d[nz] / default[nz] - 1)))
    # second-order panels: each doubling cuts the distance to the default several-fold
    assert dev[0] > 2 * dev[1] > 4 * dev[2]
    assert dev[2] < 2e-3
    # and the default itself is within 1 % of Lamb's exact spheroid (60 strips, 64-gon mesh)
    lamb = spheroid_added_mass(0.75, 0.1, rho=RHO)
    np.testing.assert_allclose(default[nz], lamb[nz], rtol=1e-2)


def test_correction_panels_ignored_without_corrections():
    v = spheroid_vehicle(n=40, sections=24)
    a, _ = diagonal(v, corrections=False)
    b, _ = diagonal(v, corrections=False, correction_panels=12)
    np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("bad", [0, 7, -40, 40.5, "many", None.__class__])
def test_bad_correction_panels(bad):
    v = spheroid_vehicle(n=40, sections=24)
    with pytest.raises(InputError, match="correction_panels"):
        estimate(v, strips=20, correction_panels=bad)
