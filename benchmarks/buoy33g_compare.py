"""Issue 33 (buoy33g): a run of ``benchmarks.diagnose_independent`` restricted to some
categories, side by side with the stored full run of the same seed, category by category.

Both are read from their summary text (the markdown a ``--write`` wrote, or the run's printed
output): each category's table row per mode (named first, ..., spurious kept), the spurious
whole-log steps of that category's logs (vehicle, category, seed: DOF effect, ``*`` kept) and
the clean logs' line. Nothing is recomputed; the stored table covers every category, the run
only the ones it was given, so only those rows are compared::

    python -m benchmarks.buoy33g_compare benchmarks/data/diagnose_independent_fresh2.md \\
        RUN_OUTPUT.txt --categories linear_drag,clean,tether_drag --modes all
"""

from __future__ import annotations

import argparse
import re

from stripcoef.files import read_text

#: One spurious whole-log step in a summary's list (``summarise``)
SPURIOUS = re.compile(r"(videoray_pro3|bluerov2_heavy) (\w+) (\d+): "
                      r"((?:\w+ \w+\*?(?: \([^)]*\))?(?:, )?)+)")
#: One step of a log's entry: DOF, effect, ``*`` when kept
STEP = re.compile(r"(\w+) (\w+)(\*?)(?: \([^)]*\))?(?:, |$)")


def table_rows(text: str, categories, modes) -> dict:
    """{(category, mode): [cells]} of the summary's table for those categories and modes."""
    out = {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) > 3 and cells[0] in categories and cells[1] in modes:
            out[(cells[0], cells[1])] = cells[2:]
    return out


def header(text: str) -> list:
    """The table's column names after ``effect | mode``."""
    for line in text.splitlines():
        if line.startswith("| effect | mode |"):
            return [c.strip() for c in line.strip().strip("|").split("|")][2:]
    return []


def spurious(text: str, categories) -> list:
    """The spurious whole-log steps of logs of ``categories``: (vehicle, category, seed, DOF,
    effect, kept)."""
    for line in text.splitlines():
        if line.startswith("Spurious whole-log steps"):
            return [(v, c, int(s), d, e, bool(k)) for v, c, s, steps in SPURIOUS.findall(line)
                    if c in categories for d, e, k in STEP.findall(steps)]
    return []


def clean_line(text: str) -> str:
    """The summary's clean-logs line ('' without one)."""
    return next((line for line in text.splitlines() if line.startswith("Clean logs:")), "")


def compare(stored: str, run: str, categories, modes) -> str:
    """The markdown comparison of the two summaries for ``categories`` and ``modes``."""
    cols = header(run) or header(stored)
    a, b = table_rows(stored, categories, modes), table_rows(run, categories, modes)
    lines = ["| category | mode | " + " | ".join(cols) + " |",
             "|" + " --- |" * (len(cols) + 2)]
    for key in sorted(set(a) | set(b)):
        cells = [f"{x} -> {y}" if x != y else x
                 for x, y in zip(a.get(key, ["?"] * len(cols)), b.get(key, ["?"] * len(cols)))]
        lines.append(f"| {key[0]} | {key[1]} | " + " | ".join(cells) + " |")
    for label, text in (("stored", stored), ("run", run)):
        steps = spurious(text, categories)
        lines.append("")
        lines.append(f"Spurious whole-log steps, {label}: " + ("; ".join(
            f"{v} {c} {s}: {d} {e}{'*' if k else ''}" for v, c, s, d, e, k in steps)
            or "none"))
        lines.append(f"{label}: {clean_line(text)}")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("stored", help="the stored run's markdown")
    ap.add_argument("run", help="the restricted run's output or markdown")
    ap.add_argument("--categories", default="linear_drag,clean,tether_drag")
    ap.add_argument("--modes", default="dof,all")
    args = ap.parse_args(argv)
    print(compare(read_text(args.stored, kind="benchmark output"),
                  read_text(args.run, kind="benchmark output"),
                  tuple(args.categories.split(",")), tuple(args.modes.split(","))))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
