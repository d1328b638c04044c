"""The validation's horizon from the log's own correlation time (issue 33, closed33d;
:mod:`stripcoef.diagnose.horizon`): the integral time scale of a series with a known
autocorrelation, the bounds of the horizons, the per-DOF segments of the losses and the
option's input check."""

import numpy as np
import pytest

from stripcoef.diagnose import heldout, horizon
from stripcoef.diagnose.heldout import HORIZON
from stripcoef.diagnose.pipeline import _horizon_setting
from stripcoef.diagnose.settings import DiagnoseSettings
from stripcoef.errors import InputError
from stripcoef.logfile import Log


def _ar1(a: float, n: int, seed: int) -> np.ndarray:
    """A stationary AR(1) series x_t = a x_{t-1} + e_t: rho(k) = a^k."""
    rng = np.random.default_rng(seed)
    e = rng.standard_normal(n)
    x = np.empty(n)
    x[0] = e[0] / np.sqrt(1.0 - a * a)
    for k in range(1, n):
        x[k] = a * x[k - 1] + e[k]
    return x


@pytest.mark.parametrize("a", [0.5, 0.8, 0.9])
def test_integral_time_scale_of_an_ar1_series(a):
    # rho(k) = a^k: dt (1/2 + sum_{k>=1} a^k) = dt (1 + a) / (2 (1 - a)); the estimate is
    # cut at the first zero crossing and biased by the finite record (1/N per lag), so a
    # 5 % tolerance on 40,000 samples
    dt = 0.1
    t = np.arange(40_000) * dt
    got = horizon.integral_time_scale(t, _ar1(a, t.size, seed=7))
    assert got == pytest.approx(dt * (1 + a) / (2 * (1 - a)), rel=0.05)


def test_a_constant_series_has_no_memory_to_measure():
    t = np.arange(100) * 0.1
    assert horizon.integral_time_scale(t, np.full(100, 0.3)) == 0.0


def _log(columns: dict, n: int = 600, dt: float = 0.1) -> Log:
    t = np.arange(n) * dt
    return Log({"t": t, **{k: v(t) if callable(v) else v for k, v in columns.items()}})


def test_horizons_lie_between_two_samples_and_the_free_simulation():
    rng = np.random.default_rng(3)
    log = _log({"u": rng.standard_normal(600),           # white: no memory
                "v": lambda t: 0.01 * t,                 # a ramp: longer than the record
                "w": _ar1(0.9, 600, seed=5)})
    h = horizon.correlation_horizons(log, [0, 1, 2, 5])
    assert h[0] == pytest.approx(0.2)                    # two sample intervals
    assert h[1] == pytest.approx(HORIZON)                # capped at the free simulation's
    assert 0.2 < h[2] < HORIZON
    assert h[3] == HORIZON                               # no yaw rate column


def test_losses_use_each_dofs_own_segments(monkeypatch):
    seen = []

    def sse(log, model, dofs, *, horizon, logged=(), **_):
        seen.append((tuple(dofs), horizon))
        n = len(heldout.segments(np.asarray(log["t"]), horizon))
        return np.ones((n, len(dofs))) * horizon, np.full(n, 2.0)

    monkeypatch.setattr(heldout, "segment_squared_errors", sse)
    log = _log({})
    got = horizon.dof_losses(log, "model", [0, 3, 5], horizon=[1.0, 0.5, 1.0])
    # the DOFs sharing a horizon are simulated together, once per horizon
    assert sorted(seen) == [((0, 5), 1.0), ((3,), 0.5)]
    assert [len(x[0]) for x in got] == [len(heldout.segments(log["t"], h))
                                        for h in (1.0, 0.5, 1.0)]
    assert horizon.rms(got) == pytest.approx([np.sqrt(0.5), np.sqrt(0.25), np.sqrt(0.5)])


def test_the_default_horizon_is_the_velocities_correlation_time():
    """The default (adopt33h) is each DOF's integral time scale; the free simulations'
    10-s horizon (:data:`RESIMULATION_HORIZON`, the default before) is asked for by number."""
    from stripcoef.diagnose.horizon import CORRELATION
    from stripcoef.diagnose.settings import RESIMULATION_HORIZON

    assert DiagnoseSettings().validation_horizon == CORRELATION
    assert DiagnoseSettings(validation_horizon=RESIMULATION_HORIZON).validation_horizons(
        None, [0, 1]) is None
    assert DiagnoseSettings(validation_horizon=2.5).validation_horizons(None, [0]) == [2.5]


@pytest.mark.parametrize("bad", [0.0, -1.0, "corr", True, float("inf")])
def test_a_bad_horizon_is_refused(bad):
    with pytest.raises(InputError, match="validation_horizon"):
        _horizon_setting(bad)
