"""Validation section: thin plates and wings against Capytaine (issue 32).

The stored run is ``benchmarks/data/thin_members.md``, written by ``python -m
benchmarks.thin_members --out benchmarks/data/thin_members.md`` (a fresh seed per run), shown
here as measured.
"""

from __future__ import annotations

from validation import ROOT

STORED = ROOT / "benchmarks" / "data" / "thin_members.md"


def section() -> str:
    if not STORED.exists():
        return ""
    return "\n".join([
        "## Thin plates and wings against Capytaine (issue 32)", "",
        "`benchmarks/thin_members.py` draws rectangular plates (t/a 0.01 to 0.05, b/a 1 to 4) "
        "and wings of NACA 00xx section (t/c 0.01 to 0.05, a knife-edge trailing edge, span "
        "1.5 to 5 chords), runs the default panel method on each (the isotropic remesh family, "
        "refined while a term's estimated error exceeds 5 %) and compares it with Capytaine "
        "(direct method, no free surface): a plate on a remesh family at the command's face "
        "counts, a wing on structured panellings (cosine-spaced section, span stations about "
        "the chordwise spacing apart: the panelling of wing panel methods, Katz & Plotkin 2001, "
        "sec. 11.1), the two finest Richardson-extrapolated. Each diagonal term's error over "
        "itself (a term under 1 % of the largest of its block over that 1 %). Plates are "
        "followed by the remesher (their rims kept as creases). A wing is not: where its "
        "section is thinner than the edge (the knife-edge trailing edge) the remesher's "
        "collapses cut it off, the remesh loses planform area (4.5 % at 3200 panels) and "
        "volume beyond the family's 2 %, the family is refused, and the panel method falls "
        "back to the input's faces refined (one span-long strip per section point): an open "
        "failure of issue 32. The stored run:",
        "", STORED.read_text().strip(), ""])
