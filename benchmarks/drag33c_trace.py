"""Trace of the validation's decisions on a whole-log BlueROV2 diagnosis under the drag-coupling
rules (issue 33, drag33c): which changes the validation removes, by which of its rules (the
summed score's backward elimination, or a DOF's own veto, ``removed_for_own_dof``), and the
free-simulation errors behind it.

``python -m benchmarks.drag33c_trace SEED CATEGORY VARIANT[,VARIANT...]`` on the independent
simulator's BlueROV2-Heavy-like logs (``validation.independent``, 300 s). VARIANT: ``none``
(diagnose's defaults), ``couplings`` (option ``drag_couplings``), ``lever_final`` (roll33b's
trial: every D_Q/D_L coupling D[i, j] scaled by DOF j's written calibration factor of the
``none`` run, put into the prior), ``truth_couplings`` (the truth's D_Q[i, j], i a moment DOF
and j a translation, put into the prior: what a calibrated coupling could at best reach),
``none_each``, ``couplings_each`` (``none``, ``couplings`` with the validation's option
``validation_others="each"``: each DOF simulated alone, the other five logged).
A trace, not a model change: benchmarks/data/drag33c_trace.md."""
from __future__ import annotations

import copy
import sys
import time
import warnings

import numpy as np

from benchmarks.diagnose_independent import _prior
from benchmarks.roll33b_swap import swapped
from stripcoef.model import HydroModel
from validation.independent import generate

DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


def _run(log, model, **options) -> tuple[dict, float]:
    from stripcoef.diagnose.pipeline import diagnose
    t0 = time.process_time()
    options.setdefault("validation_others", "logged")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, model, dof="all", time_limit=float("inf"), **options).to_dict()
    return res, time.process_time() - t0


def truth_couplings(prior, truth):
    """The prior with the truth's D_Q[i, j] for i a moment DOF, j a translation."""
    d = copy.deepcopy(prior.to_dict())
    a = np.asarray(d["quadratic_damping"], float)
    a[3:, :3] = np.asarray(truth.d_q, float)[3:, :3]
    d["quadratic_damping"] = a.tolist()
    return HydroModel.from_dict(d)


def report(name: str, res: dict, cpu: float) -> str:
    lines = [f"## {name} (CPU {cpu:.1f} s)"]
    for d, r in res["per_dof"].items():
        c = r["calibration"]
        steps = [f"{s['effect']} " + ",".join(f"{k} {v:.4f}" for k, v in s["parameters"].items())
                 + f" z {s.get('z', 0):.1f}" + ("" if s.get("kept", True) else " (removed)")
                 for s in r["steps"]]
        couplings = {k: round(v, 4) for k, v in (c.get("written") or {}).items()
                     if k.startswith("D_Q")}
        lines.append(f"- {d}: calibration kept {c.get('kept', True)}, written D_Q {couplings}, "
                     f"steps [{'; '.join(steps)}]")
    v = res.get("validation") or {}
    for key in ("prior", "all_changes", "kept_changes"):
        if v.get(key):
            lines.append(f"- validation {key}: "
                         + ", ".join(f"{d} {e:.4f}" for d, e in v[key].items()))
    lines.append(f"- removed: {v.get('removed')}; removed for own DOF: "
                 f"{v.get('removed_for_own_dof')}")
    dm = {d: (round(t.get("statistic", np.nan), 2), round(t.get("p_value", np.nan), 3))
          for d, t in (v.get("per_dof_test") or {}).items() if isinstance(t, dict)}
    lines.append(f"- Diebold-Mariano (statistic, p) of the kept model vs the prior: {dm}")
    return "\n".join(lines)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    seed, cat, which = int(argv[0]), argv[1], argv[2].split(",")
    prior = _prior("bluerov2_heavy")
    log, truth = generate(prior.to_dict(), cat, seed, duration=300.0)
    base = None
    for name in which:
        if name == "lever_final" and base is None:
            base, cpu = _run(log, prior)
            print(report(f"{seed} {cat} none", base, cpu), flush=True)
        if name == "couplings":
            res, cpu = _run(log, prior, drag_couplings=True)
        elif name in ("none_each", "couplings_each"):
            res, cpu = _run(log, prior, drag_couplings=name == "couplings_each",
                            validation_others="each")
        elif name == "truth_couplings":
            res, cpu = _run(log, truth_couplings(prior, truth))
        elif name in ("none", "lever_final"):
            res, cpu = _run(log, prior if name == "none" else swapped(prior, truth, name, base))
            base = res if name == "none" else base
        else:
            raise SystemExit(f"unknown variant {name!r}")
        print(report(f"{seed} {cat} {name}", res, cpu), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
