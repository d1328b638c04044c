"""Whole-log rows of ``benchmarks.diagnose_independent`` outputs paired by log seed, issue 33's
criteria per row and per vehicle (linked33f: ``linked_gains="identified"`` against the default
and against ``linked_gains=True``).

    python -m benchmarks.linked33f_compare DEFAULT.log LINKED.log IDENTIFIED.log [...]
        [--labels default,linked,identified]

Each file is the standard output of a ``diagnose_independent`` run (its ``row {...}`` lines);
only the whole-log rows (``mode`` "all") are read, and only the logs every file has are
paired. Per row the criteria are those of ``benchmarks.fresh_compare.row_failures`` and of
``diagnose_independent``'s spurious-step rule (:func:`benchmarks.diagnose_independent._spurious`):
library effect named first, magnitude within 15 %, error cut >= 3x, spurious step named /
kept (library-effect logs); nothing but the truth's background named (clean logs); 'unexplained'
or held-out gain under 30 % (dry friction). Printed: each row whose status differs between
the files, with its failures and, where the row has it, ``gain_links`` (the identified mode's
information ratio of each pair of thruster groups); then the counts per vehicle.
"""

from __future__ import annotations

import argparse
import json
import re

from benchmarks.diagnose_independent import _spurious, background
from benchmarks.fresh_compare import row_failures

#: (key, criterion)
CRITERIA = (("first", "library effects named first"), ("mag", "magnitude within 15 %"),
            ("cut3", "error cut >= 3x"), ("spur_named", "spurious step named"),
            ("spur_kept", "spurious step kept"),
            ("clean_ok", "clean: nothing but the background"),
            ("dry_ok", "dry friction unexplained or gain < 30 %"))


def read_rows(path: str) -> dict:
    """Log seed -> whole-log row of one output file."""
    out = {}
    with open(path) as fh:
        for line in fh:
            if " row {" in line:
                r = json.loads(line.split(" row ", 1)[1])
                if r["mode"] == "all":
                    out[r["seed"]] = r
    return out


def status(r: dict) -> dict:
    """Criterion key -> passed, for one whole-log row."""
    from validation.independent import OUTSIDE, STRENGTHS

    cat, s = r["category"], {}
    if cat in STRENGTHS:
        s["first"] = r["first"] == cat
        e = r.get("magnitude_error")
        s["mag"] = e is not None and e <= 0.15
        s["cut3"] = r["cut"] >= 3
        s["spur_named"] = bool(_spurious(r, "step_effects"))
        s["spur_kept"] = bool(_spurious(r, "step_effects_kept"))
    elif cat == "clean":
        s["clean_ok"] = not [1 for d, es in r.get("step_effects", {}).items() for e in es
                             if not background(r, d, e)]
    elif cat in OUTSIDE:
        s["dry_ok"] = bool(r["unexplained"] or r["max_gain"] < 0.3)
    return s


def read_decisions(paths) -> dict:
    """Log seed -> (information ratio against the bench band, against the log's spread), from
    ``benchmarks.linked33f_links`` outputs and from identified runs' rows (``gain_links``;
    each shipped vehicle has one pair of default groups)."""
    out = {}
    pat = re.compile(r" (\d+): .* ratio ([0-9.]+) \(spread ([0-9.]+)\)")
    for path in paths:
        with open(path) as fh:
            for line in fh:
                if " row {" in line:
                    r = json.loads(line.split(" row ", 1)[1])
                    if r["mode"] == "all" and r.get("gain_links"):
                        (lk,) = r["gain_links"]
                        out[r["seed"]] = (lk["information_ratio"],
                                          lk["information_ratio_spread"])
                elif (m := pat.search(line)):
                    out[int(m.group(1))] = (float(m.group(2)), float(m.group(3)))
    return out


def compose(default: dict, linked: dict, decisions: dict, which: int) -> tuple:
    """``(rows, missing)``: the identified mode's whole-log rows composed from the default's
    and ``linked_gains=True``'s: with two default groups the identified row *is* one of them
    (the linked one where the pair's ratio, ``decisions[seed][which]``, is at least 1), the
    rest of the diagnosis being the same code on the same groups (checked row for row by
    ``--check``). A log whose two rows pass the same criteria takes the default's (its
    status is the same either way); ``missing``: logs whose rows differ and which have no
    decision."""
    rows, missing = {}, []
    for sd in sorted(set(default) & set(linked)):
        if sd in decisions:
            rows[sd] = linked[sd] if decisions[sd][which] >= 1.0 else default[sd]
        elif status(default[sd]) == status(linked[sd]):
            rows[sd] = default[sd]
        else:
            missing.append(sd)
    return rows, missing


def _links(r: dict) -> str:
    return "; ".join(f"{'+'.join(a)} vs {'+'.join(b)} via {','.join(lk['dofs'])}: ratio "
                     f"{lk['information_ratio']:.2f}{' linked' if lk['linked'] else ''}"
                     for lk in r.get("gain_links") or () for a, b in [lk["groups"]])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="+")
    ap.add_argument("--labels", default=None, help="comma-separated, one per file")
    ap.add_argument("--compose", default=None,
                    help="comma-separated linked33f_links outputs or identified runs: the "
                         "files must be DEFAULT LINKED; adds the identified mode's rows "
                         "composed from them (bench band) and the same with the spread's "
                         "ratio (recorded, not the rule)")
    ap.add_argument("--check", action="store_true",
                    help="with --compose: each identified run's row against the row it "
                         "is composed of, every field but the timings")
    args = ap.parse_args(argv)
    labels = args.labels.split(",") if args.labels else [f"run{k}" for k in
                                                         range(len(args.files))]
    if len(labels) != len(args.files):
        ap.error(f"--labels: {len(labels)} labels for {len(args.files)} files")
    runs = [read_rows(p) for p in args.files]
    decisions = {}
    if args.compose:
        if len(runs) != 2:
            ap.error("--compose: give the files DEFAULT LINKED")
        paths = args.compose.split(",")
        decisions = read_decisions(paths)
        for which, label in ((0, "identified"), (1, "spread-ratio")):
            rows, missing = compose(runs[0], runs[1], decisions, which)
            if missing:
                print(f"{label}: no decision for {len(missing)} logs whose rows differ: "
                      + ",".join(map(str, missing)))
            runs.append(rows)
            labels.append(label)
        if args.check:
            for path in paths:
                for sd, r in read_rows(path).items():
                    ref = runs[2][sd]
                    bad = [k for k in r if k not in ("t_simulate", "t_diagnose", "gain_links")
                           and r[k] != ref.get(k)]
                    print(f"check {sd}: identified run's row "
                          + ("equals" if not bad else f"differs ({', '.join(bad)}) from")
                          + " the composed row ("
                          + ("linked" if ref is runs[1][sd] else "default") + "'s)")
    common = sorted(set.intersection(*(set(r) for r in runs)))
    print(f"common whole-log rows: {len(common)} ("
          + ", ".join(f"{lb} {len(r)}" for lb, r in zip(labels, runs)) + ")")
    tot = {}
    for sd in common:
        rows = [r[sd] for r in runs]
        st = [status(r) for r in rows]
        for k in st[0]:
            for v in (rows[0]["vehicle"], "both"):
                x = tot.setdefault((v, k), [0] * (len(runs) + 1))
                for j, s in enumerate(st):
                    x[j] += s[k]
                x[-1] += 1
        diff = [k for k in st[0] if len({s[k] for s in st}) > 1]
        cuts = " -> ".join(f"{r['cut']:.2f}" for r in rows)
        firsts = " -> ".join(str(r["first"]) for r in rows)
        print(f"{rows[0]['vehicle'][:8]} {rows[0]['category']:22s} {sd} cut {cuts} first "
              f"{firsts}{' CHANGED ' + ','.join(diff) if diff else ''}")
        if diff:
            for lb, r in zip(labels, rows):
                print(f"      {lb}: {'; '.join(row_failures(r)) or '-'}")
        if rows[-1].get("gain_links"):
            print(f"      links ({labels[-1]}): {_links(rows[-1])}")
        if args.compose and sd in decisions:
            print(f"      information ratio {decisions[sd][0]:.3f} (bench band), "
                  f"{decisions[sd][1]:.3f} (the log's spread)")
    print("\n| criterion | vehicle | " + " | ".join(labels) + " |")
    print("| --- | --- |" + " --- |" * len(labels))
    for k, name in CRITERIA:
        for v in ("bluerov2_heavy", "videoray_pro3", "both"):
            x = tot.get((v, k))
            if x:
                print(f"| {name} | {v} | " + " | ".join(f"{c}/{x[-1]}" for c in x[:-1]) + " |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
