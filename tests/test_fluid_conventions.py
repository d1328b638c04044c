"""Water properties and the conventions module."""

import numpy as np
import pytest

from stripcoef.conventions import (kinematics, parse_dof, shift_operator, skew,
                                   transform_matrix)
from stripcoef.errors import InputError
from stripcoef.fluid import Fluid, density_eos80
from stripcoef.model import coriolis_from_mass


@pytest.mark.parametrize("t,s,rho", [(15, 35, 1025.972), (15, 0, 999.101), (4, 35, 1027.786)])
def test_eos80_density(t, s, rho):
    # EOS-80 values as computed by the seawater package (shared/reference/libraries-and-bem.md)
    assert density_eos80(t, s) == pytest.approx(rho, abs=2e-3)


@pytest.mark.parametrize("t,s,nu", [(15, 35, 1.18898e-6), (15, 0, 1.13876e-6),
                                    (4, 35, 1.62556e-6), (25, 35, 0.93696e-6)])
def test_sharqawy_kinematic_viscosity(t, s, nu):
    f = Fluid.from_temperature_salinity(t, s)
    # reference table used gsw/EOS-80 density; 1e-4 relative covers the density difference
    assert f.kinematic_viscosity == pytest.approx(nu, rel=2e-4)


def test_skew_and_shift():
    a, b = np.array([1.0, 2, 3]), np.array([-2.0, 0.5, 4])
    assert skew(a) @ b == pytest.approx(np.cross(a, b))
    r = np.array([0.3, -0.1, 0.2])
    nu = np.array([1.0, 0.2, -0.3, 0.1, -0.4, 0.25])
    vp = shift_operator(r) @ nu
    assert vp[:3] == pytest.approx(nu[:3] + np.cross(nu[3:], r))


def test_transform_round_trip_and_axes():
    rng = np.random.default_rng(1)
    a = rng.normal(size=(6, 6))
    a = a @ a.T
    p, q = np.array([0.1, 0.2, -0.3]), np.array([-0.5, 0.0, 0.4])
    b = transform_matrix(a, from_point=p, to_point=q)
    assert np.allclose(transform_matrix(b, from_point=q, to_point=p), a)
    flu = transform_matrix(a, axes="FLU")
    assert np.allclose(np.diag(flu), np.diag(a))
    assert np.allclose(transform_matrix(flu, axes="FLU"), a)
    with pytest.raises(InputError):
        transform_matrix(a, axes="NED")


def test_coriolis_skew_symmetric():
    rng = np.random.default_rng(2)
    m = rng.normal(size=(6, 6))
    m = m @ m.T + 6 * np.eye(6)
    nu = rng.normal(size=6)
    c = coriolis_from_mass(m, nu)
    assert np.allclose(c, -c.T)
    assert nu @ c @ nu == pytest.approx(0.0, abs=1e-12)


def test_kinematics_identity_at_zero():
    assert np.allclose(kinematics(np.zeros(6)), np.eye(6))


def test_parse_dof():
    assert parse_dof("yaw") == 5 and parse_dof("w") == 2 and parse_dof("N") == 5
    with pytest.raises(InputError, match="unknown degree of freedom"):
        parse_dof("spin")
