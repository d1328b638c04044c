"""Issue 33 (named33f): the traces of benchmarks/data/named33f_trace.md, three named-first
misses of the fresh seed 1795938998 (and one of 1795929171), one log at a time.

- ``gate``: VideoRay thrust effectiveness 1795939008, surge, one DOF: the thrust scale's and
  the added-mass release's held-out gain, their refusal under ``heldout_rise="tie"`` (the
  default, beyond TIE = 2 %) and the one-sided Diebold-Mariano test of their cross-validated
  window losses (``diagnose.heldoutrise.rise_test``), and what each rule names.
- ``choice``: VideoRay added mass 1795939005 (and 1795929178): the scale-or-added-mass
  choice's record (``diagnose.scalechoice.choose``: each effect's likelihood-ratio test in
  the model holding both) on the prior and on the prior with the truth's thrust maps
  (``benchmarks.diagnose_independent.with_truth_maps``, an oracle), and the truth's surge
  thrust map, added mass and drag against the prior's.
- ``restoring``: BlueROV2 linear drag 1795940003, surge: the log's pitch angle, the part of
  the surge force the truth's weight-minus-buoyancy change makes, (W - B) sin(theta)
  (Fossen 2011 eq. 4.6), and its share in the linear drag's columns; the linear drag's test on
  the prior with that change and/or the truth's thrust maps, and with the gains the one-DOF
  and the whole-log fits found (both refused by their validation) and the whole-log heave
  buoyancy change carried into the surge's restoring force as a change of B.

Run::

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.named33f_trace [gate] [choice] [restoring]
"""

from __future__ import annotations

import argparse
import time
import warnings
from dataclasses import replace

import numpy as np

BASE = 1795938998


def _log(vehicle: str, category: str, seed: int):
    from validation.independent import generate

    from benchmarks.diagnose_independent import _prior
    prior = _prior(vehicle)
    log, truth = generate(prior.to_dict(), category, seed, duration=300.0)
    return prior, log, truth


def _diagnose(log, model, dof, **kw):
    from stripcoef.diagnose.pipeline import diagnose
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return diagnose(log, model, dof=dof, time_limit=float("inf"), **kw).to_dict()


def _params(step: dict) -> str:
    par = step.get("final_parameters") or step["parameters"]
    return ", ".join(f"{k} {v:.4g}" for k, v in par.items() if isinstance(v, float))


def _steps(res: dict, dof: str) -> str:
    steps = res["per_dof"][dof]["steps"]
    return "; ".join(f"{s['effect']} ({_params(s)}; kept {s.get('kept')})" for s in steps) \
        or "nothing"


def _candidate(res: dict, dof: str, name: str) -> dict:
    return next(c for c in res["per_dof"][dof]["candidates"] if c["effect"] == name)


def gate() -> None:
    """The held-out gate on VideoRay 1795939008 (module docstring)."""
    prior, log, truth = _log("videoray_pro3", "thrust_effectiveness", BASE + 10)
    print(f"VideoRay thrust effectiveness {BASE + 10}: truth scale {truth.strength:.4f}", flush=True)
    for rule in ("tie", "diebold_mariano"):
        res = _diagnose(log, prior, "surge", heldout_rise=rule)
        for name in ("thrust_effectiveness", "added_mass_error"):
            c = _candidate(res, "surge", name)
            ev = c.get("evidence") or {}
            print(f"  {rule}: {name} ({', '.join(f'{k} {v:.4g}' for k, v in c['parameters'].items())})"
                  f" held-out gain {100 * c['held_out_gain']:.1f} %, z {c['z']:.1f}, likelihood"
                  f" ratio p {ev.get('p_value', float('nan')):.2g}, Diebold-Mariano one-sided p"
                  f" (candidate better) {ev.get('held_out_p_value', float('nan')):.2f}, i.e."
                  f" p (candidate worse) {1 - ev.get('held_out_p_value', float('nan')):.2f};"
                  f" refused because {c['rejected_because'] or 'not refused'}")
        print(f"  {rule}: named {_steps(res, 'surge')}")


def _truth_surge(prior, truth) -> str:
    ratios = [t["ct_forward"] / th.ct_forward for t, th in zip(truth.thrusters, prior.thrusters)]
    return (f"truth/prior: thrust maps (C_t forward) {', '.join(f'{r:.3f}' for r in ratios)}; "
            f"X_udot {truth.m_a[0, 0]:.3f}/{prior.added_mass[0, 0]:.3f}, X_u|u| "
            f"{truth.d_q[0, 0]:.3f}/{prior.quadratic_damping[0, 0]:.3f}, m {prior.mass:.3f}")


def choice() -> None:
    """The scale-or-added-mass choice on VideoRay 1795939005 and 1795929178."""
    from stripcoef.diagnose import scalechoice

    from benchmarks.diagnose_independent import with_truth_maps
    seen = []
    orig = scalechoice.choose

    def spy(cfg, scale, release):
        out = orig(cfg, scale, release)
        seen.append(out["record"])
        return out

    scalechoice.choose = spy
    try:
        for seed in (BASE + 7, 1795929171 + 7):
            prior, log, truth = _log("videoray_pro3", "added_mass_error", seed)
            print(f"VideoRay added mass {seed}: {_truth_surge(prior, truth)}")
            for name, model in (("prior", prior),
                                ("prior with the truth's thrust maps",
                                 with_truth_maps(prior, truth))):
                seen.clear()
                res = _diagnose(log, model, "surge")
                line = f"  {name}: named {_steps(res, 'surge')}"
                for rec in seen:
                    t = rec["tests"]
                    line += (f"; choice: likelihood ratio in the model holding both, added mass"
                             f" {t['added_mass_error']['statistic']:.2f} (Holm p"
                             f" {t['added_mass_error']['p_adjusted']:.2g}), scale"
                             f" {t['thrust_effectiveness']['statistic']:.2f} (Holm p"
                             f" {t['thrust_effectiveness']['p_adjusted']:.2g}); posterior cost"
                             f" scale {rec['posterior_cost']['thrust_effectiveness']:.2f},"
                             f" added mass {rec['posterior_cost']['added_mass_error']:.2f}")
                print(line)
    finally:
        scalechoice.choose = orig


def _with_wb(model, change: float):
    """``model`` with W - B larger by ``change`` [N]: its displaced volume smaller by
    change / (rho g) [m^3] (B = rho g V, Fossen 2011 sec. 4.1), its mass unchanged."""
    return replace(model, volume=model.volume - change / (model.density * model.gravity))


def _gains(model, rec):
    from stripcoef.effects import get_effect
    return get_effect("thruster_gain").apply(
        model, None, {f"gain_{k}": float(g) for k, g in rec["gains"].items()})


def restoring() -> None:
    """The buoyancy change behind the BlueROV2 linear drag 1795940003 (module docstring)."""
    from benchmarks.diagnose_independent import with_truth_maps
    seed = BASE + 1000 + 5
    prior, log, truth = _log("bluerov2_heavy", "linear_drag", seed)
    dwb = (truth.weight - truth.buoyancy) - (prior.weight - prior.buoyancy)
    th, u = np.asarray(log["theta"], float), np.asarray(log["u"], float)
    fb, fd = dwb * np.sin(th), truth.d_l[0, 0] * u
    cols = np.column_stack([u, np.abs(u) * u, np.ones_like(u)])
    coef, *_ = np.linalg.lstsq(cols, fb, rcond=None)
    r2 = 1 - np.var(fb - cols @ coef) / np.var(fb)
    print(f"BlueROV2 linear drag {seed}: truth X_u {truth.d_l[0, 0]:.3f} N s/m, W - B truth "
          f"{truth.weight - truth.buoyancy:.3f} N, prior {prior.weight - prior.buoyancy:.3f} N "
          f"(change {dwb:+.3f} N); pitch mean {np.degrees(th.mean()):.2f} deg, sd "
          f"{np.degrees(th.std()):.2f} deg, range {np.degrees(th.min()):.1f} to "
          f"{np.degrees(th.max()):.1f} deg; surge force of the change (W - B) sin(theta): sd "
          f"{fb.std():.3f} N (the drag's X_u u: sd {fd.std():.3f} N); its share explained by "
          f"the drag's columns u, |u|u and a constant: R^2 {r2:.3f}")
    whole = _diagnose(log, prior, "all")
    heave = [s for s in whole["per_dof"]["heave"]["steps"] if s["effect"] == "buoyancy_offset"]
    b = float((heave[0].get("final_parameters") or heave[0]["parameters"])["b"]) if heave else 0.0
    one = _diagnose(log, prior, "surge")
    print(f"  whole-log: surge {_steps(whole, 'surge')}; heave {_steps(whole, 'heave')}; the "
          f"heave buoyancy change is a heave force only (effects.hydrodynamic.BuoyancyOffset: "
          f"F_i = b), the surge keeps the prior's W - B")
    print(f"  gains refused by their validation: one-DOF: {one['thruster_gains'].get('reason')};"
          f" whole-log: {whole['thruster_gains'].get('reason')}")
    variants = [("prior", prior), ("prior, truth's W - B", _with_wb(prior, dwb)),
                ("prior, whole-log heave change as W - B", _with_wb(prior, b)),
                ("prior, truth's maps", with_truth_maps(prior, truth)),
                ("prior, truth's maps and W - B", _with_wb(with_truth_maps(prior, truth), dwb)),
                ("prior, one-DOF gains", _gains(prior, one["thruster_gains"])),
                ("prior, one-DOF gains, heave change as W - B",
                 _with_wb(_gains(prior, one["thruster_gains"]), b)),
                ("prior, whole-log gains", _gains(prior, whole["thruster_gains"])),
                ("prior, whole-log gains, heave change as W - B",
                 _with_wb(_gains(prior, whole["thruster_gains"]), b))]
    for name, model in variants:
        t0 = time.process_time()
        res = _diagnose(log, model, "surge", dof_gains=False)
        c = _candidate(res, "surge", "linear_drag")
        ev = c.get("evidence") or {}
        print(f"  {name}: named {_steps(res, 'surge')}; the linear drag's test: d_L "
              f"{c['parameters'].get('d_L', float('nan')):.3f}, z {c['z']:.1f}, held-out gain "
              f"{100 * c['held_out_gain']:.1f} %, p {ev.get('p_value', float('nan')):.2g}, "
              f"refused because {c['rejected_because'] or 'not refused'} "
              f"[{time.process_time() - t0:.1f} s CPU]")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("parts", nargs="*", help="gate, choice, restoring (default: all three)")
    args = ap.parse_args(argv)
    parts = args.parts or ["gate", "choice", "restoring"]
    bad = [p for p in parts if p not in ("gate", "choice", "restoring")]
    if bad:
        ap.error(f"part {bad[0]!r}: expected gate, choice or restoring")
    for part in parts:
        t0 = time.process_time()
        {"gate": gate, "choice": choice, "restoring": restoring}[part]()
        print(f"[{part}: {time.process_time() - t0:.1f} s CPU]", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
