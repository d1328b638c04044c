"""The built wheel, installed into a fresh virtual environment without the repository, runs
the quick start on a shipped vehicle, an identification and a diagnosis on shipped logs.

Slow (builds the wheel in an isolated build environment and installs numpy, scipy, trimesh
... into a new venv: about 25 s of CPU with a warm pip cache), kept in CI.
"""

import email
import json
import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from conftest import ROOT

pytestmark = pytest.mark.slow

_SKIP = shutil.ignore_patterns(".git", ".venv", "build", "dist", "*.egg-info", "__pycache__",
                               ".pytest_cache", "out")


def _run(argv, **kw):
    proc = subprocess.run(argv, capture_output=True, text=True, timeout=900, **kw)
    assert proc.returncode == 0, f"{argv}\n{proc.stdout[-2000:]}\n{proc.stderr[-2000:]}"
    return proc


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("wheel")
    src = tmp / "src-copy"                       # build from a copy: no build/ in the work tree
    shutil.copytree(ROOT, src, ignore=_SKIP)
    dist = tmp / "dist"
    _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(dist), str(src)])
    wheel = next(dist.glob("stripcoef-*.whl"))
    venv = tmp / "venv"
    # a venv without its own pip, filled by this one's pip (--python, pip >= 22.3): the same
    # resolution from the wheel's metadata without bootstrapping pip into it (3.8 -> 0.04 s of
    # CPU); --no-compile: no .pyc for the thousands of modules of numpy, scipy ... that the
    # commands below never import (install 11.5 -> 4.0 s of CPU)
    _run([sys.executable, "-m", "venv", "--without-pip", str(venv)])
    py = venv / "bin" / "python"
    _run([sys.executable, "-m", "pip", "--python", str(py), "install", "-q", "--no-compile",
          str(wheel)])
    work = tmp / "elsewhere"                     # no clone, no geometry/ folder here
    work.mkdir()
    return {"wheel": wheel, "bin": venv / "bin", "cwd": work}


def test_wheel_metadata_and_contents(installed):
    with zipfile.ZipFile(installed["wheel"]) as z:
        names = z.namelist()
        meta = next(n for n in names if n.endswith(".dist-info/METADATA"))
        msg = email.message_from_string(z.read(meta).decode())
    assert msg["License-Expression"] == "MIT"
    assert any(n.endswith("licenses/LICENSE") for n in names)
    for sample in ("mares.yaml", "videoray_pro3.yaml", "capsule.stl", "pendulum.csv",
                   "truth.yaml", "rov_tether.csv", "rov_prior.json"):
        assert f"stripcoef/samples/{sample}" in names
    assert not any(n.startswith(("validation/", "tests/")) for n in names)


def test_quick_start_identify_and_diagnose_without_a_clone(installed):
    # the throwaway venv was installed --no-compile: its commands may write the .pyc of what
    # they import (numpy, scipy, ... once, not once per command) even where the caller's
    # environment says PYTHONDONTWRITEBYTECODE (measured 12.9 -> 10.6 s of CPU for this test)
    env = {**{k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"},
           "PYTHONPATH": ""}
    stripcoef = str(installed["bin"] / "stripcoef")
    cwd = installed["cwd"]
    out = _run([stripcoef, "coefficients", "sample:mares.yaml"], cwd=cwd, env=env).stdout
    assert "Added mass M_A" in out and "MARES" in out
    out = _run([stripcoef, "identify", "sample:yaw_onestep.csv", "--method", "one-step",
                "--dof", "yaw", "--inertia", "0.02532", "--json"], cwd=cwd, env=env).stdout
    assert json.loads(out)["parameters"]["alpha"] == pytest.approx(-0.6199, abs=0.1)
    out = _run([stripcoef, "diagnose", "sample:rov_tether.csv", "--vehicle",
                "sample:rov_prior.json", "--dof", "surge", "--no-resimulate", "--json"],
               cwd=cwd, env=env).stdout
    steps = json.loads(out)["steps"]
    assert steps and steps[0]["effect"] == "tether_drag"
    # strip theory asked for by name: the Python API and the samples of the installed wheel
    # are what this checks (``auto`` would take the panel method for this bluff vehicle:
    # about 3 s of CPU, tested in the source tree)
    code = ("import stripcoef, stripcoef.samples as s; "
            "m = stripcoef.estimate(s.path('videoray_pro3.yaml'), "
            "added_mass_method='strips'); "
            "print(stripcoef.__file__); print(m.name)")
    out = _run([str(installed["bin"] / "python"), "-c", code], cwd=cwd, env=env).stdout
    where, name = out.splitlines()
    assert Path(where).is_relative_to(installed["bin"].parent) and name == "VideoRay Pro III"
