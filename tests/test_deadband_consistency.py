"""Issue 33 (fresh33g): benchmarks.deadband_consistency classifies a whole-log row's dead bands
per DOF, and its oracle makes the validation treat the dead band as one change of every DOF
that holds it (as the current), inside the block only."""

from __future__ import annotations

from benchmarks.deadband_consistency import classify, one_change


def _row(category="deadband", **steps):
    return {"category": category, "dof": "surge", "step_detail": {
        d: [{"effect": "deadband", "parameters": {"deadband": 40.0}, "kept": k}]
        for d, k in steps.items()}}


def test_classify_names_each_arrangement():
    assert classify(_row(surge=True, yaw=False)) == "mixed"
    assert classify(_row(surge=True, yaw=True)) == "all kept"
    assert classify(_row(surge=False, heave=False)) == "all removed"
    assert classify(_row(yaw=True)) == "own DOF missing"
    assert classify(_row()) == "none"
    # a log of another category: its own DOF is not the dead band's
    assert classify(_row(category="buoyancy_offset", roll=True)) == "all kept"


CHANGES = [("calibration", "surge"), ("effect", "surge", "deadband"),
           ("calibration", "yaw"), ("effect", "yaw", "deadband")]


def test_one_change_removes_it_in_every_dof_and_only_inside_the_block():
    from stripcoef.diagnose.validate import partners
    yaw_out = {("effect", "yaw", "deadband")}
    assert ("effect", "surge", "deadband") not in partners(yaw_out, CHANGES)
    with one_change():
        assert ("effect", "surge", "deadband") in partners(yaw_out, CHANGES)
        # not removed with its DOF's calibration: one change of both DOFs
        got = partners({("calibration", "surge")}, CHANGES)
        assert ("effect", "surge", "deadband") not in got
    # the default again: an effect goes with the calibration it was fitted with
    assert ("effect", "surge", "deadband") in partners({("calibration", "surge")}, CHANGES)
    # one DOF's dead band is that DOF's: it goes with its calibration inside the block too;
    # another effect is not touched
    with one_change():
        assert ("effect", "surge", "deadband") in partners(
            {("calibration", "surge")}, CHANGES[:2])
    with one_change("thrust_effectiveness"):
        assert ("effect", "surge", "deadband") not in partners(yaw_out, CHANGES)
