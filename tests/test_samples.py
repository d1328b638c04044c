"""The sample data shipped in the wheel: reachable by name, what scripts/make_samples.py
writes (up to round-off), and the logs' truth recovered by the commands it names."""

import importlib
import json
import shlex

import pytest
import yaml

from stripcoef import samples
from stripcoef.cli import main
from stripcoef.errors import InputError

from conftest import GEOMETRY, assert_same_file


def _make_samples():
    return importlib.import_module("scripts.make_samples")


def test_vehicles_are_the_repository_geometry():
    for f in GEOMETRY.glob("*.yaml"):
        assert samples.path(f.name).read_bytes() == f.read_bytes(), \
            f"{f.name}: run python -m scripts.make_samples"


@pytest.mark.slow
def test_samples_are_what_the_script_writes():
    """Every sample is what the script writes now, compared as parsed numbers, not bytes
    (conftest.assert_same_file): the text exactly, each number within 1e-9 of the largest
    magnitude of its column or matrix (conftest.RTOL). The logs are simulated, and another
    CPU or numpy/scipy release rounds their last bits differently (measured up to 1e-13
    absolute); a change of the simulation or of the truth moves them by far more."""
    files = _make_samples().build()
    assert sorted(files) == samples.names()
    for name, data in files.items():
        assert_same_file(name, data, samples.path(name).read_bytes(),
                         hint="; run python -m scripts.make_samples")


def test_path_and_errors():
    assert samples.path("mares.yaml") == samples.FOLDER / "mares.yaml"
    assert samples.path("sample:mares.yaml") == samples.FOLDER / "mares.yaml"
    with pytest.raises(InputError, match="unknown sample.*mares.yaml"):
        samples.path("nope.yaml")
    assert samples.resolve("geometry/mares.yaml") == "geometry/mares.yaml"
    assert {"mares.yaml", "capsule.stl", "pendulum.csv", "truth.yaml"} <= set(samples.names())
    assert set(samples.descriptions()) == set(samples.names())
    assert all(samples.descriptions().values())


def test_cli_lists_and_resolves(capsys):
    assert main(["samples"]) == 0
    out = capsys.readouterr().out
    for name in samples.names():
        assert name in out
    assert main(["samples", "yaw_onestep.csv"]) == 0
    out = capsys.readouterr().out
    assert str(samples.path("yaw_onestep.csv")) in out and "recover:" in out
    assert main(["coefficients", "sample:videoray_pro3.yaml", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["name"] == "VideoRay Pro III"
    assert main(["coefficients", "sample:nothing.yaml"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "unknown sample" in err and "'nothing.yaml'" in err


def test_mesh_sample_estimates(capsys):
    assert main(["coefficients", "sample:capsule.stl", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    # a capsule L = 1 m, D = 0.2 m: volume pi r^2 (L - 2r) + 4/3 pi r^3 = 0.02932 m^3 (faceted: less)
    assert 0.97 * 0.029322 < d["volume"] < 0.029322


LOGS = [n for n in yaml.safe_load(samples.path("truth.yaml").read_text())["logs"]
        if n.endswith(".csv") and n != "rov_tether.csv"]       # diagnose: tests/test_docs_*


@pytest.mark.parametrize("log", LOGS)
def test_identify_recovers_the_truth(log, tmp_path):
    """The documented command recovers every true parameter within 3 of its standard errors."""
    truth = samples.truth(log)
    argv = shlex.split(truth["recover"])[1:] + ["--json", "-o", str(tmp_path / "fit.json")]
    assert main(argv) == 0
    fit = json.loads((tmp_path / "fit.json").read_text())
    for name, (value, unit) in truth["truth"].items():
        if name not in fit["parameters"]:
            continue
        est, sd = fit["parameters"][name], fit["std"][name]
        assert abs(est - value) <= 3 * sd, f"{log}: {name} = {est} +- {sd}, truth {value} [{unit}]"
    assert set(truth["truth"]) & set(fit["parameters"])


def test_identify_vehicle_accepts_a_model_file(tmp_path, capsys):
    """identify --vehicle reads model files like every other command (here the JSON prior of
    the tether sample, whose commands the thruster map turns into the yaw moment)."""
    from stripcoef.logfile import read_log
    log = read_log(samples.path("rov_tether.csv")).slice(0, 600)
    f = tmp_path / "yaw.csv"
    log.write_csv(f)
    assert main(["identify", str(f), "--method", "one-step", "--dof", "yaw", "--vehicle",
                 "sample:rov_prior.json", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["dof"] == "yaw" and "gamma" in d["parameters"]
