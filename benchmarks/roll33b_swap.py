"""Trace of a whole-log roll thrust scale (issue 33, roll33b): which of the truth's
coefficients, put into the prior, removes the step; and the oracle of a lever rule (every
drag coupling D[i, j], i != j, scaled by DOF j's own whole-log calibrated drag factor).

``python -m benchmarks.roll33b_swap SEED CATEGORY SWAP[,SWAP...]`` on the independent
simulator's BlueROV2-Heavy-like logs (``validation.independent``, 300 s). SWAP: none, truth, maps,
added_mass, sway_heave_mass, damping, roll_damping, roll_dq_cross, lever (the calibration before any step), lever_final (the
written calibration). A trace, not a
model change: benchmarks/data/roll33b_trace.md."""
from __future__ import annotations

import copy
import sys
import time
import warnings

import numpy as np

from benchmarks.diagnose_independent import _prior, with_truth_maps
from stripcoef.diagnose.pipeline import diagnose
from stripcoef.model import HydroModel
from validation.detectability import truth_model
from validation.independent import generate

DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


def _run(log, model) -> tuple[dict, float]:
    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, model, dof="all", time_limit=float("inf"),
                       validation_others="logged").to_dict()
    return res, time.process_time() - t0


def drag_factors(res: dict, which: str = "parameters") -> dict:
    """Each DOF's own calibrated quadratic and linear drag factor (1 + change / prior) [-]:
    ``which`` "parameters" (the calibration before any step) or "final_parameters" (the
    written one, fitted beside the DOF's kept effects)."""
    out = {}
    for d, r in res["per_dof"].items():
        c = r["calibration"]
        for key in ("D_Q", "D_L"):
            got = (c.get(which) or {}).get(key)
            if got is not None and c["prior"][key]:
                out[(d, key)] = 1.0 + got / c["prior"][key]
    return out


def swapped(prior, truth, name: str, base: dict | None = None):
    if name == "maps":
        return with_truth_maps(prior, truth)
    if name == "truth":                 # the truth's own model (its effect included)
        return truth_model(prior, truth)
    d = copy.deepcopy(prior.to_dict())
    if name == "roll_damping":          # the truth's roll rows and columns of D_L, D_Q
        for key, mat in (("linear_damping", truth.d_l), ("quadratic_damping", truth.d_q)):
            a = np.asarray(d[key], float)
            a[3, :] = mat[3, :]
            a[:, 3] = mat[:, 3]
            d[key] = a.tolist()
    elif name == "roll_dq_cross":       # only the sway-roll quadratic coupling, the truth's
        a = np.asarray(d["quadratic_damping"], float)
        a[3, 1] = truth.d_q[3, 1]
        d["quadratic_damping"] = a.tolist()
    elif name == "added_mass":
        d["added_mass"] = np.asarray(truth.m_a, float).tolist()
    elif name == "sway_heave_mass":
        a = np.asarray(d["added_mass"], float)
        a[1, 1], a[2, 2] = truth.m_a[1, 1], truth.m_a[2, 2]
        d["added_mass"] = a.tolist()
    elif name == "damping":
        d["linear_damping"] = np.asarray(truth.d_l, float).tolist()
        d["quadratic_damping"] = np.asarray(truth.d_q, float).tolist()
    elif name in ("lever", "lever_final"):   # D[i, j] scaled by DOF j's own factor
        f = drag_factors(base, "final_parameters" if name == "lever_final" else "parameters")
        for key, cal in (("quadratic_damping", "D_Q"), ("linear_damping", "D_L")):
            a = np.asarray(d[key], float)
            for j, dj in enumerate(DOFS):
                g = f.get((dj, cal), 1.0)
                for i in range(6):
                    if i != j:
                        a[i, j] *= g
            d[key] = a.tolist()
    elif name != "none":
        raise SystemExit(f"unknown swap {name!r}")
    return HydroModel.from_dict(d)


def _line(name, res, cpu) -> str:
    parts = [f"{name}: CPU {cpu:.1f} s"]
    for d, r in res["per_dof"].items():
        steps = [f"{s['effect']} z {s.get('z', 0):.1f} "
                 + ",".join(f"{k} {v:.4f}" for k, v in s["parameters"].items())
                 + ("" if s.get("kept", True) else " (removed)") for s in r["steps"]]
        if d in ("roll", "pitch") or steps:
            parts.append(f"{d} calibrated {r['calibrated_error']:.4f}"
                         + (f" [{'; '.join(steps)}]" if steps else ""))
    return " | ".join(parts)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    seed, cat, which = int(argv[0]), argv[1], argv[2].split(",")
    prior = _prior("bluerov2_heavy")
    log, truth = generate(prior.to_dict(), cat, seed, duration=300.0)
    base = None
    for name in which:
        if name.startswith("lever") and base is None:
            base, cpu = _run(log, prior)
            print(_line("none", base, cpu), flush=True)
        res, cpu = _run(log, swapped(prior, truth, name, base))
        if name == "none":
            base = res
        print(_line(name, res, cpu), flush=True)
        if name.startswith("lever"):
            which = "final_parameters" if name == "lever_final" else "parameters"
            print(f"  {name} factors:", {f"{d} {k}": round(v, 4) for (d, k), v in
                                         drag_factors(base, which).items()}, flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
