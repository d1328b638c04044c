"""The export pages show today's output: docs/export/examples/ is what
scripts/make_export_examples.py writes now, and every number in a page's excerpt is in its
example file (a change of the physics that moves MARES's matrices must regenerate both).

Numbers compare to 1e-12 relative (as tests/test_golden.py: another CPU's BLAS may round the
last bits differently); everything else exactly."""

import importlib
import re
import warnings

import pytest

from conftest import ROOT

EXAMPLES = ROOT / "docs" / "export" / "examples"
NUMBER = re.compile(r"-?\d+\.\d{6,}(?:e-?\d+)?")
ANY_NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:e-?\d+)?")
PAGES = {"gazebo.md": "mares.sdf", "uuv.md": "mares_uuv.xml", "mss.md": "mares.m"}


def _script():
    return importlib.import_module("scripts.make_export_examples")


def _same(name, got, want):
    """Equal text with numbers equal to 1e-12 relative."""
    g, w = ANY_NUMBER.split(got), ANY_NUMBER.split(want)
    assert g == w, f"{name}: run python -m scripts.make_export_examples"
    for a, b in zip(ANY_NUMBER.findall(got), ANY_NUMBER.findall(want)):
        assert abs(float(a) - float(b)) <= 1e-12 * max(abs(float(b)), 1.0), \
            f"{name}: {a} != {b}; run python -m scripts.make_export_examples"


def test_examples_are_the_current_output(tmp_path, monkeypatch):
    import stripcoef
    from stripcoef.export import write_export

    mod = _script()
    monkeypatch.chdir(ROOT)          # as the script: provenance "geometry/mares.yaml"
    model = stripcoef.estimate(stripcoef.load_vehicle("geometry/mares.yaml"))
    for name, fmt, options in mod.EXAMPLES:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            write_export(model, fmt, tmp_path / name, **options)
        _same(name, (tmp_path / name).read_text(), (EXAMPLES / name).read_text())


@pytest.mark.parametrize("page,example", sorted(PAGES.items()))
def test_excerpt_numbers_are_in_the_example(page, example):
    text = (ROOT / "docs" / "export" / page).read_text()
    excerpt = text[text.index("## Example"):]
    numbers = NUMBER.findall(excerpt)
    assert len(numbers) >= 4
    source = [float(v) for v in ANY_NUMBER.findall((EXAMPLES / example).read_text())]
    missing = [n for n in numbers
               if not any(abs(float(n) - v) <= 1e-12 * max(abs(v), 1.0) for v in source)]
    assert not missing, f"{page}: excerpt numbers not in examples/{example}: {missing}"
