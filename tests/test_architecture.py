"""The layer contract of docs/architecture.md holds: imports run one way, down the pipeline.

- import-linter's contracts (pyproject.toml, ``[tool.importlinter]``): each layer imports only
  from the layers below it; the runtime package never imports ``validation``; the outer ring
  runs scripts -> benchmarks -> validation -> stripcoef;
- no import cycles at all, between modules of one layer either;
- nothing imports tests/ (not a package, so import-linter cannot see it), and no file edits
  ``sys.path`` (benchmarks/ and scripts/ are packages run with ``python -m``);
- docs/architecture.md names every module of src/stripcoef;
- stored references live in reference_tables/ only, each computed csv named in its README;
- no CLI vocabulary below the CLI: library errors name parameters (``radii``), and the CLI
  rewords them into its flags (``--radii``);
- no module-global mutable state in the library: no ``global`` statement, and no module-level
  dict, list or set that the code changes (state lives in arguments, objects or a
  ``ContextVar`` set for a block, as ``stripcoef.progress.bars``).
"""

import ast
import functools
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

    graph = grimp.build_graph("stripcoef", "validation", "benchmarks", "scripts")
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


#: the folders of Python files in the repository: the package and its outer ring
RING = ("src", "validation", "benchmarks", "scripts", "tests")


def _python_files():
    for folder in RING:
        yield from sorted((ROOT / folder).rglob("*.py"))


def _imported_roots(tree) -> set:
    """The top-level names of every module a file imports (inside functions too)."""
    roots = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            roots |= {alias.name.split(".")[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            roots.add(node.module.split(".")[0])
    return roots


@functools.lru_cache(maxsize=None)
def _scan(path: Path) -> tuple:
    """(the top-level names the file imports, the lines that name ``sys.path``): one parse of
    each file of the ring for the two tests below (a parse of the 350 files is about 1.5 s of
    CPU); small results kept, not the trees."""
    tree = ast.parse(path.read_text())
    sys_path = [node.lineno for node in ast.walk(tree)
                if isinstance(node, ast.Attribute) and node.attr == "path"
                and isinstance(node.value, ast.Name) and node.value.id == "sys"]
    return frozenset(_imported_roots(tree)), tuple(sys_path)


def test_nothing_imports_the_tests():
    # tests/ sits on top: a helper the package, validation/, benchmarks/ or scripts/ need lives
    # in validation/ (validation.finned, validation.ingest_truth), never in a test module
    test_modules = {p.stem for p in (ROOT / "tests").glob("*.py")} | {"tests"}
    offenders = []
    for path in _python_files():
        if path.is_relative_to(ROOT / "tests"):
            continue
        hits = _scan(path)[0] & test_modules
        offenders += [f"{path.relative_to(ROOT)}: imports {name}" for name in sorted(hits)]
    assert not offenders, "\n".join(offenders)


#: files that still edit sys.path, each with the reason (none is wanted)
SYS_PATH_ALLOWED: set = set()


def test_no_sys_path_edits():
    # benchmarks/ and scripts/ are packages run from the repository root (python -m
    # benchmarks.bluff_shapes); pytest's pythonpath = ["."] lets the tests import them
    offenders = []
    for path in _python_files():
        name = str(path.relative_to(ROOT))
        if name in SYS_PATH_ALLOWED:
            continue
        offenders += [f"{name}:{line}" for line in _scan(path)[1]]
    assert not offenders, offenders


def _module_names() -> list[tuple[str, str]]:
    """(module path relative to src/stripcoef, its folder) of every module of the package,
    from the file tree: ``diagnose/report.py`` -> ("report.py", "diagnose")."""
    out = []
    for path in sorted(SRC.rglob("*.py")):
        rel = path.relative_to(SRC)
        if rel.name == "__init__.py" and rel.parent != Path("."):
            continue          # a subpackage's __init__ is named by its folder
        out.append((rel.name, str(rel.parent) if rel.parent != Path(".") else ""))
    return out


def test_architecture_page_names_every_module():
    # a module at the top is named as `name.py` in the page; a module of a subpackage as
    # `name.py` in its folder's row of the layer table (the row that names `folder/`)
    text = (ROOT / "docs" / "architecture.md").read_text()
    rows = [line for line in text.splitlines() if line.startswith("|")]
    missing = []
    for name, folder in _module_names():
        if not folder:
            if name != "__init__.py" and f"`{name}`" not in text:
                missing.append(name)
            continue
        top = folder.split("/")[0]
        row = [r for r in rows if f"`{top}/`" in r]
        if not row or not any(f"`{name}`" in r or f"`{folder.split('/', 1)[-1]}/{name}`" in r
                              or f"`{Path(folder).name}/{name}`" in r for r in row):
            missing.append(f"{folder}/{name}")
    assert not missing, "docs/architecture.md does not name: " + ", ".join(missing)


def test_stored_references_have_one_home():
    # stored reference data live in reference_tables/ (the computed ones in bem/ and
    # method_errors/, each csv named in its folder's README with the command that remakes it);
    # benchmarks/data keeps only the benchmarks' markdown outputs
    stray = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "benchmarks").rglob("*")
                   if p.is_file() and p.suffix not in (".py", ".md") and "__pycache__" not in p.parts)
    assert not stray, stray
    for folder in ("bem", "method_errors"):
        readme = (ROOT / "reference_tables" / folder / "README.md").read_text()
        for csv_file in (ROOT / "reference_tables" / folder).glob("*.csv"):
            assert f"`{csv_file.name}`" in readme, (folder, csv_file.name)


_MUTATORS = {"append", "extend", "update", "setdefault", "pop", "popitem", "clear", "add",
             "discard", "remove", "insert"}
_CONTAINERS = (ast.Dict, ast.List, ast.Set, ast.DictComp, ast.ListComp, ast.SetComp)


def _module_containers(tree) -> set[str]:
    """Names bound at module level to a dict, list or set (literal, comprehension or call)."""
    out = set()
    for node in tree.body:
        if isinstance(node, ast.Assign):
            targets, value = node.targets, node.value
        elif isinstance(node, ast.AnnAssign) and node.value is not None:
            targets, value = [node.target], node.value
        else:
            continue
        call = isinstance(value, ast.Call) and isinstance(value.func, ast.Name) \
            and value.func.id in ("dict", "list", "set", "defaultdict", "OrderedDict")
        if isinstance(value, _CONTAINERS) or call:
            out |= {t.id for t in targets if isinstance(t, ast.Name)}
    return out


def test_no_module_global_mutable_state():
    found = []
    for path in sorted(SRC.rglob("*.py")):
        tree = ast.parse(path.read_text(), filename=str(path))
        names = _module_containers(tree)
        where = path.relative_to(ROOT)
        for node in ast.walk(tree):
            if isinstance(node, ast.Global):
                found.append(f"{where}:{node.lineno}: global {', '.join(node.names)}")
            elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                  and isinstance(node.func.value, ast.Name) and node.func.value.id in names
                  and node.func.attr in _MUTATORS):
                found.append(f"{where}:{node.lineno}: {node.func.value.id}.{node.func.attr}()")
            elif isinstance(node, (ast.Assign, ast.AugAssign, ast.Delete)):
                targets = [node.target] if isinstance(node, ast.AugAssign) else node.targets
                found += [f"{where}:{node.lineno}: {t.value.id}[...] changed" for t in targets
                          if isinstance(t, ast.Subscript) and isinstance(t.value, ast.Name)
                          and t.value.id in names]
    assert found == []
