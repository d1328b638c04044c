"""One value per added mass in a whole-log diagnosis (``stripcoef.diagnose.calibrate.
contradicted``, ``consistent_fits``): a diagnosed DOF's added mass is its own calibration's;
a DOF whose fit contradicts it is selected again without it and written refitted with it
(issue 33; an option, ``diagnose(..., one_added_mass=True)``)."""

from __future__ import annotations

import tempfile
import warnings

import pytest

from benchmarks.real_logs import HOLDOUT, read_back, real_style_log, write_ros_chunks
from stripcoef.diagnose import diagnose


@pytest.mark.slow
def test_the_videoray_issue16_log_keeps_its_yaw_thrust_scale():
    """The VideoRay-like issue-16 real-style log of seed 7 (only 0.49 of the commanded thrust
    acts in every DOF): with the sway added mass free in yaw's calibration its Munk moment
    took the yaw thrust scale (+5.2 kg against sway's own +0.5 kg, which was written), no
    yaw scale was named, and the written yaw model's window error was 4x the prior's
    (0.155 against 0.039 N m). Now yaw names a thrust scale near the truth's, every DOF's
    written error is below its baseline, and the held-out part is predicted better than
    by the prior, hold-last-velocity and zero velocity in every DOF."""
    name, log, prior, widths, truth = real_style_log(3, 300.0, 7)
    with tempfile.TemporaryDirectory() as tmp:
        read, _ = read_back(tmp, write_ros_chunks(log, tmp, seed=10))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(read, prior, dof="all", holdout=HOLDOUT, time_limit=float("inf"),
                       prior_widths=widths, one_added_mass=True)
    shortfall = float(truth.split("shortfall ")[1].split(",")[0])
    yaw = [s for s in res.per_dof["yaw"].steps if s.effect == "thrust_effectiveness"]
    assert yaw and yaw[0].kept
    assert yaw[0].parameters["scale"] == pytest.approx(shortfall, rel=0.2)
    for d, r in res.per_dof.items():
        assert r.final_error < r.baseline_error, d
    errors = res.holdout["errors"]
    for d, e in errors.items():
        assert e["calibrated"] < min(e["prior"], e["hold_last_velocity"], e["zero_velocity"]), d



def test_an_unknown_rule_for_one_added_mass_is_a_one_line_input_error():
    """``one_added_mass`` is off, on (the DOF's fit's own sd) or ``"difference"`` (the sd of
    the two estimates' difference; settings.ONE_ADDED_MASS): anything else is refused before
    any fit, naming the key, the value and the choices."""
    import numpy as np

    from stripcoef.errors import InputError
    from stripcoef.logfile import Log
    from stripcoef.modelfile import load_model
    from stripcoef import samples

    t = np.arange(0.0, 30.0, 0.1)
    log = Log({"t": t, "u": np.full(t.size, 0.3), "X": np.full(t.size, 1.0)})
    with pytest.raises(InputError) as exc:
        diagnose(log, load_model(samples.path("rov_prior.json")), dof="all",
                 one_added_mass="joint")
    text = str(exc.value)
    assert "one_added_mass" in text and "joint" in text and "difference" in text
    assert "\n" not in text
