"""estimate(correction_panels=): the meridian panels of the axisymmetric 3D corrections."""

import warnings

import numpy as np
import pytest

from stripcoef.assembly.estimate import estimate
from stripcoef.hull.corrections import DEFAULT_PANELS
from stripcoef.errors import InputError
from stripcoef.fluid import Fluid
from stripcoef.geometry.mesh import mesh_body, revolved_mesh
from stripcoef.geometry.vehicle import MassSpec, Vehicle
from stripcoef.hull.lamb import spheroid_added_mass

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


def test_section_panels_round_sections_converged():
    """estimate(section_panels=): a round mesh section is converged well before the adaptive
    default (96 panels): 32 and 48 panels give the same matrix within 0.05 %, and the
    count is recorded in the model's conditions."""
    v = spheroid_vehicle(sections=96)
    default, cond = diagonal(v)
    assert "section_panels" not in cond
    nz = [0, 1, 2, 4, 5]
    for panels in (32, 48):
        d, cond = diagonal(v, section_panels=panels)
        assert cond["section_panels"] == panels
        np.testing.assert_allclose(d[nz], default[nz], rtol=5e-4)


def test_section_panels_change_the_2d_solve():
    """The knob reaches the panel method: a square section (sharp corners) moves with it."""
    from stripcoef.sections.panel import added_mass_contours
    sq = np.array([[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]])
    coarse = added_mass_contours([sq], rho=RHO, panels=24)[0, 0]
    fine = added_mass_contours([sq], rho=RHO, panels=192)[0, 0]
    assert coarse != fine
    # DNV-RP-C205 table A-1: square C_A = 1.51 on rho pi a^2 (a = half-width = 1)
    np.testing.assert_allclose(fine / (RHO * np.pi), 1.51, rtol=1e-2)


@pytest.mark.parametrize("bad", [0, 7, 40.5, "many"])
def test_bad_section_panels(bad):
    v = spheroid_vehicle(n=40, sections=24)
    with pytest.raises(InputError, match="section_panels"):
        estimate(v, strips=20, section_panels=bad)
