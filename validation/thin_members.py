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
        "(direct method, no free surface) on a remesh family at the command's face counts, "
        "or, where the remesher cannot follow the member (a trailing edge thinner than the "
        "edge length is cut off: the remesh loses planform area), on the member's own faces "
        "bisected, the two finest Richardson-extrapolated. Each diagonal term's error over "
        "itself (a term under 1 % of the largest of its block over that 1 %). The stored run:",
        "", STORED.read_text().strip(), ""])
