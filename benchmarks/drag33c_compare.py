"""The option ``drag_couplings`` against diagnose's defaults on the same whole-log diagnoses of
the independent simulator's BlueROV2-Heavy-like logs (issue 33, drag33c): per log, what each
names first in the effect's DOF, every step named in any DOF (kept or removed by the
validation), the couplings written and the CPU of each diagnosis.

``python -m benchmarks.drag33c_compare SEED:CATEGORY [SEED:CATEGORY ...]`` (a log's seed and
category as ``benchmarks.diagnose_independent`` draws them: seed 29112026's BlueROV2 rows are
29113026 + c and 29213026 + c, c the category's index in every library effect, clean,
coulomb_friction). Lighter than ``diagnose_independent`` (no oracle, no truth test of the
steps; one simulated log diagnosed twice); benchmarks/data/drag33c_trace.md.
One line per log and option, ``compare {json}``."""
from __future__ import annotations

import json
import sys
import time
import warnings

import numpy as np

from benchmarks.diagnose_independent import _prior
from validation.independent import OUTSIDE, STRENGTHS, generate


def _diagnosis(log, prior, couplings: bool) -> tuple[dict, float]:
    from stripcoef.diagnose.pipeline import diagnose
    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof="all", time_limit=float("inf"),
                       drag_couplings=couplings).to_dict()
    return res, time.process_time() - t0


def row(seed: int, category: str, res: dict, cpu: float, couplings: bool, truth) -> dict:
    dof = ({**STRENGTHS, **OUTSIDE}.get(category) or ("surge",))[0]
    steps = {d: [[s["effect"], bool(s.get("kept", True)),
                  {k: round(float(v), 4) for k, v in s["parameters"].items()}]
                 for s in r["steps"]] for d, r in res["per_dof"].items() if r["steps"]}
    own = res["per_dof"].get(dof, {"steps": []})["steps"]
    written = {f"{d}.{k}": round(float(v), 4) for d, r in res["per_dof"].items()
               for k, v in (r["calibration"].get("written") or {}).items()
               if k.startswith("D_Q_")}
    truth_dq = {f"{d}.D_Q_{t}": round(float(truth.d_q[i, j]), 4)
                for i, d in ((3, "roll"), (4, "pitch"), (5, "yaw"))
                for j, t in enumerate(("surge", "sway", "heave")) if f"{d}.D_Q_{t}" in written}
    v = res.get("validation") or {}
    return {"seed": seed, "category": category, "couplings": couplings, "dof": dof,
            "first": own[0]["effect"] if own else None, "steps": steps,
            "removed": v.get("removed"), "kept_changes": v.get("kept_changes"),
            "prior_validation": v.get("prior"), "written": written, "truth": truth_dq,
            "final_error": {d: round(float(r["final_error"]), 5)
                            for d, r in res["per_dof"].items()},
            "cpu_s": round(cpu, 2)}


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    prior = _prior("bluerov2_heavy")
    for item in argv:
        seed, category = item.split(":")
        log, truth = generate(prior.to_dict(), None if category == "clean" else category,
                              int(seed), duration=300.0)
        for couplings in (False, True):
            res, cpu = _diagnosis(log, prior, couplings)
            print("compare " + json.dumps(row(int(seed), category, res, cpu, couplings,
                                                truth), default=float), flush=True)
    return 0


if __name__ == "__main__":
    np.seterr(all="ignore")
    raise SystemExit(main())
