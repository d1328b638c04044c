"""Gazebo releases: the default file (SDF 1.11, <fluid_added_mass>, gz-sim plugin), the
Fortress file (SDF 1.9 of sdformat 12, which has no <fluid_added_mass>; ignition plugin;
legacy added-mass tags), and the buoyancy double-counting trap of gz-sim's Buoyancy system."""

import warnings
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from stripcoef.cli import main
from stripcoef.conventions import axes_operator
from stripcoef.export._common import SimulatorTrapWarning
from stripcoef.export import export_model
from stripcoef.export.gazebo import added_mass_tag


@pytest.fixture(scope="module")
def mares():
    from conftest import shipped_model     # shared with test_export_gazebo_spec.py
    return shipped_model("mares.yaml")


def _export(model, **kw):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        text = export_model(model, "gazebo", **kw)
    return ET.fromstring(text.split("?>", 1)[1]), [str(w.message) for w in caught
                                                   if w.category is SimulatorTrapWarning]


def test_default_file_is_for_sdformat_13_and_later(mares):
    root, traps = _export(mares)
    assert root.get("version") == "1.11"
    assert root.find("./model/link/inertial/fluid_added_mass") is not None
    plugin = root.find("./model/plugin")
    assert plugin.get("filename") == "gz-sim-hydrodynamics-system"
    assert not [c for c in plugin if "Dot" in c.tag]
    assert root.find("./model/link/collision[@name='buoyancy_volume']") is not None
    assert len(traps) == 1 and "sums the volume of every collision" in traps[0]


def test_fortress_file(mares):
    # the whole M_A in the explicit tags (the lumped default: test_export_gazebo_fortress.py)
    root, traps = _export(mares, fortress=True, lumped_added_mass=False)
    assert root.get("version") == "1.9"
    assert root.find("./model/link/inertial/fluid_added_mass") is None   # sdformat 12 drops it
    plugin = root.find("./model/plugin")
    assert plugin.get("filename") == "ignition-gazebo-hydrodynamics-system"
    assert plugin.get("name") == "ignition::gazebo::systems::Hydrodynamics"
    # the legacy added mass: <fi Dot Vj> = -M_A[i, j] in FLU, as in the default plugin grammar
    t = axes_operator("FLU")
    ma = t @ np.asarray(mares.added_mass) @ t
    tags = {c.tag: float(c.text) for c in plugin if c.tag != "link_name"}
    for i in range(6):
        assert tags[added_mass_tag(i, i)] == pytest.approx(-ma[i, i], rel=1e-12)
    assert any("Coriolis uses only the diagonal" in m for m in traps)


def test_without_the_buoyancy_box_no_double_counting_trap(mares):
    root, traps = _export(mares, buoyancy_volume=False)
    assert root.find("./model/link/collision") is None
    assert traps == []


def test_cli_options(tmp_path, capsys, geometry_dir):
    out = tmp_path / "f.sdf"
    assert main(["export", str(geometry_dir / "mares.yaml"), "--to", "gazebo", "--fortress",
                 "--no-buoyancy-volume", "-o", str(out)]) == 0
    text = out.read_text()
    assert '<sdf version="1.9">' in text and "buoyancy_volume" not in text.split("-->")[1]
    err = capsys.readouterr().err
    assert "sums the volume" not in err
    assert main(["export", str(geometry_dir / "mares.yaml"), "--to", "uuv", "--fortress"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--fortress" in err and "gazebo" in err
