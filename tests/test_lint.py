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
