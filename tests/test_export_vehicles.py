"""Every export format from the shipped vehicles (geometry/mares.yaml, geometry/videoray_pro3.yaml)."""

from __future__ import annotations

import io
import json
import warnings
from pathlib import Path

import numpy as np
import pytest
import yaml
from _export_models import octave_or_skip
from test_export_gazebo import parse as parse_gazebo
from test_export_mss_octave import CASES, call, expected
from test_export_uuv import parse as parse_uuv

import stripcoef
from stripcoef.export import FORMATS, SimulatorTrapWarning, export_model, write_export
from stripcoef.export.csvtable import read as read_csv
from stripcoef.model import HydroModel
from conftest import load_module, shipped_model

ROOT = Path(__file__).resolve().parent.parent
VEHICLES = ("mares", "videoray_pro3")
MATRICES = ("rigid_body_mass", "added_mass", "linear_damping", "quadratic_damping")


@pytest.fixture(scope="module", params=VEHICLES)
def vehicle(request):
    # the vehicle file's default estimate, shared with the other tests that read it
    return request.param, shipped_model(f"{request.param}.yaml")


def test_every_format_reads_back(vehicle, tmp_path):
    name, model = vehicle
    for fmt, spec in FORMATS.items():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SimulatorTrapWarning)
            warnings.simplefilter("ignore", stripcoef.errors.ModelWarning)
            path = write_export(model, fmt, tmp_path / f"{name}{spec.suffix}")
        data = path.read_bytes()
        assert data, fmt
        if fmt == "gazebo":
            _, _, lin, quad, dot, fam = parse_gazebo(data.decode())
            t = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])
            np.testing.assert_allclose(fam, np.outer(t, t) * model.added_mass, atol=1e-12)
            np.testing.assert_allclose(lin, -np.outer(t, t) * model.linear_damping, atol=1e-12)
            assert dot is None
        elif fmt == "uuv":
            p = parse_uuv(data.decode())
            assert p["volume"] == model.volume
            assert np.all(np.diag(p["Ma"]) > 0) and np.all(np.diag(p["DNonLin"]) <= 0)
        elif fmt in ("json", "yaml"):
            d = json.loads(data) if fmt == "json" else yaml.safe_load(data)
            back = HydroModel.from_dict(d)
            for key in MATRICES:
                np.testing.assert_array_equal(getattr(back, key), getattr(model, key))
        elif fmt == "csv":
            d = read_csv(data.decode())
            for key in MATRICES:
                np.testing.assert_array_equal(d[key], getattr(model, key))
        elif fmt == "npz":
            with np.load(io.BytesIO(data), allow_pickle=False) as npz:
                np.testing.assert_array_equal(npz["M_A"], model.added_mass)
        elif fmt == "python":
            mod = load_module(path, f"exported_{name}")
            np.testing.assert_array_equal(mod.D_Q, model.quadratic_damping)
            assert len(mod.THRUSTERS) == len(model.thrusters)
        elif fmt == "mss":
            assert data.decode().startswith(f"function [xdot, U, M, MRB, MA, D, g, DL, DQ, Bthr, L, Bdelta] = {name}(")
        else:
            raise AssertionError(f"no read-back check for format {fmt}")


def test_mss_export_runs_in_octave(vehicle, tmp_path):
    exe = octave_or_skip()
    name, model = vehicle
    write_export(model, "mss", tmp_path / f"{name}.m")
    for case, got in zip(CASES, call(exe, tmp_path, name, CASES)):
        want = expected(model, *case)
        for key, value in want.items():
            np.testing.assert_allclose(np.squeeze(got[key]), np.squeeze(value), rtol=1e-10,
                                       atol=1e-12, err_msg=key)


def test_slender_vehicle_traps(vehicle):
    """The known traps fire on the real vehicles where they apply."""
    name, model = vehicle
    big = [i for i in range(6) if model.added_mass[i, i] > model.rigid_body_mass[i, i]]
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        export_model(model, "gazebo", legacy_added_mass=True)
    msgs = [str(w.message) for w in rec if issubclass(w.category, SimulatorTrapWarning)]
    assert any("1923" in m for m in msgs) == bool(big)
