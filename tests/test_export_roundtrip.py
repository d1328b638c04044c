"""Every export format parses back in its own format, for awkward but valid models too.

tests/test_export_vehicles.py reads the shipped vehicles' exports back value by value; here
the model carries what breaks naive writers: a name with YAML, XML and shell metacharacters
and a newline, thruster names with spaces, an unlimited thrust (``inf``, never written as a
number) and tiny and large entries (issue 17: YAML exports that did not parse back).
"""

from __future__ import annotations

import io
import json
import shutil
import subprocess
import warnings
import xml.etree.ElementTree as ET
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import yaml

import stripcoef
from stripcoef.export import FORMATS, write_export
from stripcoef.export.csvtable import read as read_csv
from stripcoef.model import HydroModel
from conftest import load_module

ROOT = Path(__file__).resolve().parent.parent
NAMES = ['a: b # "c" \'d\' <e> & f', "two\nlines", "näme-ü", "null", "- 1e3"]
MATRICES = ("rigid_body_mass", "added_mass", "linear_damping", "quadratic_damping")


def _strict_json(data):
    def refuse(token):
        raise AssertionError(f"non-finite JSON token {token}")
    return json.loads(data, parse_constant=refuse)


@pytest.fixture(scope="module")
def base():
    model = stripcoef.estimate(ROOT / "geometry" / "mares.yaml", strips=100)
    thrusters = [replace(t, name=f"thr {k}", max_forward=float("inf"))
                 for k, t in enumerate(model.thrusters)]
    d = np.array(model.linear_damping)
    d[0, 0] = 1e-300                                 # tiny, positive: still a number written
    return replace(model, thrusters=thrusters, linear_damping=d)


@pytest.mark.parametrize("fmt", sorted(FORMATS))
@pytest.mark.parametrize("name", NAMES)
def test_export_parses_back(fmt, name, base, tmp_path):
    model = replace(base, name=name)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        path = write_export(model, fmt, tmp_path / f"out{FORMATS[fmt].suffix}")
    data = path.read_bytes()
    if fmt in ("gazebo", "uuv"):
        root = ET.fromstring(data)
        values = [float(v) for el in root.iter() if el.text and el.text.strip()
                  for v in el.text.split() if _is_number(v)]
        assert values and np.all(np.isfinite(values))
    elif fmt == "json":
        back = HydroModel.from_dict(_strict_json(data))
        assert back.name == name
        for key in MATRICES:
            np.testing.assert_array_equal(getattr(back, key), getattr(model, key))
        assert all(t.max_forward == float("inf") for t in back.thrusters)
    elif fmt == "yaml":
        back = HydroModel.from_dict(yaml.safe_load(data))
        assert back.name == name and [t.name for t in back.thrusters] == \
            [t.name for t in model.thrusters]
        for key in MATRICES:
            np.testing.assert_array_equal(getattr(back, key), getattr(model, key))
    elif fmt == "csv":
        d = read_csv(data.decode())
        for key in MATRICES:
            np.testing.assert_array_equal(d[key], getattr(model, key))
    elif fmt == "npz":
        with np.load(io.BytesIO(data), allow_pickle=False) as npz:
            np.testing.assert_array_equal(npz["M_A"], model.added_mass)
            back = HydroModel.from_dict(_strict_json(str(npz["model_json"])))
            assert back.name == name
    elif fmt == "python":
        mod = load_module(path, "exported_model")
        np.testing.assert_array_equal(mod.D_L, model.linear_damping)
    elif fmt == "mss":
        exe = shutil.which("octave-cli")
        if exe is None:
            pytest.skip("octave-cli not installed (CI installs it)")
        fn = path.stem
        run = subprocess.run([exe, "--no-gui", "--quiet", "--eval",
                              f"addpath('{tmp_path}'); [~,~,M] = {fn}(); disp(M(1,1))"],
                             capture_output=True, text=True, timeout=120)
        assert run.returncode == 0, run.stderr
        m11 = model.rigid_body_mass[0, 0] + model.added_mass[0, 0]
        assert float(run.stdout.split()[-1]) == pytest.approx(m11, rel=1e-4)
    else:
        raise AssertionError(f"no parse-back check for format {fmt}")


def _is_number(text):
    try:
        float(text)
    except ValueError:
        return False
    return True
