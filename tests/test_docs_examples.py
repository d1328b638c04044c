"""Every ```bash / ```sh / ```python block of the documentation runs.

The blocks of one page run in order in one fresh folder (a later block may read what an
earlier one wrote), with ``geometry/`` of the repository linked into it (the pages that name
the repository's files) and ``stripcoef`` and ``python`` on the PATH running this checkout. A
bash block runs in bash with ``set -e`` (every command must succeed); a python block must exit
0.

Each ``stripcoef`` or ``python`` command is its own process, forked from one server that has
imported the package once per test module (tests/_doc_commands.py): the commands, their
folders, pipes and exit statuses are what the page says, without 0.5-1.5 s of imports each.
:func:`test_forked_commands_are_fresh_interpreters` checks that a fork prints what a fresh
interpreter and the installed console script print, and :data:`FRESH` pages run on fresh
interpreters (``python -m stripcoef``).
"""

import json
import os
import re
import socket
import subprocess
import sys
from pathlib import Path

import pytest

import _doc_commands
from conftest import ROOT

DOCS = ROOT / "docs"
FENCE = re.compile(r"^```(bash|sh|python)[^\n]*\n(.*?)^```", re.S | re.M)
#: Pages whose blocks took more than ~2.5 s of CPU on fresh interpreters (BEM, diagnosis,
#: studies, limits plots; measured, docs/development.md): still run in CI. Forked, identify,
#: meshes, export/index and export/python take 1-2.5 s, and stay out of the fast loop.
SLOW = {"tutorial.md", "diagnose.md", "uncertainty.md", "limits.md", "identify.md",
        "export/index.md", "export/gazebo.md", "export/python.md", "meshes.md"}
#: Pages run on fresh interpreters, one per command, as a user's shell runs them (the home
#: page: one command).
FRESH = {"index.md"}
#: The environment of the commands (PATH added per test): this checkout's code.
ENV = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT / "src"), str(ROOT)]),
       "MPLBACKEND": "Agg"}


def _tether(folder: Path):
    """c_t and its std in the tutorial's diagnosis report."""
    m = re.search(r"\*\*tether_drag\*\*: c_t = (\S+) ± (\S+?);",
                  (folder / "diagnosis.md").read_text())
    return float(m[1]), float(m[2])


def _pendulum(folder: Path):
    """m_a and its std in the tutorial's pendulum identification."""
    fit = json.loads((folder / "pendulum.json").read_text())
    return fit["parameters"]["m_a"], fit["std"]["m_a"]


#: What a page's text says its commands find: page -> [(the pattern of the value and its std
#: in the page, what the commands wrote now)], within one unit of the page's last digit.
CLAIMS = {"tutorial.md": [(r"c_t = ([\d.]+) ± ([\d.]+) N", _tether),
                          (r"m_a = ([\d.]+) ± ([\d.]+) kg", _pendulum)]}


def blocks(page: Path):
    return [(m.group(1), m.group(2)) for m in FENCE.finditer(page.read_text())]


PAGES = sorted(p.relative_to(DOCS).as_posix() for p in DOCS.rglob("*.md") if blocks(p))


@pytest.fixture(scope="module")
def shim(tmp_path_factory):
    """A bin folder with ``stripcoef`` and ``python`` running this checkout's code, each
    command a fresh interpreter."""
    folder = tmp_path_factory.mktemp("bin")
    exe = folder / "stripcoef"
    exe.write_text(f"#!/bin/sh\nexec {sys.executable} -m stripcoef \"$@\"\n")
    exe.chmod(0o755)
    py = folder / "python"
    py.write_text(f"#!/bin/sh\nexec {sys.executable} \"$@\"\n")
    py.chmod(0o755)
    return folder


@pytest.fixture(scope="module")
def forks(tmp_path_factory, shim):
    """A bin folder with ``stripcoef`` and ``python`` running this checkout's code, each
    command a fork of one server that imported the package (tests/_doc_commands.py); the
    fresh interpreters of :func:`shim` where there is no fork or no descriptor passing."""
    if not (hasattr(os, "fork") and hasattr(socket, "send_fds")):
        yield shim
        return
    folder = tmp_path_factory.mktemp("forks")
    server = _doc_commands.start(folder, ENV)
    yield folder
    _doc_commands.stop(server)


def run_blocks(where: str, code_blocks, tmp_path, bin_folder):
    """Run ``[(lang, code), ...]`` in order in ``tmp_path`` with ``bin_folder`` first on the
    PATH; each must exit 0."""
    env = {**ENV, "PATH": f"{bin_folder}{os.pathsep}{os.environ.get('PATH', '')}"}
    for k, (lang, code) in enumerate(code_blocks):
        if lang == "python":
            script = tmp_path / f"block{k}.py"
            script.write_text(code)
            argv = [str(bin_folder / "python"), str(script)]
        else:
            argv = ["bash", "-e", "-o", "pipefail", "-c", code]
        out = subprocess.run(argv, cwd=tmp_path, env=env, capture_output=True, text=True,
                             timeout=600)
        assert out.returncode == 0, (f"{where}, block {k + 1} ({lang}) failed:\n{code}\n"
                                     f"--- stdout\n{out.stdout[-3000:]}\n"
                                     f"--- stderr\n{out.stderr[-3000:]}")


def test_every_page_with_code_is_checked():
    assert {"tutorial.md", "getting-started.md", "samples.md", "identify.md"} <= set(PAGES)


@pytest.mark.parametrize("page", [pytest.param(p, marks=pytest.mark.slow) if p in SLOW
                                  else p for p in PAGES])
def test_page_examples_run(page, tmp_path, request):
    (tmp_path / "geometry").symlink_to(ROOT / "geometry")
    bin_folder = request.getfixturevalue("shim" if page in FRESH else "forks")
    run_blocks(page, blocks(DOCS / page), tmp_path, bin_folder)
    text = (DOCS / page).read_text()
    for pattern, written in CLAIMS.get(page, []):
        stated = re.search(pattern, text).groups()
        for said, found in zip(stated, written(tmp_path)):
            unit = 10.0 ** -len(said.partition(".")[2])
            assert abs(float(said) - found) <= 1.01 * unit, \
                f"{page} says {pattern!r}: {stated}, the commands give {written(tmp_path)}"


def test_readme_python_block_runs(tmp_path, forks):
    """The README's Python example (its bash blocks create virtual environments: CI runs
    the test one itself, tests/test_wheel.py the install)."""
    (tmp_path / "geometry").symlink_to(ROOT / "geometry")
    code = [("python", c) for lang, c in blocks(ROOT / "README.md") if lang == "python"]
    assert code
    run_blocks("README.md", code, tmp_path, forks)


def test_forked_commands_are_fresh_interpreters(tmp_path, shim, forks):
    """The same commands, forked and on fresh interpreters (a ``stripcoef`` command that
    succeeds also through the installed console script, when there is one): the same exit
    status, stdout and stderr, a failure included (exit 2 and its one line; a Python
    exception: exit 1 and its traceback's last line); the same ``sys.argv`` and
    ``sys.path[0]``, folder, environment and stdin."""
    (tmp_path / "m.py").write_text("import sys\nprint('module', sys.argv)\n")
    commands = {
        "stripcoef coefficients sample:sphere.yaml --strips 50 > c.txt; head -c 400 c.txt": 0,
        "stripcoef coefficients sample:nothing.yaml": 2,
        "python -c 'import os, sys; print(sys.argv, repr(sys.path[0]), os.getcwd(), "
        "os.environ[\"EXTRA\"], sys.stdin.read())' x y <<< 'from stdin'": 0,
        "python -c 'import m; m' && python m.py a b": 0,
        "python -c 'raise SystemExit(7)'": 7,
        "python -c '1 / 0' 2>&1 | tail -n 1": 1,
    }
    ways = {"fresh": shim, "forked": forks}
    installed = Path(sys.executable).parent / "stripcoef"
    if installed.is_file():
        console = tmp_path / "console"
        console.mkdir()
        (console / "stripcoef").symlink_to(installed)
        ways["installed"] = console
    for command, status in commands.items():
        seen = {}
        for way, folder in ways.items():
            if way == "installed" and (status != 0 or not command.startswith("stripcoef")):
                continue
            env = {**ENV, "EXTRA": "extra",
                   "PATH": f"{folder}{os.pathsep}{os.environ.get('PATH', '')}"}
            out = subprocess.run(["bash", "-o", "pipefail", "-c", command], cwd=tmp_path,
                                 env=env, capture_output=True, text=True, timeout=300)
            seen[way] = (out.returncode, out.stdout, out.stderr)
        assert len(set(seen.values())) == 1, (command, seen)
        assert seen["forked"][0] == status, (command, seen["forked"])
    assert "ZeroDivisionError" in seen["forked"][1]
