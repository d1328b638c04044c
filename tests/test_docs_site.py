"""The documentation site builds with warnings as errors (mkdocs --strict): every page in the
nav, every link and anchor resolved, every docstring of the API reference parsed."""

import os
import subprocess
import sys
from importlib.util import find_spec

import pytest

from conftest import ROOT

# found, not imported: the build runs in a subprocess, and importing mkdocs, mkdocstrings
# and material cost each test worker about 0.5 s of CPU while collecting
_MISSING = [name for name in ("mkdocs", "mkdocstrings", "material") if find_spec(name) is None]
if _MISSING:
    pytest.skip(f"not installed: {', '.join(_MISSING)}", allow_module_level=True)


@pytest.mark.slow
def test_site_builds_strictly(tmp_path):
    env = {**os.environ, "NO_MKDOCS_2_WARNING": "1",
           "PYTHONPATH": os.pathsep.join([str(ROOT / "src"), str(ROOT)])}
    out = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-f",
                          str(ROOT / "mkdocs.yml"), "-d", str(tmp_path / "site")],
                         capture_output=True, text=True, env=env, timeout=600, cwd=ROOT)
    assert out.returncode == 0, out.stderr[-4000:]
    site = tmp_path / "site"
    for page in ("index.html", "tutorial/index.html", "api/index.html",
                 "export/gazebo/index.html"):
        assert (site / page).is_file(), page
    api = (site / "api" / "index.html").read_text()
    assert "HydroModel" in api and "summarize_motion" in api and "load_vehicle" in api
    # the docstrings' reST is rendered (scripts/docs_hooks.py), never shown raw, on any page
    import re
    raw = re.compile(r":(?:math|func|class|meth|mod|data|attr|obj|exc):`?<code>|\.\. math::")
    for page in site.rglob("*.html"):
        hit = raw.search(page.read_text())
        assert hit is None, f"{page.relative_to(site)}: raw reST {hit.group(0)!r}"
    assert 'class="arithmatex"' in api
