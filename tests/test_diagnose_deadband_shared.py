"""Issue 33 (mag33g): a dead band named in several DOFs is the thrusters' one property
(Deadband.apply writes it on every acting thruster): the validation keeps or removes it in
all its DOFs at once, as the thrusters' shared timing; named in one DOF it goes with that
DOF's calibration."""

from __future__ import annotations

from stripcoef.diagnose.validate import THRUSTER_PROPERTIES, partners


def test_a_dead_band_of_several_dofs_is_one_change():
    changes = [("calibration", "surge"), ("effect", "surge", "deadband"),
               ("calibration", "sway"), ("effect", "sway", "deadband"),
               ("calibration", "yaw"), ("effect", "yaw", "deadband"),
               ("effect", "yaw", "linear_drag")]
    assert "deadband" in THRUSTER_PROPERTIES
    # removed in one DOF: removed in all
    assert partners({("effect", "surge", "deadband")}, changes) == {
        ("effect", "surge", "deadband"), ("effect", "sway", "deadband"),
        ("effect", "yaw", "deadband")}
    # a DOF's calibration takes its own effects, not the thrusters' dead band
    assert partners({("calibration", "yaw")}, changes) == {
        ("calibration", "yaw"), ("effect", "yaw", "linear_drag")}


def test_a_dead_band_of_one_dof_goes_with_its_calibration():
    changes = [("calibration", "surge"), ("effect", "surge", "deadband"),
               ("calibration", "yaw"), ("effect", "yaw", "linear_drag")]
    assert partners({("calibration", "surge")}, changes) == {
        ("calibration", "surge"), ("effect", "surge", "deadband")}
    assert partners({("effect", "surge", "deadband")}, changes) == {
        ("effect", "surge", "deadband")}
