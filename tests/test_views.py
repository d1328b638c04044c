"""Labelled views of the model (pandas DataFrame with DOF names and units, the notebook's
HTML) and BLAS pinned to one thread inside the library."""

import os
import subprocess
import sys

import numpy as np
import pytest

from stripcoef.errors import InputError
from stripcoef.modelfile import load_model
from stripcoef.views import entry_unit

from conftest import ROOT


@pytest.fixture(scope="module")
def mares():
    from conftest import GEOMETRY
    return load_model(GEOMETRY / "mares.yaml")


def test_frame_labels_values_and_units(mares):
    pd = pytest.importorskip("pandas")
    f = mares.frame("added_mass")
    assert isinstance(f, pd.DataFrame)
    assert list(f.index)[1] == "Y (sway)" and list(f.columns)[5] == "r (yaw)"
    assert f.loc["Y (sway)", "v (sway)"] == mares.added_mass[1, 1]
    assert np.array_equal(f.to_numpy(), mares.added_mass)
    units = f.attrs["units"]
    assert units.loc["Y (sway)", "v (sway)"] == "kg"
    assert units.loc["N (yaw)", "v (sway)"] == "kg m"
    assert units.loc["N (yaw)", "r (yaw)"] == "kg m^2"
    q = mares.frame("quadratic_damping").attrs["units"]
    assert q.loc["X (surge)", "u (surge)"] == "kg/m" and q.loc["N (yaw)", "v (sway)"] == "kg"
    with pytest.raises(InputError, match="unknown matrix.*added_mass"):
        mares.frame("inertia")


def test_units_are_force_over_velocity():
    # (i, j) times velocity j [m/s or rad/s] is force i [N or N m]: kg/s, kg m/s, kg m^2/s
    want = {(False, False): "kg/s", (False, True): "kg m/s", (True, False): "kg m/s",
            (True, True): "kg m^2/s"}
    for i in range(6):
        for j in range(6):
            assert entry_unit("linear_damping", i, j) == want[(i >= 3, j >= 3)]
    assert entry_unit("added_mass", 0, 4) == "kg m"
    with pytest.raises(InputError):
        entry_unit("stiffness", 0, 0)


def test_notebook_html(mares):
    html = mares._repr_html_()
    assert html.startswith("<div><b>HydroModel MARES</b>")
    for symbol in ("M_RB", "M_A", "D_L", "D_Q"):
        assert f"<b>{symbol}</b>" in html
    assert "Y (sway)" in html and 'title="kg m^2"' in html
    assert f"{mares.added_mass[1, 1]:.4g}" in html


@pytest.mark.slow     # 2.7-2.9 s of CPU (-n 0, load ~11): two fresh interpreters
def test_blas_pinned_inside_estimate_without_the_cli():
    """In a plain Python process (no CLI, no thread variables) estimate runs with one BLAS
    thread; a user's OPENBLAS_NUM_THREADS is left alone."""
    pytest.importorskip("threadpoolctl")
    code = f"""
import sys
from threadpoolctl import threadpool_info
import importlib
est = importlib.import_module("stripcoef.assembly.estimate")
methods = importlib.import_module("stripcoef.assembly.methods")   # strips' compute
seen = []
real = methods.added_mass
def spy(*a, **k):
    seen.append(max([i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"],
                    default=1))
    return real(*a, **k)
methods.added_mass = spy
est.estimate({str(ROOT / 'geometry' / 'sphere.yaml')!r})
print(seen[0])
"""
    env = {k: v for k, v in os.environ.items()
           if k not in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env=env, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.strip() == "1"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env={**env, "OPENBLAS_NUM_THREADS": "2"}, timeout=300)
    assert out.returncode == 0 and out.stdout.strip() in ("1", "2")   # 1 on a 1-core BLAS
