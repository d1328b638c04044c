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


@pytest.mark.parametrize("t,s", [(15, 35), (4, 35), (25, 30), (10, 5)])
def test_teos10_density_agrees_with_eos80(t, s):
    """TEOS-10 (IOC et al. 2010) and EOS-80 give sea-water density within 0.05 kg/m^3 in the
    oceanographic range (the TEOS-10 manual, sec. 2.5 and its comparison with EOS-80: the
    reference-composition salinity shifts rho by a few 0.01 kg/m^3)."""
    pytest.importorskip("gsw")
    from stripcoef.fluid import density_teos10
    assert density_teos10(t, s) == pytest.approx(density_eos80(t, s), abs=0.05)
    f = Fluid.from_temperature_salinity(t, s, equation="teos10")
    assert f.density == pytest.approx(density_teos10(t, s), rel=1e-15)
    assert "TEOS-10" in f.source


def test_teos10_without_gsw_names_the_extra(monkeypatch):
    import sys
    monkeypatch.setitem(sys.modules, "gsw", None)     # import gsw -> ImportError
    with pytest.raises(InputError, match="gsw") as err:
        Fluid.from_temperature_salinity(15, 35, equation="teos10")
    assert "stripcoef[seawater]" in str(err.value)
    with pytest.raises(InputError, match="unknown equation of state"):
        Fluid.from_temperature_salinity(15, 35, equation="unesco")


def test_vehicle_file_and_cli_take_the_equation(tmp_path):
    pytest.importorskip("gsw")
    import subprocess
    import sys

    import yaml

    from stripcoef.geometry.vehicle import parse_vehicle
    from conftest import GEOMETRY
    data = yaml.safe_load((GEOMETRY / "sphere.yaml").read_text())
    data["fluid"] = {"temperature": 10.0, "salinity": 35.0, "equation": "teos10"}
    veh = parse_vehicle(data, file="s.yaml")
    from stripcoef.fluid import density_teos10
    assert veh.fluid.density == pytest.approx(density_teos10(10.0, 35.0), rel=1e-15)
    data["fluid"] = {"density": 1000.0, "equation": "teos10"}
    with pytest.raises(InputError, match="fluid.equation"):
        parse_vehicle(data, file="s.yaml")
    out = subprocess.run([sys.executable, "-m", "stripcoef", "coefficients",
                          str(GEOMETRY / "sphere.yaml"), "--water-equation", "teos10"],
                         capture_output=True, text=True)
    assert out.returncode == 2 and "--water-equation" in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1
