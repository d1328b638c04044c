"""A seeded noisy log of the synthetic ROV (validation.synthetic.rov_model) under square-wave
surge and yaw forces, and the same ROV 1 % heavier: the pair of models and the log that the
held-out segment tests compare (tests/test_heldout_segments.py,
tests/test_diagnose_combination.py)."""

from __future__ import annotations

import warnings

import numpy as np

from stripcoef.errors import ModelWarning
from stripcoef.simulate import simulate
from validation.synthetic import add_noise, rov_model


def square_wave_log(duration: float = 25.0, dt: float = 0.2, seed: int = 3):
    """(model, log, heavier): ``duration`` [s] of the ROV sampled every ``dt`` [s] under a
    surge force of +20 / -10 N (period 8 s) and a yaw moment of +-2 N m (period 6 s), with
    the synthetic sensors' noise drawn from ``seed``; ``heavier`` the ROV with 1 % more
    volume."""
    model = rov_model()
    t = np.arange(0.0, duration, dt)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        tau = np.zeros((t.size, 6))
        tau[:, 0] = np.where(t % 8 < 4, 20.0, -10.0)
        tau[:, 5] = np.where(t % 6 < 3, 2.0, -2.0)
        log = add_noise(simulate(model, t, forces=tau), np.random.default_rng(seed))
    heavier = model.__class__.from_dict({**model.to_dict(),
                                         "volume": 1.01 * float(model.volume)})
    return model, log, heavier
