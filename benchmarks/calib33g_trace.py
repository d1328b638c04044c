"""Is the calibration of a lag or delay log fitted before the timing effect? (issue 33,
calib33g): one log of ``benchmarks.diagnose_independent`` diagnosed by default, and per DOF
that holds the thrusters' lag or delay

- the calibration as its record reports it (``DofResult.calibration.parameters``, band z:
  fitted alone, before any effect) and as the final fit holds it (the effects' fit, the
  timing effect's parameter profiled with the calibration's columns free: the values the
  validation judges and the model writes), beside the prior's and the truth's;
- the timing parameter's profile: the joint fit's inertia change and cost along a grid of
  the lag's or delay's value (the truth's value marked), so that the inertia the joint fit
  gives at the truth's timing can be read;
- the validation's free-simulation error (``stripcoef.diagnose.validate.validation_errors``,
  the validation part of the log) of the written model, of it with the own M and D_Q the
  final fit holds for each DOF whose calibration the validation removed, and with the
  truth's own M, D_L, D_Q in each diagnosed DOF.

Usage:
    python -m benchmarks.calib33g_trace --rows VEHICLE:CATEGORY:SEED:MODE[,...]
        [--gains-beside-timing]
"""

from __future__ import annotations

import argparse
import os
import warnings
from dataclasses import replace

import numpy as np

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

#: The model matrices of the calibration's own coefficients
MATRICES = {"M": "added_mass", "D_L": "linear_damping", "D_Q": "quadratic_damping"}
TIMING = ("thruster_lag", "actuation_delay")


def _with_changes(model, changes: dict):
    """``model`` with ``{(key, i): change}`` added to the diagonal of its matrices."""
    mats = {k: np.array(getattr(model, v), float) for k, v in MATRICES.items()}
    for (key, i), v in changes.items():
        mats[key][i, i] += v
    return replace(model, added_mass=mats["M"], linear_damping=mats["D_L"],
                   quadratic_damping=mats["D_Q"], added_mass_error=None)


def _profile(cfg, sigma, grid):
    """(value, cost, inertia change) along ``grid`` of the timing term of ``cfg``."""
    from stripcoef.diagnose.fit import _solve
    k = next(j for j, (e, _) in enumerate(cfg.terms) if e.name in TIMING)
    out = []
    for h in grid:
        terms = list(cfg.terms)
        terms[k] = (terms[k][0], np.array([h]))
        c = cfg.with_terms(terms)
        y, H, sd = c.design()
        th, _, w = _solve(y, H, sd, sigma, c.lower(), c.m_info(), c.upper(), with_cov=False)
        out.append((float(h), float(w @ w), float(th[0]) if c.cal_has_m else float("nan")))
    return out


def trace(vehicle, category, seed, mode, duration=300.0, gains_beside_timing=False) -> str:
    from stripcoef.conventions import parse_dof
    from stripcoef.diagnose.heldout import split
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.diagnose.settings import VALIDATION_FRACTION
    from stripcoef.diagnose.validate import validation_errors
    from validation.independent import STRENGTHS, generate

    from benchmarks.cut_trace import truth_dict
    from benchmarks.diagnose_independent import _prior

    prior = _prior(vehicle)
    dof_name = STRENGTHS[category][0]
    log, truth = generate(prior.to_dict(), category, seed, duration=duration)
    td = truth_dict(prior, truth)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof=dof_name if mode == "dof" else "all",
                       time_limit=float("inf"), gains_beside_timing=gains_beside_timing)
    _, val = split(log, VALIDATION_FRACTION, key="validation")
    dofs = [parse_dof(d) for d in res.per_dof]
    logged = [j for j in range(6) if j not in dofs] if len(dofs) == 1 else []

    def ve(model):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            e = validation_errors(val, model, dofs, logged)
        return "diverged" if e is None else ", ".join(f"{d} {v:.4f}" for d, v in e.items())

    lines = [f"## {vehicle} {category} {seed} {mode}"
             + (" (gains_beside_timing)" if gains_beside_timing else ""), "",
             f"truth's effect: {td['effects']}; removed by the validation: "
             f"{(res.validation or {}).get('removed')}", ""]
    own, truths = {}, {}
    for d, f in res.fits.items():
        i = parse_dof(d)
        cfg = f.config
        terms = [(e.name, None if h is None else round(float(np.ravel(h)[0]), 4))
                 for e, h in cfg.terms]
        r = res.per_dof[d]
        th = f.evaluation["full"]["theta"]
        joint = dict(zip(cfg.cal.names, th[:len(cfg.cal.names)]))
        lines.append(f"- {d}: terms {terms}; calibration kept {r.calibration.kept}")
        for key, attr in MATRICES.items():
            p0 = float(getattr(prior, attr)[i, i])
            t0 = float(td[attr][i][i]) - p0
            alone = r.calibration.parameters.get(key)
            z = r.calibration.band_z.get(key)
            lines.append(
                f"  - {key}: prior {p0:.4g}; change alone (reported) "
                + ("-" if alone is None else f"{alone:+.3f} (band z {z:+.2f})")
                + "; with the effects (validated) "
                + ("-" if key not in joint else f"{joint[key]:+.3f}")
                + f"; the truth's {t0:+.3f}")
            if key in joint and key != "D_L" and r.calibration.kept is False:
                own[(key, i)] = float(joint[key])
            truths[(key, i)] = float(td[attr][i][i]) - float(getattr(res.model, attr)[i, i])
        if any(e.name in TIMING for e, _ in cfg.terms) and cfg.cal_has_m:
            true_value = float(next(iter(td["effects"][0]["parameters"].values()))) \
                if td["effects"] else float("nan")
            prof = _profile(cfg, float(f.evaluation["full"]["sigma"]),
                            np.unique(np.append(np.linspace(0.6, 1.2, 7) * true_value,
                                                true_value)))
            lines.append("  - the timing's profile (value [s], cost, inertia change): "
                         + "; ".join(f"{h:.3f}{' (truth)' if h == true_value else ''} "
                                     f"{c:.1f} {m:+.2f}" for h, c, m in prof))
    lines += ["", "Validation free-simulation error [m/s or rad/s]:",
              f"- written: {ve(res.model)}",
              f"- written + the own M, D_Q fitted with the effects, of each DOF whose "
              f"calibration the validation removed: "
              f"{ve(_with_changes(res.model, own))}",
              f"- written + the truth's own M, D_L, D_Q of each DOF (the written "
              f"values replaced): {ve(_with_changes(res.model, truths))}",
              f"- validation record: prior {(res.validation or {}).get('prior')}, all "
              f"changes {(res.validation or {}).get('all_changes')}", ""]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", required=True,
                    help="comma-separated VEHICLE:CATEGORY:SEED:MODE (mode dof or all)")
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--gains-beside-timing", action="store_true")
    args = ap.parse_args(argv)
    for spec in args.rows.split(","):
        vehicle, category, seed, mode = spec.split(":")
        print(trace(vehicle, category, int(seed), mode, args.duration,
                    args.gains_beside_timing), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
