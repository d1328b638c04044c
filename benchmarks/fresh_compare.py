"""Issue 33's criteria on two runs of ``benchmarks.diagnose_independent``, side by side, each
rate with its binomial 95 % interval (Wilson 1927).

The runs are read from the markdown files their ``--write`` option wrote (the summary lines
``summarise`` prints: every count is read from the file, none recomputed), e.g. the seed the
team built against and a fresh one:

    python -m benchmarks.fresh_compare benchmarks/data/diagnose_independent_300s.md \
        benchmarks/data/diagnose_independent_fresh_1795929171.md
    python -m benchmarks.fresh_compare --rows RUN_OUTPUT.txt   (each row's failed criteria)
    python -m benchmarks.fresh_compare --pairs BASE_1.md OTHER_1.md [BASE_2.md OTHER_2.md ...]
        (two configurations of each seed: base -> other per criterion, each with its interval)

A file may be given as ``LABEL=PATH`` (the column's label; default: the seed its text names).

Per criterion: each run's count, its rate and the Wilson score interval
(:func:`wilson_interval`), and the issue's bar where it sets one. A rate whose interval lies
wholly below the bar misses it on that run beyond the draw's chance; two runs whose intervals
overlap are not told apart by these sample sizes.
"""

from __future__ import annotations

import argparse
import math
import re

#: The two-sided 95 % standard normal quantile [-]
Z95 = 1.959963984540054

#: (name, pattern of the summary text with the count and the total, the issue's bar as the
#: least acceptable rate or None, whether a *lower* rate is better)
CRITERIA = (
    ("library effects named first", r"Library effects named first: (\d+)/(\d+)", 0.95, False),
    ("named first after the background",
     r"named first after the truth's background \(buoyancy, thrust gains\): (\d+)/(\d+)",
     None, False),
    ("magnitude within 15 %", r"; magnitude within 15 %: (\d+)/(\d+)", None, False),
    ("magnitude within 15 %, held by the written model",
     r"held by the written model, not removed by its validation: (\d+)/(\d+)", None, False),
    ("error cut >= 3x", r"error cut >= 3x: (\d+)/(\d+)", None, False),
    ("the truth's own cut >= 3x", r"cuts the prior's error >= 3x in (\d+)/(\d+)", None, False),
    ("error cut >= 3x where the truth's is",
     r"of those the diagnosis does in (\d+)/(\d+)", None, False),
    ("whole-log runs with a spurious step named", r"named in (\d+)/(\d+), kept in the written",
     0.10, True),
    ("whole-log runs with a spurious step kept",
     r"kept in the written model in (\d+)/(\d+) \(by the earlier", 0.10, True),
    ("clean logs naming an effect other than the background",
     r"an effect other than the background named in (\d+) of (\d+)", 0.0, True),
    ("dry friction unexplained or held-out gains under 30 %",
     r"held-out gains under 30 % in (\d+) of (\d+)", 1.0, False),
)


def wilson_interval(k: int, n: int, z: float = Z95) -> tuple[float, float]:
    r"""The Wilson score interval of a binomial proportion [-] (Wilson 1927, J. Am. Stat.
    Assoc. 22:209-212; Newcombe 1998, Stat. Med. 17:857-872, method 3):

    .. math:: \frac{\hat p + z^2/2n \pm z\sqrt{\hat p(1-\hat p)/n + z^2/4n^2}}{1 + z^2/n},
              \quad \hat p = k/n

    ``k`` successes of ``n`` trials, ``z`` the normal quantile (95 %: 1.96). Unlike the
    Wald interval it stays inside [0, 1] and is not empty at k = 0 or k = n."""
    if n <= 0 or not 0 <= k <= n:
        raise ValueError(f"wilson_interval: k={k}, n={n}; expected 0 <= k <= n and n > 0")
    p = k / n
    den = 1.0 + z * z / n
    mid = (p + z * z / (2 * n)) / den
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / den
    return max(0.0, mid - half), min(1.0, mid + half)


def counts(text: str) -> dict:
    """Each criterion's (count, total) from a run's summary text; a criterion the text lacks
    is left out."""
    out = {}
    for name, pattern, _, _ in CRITERIA:
        m = re.search(pattern, text)
        if m:
            out[name] = (int(m.group(1)), int(m.group(2)))
    return out


def _cell(k: int, n: int) -> str:
    lo, hi = wilson_interval(k, n)
    return f"{k}/{n} ({100 * k / n:.0f} %; {100 * lo:.0f}-{100 * hi:.0f} %)"


def _verdict(k: int, n: int, bar: float | None, lower_better: bool) -> str:
    if bar is None:
        return "-"
    lo, hi = wilson_interval(k, n)
    rate = k / n
    met = rate <= bar if lower_better else rate >= bar
    if met:
        return "met"
    sure = lo > bar if lower_better else hi < bar
    return "missed" + (" (interval beyond the bar)" if sure else " (interval reaches the bar)")


def table(texts: dict) -> str:
    """The markdown table of the criteria for the runs ``{label: summary text}``."""
    runs = {label: counts(text) for label, text in texts.items()}
    labels = list(runs)
    lines = ["| criterion | issue's bar | " + " | ".join(
        f"{label}: count (rate; Wilson 95 %) | verdict" for label in labels) + " |",
        "| --- | --- | " + " | ".join("--- | ---" for _ in labels) + " |"]
    for name, _, bar, lower in CRITERIA:
        if not all(name in runs[label] for label in labels):
            continue
        bar_text = "-" if bar is None else (f"<= {100 * bar:.0f} %" if lower
                                            else f">= {100 * bar:.0f} %")
        cells = []
        for label in labels:
            k, n = runs[label][name]
            cells.append(f"{_cell(k, n)} | {_verdict(k, n, bar, lower)}")
        lines.append(f"| {name} | {bar_text} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def pair_table(pairs: dict) -> str:
    """The markdown table of the criteria for pairs of runs ``{label: (base text, other
    text)}`` (two configurations of one seed, e.g. the default and an option): per pair,
    ``k_base -> k_other of n`` and the two Wilson intervals; with several pairs, a last column
    ``pooled``: the counts and totals summed over the pairs (the seeds' logs are independent
    draws). A criterion either side lacks is left out; two totals that differ are both shown."""
    runs = {label: (counts(a), counts(b)) for label, (a, b) in pairs.items()}
    if len(runs) > 1:
        both = [name for name, _, _, _ in CRITERIA
                if all(name in a and name in b for a, b in runs.values())]
        runs["pooled"] = tuple(
            {name: tuple(sum(runs[label][side][name][j] for label in pairs) for j in (0, 1))
             for name in both} for side in (0, 1))
    labels = list(runs)
    lines = ["| criterion | issue's bar | " + " | ".join(
        f"{label}: base -> other (Wilson 95 %)" for label in labels) + " |",
        "| --- | --- | " + " | ".join("---" for _ in labels) + " |"]
    for name, _, bar, lower in CRITERIA:
        if not all(name in a and name in b for a, b in runs.values()):
            continue
        bar_text = "-" if bar is None else (f"<= {100 * bar:.0f} %" if lower
                                            else f">= {100 * bar:.0f} %")
        cells = []
        for label in labels:
            (k0, n0), (k1, n1) = runs[label][0][name], runs[label][1][name]
            (a0, b0), (a1, b1) = wilson_interval(k0, n0), wilson_interval(k1, n1)
            of = f" of {n0}" if n0 == n1 else f"/{n0} -> {k1}/{n1}"
            head = f"{k0} -> {k1}{of}" if n0 == n1 else f"{k0}{of}"
            cells.append(f"{head} ({100 * a0:.0f}-{100 * b0:.0f} % -> "
                         f"{100 * a1:.0f}-{100 * b1:.0f} %)")
        lines.append(f"| {name} | {bar_text} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _labelled(arg: str, text: str) -> tuple[str, str]:
    """``(label, path)`` of a ``LABEL=PATH`` argument; a bare path's label is the seed its
    ``text`` names (or the path)."""
    if "=" in arg:
        label, path = arg.split("=", 1)
        return label, path
    m = re.search(r"^Seed (\d+)", text, flags=re.M)
    return (f"seed {m.group(1)}" if m else arg), arg


def row_failures(row: dict) -> list[str]:
    """The criteria one row of ``diagnose_independent`` (its ``row`` JSON) fails, each as a
    short text: a library effect not named first (what was named), its magnitude beyond
    15 %, its error cut under 3x where the truth's own is at least 3x, a whole-log spurious
    step named (kept); a clean log naming an effect other than the background; dry friction
    neither unexplained nor under 30 % of held-out gain. The rules are the benchmark's own
    (``benchmarks.diagnose_independent``)."""
    from benchmarks.diagnose_independent import _spurious, background, spurious_steps
    from validation.independent import OUTSIDE, STRENGTHS
    out = []
    cat = row["category"]
    if cat in STRENGTHS:
        if row["first"] != cat:
            out.append(f"named first {row['first']}")
        err = row.get("magnitude_error")
        if err is None or not err <= 0.15:
            out.append("magnitude " + ("not claimed" if row.get("magnitude_not_claimed")
                                       else "none" if err is None else f"{100 * err:.0f} %"))
        if row["cut"] < 3 and row.get("truth_cut", 0.0) >= 3:
            out.append(f"cut {row['cut']:.2f} (truth's {row['truth_cut']:.2f})")
        if row["mode"] == "all" and _spurious(row, "step_effects"):
            out += [s.split(": ", 1)[1] for s in spurious_steps([row])]
    elif cat == "clean":
        other = [f"{d} {e}" for d, es in row.get("step_effects", {}).items() for e in es
                 if not background(row, d, e)]
        if other:
            out.append("clean names " + ", ".join(other))
    elif cat in OUTSIDE:
        if not (row["unexplained"] or row["max_gain"] < 0.3):
            out.append(f"{cat} explained by {row['first']} (held-out gain "
                       f"{100 * row['max_gain']:.0f} %)")
    return out


def main(argv=None) -> int:
    from stripcoef.files import read_text
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="*", help="markdown outputs of diagnose_independent --write")
    ap.add_argument("--rows", default=None,
                    help="a run's printed output (its 'row' lines): list each row's failed "
                         "criteria instead")
    ap.add_argument("--pairs", action="store_true",
                    help="the files are pairs (base, other) of the same seeds: base -> other "
                         "per criterion")
    args = ap.parse_args(argv)
    if args.rows:
        import json
        rows = [json.loads(line.split(" row ", 1)[1])
                for line in read_text(args.rows, kind="benchmark output").splitlines()
                if " row {" in line]
        # rows of runs before fresh33f: magnitudes in the written model's units
        from benchmarks.diagnose_independent import converted_rows
        rows = converted_rows(rows)
        for r in sorted(rows, key=lambda r: (r["category"], r["vehicle"], r["seed"], r["mode"])):
            fails = row_failures(r)
            if fails:
                print(f"- {r['category']} {r['vehicle']} {r['seed']} {r['mode']}: "
                      + "; ".join(fails))
        return 0
    def _read(arg):
        text = read_text(arg.split("=", 1)[1] if "=" in arg else arg, kind="benchmark output")
        return _labelled(arg, text)[0], text

    if args.pairs:
        if len(args.files) % 2:
            print(f"fresh_compare: --pairs needs an even number of files, got "
                  f"{len(args.files)}")
            return 2
        pairs = {}
        for base, other in zip(args.files[::2], args.files[1::2]):
            label, a = _read(base)
            pairs[label] = (a, _read(other)[1])
        print(pair_table(pairs))
        return 0
    texts = {}
    for arg in args.files:
        label, text = _read(arg)
        texts[label] = text
    print(table(texts))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
