"""The export pages show today's output: docs/export/examples/ is what
scripts/make_export_examples.py writes now, and every number in a page's excerpt is in its
example file (a change of the physics that moves MARES's matrices must regenerate both).

The examples compare as parsed numbers, not bytes (conftest.assert_same_file): JSON and YAML
as data, CSV by cell, the other formats as text whose words must be equal (a run of whitespace
counts as one space: a longer number may wrap a YAML line elsewhere) and whose numbers must be
within 1e-9 of the largest magnitude of their matrix, column or block of lines (conftest.RTOL).
Another CPU, BLAS or numpy/scipy release rounds the last bits of MARES's matrices differently;
a change of the physics moves them by far more."""

import importlib
import re
import warnings

import pytest

from conftest import ROOT, assert_same_file

EXAMPLES = ROOT / "docs" / "export" / "examples"
NUMBER = re.compile(r"-?\d+\.\d{6,}(?:e-?\d+)?")
ANY_NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:e-?\d+)?")
PAGES = {"gazebo.md": "mares.sdf", "uuv.md": "mares_uuv.xml", "mss.md": "mares.m"}


def _script():
    return importlib.import_module("scripts.make_export_examples")


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
        assert_same_file(name, (tmp_path / name).read_text(), (EXAMPLES / name).read_text(),
                         hint="; run python scripts/make_export_examples.py")


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


def test_the_comparison_allows_round_off_and_nothing_else():
    """assert_same_file passes a re-wrapped line and last-bit round-off, and fails a changed
    word, a changed number of numbers, and a change of 1e-8 of a matrix's scale."""
    from conftest import assert_same_file

    want = "m: [41.036429297212806, 7.994691826494531e-09,\n  0.15]\n# mass 41.3 kg\n"
    assert_same_file("a.yaml", "m: [41.036429297212806, 7.994691826e-09, 0.15]\n# mass 41.3 kg\n",
                     want)
    with pytest.raises(AssertionError):
        assert_same_file("a.yaml", want.replace("41.036429297212806", "41.03643"), want)
    with pytest.raises(AssertionError):
        assert_same_file("a.yaml", want.replace("kg", "g"), want)
    xml = "<xx>41.036429297212806</xx>\n<xy>7.994691826494531e-09</xy>\n"
    assert_same_file("a.sdf", xml.replace("7.994691826494531e-09", "0"), xml)
    assert_same_file("a.sdf", xml.replace("<xy>", " <xy>"), xml)
    for bad in (xml.replace("<xy>", "<yx>"), xml.replace("41.036429297212806", "41.0364297"),
                xml + "<xz>0</xz>\n"):
        with pytest.raises(AssertionError):
            assert_same_file("a.sdf", bad, xml)
    csv = "quantity,row,col,value\nadded_mass,0,0,41.0\nadded_mass,0,1,8e-09\nmass,,,1.5e6\n"
    assert_same_file("a.csv", csv.replace("8e-09", "8.1e-09"), csv)
    with pytest.raises(AssertionError):
        assert_same_file("a.csv", csv.replace("8e-09", "1e-06"), csv)
    with pytest.raises(AssertionError):
        assert_same_file("a.csv", csv.replace("added_mass,0,1", "added_mass,1,0"), csv)
