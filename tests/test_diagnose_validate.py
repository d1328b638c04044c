"""The validation's acceptance rule (diagnose/validate.py, issue 33): a change is kept only if
it lowers the free-simulation error of its own DOF on data it was not fitted on, judged over
the segments of the free simulations."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from stripcoef.diagnose.heldout import free_simulation_errors, segment_squared_errors
from stripcoef.diagnose.validate import MIN_VALIDATION_GAIN, paired_gain
from stripcoef.errors import ModelWarning
from stripcoef.simulate import simulate
from validation.synthetic import add_noise, rov_model


def test_paired_gain_is_the_paired_t_statistic():
    # d = without - with = 1, 2, 3: mean 2, standard deviation 1, standard error 1/sqrt(3)
    assert paired_gain([2.0, 4.0, 6.0], [1.0, 2.0, 3.0]) == pytest.approx(2.0 * math.sqrt(3.0))
    assert paired_gain([1.0, 2.0], [1.0, 2.0]) == 0.0
    assert paired_gain([2.0, 3.0, 4.0], [1.0, 2.0, 3.0]) == math.inf     # the same gain
    assert paired_gain([1.0, 2.0, 3.0], [2.0, 3.0, 4.0]) == -math.inf
    assert paired_gain([2.0], [1.0]) == math.inf                         # one segment: its sign
    assert paired_gain([1.0], [2.0]) == -math.inf
    # a change that helps on average but by less than its spread has a small gain
    assert 0.0 < paired_gain([1.0, 5.0, 1.0, 5.0], [2.0, 1.0, 2.0, 1.0]) < 2.0


def test_a_change_must_lower_its_own_dofs_error():
    assert MIN_VALIDATION_GAIN == 0.0


def test_segment_squared_errors_pool_to_the_free_simulation_errors():
    model = rov_model()
    t = np.arange(0.0, 25.0, 0.2)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        tau = np.zeros((t.size, 6))
        tau[:, 0] = np.where(t % 8 < 4, 20.0, -10.0)
        tau[:, 5] = np.where(t % 6 < 3, 2.0, -2.0)
        log = add_noise(simulate(model, t, forces=tau), np.random.default_rng(3))
        other = model.__class__.from_dict({**model.to_dict(),
                                           "volume": 1.01 * float(model.volume)})
        sse, counts = segment_squared_errors(log, other, [0, 5], horizon=10.0)
        pooled = free_simulation_errors(log, other, [0, 5], horizon=10.0)
    assert sse.shape == (3, 2) and counts.sum() == t.size
    assert np.sqrt(sse.sum(axis=0) / counts.sum()) == pytest.approx(pooled, rel=1e-12)
