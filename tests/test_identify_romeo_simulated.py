"""ROMEO heave from the 6-DOF simulation: depth + thruster commands -> steady points -> eta.

The five trials of the chapter (one lead weight apart), simulated by stripcoef.simulate with
the eta-model truth; the log holds only time, noisy depth and commands, as a real trial.
"""

import numpy as np
import pytest

pytest.importorskip("stripcoef.simulate")

from validation.experiments import ROMEO_TRUTH, romeo_heave_log  # noqa: E402
from stripcoef.identify.inputs import applied_force  # noqa: E402
from stripcoef.identify.steady import fit_steady, steady_points  # noqa: E402


@pytest.fixture(scope="module")
def trials():
    out = []
    for i in range(1, 6):
        log, model, w = romeo_heave_log(i, seed=i)
        force, _ = applied_force(log, "heave", model)       # bench map: eta = 1
        out.append((steady_points(log, "heave", force=force, settle=45.0), w))
    return out


@pytest.mark.slow
def test_simulated_trials_reproduce_the_chapter(trials):
    """Standard-model W > 0 in all five; its residual sigma > 3x the eta model's; the eta
    model within 2 sigma of the truth for >= 17 of 20 estimates (nu = 8: t-coverage ~0.92)."""
    hits = 0
    for pts, w_true in trials:
        assert len(pts) == 12
        std, eta = fit_steady(pts, "standard"), fit_steady(pts, "eta")
        assert std.value("W") > 0
        assert np.sqrt(std.sigma2 / eta.sigma2) > 3
        truth = dict(ROMEO_TRUTH, W=w_true)
        hits += sum(abs(eta.value(k) - truth[k]) <= 2 * eta.std[k]
                    for k in ("k_w", "k_ww", "W", "eta"))
    assert hits >= 17
