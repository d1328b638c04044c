"""ROMEO heave from the 6-DOF simulation: depth + thruster commands -> steady points -> eta.

The five trials of the chapter (one lead weight apart), simulated by stripcoef.simulate with
the eta-model truth; the log holds only time, noisy depth and commands, as a real trial.
"""

import numpy as np
import pytest

pytest.importorskip("stripcoef.simulate")

from validation.experiments import ROMEO_TRUTH  # noqa: E402
from validation.identification import romeo_simulated_trials  # noqa: E402
from stripcoef.identify.steady import fit_steady  # noqa: E402


@pytest.fixture(scope="module")
def trials():
    """(steady points, true W) of the five trials; the same (cached) computation the
    identification section of docs/validation.md prints, checked below."""
    return romeo_simulated_trials()


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


@pytest.mark.slow
def test_validation_doc_identification_section_is_current():
    """docs/validation.md's identification section is what the code writes now
    (tests/test_validation_doc.py), checked here beside the test that simulates the same five
    trials (``validation.identification.romeo_simulated_trials``, cached in the process).
    The text only: the figures the section links are drawn by scripts.make_validation, not
    here (nothing written into docs/figures by a test; about 5 s of CPU)."""
    from test_validation_doc import assert_section_is_current

    assert_section_is_current("identification", draw_figures=False)
