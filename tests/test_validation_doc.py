"""docs/validation.md is what scripts/make_validation.py writes from the code as it is now.

Every word the same, and every number within one unit of its last printed digit: the documents
print 4-5 significant digits of results whose last bits depend on the machine's BLAS kernels, so
a rounding may flip.  A claim that changed with the code (a number, a "grows" that no longer
holds) fails here until the document is generated again.

The document is checked one section at a time (``validation.SECTIONS``, one ``## `` part of the
document each), so that the sections regenerate in parallel on the test workers; together the
tests cover every line that ``validation.build()`` writes.  A section whose results a topic's
test module computes anyway is checked there (:data:`ELSEWHERE`), from the same results.
"""

from __future__ import annotations

import contextlib
import importlib
import re
from pathlib import Path

import pytest

from validation import SECTIONS, build

ROOT = Path(__file__).resolve().parent.parent
#: the expensive sections (measured: docs/development.md; cad_shapes 3.8 s of CPU, -n 0; lift
#: is checked in tests/test_lift_data.py, :data:`ELSEWHERE`)
SLOW = {"drag", "cad_shapes"}

#: a number as the documents print it: sign (ASCII or the minus sign), digits (with thousands
#: commas), decimals, exponent
NUMBER = re.compile(r"[-+\u2212]?(?:\d{1,3}(?:,\d{3})+|\d+)(?:\.\d+)?(?:[eE][-+]?\d+)?")


def _value(token: str):
    try:
        return float(token.replace("\u2212", "-").replace(",", ""))
    except ValueError:
        return None


def _close(a: str, b: str) -> bool:
    """Two printed numbers agree within one unit of the last printed decimal (relative 1e-3 in
    exponent notation); integers (counts, mesh sizes) must be equal."""
    if a == b:
        return True
    va, vb = _value(a), _value(b)
    if va is None or vb is None:
        return False
    if "e" in (a + b).lower():
        return abs(va - vb) <= 1e-3 * max(abs(va), abs(vb))
    decimals = max(len(t.split(".")[1]) if "." in t else 0 for t in (a, b))
    return va == vb or (decimals > 0 and abs(va - vb) <= 1.01 * 10.0 ** -decimals)


def stale_lines(stored: str, fresh: str) -> list:
    """(line number, stored line, fresh line) of every line whose words or numbers differ."""
    out = []
    old, new = stored.splitlines(), fresh.splitlines()
    if len(old) != len(new):
        return [(0, f"{len(old)} lines", f"{len(new)} lines")]
    for k, (a, b) in enumerate(zip(old, new), start=1):
        if a == b:
            continue
        if NUMBER.sub("#", a) != NUMBER.sub("#", b) or not all(
                _close(x, y) for x, y in zip(NUMBER.findall(a), NUMBER.findall(b))):
            out.append((k, a, b))
    return out


def test_the_comparison_allows_a_rounding_and_nothing_else():
    assert not stale_lines("x = 0.4062, y = +2.73 %", "x = 0.4063, y = +2.72 %")
    assert stale_lines("x = 0.4062", "x = 0.4064")
    assert stale_lines("the coupling grows", "the coupling falls")
    assert not stale_lines("1,600 panels, 1e-06", "1,600 panels, 1.0005e-06")
    assert stale_lines("mesh 16,4,16", "mesh 16,4,17")
    assert stale_lines("a\nb", "a")


def stored_parts(text: str) -> list:
    """The stored document cut before each line that starts with ``## ``: the title and its
    introduction, then one part per section (trailing blank lines dropped)."""
    parts, current = [], []
    for line in text.splitlines():
        if line.startswith("## "):
            parts.append(current)
            current = []
        current.append(line)
    parts.append(current)
    return ["\n".join(p).rstrip() + "\n" for p in parts]


def _stale(name, stored, fresh):
    stale = stale_lines(stored, fresh)
    assert not stale, (f"docs/validation.md, section {name!r}, is stale: run python -m "
                       f"scripts.make_validation; first difference at line {stale[0][0]} of "
                       f"the section:\n{stale[0][1]}\n{stale[0][2]}")


def test_the_document_has_the_introduction_and_one_part_per_section(monkeypatch):
    """The title and introduction that ``build()`` writes (run with no section), and as many
    ``## `` parts as sections: with the test below, every line of the document is checked."""
    import validation

    parts = stored_parts((ROOT / "docs" / "validation.md").read_text())
    assert len(parts) == 1 + len(SECTIONS), \
        f"{len(parts) - 1} sections in docs/validation.md, {len(SECTIONS)} in validation.SECTIONS"
    monkeypatch.setattr(validation, "SECTIONS", ())
    _stale("introduction", parts[0], build().rstrip() + "\n")


def assert_section_is_current(name, **section_args):
    """The stored section ``name`` of docs/validation.md is what its module writes now
    (``section(**section_args)``)."""
    k = SECTIONS.index(name)
    stored = stored_parts((ROOT / "docs" / "validation.md").read_text())
    assert len(stored) == 1 + len(SECTIONS)
    fresh = importlib.import_module(f"validation.{name}").section(**section_args).rstrip() + "\n"
    _stale(name, stored[1 + k], fresh)


#: Sections checked in the test module that computes the same results (a module fixture or the
#: section's own cache, computed once for both on one worker): section -> (module, test).
ELSEWHERE = {
    "cfd": ("test_damping_rotation", "test_validation_doc_cfd_section_is_current"),
    "diagnosis": ("test_diagnose_papers", "test_validation_doc_diagnosis_section_is_current"),
    "fins": ("test_fin_plate", "test_validation_doc_fins_section_is_current"),
    "lift": ("test_lift_data", "test_validation_doc_lift_section_is_current"),
    "rotary_trace": ("test_rotary_trace", "test_validation_doc_rotary_trace_section_is_current"),
    "fin_incidence": ("test_fin_incidence",
                      "test_validation_doc_fin_incidence_section_is_current"),
    "identification": ("test_identify_romeo_simulated",
                       "test_validation_doc_identification_section_is_current"),
    "meshes": ("test_mesh_consistency", "test_validation_doc_meshes_section_is_current"),
    "vehicle_surface": ("test_vehicle_surface",
                        "test_validation_doc_vehicle_surface_section_is_current"),
}


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW else n
                                  for n in SECTIONS if n not in ELSEWHERE])
def test_validation_doc_section_is_generated_from_the_current_code(name, monkeypatch):
    if name in PANEL_FAMILY:
        with _base_panel_family(name, monkeypatch):
            assert_section_is_current(name)
        return
    assert_section_is_current(name)


#: Sections whose numbers are a bluff vehicle file's 3D panel solve, whose levels are the
#: input's faces refined (the base install, as CI runs and as the document is written) or,
#: with the ``remesh`` extra, isotropic remeshes: other levels, other numbers within their
#: estimated error (tests/test_golden.py checks the VideoRay's remeshed M_A against the base
#: family's within the two estimated errors).
PANEL_FAMILY = {"videoray"}


@contextlib.contextmanager
def _base_panel_family(name, monkeypatch):
    """The section ``name`` computed as the base install computes it: the remesher (the
    ``remesh`` extra) hidden, the module's cached results cleared before and after."""
    from stripcoef.hull import remesh

    if not remesh.available():
        yield
        return
    module = importlib.import_module(f"validation.{name}")
    caches = [f for f in vars(module).values() if callable(getattr(f, "cache_clear", None))]
    for f in caches:
        f.cache_clear()
    monkeypatch.setattr(remesh, "available", lambda: False)
    try:
        yield
    finally:
        monkeypatch.undo()
        for f in caches:
            f.cache_clear()


def test_every_section_is_checked_somewhere():
    """The sections left out of the test above have their check in the test module that
    computes the same results."""
    for name, (module, test) in ELSEWHERE.items():
        assert name in SECTIONS, name
        assert callable(getattr(importlib.import_module(module), test, None)), (name, test)
