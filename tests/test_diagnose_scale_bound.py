"""Issue 33: a thrust scale pinned at a bound of its search range is refused by the step
test (stripcoef.diagnose.select._judge), as a linear parameter pinned at its physical bound
already was.

At a bound the fitted value is not a stationary point of the likelihood: its curvature z,
and the chi-square of its likelihood ratio, do not hold there (Self & Liang 1987, JASA 82,
605-610, Theorem 2: on the boundary the statistic is a mixture, not the interior's normal
z). The independent benchmark's whole-log runs named BlueROV2 roll and pitch scales of
exactly 2.0 (the upper bound, ThrustEffectiveness.BOUNDS) with z 3.5-4.2 on logs whose
truth changes the DOF's thrust by 3 % or less (benchmarks/data/roll33_scale_bound.md).

The log is generated from a known truth with seeded noise.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from stripcoef.diagnose.fit import _Config, _evaluate
from stripcoef.diagnose.select import _dof_calibration, _judge
from stripcoef.diagnose.settings import DiagnoseSettings
from stripcoef.effects.laws import get_effect
from stripcoef.effects.windows import window_data
from validation.synthetic import rov_model
from validation.synthetic import surge_log as _surge_log


def _judged(factor: float, seed: int = 3):
    prior = rov_model()
    truth = replace(prior, thrusters=[replace(t, ct_forward=factor * t.ct_forward,
                                              ct_backward=factor * t.ct_backward)
                                      for t in prior.thrusters])
    data = window_data(_surge_log(truth, seed, duration=40.0), prior, window=2.0)
    cal, _ = _dof_calibration(data, 0, DiagnoseSettings(), [0], [])
    base = _Config(data, 0, cal, [])
    eff = get_effect("thrust_effectiveness")
    cfg = base.with_terms([(eff, None)])
    return _judge(eff, cfg, _evaluate(cfg), _evaluate(base), data, 0, list(cal.names),
                  cal.sd)


def test_a_scale_at_its_upper_bound_is_refused():
    """Thrusters delivering 3x their map: the scale's search stops at its bound 2.0, where
    no z is valid; the step is refused with that reason whatever its z."""
    rec = _judged(3.0)
    assert rec["parameters"]["scale"] == pytest.approx(2.0, abs=1e-4)
    assert not rec["significant"]
    assert any("pinned at its bound" in r for r in rec["rejected_because"])


def test_an_interior_scale_is_not_called_pinned():
    """The same log at 0.7 of the map: an interior scale, no pinned reason."""
    rec = _judged(0.7)
    assert 0.05 + 1e-3 < rec["parameters"]["scale"] < 2.0 - 1e-3
    assert not any("pinned" in r for r in rec["rejected_because"])
    assert np.isfinite(rec["z"])
