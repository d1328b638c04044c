"""Issue 33: an out-of-library shape vetoes a library effect only when it is needed beyond
it (stripcoef.diagnose.shapetest): a shape in the span of the published drag law (linear
plus quadratic, Wang & Clark 2006 eq. 7) is not evidence against a linear drag, dry
friction's sign(v) still is.

Every log is generated from a known truth with seeded noise.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from conftest import synthetic
from stripcoef.diagnose.fit import _calibration, _Config, _evaluate
from stripcoef.diagnose.select import _generic_shapes
from stripcoef.diagnose.shapetest import needed_beyond, vetoes
from stripcoef.effects.laws import get_effect
from stripcoef.effects.windows import window_data
from validation.synthetic import rov_model
from validation.synthetic import surge_log as _surge_log


def _with_linear_drag(log, prior):
    """The surge fit of ``log`` against ``prior`` with a linear drag as the effect: its
    configuration, evaluation and the generic shapes."""
    data = window_data(log, prior, window=4.0)
    cfg = _Config(data, 0, _calibration(data, 0), [(get_effect("linear_drag"), None)])
    return cfg, _evaluate(cfg), _generic_shapes(data, 0)



def test_a_shape_between_linear_and_quadratic_drag_does_not_veto_a_linear_drag():
    """Truth: the prior with a surge linear drag 50x its own (2 N s/m for 0.04, the size
    of Wang & Clark 2006's identified X_u beside a Reynolds-number share) and 0.8 x its
    quadratic drag. With the linear drag fitted, sqrt(|v|) v (between v and v|v|) has
    nothing left to explain: not needed, no veto; the test is the selection's step test."""
    prior = rov_model()
    d = np.array(prior.linear_damping, float)
    d[0, 0] = 0.04
    prior = replace(prior, linear_damping=d)
    dl, dq = d.copy(), np.array(prior.quadratic_damping, float)
    dl[0, 0], dq[0, 0] = 2.0, 0.8 * dq[0, 0]
    log = _surge_log(replace(prior, linear_damping=dl, quadratic_damping=dq), 41)
    cfg, ev, shapes = _with_linear_drag(log, prior)
    shape = {"shape": "sqrt(|v|) v"}
    test = needed_beyond(cfg, ev, shapes, shape)
    assert test is not None and test["needed"] is False
    assert test["p_value"] > test["level"] == 0.05
    assert vetoes(cfg, ev, shapes, shape) is False
    assert shape["needed_beyond_effect"]["needed"] is False
    # a shape that is not among the log's shapes cannot be tested: the veto stays
    assert vetoes(cfg, ev, shapes, {"shape": "no such shape"}) is True


def test_dry_friction_is_needed_beyond_a_linear_drag():
    """Coulomb friction (outside the library, validation.synthetic's coulomb_friction log
    of test_diagnose_select.py): with a linear drag fitted, sign(v) is still needed, so
    its veto stands."""
    log, prior, _ = synthetic("coulomb_friction", 2)
    cfg, ev, shapes = _with_linear_drag(log, prior)
    shape = {"shape": "sign(v)"}
    test = needed_beyond(cfg, ev, shapes, shape, n_dofs=6)
    assert test["needed"] is True and test["level"] == 0.05 / 6
    assert test["held_out_error_joint"] < ev["held_out_error"]
    assert vetoes(cfg, ev, shapes, shape) is True
