"""The Gazebo path of an ROV on Fortress (ROS 2 Humble) and Harmonic: thrusters exported, the
legacy added mass kept stable by lumping, a world to try it, and the Fortress file parsed by
sdformat 12 (Debian's libsdformat-dev, the version Fortress uses)."""

import os
import shutil
import subprocess
import warnings
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from stripcoef.export import export_model, write_export
from stripcoef.export._common import ExportView
from stripcoef.export.gazebo import lumped_added_mass_split

CHECKER = Path(__file__).resolve().parent / "sdformat_check.cc"


# the BlueROV2 Heavy vehicle file is panelled (about 8 s of CPU for the module fixture)
pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def rov(run_once):
    from conftest import shipped_model_once     # shared with test_export_gazebo_spec.py
    return shipped_model_once(run_once, "bluerov2_heavy.yaml")


def _root(text):
    return ET.fromstring(text.split("?>", 1)[1])


def _quiet(model, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return export_model(model, "gazebo", **kw)


def test_lumping_makes_the_explicit_added_mass_stable(rov):
    """The full M_A applied explicitly diverges on this ROV (spectral radius of
    M_RB^-1 M_A above 1: M_A > M_RB in several DOFs); the lumped split leaves a remainder
    whose explicit feedback contracts, and the lumped part plus the remainder is M_A."""
    view = ExportView.of(rov, "CO", "FLU")
    ma, mrb = view.matrix("added_mass"), view.matrix("rigid_body_mass")
    full = np.max(np.abs(np.linalg.eigvals(np.linalg.solve(mrb, ma))))
    assert full > 1.0
    m_t, j, rest, radius = lumped_added_mass_split(ma, mrb, view.r_g)
    assert m_t > 0 and np.all(j >= 0) and radius < 1.0
    # the explicit iteration a_{k+1} = M'^-1 (F - rest a_k) converges to the true acceleration
    lump = ma - rest
    force = np.array([10.0, -3.0, 5.0, 0.2, -0.4, 0.3])
    a = np.zeros(6)
    for _ in range(200):
        a = np.linalg.solve(mrb + lump, force - rest @ a)
    assert np.allclose(a, np.linalg.solve(mrb + ma, force), rtol=1e-9, atol=1e-12)


def test_fortress_file_carries_thrusters_and_balances_the_lumped_weight(rov):
    root = _root(_quiet(rov, fortress=True))
    model = root.find("model")
    n = len(rov.thrusters)
    plugins = model.findall("plugin")
    assert [p.get("filename") for p in plugins].count("ignition-gazebo-thruster-system") == n
    assert len(model.findall("joint")) == n and len(model.findall("link")) == n + 1
    view = ExportView.of(rov, "CO", "FLU")
    m_t, _, rest, _ = lumped_added_mass_split(view.matrix("added_mass"),
                                              view.matrix("rigid_body_mass"), view.r_g)
    mass = float(model.find("link/inertial/mass").text)
    assert mass == pytest.approx(rov.mass + m_t, rel=1e-12)
    # net weight unchanged: the boxes displace V + m_t / rho
    volume = sum(float(b.find("geometry/box/size").text.split()[0]) ** 3
                 for b in model.findall("link/collision"))
    assert rov.density * volume - mass == pytest.approx(rov.density * rov.volume - rov.mass,
                                                        abs=1e-9 * mass)
    weight = model.find("link/collision[@name='added_mass_weight']/pose").text.split()[:3]
    assert np.allclose([float(v) for v in weight], view.r_g, atol=1e-12)
    # the legacy tags hold the remainder only
    hydro = next(p for p in plugins if "hydrodynamics" in p.get("filename"))
    assert float(hydro.find("xDotU").text) == pytest.approx(-rest[0, 0], abs=1e-9)
    # each thruster: a revolute joint along its direction; omega = command gives eta C_t n|n|
    for t in rov.thrusters:
        joint = model.find(f"joint[@name='thruster_{t.name}_joint']")
        axis = np.array([float(v) for v in joint.find("axis/xyz").text.split()])
        assert np.allclose(axis, view.vector(t.direction) / np.linalg.norm(t.direction))
        plug = next(p for p in plugins if p.findtext("joint_name") == f"thruster_{t.name}_joint")
        ct, rho, d = (float(plug.findtext(k)) for k in ("thrust_coefficient", "fluid_density",
                                                         "propeller_diameter"))
        assert ct * rho * d ** 4 * 0.6 ** 2 == pytest.approx(t.thrust(0.6), rel=1e-12)
        assert plug.findtext("use_angvel_cmd") == "true"


def test_world_holds_the_model_and_the_buoyancy_system(rov):
    for fortress in (False, True):
        root = _root(_quiet(rov, fortress=fortress, world=True))
        world = root.find("world")
        assert world.find("model").get("name") == rov.name
        buoy = [p for p in world.findall("plugin") if "buoyancy" in p.get("filename")]
        assert float(buoy[0].findtext("uniform_fluid_density")) == rov.density
        assert root.get("version") == ("1.9" if fortress else "1.11")


def _checker(tmp_path):
    need = os.environ.get("STRIPCOEF_REQUIRE_SDFORMAT") == "1"
    cflags = subprocess.run(["pkg-config", "--cflags", "--libs", "sdformat12"],
                            capture_output=True, text=True) if shutil.which("pkg-config") else None
    if cflags is None or cflags.returncode != 0 or not shutil.which("g++"):
        if need:
            pytest.fail("sdformat 12 is required (apt-get install libsdformat-dev)")
        pytest.skip("sdformat 12 not installed (apt-get install libsdformat-dev)")
    exe = tmp_path / "sdformat_check"
    subprocess.run(["g++", "-std=c++17", str(CHECKER), "-o", str(exe), *cflags.stdout.split()],
                   check=True, capture_output=True)
    return exe


@pytest.mark.slow
def test_fortress_files_parse_with_sdformat_12(rov, tmp_path):
    exe = _checker(tmp_path)
    for world in (False, True):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            path = write_export(rov, "gazebo", tmp_path / f"rov_{world}.sdf", fortress=True,
                                world=world)
        out = subprocess.run([str(exe), str(path)], capture_output=True, text=True)
        assert out.returncode == 0, out.stdout + out.stderr
        lines = out.stdout.splitlines()
        n = len(rov.thrusters)
        assert f"links {n + 1} joints {n}" in lines[0]
        assert lines.count("plugin ignition-gazebo-thruster-system") == n
        assert "plugin ignition-gazebo-hydrodynamics-system" in lines
