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
        "followed by the remesher (their rims kept as creases). A wing's knife-edge trailing "
        "edge is where the remesher's edge flips join the two faces of the thin wedge and its "
        "collapses then cut it off (5-8 % of the whole area lost with flips): a remesh level "
        "whose area moves by more than 1 % is refused and remeshed without flips under a "
        "tighter surface-distance bound, and where no remesh keeps the area the levels are "
        "the input's faces split along their longest edges, with a warning "
        "(`hull.remesh`; `python -m benchmarks.remesh_choice --knife`). The wings' sway and "
        "roll are then within 2.6 % and 9.1 % (they were +5 to +8.5 % and +25 to +32 % when "
        "the trailing edge was cut); yaw of the thinnest wing (t/c 0.017) is +8.3 % and roll "
        "of the t/c 0.046 wing +9.1 %, both inside the estimated error, against Capytaine "
        "references whose own estimated error is 24-27 %. The stored run:",
        "", STORED.read_text().strip(), ""])
