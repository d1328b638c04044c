"""Validation section: internal consistency of the published reference tables."""

from __future__ import annotations

from validation import reference
from validation import markdown_table


def section() -> str:
    """Markdown: every cross-check of :data:`validation.reference.CHECKS`, printed vs recomputed."""
    def esc(text):
        return str(text).replace("|", "\\|")

    rows = []
    for r in reference.check_results():
        c = r["check"]
        p = r["printed"]
        status = "agrees" if r["agrees"] else "**differs**"
        if c.mismatch and r["agrees"]:
            status = "agrees (listed as a mismatch: update CHECKS)"
        rows.append([c.source, f"`{c.printed}`", p["value_text"], f"`{c.computed}`", f"{r['computed']:.5g}",
                     f"{100 * r['relative_difference']:+.2f}%", status, esc(c.mismatch or "")])
    table = markdown_table(["source", "printed row", "printed", "recomputed row", "recomputed", "diff",
                            "result", "known inconsistency"], rows)
    return ("## Reference tables: internal consistency of the papers\n\n"
            "Each published number that a paper's own inputs determine, recomputed from those inputs "
            "(`reference_tables/`, `validation.reference.CHECKS`; agreement = within the printed precision). "
            "What each table holds and the full list of inconsistencies: `docs/reference-tables.md`.\n\n"
            + table + "\n")
