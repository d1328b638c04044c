"""Paired trade of diagnose's ``one_added_mass`` option against main's default on the same
logs of the independent 6-DOF simulator (issue 33).

Each log of ``benchmarks.diagnose_independent`` (same seeds, same categories) is simulated
once and diagnosed whole-log with the option off and on; per-DOF runs are diagnosed once,
because the option acts only in a whole-log diagnosis (``diagnose.pipeline.run``: a DOF is
selected again only when several DOFs are diagnosed), so a per-DOF row is its own pair and
ties by construction. Per log and criterion (the benchmark's: named first, named first after
the truth's background, magnitude within 15 %, error cut >= 3x, a spurious step named, one
kept; clean logs: an effect other than the background named) the option wins, loses or ties
against the default; the two-sided sign test (exact binomial, ties dropped; Dixon & Mood
1946, J. Am. Stat. Assoc. 41:557) says whether the wins and losses differ beyond chance.
A log's composite is the number of criteria it meets (spurious ones counted as met when
absent). The oracle of ``diagnose_independent`` is not run (it does not depend on the
option).

Usage:
    python -m benchmarks.one_added_mass_trade --seed S [--categories a,b] [--repeats 1]
        [--vehicles videoray_pro3,bluerov2_heavy] [--jobs 1] [--from-rows FILE]
"""

from __future__ import annotations

import argparse
import json
import math
import time

import numpy as np

from benchmarks.diagnose_independent import (VEHICLES, _background, _diagnosed,
                                             _first_after_background, _prior, _spurious,
                                             background)

#: the option's settings, each compared with main pairwise (``--variant``)
VARIANTS = {"main": False, "one_added_mass": True, "difference": "difference"}

#: the categories in which another DOF's added mass enters a whole-log diagnosis's balance
#: through C_A(nu) nu (the ones the option can move), beside the clean logs
DEFAULT_CATEGORIES = ("tether_drag", "momentum_drag", "thrust_effectiveness",
                      "added_mass_error", "linear_drag", "current", "clean")


def run_log(vehicle: str, category: str | None, seed: int, duration: float,
            modes: tuple, variants: tuple = ("main", "one_added_mass")) -> list[dict]:
    """One log simulated once; the rows of each (mode, variant): per-DOF once (variant
    ``"both"``), whole-log once per variant of :data:`VARIANTS` named in ``variants``."""
    from validation.independent import OUTSIDE, STRENGTHS, generate

    prior = _prior(vehicle)
    dof_name = ({**STRENGTHS, **OUTSIDE}.get(category) or ("surge",))[0]
    t0 = time.process_time()
    log, truth = generate(prior.to_dict(), category, seed, duration=duration)
    t_sim = time.process_time() - t0
    back = _background(truth, prior.to_dict())
    rows = []
    for mode in modes:
        todo = ([(v, VARIANTS[v]) for v in variants] if mode == "all"
                else (("both", False),))
        for name, flag in todo:
            row = _diagnosed(log, truth, prior, vehicle, category, seed, mode, dof_name, t_sim,
                             one_added_mass=flag)
            row.update(back, variant=name)
            print(f"  {vehicle} {row['category']} {seed} {mode} {name}: first {row['first']}"
                  f", cut {row['cut']:.2f}, magnitude error "
                  f"{row.get('magnitude_error', float('nan')):.2f}, "
                  f"{row['t_diagnose']:.1f} s row " + json.dumps(row, default=float),
                  flush=True)
            rows.append(row)
    return rows


def _run(args):
    return run_log(*args)


def criteria(row: dict) -> dict:
    """The criteria a row meets (bool each; absent where they do not apply)."""
    cat = row["category"]
    out = {}
    if cat == "clean":
        out["no effect other than the background"] = not any(
            not background(row, d, e) for d, es in row.get("step_effects", {}).items()
            for e in es)
        out["nothing kept"] = row.get("n_steps_kept", 0) == 0
    else:
        out["named first"] = row["first"] == cat
        out["named first after background"] = _first_after_background(row) == cat
        out["magnitude within 15 %"] = bool(row.get("magnitude_error", np.inf) <= 0.15)
        out["error cut >= 3x"] = bool(row["cut"] >= 3)
    if row["mode"] == "all" and cat != "clean":
        for key, name in (("step_effects", "no spurious step named"),
                          ("step_effects_kept", "no spurious step kept")):
            s = _spurious(row, key)
            if s is not None:
                out[name] = not s
    return out


def sign_test(wins: int, losses: int) -> float:
    """Two-sided exact sign test p-value of ``wins`` against ``losses`` (ties dropped):
    2 P(X <= min) for X ~ Binomial(n, 1/2), at most 1."""
    n = wins + losses
    if n == 0:
        return 1.0
    k = min(wins, losses)
    p = sum(math.comb(n, i) for i in range(k + 1)) / 2.0 ** n
    return min(1.0, 2.0 * p)


def summarise(rows: list[dict], variant: str = "one_added_mass") -> str:
    """The paired table of ``variant`` against main: per criterion the count met by each and
    the variant's wins/losses/ties with the sign test; then the composite per log."""
    key = (lambda r: (r["vehicle"], r["category"], r["seed"]))
    whole = {}
    for r in rows:
        if r["mode"] == "all":
            whole.setdefault(key(r), {})[r["variant"]] = r
    pairs = [(v["main"], v[variant]) for v in whole.values() if "main" in v and variant in v]
    per_dof = [r for r in rows if r["mode"] == "dof"]
    names = []
    for a, _ in pairs:
        for n in criteria(a):
            if n not in names:
                names.append(n)
    lines = [f"Whole-log pairs: {len(pairs)} logs (per-DOF rows: {len(per_dof)}, the option "
             "does not act there: ties by construction).", "",
             f"| criterion | logs | main | {variant} | wins / losses / ties | sign test p |",
             "| --- | --- | --- | --- | --- | --- |"]
    for n in names:
        got = [(criteria(a).get(n), criteria(b).get(n)) for a, b in pairs]
        got = [(x, y) for x, y in got if x is not None and y is not None]
        w = sum(y and not x for x, y in got)
        lo = sum(x and not y for x, y in got)
        lines.append(f"| {n} | {len(got)} | {sum(x for x, _ in got)} | {sum(y for _, y in got)}"
                     f" | {w} / {lo} / {len(got) - w - lo} | {sign_test(w, lo):.2f} |")
    comp = [(sum(criteria(a).values()), sum(criteria(b).values())) for a, b in pairs]
    w = sum(y > x for x, y in comp)
    lo = sum(y < x for x, y in comp)
    lines += ["", f"Composite (criteria met per log): {variant} wins {w}, loses {lo}, ties "
              f"{len(comp) - w - lo} of {len(comp)} (sign test p {sign_test(w, lo):.2f}); "
              f"criteria met in all: main {sum(x for x, _ in comp)}, {variant} "
              f"{sum(y for _, y in comp)}."]
    same = sum(a["step_effects"] == b["step_effects"] and abs(a["cut"] - b["cut"])
               <= 1e-9 * abs(a["cut"]) for a, b in pairs)
    lines.append(f"Whole-log diagnoses identical in steps and cut: {same} of {len(pairs)}.")
    diff = [f"{a['vehicle']} {a['category']} {a['seed']}: first {a['first']} -> {b['first']}"
            f", cut {a['cut']:.2f} -> {b['cut']:.2f}, magnitude error "
            f"{a.get('magnitude_error', float('nan')):.2f} -> "
            f"{b.get('magnitude_error', float('nan')):.2f}; "
            + ", ".join(("+ " if criteria(b)[n] else "- ") + n for n in criteria(a)
                        if criteria(a)[n] != criteria(b).get(n))
            for a, b in pairs if criteria(a) != criteria(b)]
    if diff:
        lines += ["", f"Logs whose criteria differ (main -> {variant}; + gained, - lost):", ""]
        lines += [f"- {d}" for d in sorted(diff)]
    ta = np.mean([a["t_diagnose"] for a, _ in pairs]) if pairs else float("nan")
    tb = np.mean([b["t_diagnose"] for _, b in pairs]) if pairs else float("nan")
    lines += ["", f"Mean whole-log diagnosis CPU: main {ta:.1f} s, option {tb:.1f} s."]
    return "\n".join(lines)


def main(argv=None) -> int:
    from benchmarks.diagnose_independent import log_seed, run_categories

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--categories", default=",".join(DEFAULT_CATEGORIES))
    ap.add_argument("--vehicles", default=",".join(VEHICLES))
    ap.add_argument("--modes", default="all,dof")
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--variant", default="one_added_mass", choices=sorted(set(VARIANTS) - {"main"}),
                    help="the setting compared with main")
    ap.add_argument("--only", default=None,
                    help="only these logs, comma-separated vehicle:category:seed (e.g. the "
                         "logs where another variant differs from main)")
    ap.add_argument("--skip-main", action="store_true",
                    help="diagnose only --variant (pair it with main's rows of an earlier run "
                         "of the same seeds through --from-rows)")
    ap.add_argument("--from-rows", default=None,
                    help="summarise the 'row' lines of earlier runs' output files "
                         "(comma-separated)")
    args = ap.parse_args(argv)
    if args.from_rows:
        from stripcoef.files import read_text
        rows = [json.loads(line.split(" row ", 1)[1]) for f in args.from_rows.split(",")
                for line in read_text(f, kind="benchmark output").splitlines()
                if " row {" in line]
        print(summarise(rows, args.variant))
        return 0
    seed = args.seed if args.seed is not None else int(np.random.SeedSequence().entropy % 10**6)
    every = run_categories()
    jobs = []
    for rep in range(args.repeats):
        for v, vehicle in enumerate(args.vehicles.split(",")):
            for cat in args.categories.split(","):
                # diagnose_independent --same-seeds: a log seeded as a run of every category
                s = log_seed(seed, rep, v, every.index(cat))
                if args.only and f"{vehicle}:{cat}:{s}" not in args.only.split(","):
                    continue
                jobs.append((vehicle, None if cat == "clean" else cat, s, args.duration,
                             tuple(args.modes.split(",")),
                             (args.variant,) if args.skip_main else ("main", args.variant)))
    print(f"seed {seed}: {len(jobs)} logs", flush=True)
    if args.jobs > 1:
        import multiprocessing
        with multiprocessing.Pool(args.jobs) as pool:
            rows = [r for rs in pool.imap_unordered(_run, jobs) for r in rs]
    else:
        rows = [r for j in jobs for r in _run(j)]
    print(summarise(rows, args.variant))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
