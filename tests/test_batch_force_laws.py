"""The effects' force laws for many segments at once (``batch_force_law``, used by the free
simulations of stripcoef.diagnose.freesim and by Effect.window_force) give the numbers of
their scalar laws (``force_law``): a lag's state from the log's first sample, a delay's
held input, the thrust asymmetry's sums over the thrusters, a thrust scale and a bias.
"""

from types import SimpleNamespace

import numpy as np
import pytest

from stripcoef.effects.laws import get_effect


def _history(seed=3, n=400, k=5):
    rng = np.random.default_rng(seed)
    t = np.cumsum(np.r_[0.0, rng.uniform(0.04, 0.06, n - 1)])      # uneven sampling [s]
    thrust = rng.normal(0.0, 20.0, (n, k))                            # [N]
    alloc = rng.normal(0.0, 1.0, (6, k))
    tau = thrust @ alloc.T
    model = SimpleNamespace(thrusters=[SimpleNamespace(name=f"t{j}") for j in range(k)])
    return t, thrust, alloc, tau, model


def _scalar(law, t, thrust, alloc, tau, model, time, row, last):
    names = [th.name for th in model.thrusters]
    hook = {"tau": tau[row], "thrust": dict(zip(names, thrust[row])), "model": model,
            "allocation": alloc, "input_history": (t[:last + 1], tau[:last + 1])}
    return law(time, np.zeros(6), np.zeros(6), hook)


@pytest.mark.parametrize("name, params, dof", [
    ("thruster_lag", {"time_constant": 0.37}, 2),
    ("thruster_lag", {"time_constant": 0.37}, None),
    ("actuation_delay", {"delay": 0.13}, 0),
    ("thrust_asymmetry", {"eta_forward": 0.9, "eta_backward": 1.3}, 5),
    ("thrust_effectiveness", {"scale": 0.8}, 1),
    ("buoyancy_offset", {"b": -2.5}, 2),
])
def test_batch_law_equals_the_scalar_law(name, params, dof):
    t, thrust, alloc, tau, model = _history()
    eff = get_effect(name)
    g = eff.batch_force_law(params, dof, {"t": t, "tau": tau, "allocation": alloc,
                                          "thrust": thrust})
    rng = np.random.default_rng(11)
    rows = np.sort(rng.choice(np.arange(5, t.size - 2), 40, replace=False))
    last = np.minimum(rows + rng.integers(1, 30, rows.size), t.size - 1)
    for frac in (0.0, 0.3, 1.0):        # within each segment's interval, at both ends
        times = t[rows] + frac * (t[rows + 1] - t[rows])
        got = g(times, rows, last)
        # every segment its own scalar law (a lag's state starts at the log's first sample)
        want = np.array([_scalar(eff.force_law(params, dof), t, thrust, alloc, tau, model,
                                 float(tm), int(r), int(la))
                         for tm, r, la in zip(times, rows, last)])
        np.testing.assert_allclose(got, want, rtol=1e-15, atol=1e-12)
