"""Issue 33: whole-log mode does not move an effect of the thrusters into a DOF whose
residual it does not explain: a thruster effect found in one DOF must also hold in every
other diagnosed DOF the same thrusters drive (:class:`stripcoef.diagnose.select.Siblings`).

Every log is generated from a known truth (stripcoef's simulate of the VideoRay-like ROV of
Wang & Clark 2006, surge and yaw by the same two horizontal thrusters) with seeded noise.
"""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

import numpy as np
import pytest

from stripcoef.diagnose.fit import _evaluate
from stripcoef.diagnose.select import THRUSTER_EFFECTS, Siblings
from stripcoef.effects.laws import get_effect
from stripcoef.effects.windows import window_data
from stripcoef.logfile import Log
from stripcoef.simulate import simulate
from validation.synthetic import add_noise, manoeuvre, rov_model

SURGE, HEAVE, YAW = 0, 2, 5
#: the true dead band of the horizontal thrusters [command units] (commands reach 120)
DEADBAND = 25.0


@lru_cache(maxsize=None)
def _data(deadband: float, seed: int = 5):
    """Window data of a 120-s log (surge, yaw and heave steps with small commands) of the
    ROV whose port and starboard thrusters have ``deadband``, against the prior without."""
    prior = rov_model()
    truth = replace(prior, thrusters=[replace(th, deadband=deadband)
                                      if th.name in ("port", "starboard") else th
                                      for th in prior.thrusters])
    rng = np.random.default_rng(seed)
    t, cmds = manoeuvre(rng, duration=120.0, small_commands=True)
    sim = simulate(truth, t, commands=cmds, rtol=1e-7, atol=1e-9)
    cols = {k: v for k, v in sim.columns.items() if k not in ("X", "Y", "Z", "K", "M", "N")}
    cols.update({"n_" + k: v for k, v in cmds.items()})
    log = add_noise(Log(cols, source=f"deadband {deadband} (seed {seed})"), rng)
    return window_data(log, prior)


def _trial(siblings: Siblings, name: str, dof: int, hyper) -> dict:
    """A selection's record of ``name`` fitted in ``dof`` at ``hyper`` (as :func:`_judge`
    leaves it: the effect, its parameters, its configuration and evaluation)."""
    eff = get_effect(name)
    cfg = siblings.configs[dof].with_terms([(eff, None if hyper is None
                                             else np.atleast_1d(hyper))])
    ev = _evaluate(cfg)
    return {"effect": name, "parameters": eff.to_parameters(
        ev["full"]["theta"][cfg.cal_cols.shape[1]:], cfg.terms[-1][1]), "_cfg": cfg, "_ev": ev}


def test_a_dead_band_the_other_dof_of_its_thrusters_refutes_is_contradicted():
    """No dead band in the truth: a yaw dead band of 80 command units (most of the yaw
    commands) raises the held-out error of surge, driven by the same two thrusters, so it
    is contradicted by surge; heave (the vertical thruster) is not asked."""
    data = _data(0.0)
    sib = Siblings(data, [SURGE, HEAVE, YAW])
    why = sib.contradictions(_trial(sib, "deadband", YAW, 80.0), YAW)
    assert len(why) == 1 and why[0].startswith("contradicted by surge")


def test_the_true_dead_band_holds_in_both_dofs_of_its_thrusters():
    """The truth's dead band of 25 command units on the horizontal thrusters, fitted in
    either surge or yaw, is not contradicted by the other (the same thrusters)."""
    data = _data(DEADBAND)
    sib = Siblings(data, [SURGE, HEAVE, YAW])
    for dof in (SURGE, YAW):
        assert sib.contradictions(_trial(sib, "deadband", dof, DEADBAND), dof) == []


def test_effects_of_a_dof_are_not_asked_of_the_others():
    """A DOF's own effects (a bias, a linear drag) are not tested in other DOFs: only the
    effects of the thrusters are (the thrust effectiveness is a scale per axis)."""
    assert set(THRUSTER_EFFECTS) == {"deadband", "thrust_asymmetry", "thruster_lag",
                                     "actuation_delay"}
    data = _data(0.0)
    sib = Siblings(data, [SURGE, YAW])
    trial = _trial(sib, "buoyancy_offset", YAW, None)
    assert sib.contradictions(trial, YAW) == []


if __name__ == "__main__":
    raise SystemExit(pytest.main([__file__, "-q"]))
