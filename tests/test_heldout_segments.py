"""Per-segment free-simulation errors (diagnose/heldout.py): the independent units of a
paired comparison of two models on held-out data (issue 33)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from stripcoef.diagnose.heldout import free_simulation_errors, segment_squared_errors
from stripcoef.errors import ModelWarning
from stripcoef.simulate import simulate
from validation.synthetic import add_noise, rov_model


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
