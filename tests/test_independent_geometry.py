"""The independent simulator's thrusters sit where the prior's do (issue 33).

Whole-log diagnoses of the independent benchmark named a pitch or heave thrust asymmetry where
the truth has none (22 of 44 runs of seed 5092026). The last stop traced it to a thruster
moment-arm error of the truth (the horizontal pair at z = -0.010 m, the vertical at
x = +0.009 m, where the prior has 0). That was a reading of two coordinate systems: the truth
stores each thruster's position about the vehicle's reference point (``perturbed_truth``), the
vehicle file about its own origin, and the VideoRay's reference point is (-0.009, 0, 0.010) m.
Both configuration matrices are taken about the reference point and are the same: the truth
has no thruster-geometry error. What it has are the thrusters' own gains, each drawn
U(0.75, 1.25) x the file's map, which the benchmark's ``--truth-maps`` oracle removes
(benchmarks/data/diagnose_independent_truthmaps.md).
"""

from __future__ import annotations

import numpy as np
import pytest

from conftest import shipped_model
from validation.independent import Simulator, _thrust, generate, perturbed_truth


@pytest.mark.parametrize("vehicle", ["videoray_pro3", "bluerov2_heavy"])
def test_the_truths_configuration_matrix_is_the_priors(vehicle):
    prior = shipped_model(f"{vehicle}.yaml")
    model = prior.to_dict()
    ref = np.asarray(model["reference_point"], float)
    for seed in (1, 2, 3):
        truth = perturbed_truth(model, np.random.default_rng(seed))
        # the same matrix B (6, N) about the reference point: no moment-arm error
        np.testing.assert_allclose(Simulator(truth).b, prior.allocation(), rtol=0, atol=1e-12)
        for th, t in zip(prior.thrusters, truth.thrusters):
            np.testing.assert_allclose(t["position"], np.asarray(th.position) - ref,
                                       rtol=0, atol=1e-15)


@pytest.mark.parametrize("effect", [None, "thrust_effectiveness", "thrust_asymmetry"])
def test_truth_maps_carry_the_thrusters_gains_but_not_the_logs_effect(effect):
    from benchmarks.diagnose_independent import with_truth_maps

    prior = shipped_model("videoray_pro3.yaml")
    _, truth = generate(prior.to_dict(), effect, 11, duration=1.0)
    oracle = with_truth_maps(prior, truth)
    np.testing.assert_allclose(oracle.allocation(), prior.allocation(), rtol=0, atol=0)
    fwd = truth.strength if effect == "thrust_effectiveness" else 1.0
    bwd = truth.strength if effect is not None else 1.0
    for th, t in zip(oracle.thrusters, truth.thrusters):
        unlimited = {**t, "max_forward": np.inf, "max_backward": np.inf}
        for n, s in ((0.3, fwd), (-0.3, bwd)):
            # the truth's thrust (its map, both branches) over the log's own effect [N]
            want = _thrust(unlimited, n) / s
            got = (th.eta_forward * th.ct_forward if n >= 0
                   else th.eta_backward * th.ct_backward) * n * abs(n)
            assert got == pytest.approx(want, rel=1e-12)
