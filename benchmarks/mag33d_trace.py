r"""Why a named effect's magnitude misses the truth by more than 15 % (issue 33): one log of
``benchmarks.diagnose_independent`` diagnosed again against swapped priors and a noise-free
copy of the log.

For one log (vehicle, category, seed, mode) the diagnosis (``stripcoef.diagnose.pipeline.
diagnose``, its defaults) is run on

- ``prior``: the prior, as the benchmark runs it (the row's written value);
- ``prior <- truth G``: the prior with one group G of :data:`benchmarks.cut_trace.GROUPS`
  (the DOF's own added mass, its own drags, the other DOFs' added masses, the other drags,
  the buoyancy, the thrust map) taken from the truth's model without the effect
  (``validation.detectability.truth_without``, as ``benchmarks.hidden_trace``): a group whose
  swap brings the value to the truth is the prior's background that biases it;
- ``truth``: the truth's model without the effect (every group swapped): what is left is the
  log's (its noise, its excitation) or the method's (the effect's law, its partners);
- ``truth, noise-free``, ``prior, noise-free``: the same log with the logged states written
  without their sensor noise (``validation.independent.generate(logged_noise=False)``: the
  same truth, commands and trajectory): the attenuation of an errors-in-variables regressor
  (noisy velocity in a drag or added-mass column; Fuller 1987, sec. 1.1) is the difference
  from the noisy log's value;
- ``truth, noise draw k`` (``--noise-draws K``): the noise-free log with K fresh draws of the
  sensor noise (:func:`renoised`) against the truth's model: their mean off the truth is an
  errors-in-variables bias, their spread the noise's own scatter (a single log's miss of
  1-2 of those standard deviations is the draw's).

Each diagnosis's value is compared with the truth in the units the log determines it in
against *that* model (``benchmarks.diagnose_independent.magnitude_truth`` with the model's
thrust map and the diagnosis's own thrust scale and written gains): swapping the thrust map
changes the reference, not only the value. Reported per model: the value, its standard
deviation (the step's ``std``), the reference, the error, the other steps of the DOF (the
effect's partners) and the calibration's written values with their band z (the shrinkage to
the prior band, ``stripcoef.diagnose.priors``).

``--rescore OUT[,OUT...]`` diagnoses nothing: it reads the ``row`` lines of
``benchmarks.diagnose_independent`` outputs and scores each row's written magnitude again with
the benchmark's present ``magnitude_truth`` (its rule for an effect that replaces a term the
prior holds: the buoyancy offset and the linear drag), from the row's own numbers (the drawn
strength, the old reference's thrust-unit factor :math:`s\,g_w/g`) and the prior's: the counts
the scoring fix changes, without running the diagnoses again.

Usage:
    python -m benchmarks.mag33d_trace --rows VEHICLE:CATEGORY:SEED:MODE[,...]
        [--duration 300] [--models prior,truth,...]
    python -m benchmarks.mag33d_trace --rescore OUT[,OUT...]
"""

from __future__ import annotations

import argparse
import json
import os
import time
import warnings

import numpy as np

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

#: The models a trace diagnoses the log against (module docstring)
SWAPS = ("own_added_mass", "own_drag", "other_added_mass", "other_drag", "buoyancy",
         "thrust_map")


def _value(res: dict, model: dict, truth, category: str, dof_name: str) -> dict:
    """The effect's value in one diagnosis's result ``res`` (against ``model``) and the
    truth's in the same units (``magnitude_truth``)."""
    from stripcoef.effects import get_effect

    from benchmarks.diagnose_independent import magnitude_truth, written_gain
    per = res.get("per_dof") or {dof_name: res}
    own = per.get(dof_name, {"steps": []})
    steps = own["steps"]
    scale = float(np.prod([(s.get("final_parameters") or s["parameters"]).get(
        "scale", s["parameters"].get("scale", 1.0)) for s in steps
        if s["effect"] == "thrust_effectiveness"]))
    ref = float(magnitude_truth(truth, model, category, dof_name, scale,
                                written_gain(res, model, dof_name)))
    out = {"steps": [(s["effect"], bool(s.get("kept", True))) for s in steps],
           "reference": ref, "scale": scale}
    match = [s for s in steps if s["effect"] == category]
    if match:
        s = match[0]
        eff = get_effect(category)
        final = s.get("final_parameters") or s["parameters"]
        sel = s.get("selected_parameters") or s["parameters"]
        est = float(eff.magnitude(final))
        out.update({"estimate": est, "selected": float(eff.magnitude(sel)),
                    "std": {k: float(v) for k, v in (s.get("std") or {}).items()},
                    "z": float(s.get("z") or np.nan),
                    "error": (abs(est) - abs(ref)) / abs(ref),
                    "not_determined": bool(s.get("not_determined"))})
    cal = own.get("calibration") or {}
    if cal:
        # each coefficient: the prior's value, the written one, and the final fit's change
        # in prior bands (the band's 1-sigma width, band_relative x |prior|): a value held at
        # its band's edge is shrunk to the prior
        fin = cal.get("final_parameters") or cal.get("parameters") or {}
        out["calibration"] = {}
        for n in cal.get("parameters", ()):
            p0 = float(cal["prior"][n])
            width = float((cal.get("band_relative") or {}).get(n, np.nan)) * abs(p0)
            out["calibration"][n] = [p0, float((cal.get("written") or {}).get(n, np.nan)),
                                     float(fin.get(n, np.nan)) / width if width else np.nan]
        out["calibration_kept"] = bool(cal.get("kept"))
    return out


def renoised(clean, seed: int, k: int):
    """The noise-free log ``clean`` with a fresh draw ``k`` of the sensor noise
    (``validation.independent.NOISE``, the generator's levels, seeded from the log's seed and
    ``k``): another realisation of the same log's noise, for the spread and the mean of a
    value over noise draws (an errors-in-variables bias is a mean off the truth; a draw's own
    miss is a spread)."""
    from stripcoef.logfile import Log
    from validation.independent import NOISE
    rng = np.random.default_rng([seed, 1000 + k])
    cols = {c: np.array(v, float) for c, v in clean.columns.items()}
    for name, sd in NOISE.items():
        if name in cols:
            cols[name] = cols[name] + rng.normal(0.0, sd, cols[name].shape[0])
    return Log(cols, source=f"{clean.source}, noise draw {k}", meta=dict(clean.meta))


def trace(vehicle: str, category: str, seed: int, mode: str, duration: float = 300.0,
          models: tuple | None = None, noise_draws: int = 0) -> dict:
    """The record of one log (module docstring): ``{label: value record}``;
    ``noise_draws``: that many diagnoses against the truth's model of the noise-free log with
    a fresh noise draw each (:func:`renoised`)."""
    from stripcoef.conventions import parse_dof
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.model import HydroModel
    from validation.detectability import truth_model, truth_without
    from validation.independent import STRENGTHS, generate

    from benchmarks.cut_trace import _swap
    from benchmarks.diagnose_independent import _prior

    prior = _prior(vehicle)
    dof_name = STRENGTHS[category][0]
    i = parse_dof(dof_name)
    log, truth = generate(prior.to_dict(), category, seed, duration=duration)
    clean, _ = generate(prior.to_dict(), category, seed, duration=duration,
                        logged_noise=False)
    source = truth_model(prior, truth_without(prior, truth)).to_dict()
    cases = {"prior": (log, prior.to_dict())}
    cases.update({f"prior <- truth {g}": (log, _swap(prior.to_dict(), source, g, i))
                  for g in SWAPS})
    cases["truth"] = (log, source)
    cases["truth, noise-free"] = (clean, source)
    cases["prior, noise-free"] = (clean, prior.to_dict())
    for k in range(noise_draws):
        cases[f"truth, noise draw {k + 1}"] = (renoised(clean, seed, k), source)
    if models:
        cases = {k: v for k, v in cases.items()
                 if k in models or k.startswith("truth, noise draw")}
    out = {"vehicle": vehicle, "category": category, "seed": seed, "mode": mode,
           "dof": dof_name, "drawn": float(truth.strength), "models": {}}
    for label, (lg, model) in cases.items():
        t0 = time.process_time()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = diagnose(lg, HydroModel.from_dict(model),
                           dof=dof_name if mode == "dof" else "all",
                           time_limit=float("inf")).to_dict()
        rec = _value(res, model, truth, category, dof_name)
        rec["cpu_s"] = time.process_time() - t0
        out["models"][label] = rec
        print(f"  {vehicle} {category} {seed} {mode} {label}: " + _cell(rec), flush=True)
    return out


def _cell(rec: dict) -> str:
    if "estimate" not in rec:
        return f"not named (steps {rec['steps']}; reference {rec['reference']:.4g})"
    sd = ", ".join(f"{k} {v:.3g}" for k, v in rec["std"].items())
    return (f"{rec['estimate']:.4g} (sd {sd}; selected alone {rec['selected']:.4g}) vs "
            f"{rec['reference']:.4g}: {100 * rec['error']:+.1f} %; steps {rec['steps']}")


def _text(rec: dict) -> str:
    lines = [f"### {rec['vehicle']} {rec['category']} {rec['seed']} {rec['mode']} "
             f"({rec['dof']}; drawn {rec['drawn']:.4g})", "",
             "| model | value (sd) | truth in its units | error | steps of the DOF | "
             "calibration: prior -> written (final change in bands) |", "| --- | --- | --- | --- | --- | --- |"]
    for label, m in rec["models"].items():
        cal = "; ".join(f"{n} {p:.4g} -> {w:.4g} ({z:+.1f})"
                        for n, (p, w, z) in (m.get("calibration") or {}).items()
                        if np.isfinite(w))
        if "estimate" in m:
            sd = ", ".join(f"{v:.3g}" for v in m["std"].values())
            val, err = f"{m['estimate']:.4g} ({sd})", f"{100 * m['error']:+.1f} %"
        else:
            val, err = "not named", "-"
        steps = ", ".join(e + ("" if k else " (removed)") for e, k in m["steps"])
        lines.append(f"| {label} | {val} | {m['reference']:.4g} | {err} | {steps} | "
                     f"{cal or '-'} |")
    return "\n".join(lines)


def rescore(rows: list[dict]) -> list[dict]:
    """Each row with a written magnitude of a buoyancy offset or a linear drag scored again
    (module docstring): ``{vehicle, category, seed, mode, estimate, old, new, old_error,
    new_error}`` (references in the thrust's units; errors relative)."""
    from validation.independent import GRAVITY

    from benchmarks.diagnose_independent import _prior
    priors, out = {}, []
    for r in rows:
        if r["category"] not in ("buoyancy_offset", "linear_drag") or "estimate" not in r:
            continue
        d = priors.setdefault(r["vehicle"], _prior(r["vehicle"]).to_dict())
        s, old = float(r["truth"]), float(r["magnitude_truth"])
        k = old / s                                  # s g_w / g of the force rule
        if r["category"] == "buoyancy_offset":
            w = float(d["mass"]) * GRAVITY
            b_p = float(d["density"]) * float(d["volume"]) * GRAVITY
            new = (w - (b_p + s)) * k - (w - b_p)
        else:
            new = old - float(np.asarray(d["linear_damping"], float)[0, 0])
        est = float(r["estimate"])
        out.append({k2: r[k2] for k2 in ("vehicle", "category", "seed", "mode")}
                   | {"estimate": est, "old": old, "new": new,
                      "old_error": abs(abs(est) - abs(old)) / abs(old),
                      "new_error": abs(abs(est) - abs(new)) / abs(new)})
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rescore", default=None,
                    help="comma-separated outputs of benchmarks.diagnose_independent: score "
                         "their rows' magnitudes again (no diagnosis)")
    ap.add_argument("--rows", default=None,
                    help="comma-separated VEHICLE:CATEGORY:SEED:MODE (mode dof or all)")
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--noise-draws", type=int, default=0,
                    help="diagnoses of the truth's model on the noise-free log with that many "
                         "fresh noise draws")
    ap.add_argument("--models", default=None,
                    help="comma-separated labels of the models to diagnose against (default: "
                         "all; 'prior', 'prior <- truth G', 'truth', 'truth, noise-free', "
                         "'prior, noise-free')")
    args = ap.parse_args(argv)
    if args.rescore:
        from stripcoef.files import read_text
        for path in args.rescore.split(","):
            rows = [json.loads(line.split(" row ", 1)[1])
                    for line in read_text(path, kind="benchmark output").splitlines()
                    if " row {" in line]
            got = rescore(rows)
            print(f"{path}: {len(got)} rows rescored; within 15 %: "
                  f"{sum(g['old_error'] <= 0.15 for g in got)} -> "
                  f"{sum(g['new_error'] <= 0.15 for g in got)}")
            for g in got:
                print(f"  {g['vehicle']} {g['category']} {g['seed']} {g['mode']}: written "
                      f"{g['estimate']:+.4g}, reference {g['old']:+.4g} -> {g['new']:+.4g}, "
                      f"error {100 * g['old_error']:.1f} % -> {100 * g['new_error']:.1f} %")
        return 0
    if not args.rows:
        ap.error("--rows or --rescore is required")
    models = tuple(args.models.split(",")) if args.models else None
    for spec in args.rows.split(","):
        vehicle, category, seed, mode = spec.split(":")
        t0 = time.process_time()
        rec = trace(vehicle, category, int(seed), mode, args.duration, models,
                    args.noise_draws)
        rec["cpu_s"] = time.process_time() - t0
        print("trace " + json.dumps(rec, default=float), flush=True)
        print(_text(rec), flush=True)
        draws = [m["error"] for k, m in rec["models"].items()
                 if k.startswith("truth, noise draw") and "error" in m]
        if draws:
            print(f"Noise draws against the truth's model: {len(draws)}, mean error "
                  f"{100 * np.mean(draws):+.1f} % (its standard error "
                  f"{100 * np.std(draws, ddof=1) / np.sqrt(len(draws)):.1f} %), spread (sd) "
                  f"{100 * np.std(draws, ddof=1):.1f} %" if len(draws) > 1 else "", flush=True)
        print(f"({rec['cpu_s']:.0f} s of CPU)", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
