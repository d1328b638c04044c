"""Issue 33 (buoy33g): heave's buoyancy offset as one change of the buoyancy B, acting in every
DOF through the restoring force (Fossen 2011, eq. 4.6) and carried into the other DOFs' fits
of a whole-log diagnosis (``diagnose.buoyancy``, option ``buoyancy_carry``, off by default;
measured in benchmarks/data/buoy33g_trace.md)."""

from __future__ import annotations

import numpy as np
import pytest

from stripcoef.diagnose import buoyancy
from stripcoef.diagnose.settings import DiagnoseSettings
from stripcoef.effects.laws import get_effect
from stripcoef.effects.windows import window_data
from validation.synthetic import gains_off_log


def test_the_option_is_off_by_default():
    assert DiagnoseSettings().buoyancy_carry is False


def test_a_heave_offset_is_written_as_the_change_of_b():
    """b [N] positive down in heave is Delta B = -b: the volume moves by -b / (rho g) and the
    restoring force changes in every DOF by -Delta B [k, r_b x k] (Fossen 2011, eq. 4.6)."""
    _, prior, _ = gains_off_log(None, 1, duration=40.0)
    b = 0.75
    m = buoyancy.BUOYANCY_CHANGE.apply(prior, 2, {"b": b})
    assert m.volume == pytest.approx(prior.volume - b / (prior.density * prior.gravity),
                                     rel=1e-12)
    assert m.buoyancy - prior.buoyancy == pytest.approx(-b, rel=1e-9)
    assert not m.effects                                  # native: no force entry
    eta = np.array([0.0, 0.0, 0.0, 0.1, -0.2, 0.3])
    dg = m.restoring(eta) - prior.restoring(eta)
    phi, theta = eta[3], eta[4]
    k = np.array([-np.sin(theta), np.cos(theta) * np.sin(phi), np.cos(theta) * np.cos(phi)])
    # g = -[(W - B) k; (W r_g - B r_b) x k]: a change of B alone moves it by +dB [k; r_b x k]
    np.testing.assert_allclose(dg[:3], -b * k, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(dg[3:], -b * np.cross(prior.r_b, k), rtol=1e-9, atol=1e-12)
    # level, the heave force of the change is the offset's b (the fitted constant)
    level = m.restoring(np.zeros(6)) - prior.restoring(np.zeros(6))
    assert -level[2] == pytest.approx(b, rel=1e-9)
    # in another DOF the offset stays a constant force entry
    assert buoyancy.BUOYANCY_CHANGE.apply(prior, 5, {"b": 0.1}).effects
    assert get_effect("buoyancy_offset").native is False


def test_the_carried_data_are_the_prior_with_the_change_but_heave():
    log, prior, _ = gains_off_log(None, 1, duration=40.0)
    data = window_data(log, prior)
    moved = buoyancy.carried(data, 1.3)
    again = window_data(log, buoyancy.with_buoyancy_change(prior, 1.3))
    others = [0, 1, 3, 4, 5]
    np.testing.assert_allclose(moved.e0[:, others], again.e0[:, others], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(moved.e0[:, 2], data.e0[:, 2], rtol=0, atol=0)
    assert moved.model.buoyancy - prior.buoyancy == pytest.approx(1.3, rel=1e-9)
    assert buoyancy.order([0, 1, 2, 5]) == [2, 0, 1, 5]


@pytest.mark.slow
def test_a_videoray_clean_log_with_a_buoyancy_change_names_no_surge_tether_when_carried():
    """Independent simulator, VideoRay-like, clean, seed 1796048670 (the fresh seed
    1795948659's repeat 1): the truth's buoyancy is 0.90 N above the prior's (no effect) and the log
    pitches. Whole-log on the default the surge balance has no column for the change,
    -(Delta B) sin(theta), and a tether law takes it (c_t 0.088, kept;
    benchmarks/data/fresh33f_compare.md sec. 3.7). With the change found in heave carried as
    one change of B, surge names neither a tether nor a drag, and the change written into B
    is the heave step's, within 20 % of the truth's (0.76 N: the rest is the thrust map's)."""
    from test_diagnose_scalechoice import _independent

    from stripcoef.diagnose.pipeline import diagnose
    from validation.independent import GRAVITY

    prior, log, truth = _independent("videoray_pro3", None, 1796048670)
    change = float(truth.buoyancy) - float(prior.density) * float(prior.volume) * GRAVITY
    assert change == pytest.approx(0.90, abs=0.01)   # B larger: the truth is lighter in water
    res = diagnose(log, prior, dof="all", time_limit=float("inf"), buoyancy_carry=True)
    surge = [s.effect for s in res.per_dof["surge"].steps if s.kept]
    assert not {"tether_drag", "linear_drag"} & set(surge)
    heave = [s for s in res.per_dof["heave"].steps if s.effect == "buoyancy_offset"]
    assert heave and heave[0].kept
    written = res.model.buoyancy - prior.buoyancy
    assert written == pytest.approx(-heave[0].parameters["b"], rel=1e-9)
    assert written == pytest.approx(change, rel=0.2)
