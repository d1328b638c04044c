r"""Named-first misses of the independent benchmark traced at the first step (issue 33,
named33c): which effect is named first instead, with what evidence, and what each group of
the truth's background does to that first step.

For one log of ``benchmarks.diagnose_independent`` (vehicle, category, seed; 300 s) the
diagnosis (one DOF, the effect's, or whole-log) is run on the prior and on the prior with
one group of the truth's coefficients put in at a time (:data:`SWAPS`): ``buoyancy`` (the
truth's volume), ``maps`` (each thruster's forward and backward C_t, the log's own thruster
effect left out: ``benchmarks.diagnose_independent.with_truth_maps``), ``own_added_mass``,
``own_drag``, ``other_added_mass``, ``other_drag`` (``benchmarks.cut_trace``'s groups),
``background`` (buoyancy and maps) and ``coefficients`` (every group: the truth's model
without its effect). Per run: the first step's candidate table (held-out gain, z, delta
BIC, the step test's p and Holm-adjusted p, why refused), the step's pair tests (the
comprehensive model of Atkinson 1970, ``diagnose.select._competing``), the steps named.

Beside them, the non-nested comparison of the two best single candidates of the first
step (each fitted alone beside the calibration): Vuong's (1989, Econometrica 57, 307-333,
eq. 5.6) statistic
:math:`Z = \sum_i \ell_i / (\sqrt{n}\,\hat\omega)` with
:math:`\ell_i = \ln f_A(e_i) - \ln f_B(e_i)` the pointwise Gaussian log-likelihood ratio of
the two fits' window residuals at their ML variances, :math:`\hat\omega` the standard
deviation of :math:`\ell_i`, and the Schwarz correction :math:`(k_A - k_B)\ln(n)/2`
(Vuong 1989, sec. 5, eq. 5.7); with :math:`n` also counted on the effective windows of an
AR(1) series, :math:`n (1-\rho)/(1+\rho)` (Bartlett 1935; Bretherton et al. 1999 eq. 30),
:math:`\rho` the lag-1 autocorrelation of :math:`\ell_i`. Z > 0 favours A. The fits are
the selection's own (``diagnose.select._judge`` is wrapped to keep each first-step
candidate's evaluation; nothing in the diagnosis is changed).

Usage:
    python -m benchmarks.named33c_swap --rows VEHICLE:CATEGORY:SEED:MODE[,...]
        [--swaps none,buoyancy,maps,...] [--duration 300]

Output (one JSON line per run) summarised in ``benchmarks/data/named33c_trace.md``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time
import warnings

import numpy as np

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

#: The groups of the truth put into the prior, one run each (module docstring)
SWAPS = ("none", "buoyancy", "maps", "own_added_mass", "own_drag", "other_added_mass",
         "other_drag", "background", "coefficients")
_COEF_GROUPS = ("own_added_mass", "own_drag", "other_added_mass", "other_drag")


def swapped_prior(prior, truth, dof: int, name: str):
    """The prior with the truth's group ``name`` (:data:`SWAPS`) in it."""
    from benchmarks.cut_trace import _swap, truth_dict
    from benchmarks.diagnose_independent import with_truth_maps
    from stripcoef.model import HydroModel
    if name == "none":
        return prior
    source = truth_dict(prior, truth)
    groups = {"background": ("buoyancy", "maps"),
              "coefficients": ("buoyancy", "maps") + _COEF_GROUPS}.get(name, (name,))
    if name not in SWAPS:
        raise SystemExit(f"unknown swap {name!r}; expected one of {', '.join(SWAPS)}")
    d = prior.to_dict()
    if "maps" in groups:
        d["thrusters"] = with_truth_maps(prior, truth).to_dict()["thrusters"]
    for g in groups:
        if g != "maps":
            d = _swap(d, source, g, dof)
    return HydroModel.from_dict(d)


def _ml_loglik(e):
    """Pointwise Gaussian log-likelihood of residuals ``e`` at their ML variance."""
    e = np.asarray(e, float)
    s2 = float(e @ e) / e.size
    return -0.5 * (math.log(2.0 * math.pi * s2) + e ** 2 / s2)


def vuong(ea, eb, ka: int, kb: int) -> dict:
    """Vuong's (1989) non-nested statistic of fit A against fit B (module docstring) from
    their window residuals ``ea``, ``eb`` and free parameter counts ``ka``, ``kb``."""
    from scipy.stats import norm
    ell = _ml_loglik(ea) - _ml_loglik(eb)
    n = ell.size
    omega = float(np.std(ell))
    lr = float(ell.sum())
    corrected = lr - 0.5 * (ka - kb) * math.log(n)
    rho = float(np.corrcoef(ell[:-1], ell[1:])[0, 1]) if n > 3 else 0.0
    frac = (1.0 - rho) / (1.0 + rho) if rho > 0.0 else 1.0
    z = corrected / (math.sqrt(n) * omega) if omega > 0 else 0.0
    z_eff = z * math.sqrt(frac)
    return {"lr": lr, "lr_bic": corrected, "z": z, "p_two_sided": float(2 * norm.sf(abs(z))),
            "rho": rho, "z_effective": z_eff,
            "p_effective": float(2 * norm.sf(abs(z_eff))), "windows": int(n)}


def run(log, model, dof_name: str, mode: str) -> dict:
    """One diagnosis with the first step's candidate evaluations kept (module docstring)."""
    from stripcoef.diagnose import select
    from stripcoef.diagnose.pipeline import diagnose
    kept = {}
    judge = select._judge

    def wrapped(eff, cfg, ev, cur, data, dof, *args, **kw):
        t = judge(eff, cfg, ev, cur, data, dof, *args, **kw)
        if select.DOF[dof] == dof_name and eff.name not in kept:
            kept[eff.name] = {"resid": np.asarray(ev["full"]["resid"], float),
                              "n_free": int(ev["n_free"]),
                              "k": int(len(ev["full"]["theta"]))}
        return t

    select._judge = wrapped
    try:
        t0 = time.process_time()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = diagnose(log, model, dof=dof_name if mode == "dof" else "all",
                           time_limit=float("inf")).to_dict()
        cpu = time.process_time() - t0
    finally:
        select._judge = judge
    r = (res.get("per_dof") or {dof_name: res})[dof_name]
    cands = []
    for c in r["candidates"]:
        if not c.get("applicable"):
            continue
        e = c.get("evidence") or {}
        cands.append({"effect": c["effect"], "held_out_gain": c["held_out_gain"],
                      "z": c["z"], "delta_bic": c["delta_bic"],
                      "p": e.get("p_value"), "p_holm": e.get("p_adjusted"),
                      "significant": c["significant"],
                      "parameters": c["parameters"],
                      "rejected_because": c["rejected_because"]})
    cands.sort(key=lambda c: -(c["held_out_gain"] or -1e9))
    comparison = next((s.get("comparison") for s in r["steps"] if s.get("comparison")), None)
    pairs = [{"pair": t["pair"], "held_out_error_joint": t["held_out_error_joint"],
              "p": {k: v.get("adjusted", {}).get("force", v["p_value"])
                    for k, v in t["members"].items()}}
             for t in (comparison or {}).get("tests", [])]
    top = [c["effect"] for c in cands if c["effect"] in kept][:2]
    nonnested = None
    if len(top) == 2:
        a, b = kept[top[0]], kept[top[1]]
        if a["resid"].shape == b["resid"].shape:
            nonnested = {"a": top[0], "b": top[1],
                         **vuong(a["resid"], b["resid"], a["k"], b["k"])}
    return {"cpu_s": cpu, "baseline_error": r["baseline_error"],
            "final_error": r["final_error"], "candidates": cands, "pairs": pairs,
            "vuong_top_two": nonnested,
            "steps": [{"effect": s["effect"], "z": s.get("z"),
                       "held_out_gain": s.get("held_out_gain"),
                       "parameters": s.get("final_parameters") or s["parameters"],
                       "kept": s.get("kept", True)} for s in r["steps"]]}


def summary(records: list[dict], top: int = 4) -> list[str]:
    """Markdown lines of :func:`run`'s records (``--summarise``): per log, per swap, the
    steps named and the first step's ``top`` candidates by held-out gain."""
    out = []
    for r in records:
        steps = "; ".join(f"{s['effect']} ("
                          + ", ".join(f"{k} {v:.4g}" for k, v in s["parameters"].items())
                          + ("" if s["kept"] else ", removed") + ")" for s in r["steps"])
        cands = "; ".join(
            f"{c['effect']} {100 * c['held_out_gain']:.1f} %, z {c['z']:.1f}, dBIC "
            f"{c['delta_bic']:.1f}" + ("" if c["p_holm"] is None else
                                       f", Holm p {c['p_holm']:.2g}")
            + ("" if c["significant"] else " (refused)") for c in r["candidates"][:top])
        v = r.get("vuong_top_two")
        vs = ("" if not v else f" Vuong {v['a']} vs {v['b']}: Z {v['z']:.2f} "
              f"(effective {v['z_effective']:.2f}, p {v['p_effective']:.2g}).")
        out.append(f"- {r['vehicle']} {r['category']} {r['seed']} {r['mode']}, prior + truth's "
                   f"{r['swap']}: error {r['baseline_error']:.4f} -> {r['final_error']:.4f}; "
                   f"steps: {steps or 'none'}. First step: {cands}.{vs}")
    return out


def main(argv=None) -> int:
    from benchmarks.diagnose_independent import _background, _prior
    from stripcoef.conventions import parse_dof
    from validation.independent import STRENGTHS, generate
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--summarise", default=None,
                    help="print the markdown summary of an earlier run's JSON lines (a file)")
    ap.add_argument("--rows", default="",
                    help="VEHICLE:CATEGORY:SEED:MODE[,...] (MODE dof or all)")
    ap.add_argument("--swaps", default=",".join(SWAPS))
    ap.add_argument("--duration", type=float, default=300.0)
    args = ap.parse_args(argv)
    if args.summarise:
        with open(args.summarise) as f:
            print("\n".join(summary([json.loads(x) for x in f if x.strip()])))
        return 0
    for row in filter(None, args.rows.split(",")):
        vehicle, category, seed, mode = row.split(":")
        prior = _prior(vehicle)
        dof_name = STRENGTHS[category][0]
        log, truth = generate(prior.to_dict(), category, int(seed), duration=args.duration)
        head = {"vehicle": vehicle, "category": category, "seed": int(seed), "mode": mode,
                "dof": dof_name, "truth": float(truth.strength),
                "background": _background(truth, prior.to_dict())}
        for name in args.swaps.split(","):
            model = swapped_prior(prior, truth, parse_dof(dof_name), name)
            print(json.dumps({**head, "swap": name, **run(log, model, dof_name, mode)},
                             default=float), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
