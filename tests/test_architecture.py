"""The layer contract of docs/architecture.md holds: imports run one way, down the pipeline.

- import-linter's contracts (pyproject.toml, ``[tool.importlinter]``): each layer imports only
  from the layers below it; the runtime package never imports ``validation``;
- no import cycles at all, between modules of one layer either;
- no CLI vocabulary below the CLI: library errors name parameters (``radii``), and the CLI
  rewords them into its flags (``--radii``).
"""

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SRC = ROOT / "src" / "stripcoef"


def test_import_contracts_hold():
    exe = shutil.which("lint-imports", path=str(Path(sys.executable).parent))
    if exe is None:
        pytest.fail("lint-imports not installed: pip install -e '.[test]'")
    env = {"PYTHONPATH": f"{ROOT / 'src'}:{ROOT}", "PATH": str(Path(sys.executable).parent)}
    run = subprocess.run([exe, "--config", str(ROOT / "pyproject.toml")], cwd=ROOT, env=env,
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-2000:]
    assert "0 broken" in run.stdout


def test_no_import_cycles():
    import grimp
    import networkx as nx

    graph = grimp.build_graph("stripcoef")
    g = nx.DiGraph()
    for module in graph.modules:
        for imported in graph.find_modules_directly_imported_by(module):
            # a package's __init__ re-exporting its own modules is not a cycle of the pipeline
            if not imported.startswith(module + "."):
                g.add_edge(module, imported)
    cycles = list(nx.simple_cycles(g))
    assert not cycles, cycles[:5]


def test_no_cli_flags_below_the_cli():
    offenders = []
    for path in SRC.rglob("*.py"):
        if path.parent.name == "cli":
            continue
        for n, line in enumerate(path.read_text().splitlines(), 1):
            if re.search(r"""key=f?["']--""", line):
                offenders.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()}")
    assert not offenders, "\n".join(offenders)


def test_the_cli_names_its_flag_for_a_library_parameter(capsys):
    from stripcoef.cli import main

    assert main(["limits", str(ROOT / "geometry" / "mares.yaml"), "--radii", "5:1:3"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("stripcoef limits: error: --radii:") and "\n" not in err
