r"""Trace of a one-DOF added-mass release against a thrust scale (issue 33): the profiled
inertia change the fit takes beside the minimum of its cost, and the step's choice.

For each log seed of the independent simulator: the release's configuration (the DOF's
calibration and an ``added_mass_error`` term, ``diagnose.fit._Config``) on the fitting part
of the log; its profiled inertia change mu as ``diagnose.fit._solve`` takes it at the fit's
noise level (``diagnose.fit._sigma``), the profiled
cost there, and the minimum of the same cost over a grid of mu (``--grid`` points over the
search range, the cost evaluated as ``_solve_profiled`` defines it); then the one-DOF
diagnosis: its steps and the scale-or-release choice (posterior costs, Holm-adjusted p).
``--background truth``: the prior given the truth's buoyancy and thrust maps (the
background removed: what is left is the effect and the truth's +-25 % coefficients).

Run: ``python -m benchmarks.profile_trace --seeds 29113033,29213033`` (BlueROV2-like, added
mass, 300 s; the logs of ``python -m benchmarks.diagnose_independent --seed 29112026
--repeats 2 --categories added_mass_error``). Output in ``benchmarks/data/named33_trace.md``.
"""
from __future__ import annotations

import argparse
import json
import time
import warnings

import numpy as np


def _prior_for(vehicle: str, truth, background: str):
    from benchmarks.diagnose_independent import _prior, with_truth_maps
    from stripcoef.model import HydroModel
    from validation.independent import GRAVITY

    prior = _prior(vehicle)
    if background != "truth":
        return prior
    d = prior.to_dict()
    d["volume"] = float(truth.buoyancy) / (float(d["density"]) * GRAVITY)
    return with_truth_maps(HydroModel.from_dict(d), truth)


def trace(seed: int, vehicle: str, category: str, background: str, grid: int) -> dict:
    """One log's trace (module docstring) as a dict."""
    from benchmarks.diagnose_independent import _prior, magnitude_truth
    from stripcoef.conventions import parse_dof
    from stripcoef.diagnose.cross import moving_dofs
    from stripcoef.diagnose.fit import _Config, _sigma, _solve, _solve_linear
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.diagnose.select import _dof_calibration, excited_dofs
    from stripcoef.diagnose.settings import DiagnoseSettings
    from stripcoef.effects.laws import get_effect
    from stripcoef.effects.windows import window_data
    from validation.detectability import DEFAULT_WINDOW, VALIDATION_FRACTION, split
    from validation.independent import STRENGTHS, generate

    dof = STRENGTHS[category][0]
    i = parse_dof(dof)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        log, truth = generate(_prior(vehicle).to_dict(), category, seed, duration=300.0)
        prior = _prior_for(vehicle, truth, background)
        train, _ = split(log, VALIDATION_FRACTION, key="validation")
        data = window_data(train, prior, window=DEFAULT_WINDOW)
        settings = DiagnoseSettings()
        cal, _ = _dof_calibration(data, i, settings, excited_dofs(data), moving_dofs(data))
        cfg = _Config(data, i, cal, [(get_effect("added_mass_error"), None)],
                      settings=settings)
        y, H, sd = cfg.design()
        lower, upper, m = cfg.lower(), cfg.upper(), cfg.m_info()
        sigma = float(_sigma(y, H, sd, lower, m, upper))     # the fit's own noise level
        theta = _solve(y, H, sd, sigma, lower, m, upper, with_cov=False)[0]
        cols, m_total, v = m
        keep = [j for j in range(H.shape[1]) if j not in cols]

        def cost(mu):
            res = _solve_linear(y - mu * H[:, cols[0]], H[:, keep], sd[keep], sigma,
                                lower[keep], upper=upper[keep], with_cov=False)[2]
            return float(res @ res) - y.size * (m_total + mu) ** 2 * v / sigma ** 2

        mu = float(sum(theta[c] for c in cols))
        hi = min(5.0 * m_total, float(np.min(upper[cols])))
        mus = np.linspace(-0.95 * m_total, hi, grid)
        costs = [cost(x) for x in mus]
        t0 = time.process_time()
        res = diagnose(log, prior, dof=dof, time_limit=float("inf")).to_dict()
        cpu = time.process_time() - t0
    steps = res["steps"]
    choice = next((s.get("choice") for s in steps if s.get("choice")), None)
    return {"seed": seed, "vehicle": vehicle, "category": category, "background": background,
            "truth_thrust_units": float(magnitude_truth(truth, _prior(vehicle).to_dict(),
                                                        category, dof)),
            "calibration": list(cal.names), "sigma": sigma,
            "mu_fit": mu, "cost_at_fit": cost(mu),
            "mu_grid_min": float(mus[int(np.argmin(costs))]), "cost_grid_min": float(min(costs)),
            "steps": [{"effect": s["effect"], "z": s["z"],
                       "parameters": s.get("final_parameters") or s["parameters"],
                       "ambiguous_with": s.get("ambiguous_with")} for s in steps],
            "choice": None if choice is None else {
                "posterior_cost": choice["posterior_cost"],
                "p_adjusted": {k: t["p_adjusted"] for k, t in choice["tests"].items()},
                "needed": choice["needed"]},
            "cpu_s": cpu}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seeds", default="29113033,29213033")
    ap.add_argument("--vehicle", default="bluerov2_heavy")
    ap.add_argument("--category", default="added_mass_error")
    ap.add_argument("--background", choices=("prior", "truth"), default="prior")
    ap.add_argument("--grid", type=int, default=201)
    args = ap.parse_args(argv)
    for seed in (int(s) for s in args.seeds.split(",")):
        print(json.dumps(trace(seed, args.vehicle, args.category, args.background, args.grid),
                         default=float), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
