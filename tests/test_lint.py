"""The tree has no undefined or unused names and no syntax errors (ruff's F and E9 rules,
configured in pyproject.toml [tool.ruff.lint])."""

import subprocess
import sys

import pytest

from conftest import ROOT


def test_ruff_finds_no_defects():
    pytest.importorskip("ruff")
    proc = subprocess.run([sys.executable, "-m", "ruff", "check", "--no-cache",
                           "--output-format", "concise", "src", "tests", "validation",
                           "scripts", "benchmarks"],
                          cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-2000:]


def test_no_control_characters_in_sources():
    """A backslash sequence typed into a non-raw string and written back (\\b, \\f, \\r, \\a,
    \\v) leaves a control character in the file and garbles the formula it was part of
    (found in three docstrings: \\begin, \\frac, \\rho, \\alpha)."""
    bad = []
    for folder in ("src", "tests", "validation", "scripts", "benchmarks"):
        for path in sorted((ROOT / folder).rglob("*.py")):
            text = path.read_bytes()
            hits = [c for c in text if c < 32 and c not in (9, 10)]
            if hits:
                bad.append(f"{path.relative_to(ROOT)}: {sorted(set(hits))}")
    assert not bad, "\n".join(bad)
