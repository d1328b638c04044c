"""The effects library: registry, vectorised terms, and force laws that match regressors."""

from dataclasses import replace

import numpy as np
import pytest

from stripcoef.errors import InputError
from stripcoef.effects.laws import EFFECTS, coriolis_times_velocity, damping_times_velocity, effect_forces, get_effect
from stripcoef.effects.windows import window_data
from validation.synthetic import manoeuvre, rov_model
from stripcoef.logfile import Log
from stripcoef.simulate import simulate

NAMES = ("tether_drag", "thrust_asymmetry", "momentum_drag", "buoyancy_offset", "current",
         "linear_drag", "deadband", "added_mass_error")


def test_registry_has_the_issue_names_with_physics_and_units():
    assert set(NAMES) <= set(EFFECTS)
    for name in NAMES:
        eff = get_effect(name)
        doc = type(eff).__doc__
        assert ".. math::" in doc and ("Source" in doc or "source" in doc), name
        assert eff.parameters and all(isinstance(u, str) for u in eff.parameters.values())
        assert eff.source


def test_unknown_effect_lists_valid_names():
    with pytest.raises(InputError) as exc:
        get_effect("tether")
    assert "tether_drag" in str(exc.value) and "deadband" in str(exc.value)


def test_vectorised_terms_match_the_model():
    model = rov_model()
    rng = np.random.default_rng(1)
    nu = rng.normal(size=(7, 6))
    for m in (model.rigid_body_mass, model.added_mass):
        ref = np.array([__import__("stripcoef.model", fromlist=["x"]).coriolis_from_mass(m, v) @ v
                        for v in nu])
        np.testing.assert_allclose(coriolis_times_velocity(m, nu), ref, atol=1e-13)
    ref = np.array([model.damping(v) @ v for v in nu])
    np.testing.assert_allclose(damping_times_velocity(model, nu), ref, atol=1e-13)


CASES = {
    "tether_drag": {"c_t": 0.2},
    "thrust_asymmetry": {"eta_forward": 1.0, "eta_backward": 0.6},
    "momentum_drag": {"alpha": 0.05},
    "buoyancy_offset": {"b": -0.5},
    "current": {"current_north": 0.15, "current_east": -0.1},
}
DOFS = {"tether_drag": 0, "thrust_asymmetry": 0, "momentum_drag": 2, "buoyancy_offset": 2,
        "current": 0}


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(CASES))
def test_force_law_and_regressor_agree(name):
    """Simulate a model carrying the effect (noise-free); the prior's window residual must
    equal the effect's regressor times its parameters (the same physics in both places)."""
    prior = rov_model()
    dof = DOFS[name]
    truth = rov_model()
    truth = truth.with_effects({"name": name, "dof": ["surge", "sway", "heave"][dof],
                                "parameters": CASES[name]})
    rng = np.random.default_rng(0)
    t, cmds = manoeuvre(rng, duration=40.0)
    length = 2.0 + 0.3 * t
    log = simulate(truth, t, commands=cmds, channels={"tether_length": length},
                   rtol=1e-8, atol=1e-10)
    log = Log({k: v for k, v in log.columns.items() if k not in "XYZKMN"})
    data = window_data(log, prior, window=2.0)
    eff = get_effect(name)
    params = CASES[name]
    if name == "current":
        off, cols = eff.own_design(data, dof, (params["current_north"], params["current_east"]))
        model_force = off
    else:
        off, cols = eff.own_design(data, dof)
        theta = {"tether_drag": [0.2], "thrust_asymmetry": [-0.4], "momentum_drag": [0.05],
                 "buoyancy_offset": [-0.5]}[name]
        model_force = cols @ np.asarray(theta)
    e0 = data.e0[:, dof]
    scale = np.sqrt(np.mean(model_force ** 2))
    assert scale > 0.05
    # trapezoidal window integrals of a sampled nonlinear state: a few per cent
    assert np.sqrt(np.mean((e0 - model_force) ** 2)) < 0.05 * scale


def test_native_effects_change_the_model_and_are_not_forces():
    model = rov_model()
    for name, params in (("linear_drag", {"d_L": 2.0}), ("deadband", {"deadband": 30.0}),
                         ("added_mass_error", {"delta_m": 1.0})):
        eff = get_effect(name)
        m = eff.apply(model, 0, params)
        assert m.effects == ()
    m = get_effect("linear_drag").apply(model, 0, {"d_L": 2.0})
    assert m.linear_damping[0, 0] == pytest.approx(model.linear_damping[0, 0] + 2.0)
    m = get_effect("deadband").apply(model, 0, {"deadband": 30.0})
    assert [th.deadband for th in m.thrusters] == [30.0, 30.0, 0.0, 0.0]


def test_effect_forces_reject_bad_entries():
    model = rov_model()
    model = replace(model, effects=[{"name": "nope", "dof": "surge", "parameters": {}}])
    with pytest.raises(InputError, match="tether_drag"):
        effect_forces(model)
    model = replace(model, effects=[{"name": "tether_drag", "dof": "surge", "parameters": {}}])
    with pytest.raises(InputError, match="c_t"):
        effect_forces(model)


def test_savgol_centre_weights_are_the_quadratic_fit():
    """Savitzky-Golay (1964) table I: 5 points (-3, 12, 17, 12, -3)/35; exact on cubics at
    the centre; the variance factor is the centre weight."""
    from stripcoef.effects.windows import savgol_centre_weights
    np.testing.assert_allclose(savgol_centre_weights(2), np.array([-3, 12, 17, 12, -3]) / 35,
                               rtol=1e-13)
    for h in range(2, 8):
        w = savgol_centre_weights(h)
        k = np.arange(-h, h + 1)
        for p in range(4):  # 1, k, k^2, k^3 -> their value at k = 0
            assert np.dot(w, k ** p) == pytest.approx(1.0 if p == 0 else 0.0, abs=1e-12)
        assert np.sum(w ** 2) == pytest.approx(w[h], rel=1e-12)


@pytest.mark.slow
def test_end_values_do_not_bias_the_true_model_and_cut_the_noise():
    """Noise-free log of the prior itself: its window residual is the discretisation error
    of the window operators only; with the smoothed end values it stays far below the noise
    floor they remove (the input jumps are not smoothed across)."""
    from validation.synthetic import NOISE
    model = rov_model()
    rng = np.random.default_rng(3)
    t, cmds = manoeuvre(rng, duration=120.0)
    log = simulate(model, t, commands=cmds, rtol=1e-9, atol=1e-11)
    log = Log({k: v for k, v in log.columns.items() if k not in "XYZKMN"})
    data = window_data(log, model, window=4.0)
    h0, h1 = data._endpoint_halfwidths()
    assert h0.max() == 2 and np.mean(h0 == 2) > 0.5      # 0.2 s at 10 Hz, mostly smoothed
    for dof in (0, 1, 2):
        floor_raw = model.mass_matrix[dof, dof] * np.sqrt(2) * NOISE["uvw"[dof]] / 4.0
        assert np.sqrt(np.mean(data.e0[:, dof] ** 2)) < 0.1 * floor_raw
    noisy = Log({**log.columns, "u": log["u"] + rng.normal(scale=0.01, size=t.size)})
    d2 = window_data(noisy, model, window=4.0)
    assert d2.rate_noise_variance(0) < 0.75 * 2 * 0.01 ** 2 / 16.0   # about 0.6 of raw
