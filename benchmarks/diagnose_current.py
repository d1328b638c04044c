"""The water current a whole-log diagnosis finds, per DOF and shared (issue 33).

A current is one vector of the water (``stripcoef.diagnose.current``); fitted per DOF, each
DOF's fit found its own (real-style log, seed 58: surge and sway different currents). This
script diagnoses logs with an undeclared current and prints, per DOF, the current its
selection found, the one shared current with its band (``comparison.shared_current``), the
currents the written model holds, the truth, the held-out free-simulation errors and the
CPU time of the diagnosis and of the shared fit alone.

- ``--real SEED``: the BlueROV2-Heavy-like real-style current log of
  ``benchmarks.real_logs`` (log 2 of that seed: written as ROS-style chunk files, read back)
  on both splits (forward: fitted on the first 70 %, the held-out errors of the last 30 %;
  reverse: fitted on the last 70 %, compared on the first 30 %);
- ``--independent SEED ...``: 120-s logs of ``validation.independent`` (``--vehicle``,
  ``--category`` current or clean), diagnosed whole-log.

Run:  python -m benchmarks.diagnose_current --real 58
      python -m benchmarks.diagnose_current --independent 4242 303 --category current
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
import warnings
from unittest import mock

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


def _timed_diagnose(log, prior, **kw):
    """``(result, diagnosis CPU [s], shared-current CPU [s] or None)``."""
    import stripcoef.diagnose.pipeline as pipeline
    from stripcoef.diagnose import diagnose

    spent = []
    orig = getattr(pipeline, "share_current", None)

    def timed(per, fits):
        t0 = time.process_time()
        out = orig(per, fits)
        spent.append(time.process_time() - t0)
        return out
    c0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if orig is None:
            res = diagnose(log, prior, dof="all", time_limit=float("inf"), **kw)
        else:
            with mock.patch.object(pipeline, "share_current", timed):
                res = diagnose(log, prior, dof="all", time_limit=float("inf"), **kw)
    return res, time.process_time() - c0, (sum(spent) if spent else None)


def currents(res) -> list[str]:
    """Lines: per DOF the current selected and as written, and the shared fit's record."""
    lines, shared = [], None
    for d, r in res.per_dof.items():
        for s in r.steps:
            if s.effect != "current":
                continue
            sel = dict(s.selected_parameters or s.parameters)
            lines.append(f"  {d}: selected ({sel['current_north']:+.4f}, "
                         f"{sel['current_east']:+.4f}) m/s N, E; kept {s.kept}")
            if s.comparison and "shared_current" in s.comparison:
                shared = s.comparison["shared_current"]
        for c in r.candidates:
            if "shared_current" in c:
                lines.append(f"  {d}: removed: {c['rejected_because'][0]}")
    if shared is not None:
        sd = shared["std"]
        lines.append(f"  shared ({shared['current_north']:+.4f} +- {sd['current_north']:.4f}, "
                     f"{shared['current_east']:+.4f} +- {sd['current_east']:.4f}) m/s, "
                     f"speed {shared['speed']:.4f} +- {shared['speed_std']:.4f}, on "
                     f"{', '.join(shared['dofs'])}; widened x{shared['widened_by']:.2f}; "
                     f"LR {shared['joint_test']['statistic']:.3g} "
                     f"(p {shared['joint_test']['p_value']:.2g})")
    written = [(e["dof"], e["parameters"]) for e in res.model.effects if e["name"] == "current"]
    lines.append("  written: " + ("; ".join(
        f"{d} ({p['current_north']:+.4f}, {p['current_east']:+.4f})" for d, p in written)
        or "no current"))
    return lines


def _errors(errors: dict) -> list[str]:
    return [f"    {d}: " + ", ".join(f"{k} {v:.4f}" if v is not None else f"{k} -"
                                   for k, v in e.items()) for d, e in errors.items()]


def real(seed: int, duration: float) -> None:
    from benchmarks import real_logs as rl
    from stripcoef.diagnose.heldout import compare, split

    k = rl.EFFECTS.index("current")
    name, log, prior, widths, truth, oracle = rl.real_style_log(k, duration, seed, oracle=True)
    with tempfile.TemporaryDirectory() as tmp:
        read, _ = rl.read_back(tmp, rl.write_ros_chunks(log, tmp, seed=seed + k))
    vc = next(e["parameters"] for e in oracle.effects if e["name"] == "current")
    print(f"{name}, {truth}: truth ({vc['current_north']:+.4f}, {vc['current_east']:+.4f}) m/s")
    res, cpu, cur = _timed_diagnose(read, prior, holdout=rl.HOLDOUT, prior_widths=widths)
    print(f"forward: diagnosis {cpu:.1f} s CPU, shared current "
          + ("-" if cur is None else f"{cur:.2f} s"))
    print("\n".join(currents(res) + _errors(res.holdout["errors"])), flush=True)
    head, tail = split(read, 1.0 - rl.HOLDOUT)
    rev, cpu, cur = _timed_diagnose(tail, prior, prior_widths=widths)
    errors = compare(head, {"prior": prior, "calibrated": rl._written(rev.model)},
                     list(rev.diagnosed))
    print(f"reverse: diagnosis {cpu:.1f} s CPU, shared current "
          + ("-" if cur is None else f"{cur:.2f} s"))
    print("\n".join(currents(rev) + _errors(errors)), flush=True)


def independent(seeds, vehicle: str, category: str, duration: float) -> None:
    from benchmarks.diagnose_independent import _prior
    from validation.independent import generate

    prior = _prior(vehicle)
    for seed in seeds:
        log, truth = generate(prior.to_dict(), None if category == "clean" else category,
                              seed, duration=duration)
        res, cpu, cur = _timed_diagnose(log, prior)
        print(f"{vehicle} {category} seed {seed}: truth ({truth.current[0]:+.4f}, "
              f"{truth.current[1]:+.4f}) m/s; diagnosis {cpu:.1f} s CPU, shared current "
              + ("-" if cur is None else f"{cur:.2f} s"))
        print("\n".join(currents(res)), flush=True)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--real", type=int, metavar="SEED", help="the real-style current log")
    ap.add_argument("--independent", type=int, nargs="*", default=[], metavar="SEED")
    ap.add_argument("--vehicle", default="bluerov2_heavy")
    ap.add_argument("--category", default="current", choices=("current", "clean"))
    ap.add_argument("--duration", type=float, default=None,
                    help="log length [s] (default 300 real-style, 120 independent)")
    args = ap.parse_args(argv)
    if args.real is not None:
        real(args.real, args.duration or 300.0)
    if args.independent:
        independent(args.independent, args.vehicle, args.category, args.duration or 120.0)
    if args.real is None and not args.independent:
        ap.error("give --real SEED and/or --independent SEED ...")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
