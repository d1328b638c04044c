"""Uncertainty studies and sweeps: key paths, sampling, propagation, execution anywhere."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from stripcoef.cli import main
from stripcoef.errors import InputError
from stripcoef.geometry.keypaths import (get_value, nominal, parse_path, set_value,
                                         uncertain_values)
from stripcoef.study.sources import Source, scale_matrix
from stripcoef.study.sweep import parse_vary, sweep
from stripcoef.study.uncertainty import uncertainty

ROOT = Path(__file__).resolve().parent.parent
MARES = ROOT / "geometry" / "mares.yaml"
SPHEROID = ROOT / "geometry" / "spheroid.yaml"


@pytest.fixture
def uncertain_spheroid(tmp_path):
    """The shipped spheroid with a declared mass (normal) and a uniform thrust limit; 40
    strips: the declared mass is propagated whatever the strip count (the same 256 masses to
    round-off at 200 strips: sd 0.50513, median 20.00016; 5.6 instead of 14 s of CPU)."""
    data = yaml.safe_load(SPHEROID.read_text())
    data["strips"] = 40
    data.setdefault("mass", {})
    data["mass"] = {"mass": {"value": 20.0, "sd": 0.5}}
    path = tmp_path / "spheroid_uq.yaml"
    path.write_text(yaml.safe_dump(data))
    return path


# -- key paths -----------------------------------------------------------------------------

def test_key_paths_round_trip_and_name_what_is_missing():
    assert parse_path("hull.profile[1].radius") == ("hull", "profile", 1, "radius")
    data = {"hull": {"profile": [{"radius": 0.1}, {"radius": 0.2}]}, "name": "x"}
    assert get_value(data, "hull.profile[1].radius") == 0.2
    new = set_value(data, "hull.profile[1].radius", 0.3)
    assert new["hull"]["profile"][1]["radius"] == 0.3 and data["hull"]["profile"][1]["radius"] == 0.2
    with pytest.raises(InputError, match=r"hull.profile\[5\]"):
        set_value(data, "hull.profile[5].radius", 1.0, file="v.yaml")
    with pytest.raises(InputError, match="not a number"):
        set_value(data, "name", 1.0)
    with pytest.raises(InputError, match="not a key path"):
        parse_path("hull..profile")


def test_uncertain_values_are_listed_and_nominal_replaces_them():
    data = {"mass": {"mass": {"value": 11.5, "sd": 0.2},
                     "center_of_gravity": [0, 0, {"value": 0.02, "tol": 0.005}]}}
    found = uncertain_values(data)
    assert [(u.path, u.kind, u.spread) for u in found] == [
        ("mass.mass", "normal", 0.2), ("mass.center_of_gravity[2]", "uniform", 0.005)]
    assert found[1].sd == pytest.approx(0.005 / math.sqrt(3))
    assert nominal(data) == {"mass": {"mass": 11.5, "center_of_gravity": [0, 0, 0.02]}}
    with pytest.raises(InputError, match="mass.mass.sd"):
        uncertain_values({"mass": {"mass": {"value": 1.0, "sd": -1}}})


# -- sampling and the method factors ---------------------------------------------------------

def test_source_draws_follow_their_distributions():
    u = (np.arange(20000) + 0.5) / 20000
    normal = Source("input", "x", "normal", 0.2, 11.5, "").draw(u)
    assert normal.mean() == pytest.approx(11.5, abs=1e-6) and normal.std() == pytest.approx(0.2, rel=2e-3)
    uni = Source("input", "x", "uniform", 0.5, 1.0, "").draw(u)
    assert uni.min() >= 0.5 and uni.max() <= 1.5 and uni.std() == pytest.approx(0.5 / math.sqrt(3), rel=1e-3)
    logn = Source("method", "x", "lognormal", 0.7, 1.0, "").draw(u)
    assert np.all(logn > 0) and np.median(logn) == pytest.approx(1.0, rel=1e-3)


def test_scaling_keeps_added_mass_symmetric_and_positive_definite():
    rng = np.random.default_rng(3)
    a = rng.normal(size=(6, 6))
    m = a @ a.T + 6 * np.eye(6)
    f = rng.uniform(0.5, 1.5, 6)
    s = scale_matrix(m, f)
    assert np.allclose(s, s.T) and np.all(np.linalg.eigvalsh(s) > 0)
    np.testing.assert_allclose(np.diag(s), np.diag(m) * f)


# -- the study -----------------------------------------------------------------------------

@pytest.mark.slow
def test_declared_input_is_propagated_exactly(uncertain_spheroid):
    """The model's mass is the declared input itself: its sample sd is the declared sd."""
    res = uncertainty(uncertain_spheroid, samples=256, seed=1, limits=False, method=False,
                      workers=1, progress=False)
    mass = res.column("mass")
    assert mass.std(ddof=1) == pytest.approx(0.5, rel=0.05)
    assert np.median(mass) == pytest.approx(20.0, abs=0.05)
    assert res.summary()["mass"]["nominal"] == 20.0
    # the added mass does not depend on the mass: no spread without the method error
    assert np.ptp(res.column("Y_vdot")) == 0.0


def test_method_error_band_has_the_stated_width():
    """Translational added mass of a body of revolution: the sd of ln the method table states
    for the class (data/method_uncertainty.csv, measured against Lamb and the BEM)."""
    res = uncertainty(SPHEROID, samples=64, seed=0, limits=False, strips=200, workers=1,
                      progress=False)
    assert res.shape_class == "revolution"
    sd = next(s.spread for s in res.sources if s.name == "added_mass.translation")
    y = res.column("Y_vdot")
    assert np.std(np.log(y / res.nominal["Y_vdot"]), ddof=1) == pytest.approx(sd, rel=0.1)
    assert all(s.reason for s in res.sources)


@pytest.mark.slow
def test_same_seed_same_numbers_in_process_in_processes_and_on_a_dask_cluster():
    pytest.importorskip("dask.distributed")
    from dask.distributed import LocalCluster

    # 50 strips: the same numbers in every execution is what is checked, whatever the model's
    # resolution (a run of 16 samples: 1.2 instead of 2.1 s of CPU at 200 strips)
    kw = dict(samples=16, seed=7, limits=True, radii=(2.0, 10.0), strips=50, progress=False)
    one = uncertainty(MARES, workers=1, **kw)
    two = uncertainty(MARES, workers=2, **kw)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster:
        dask = uncertainty(MARES, scheduler=cluster, **kw)
    for other in (two, dask):
        assert other.names == one.names
        np.testing.assert_array_equal(other.samples, one.samples)   # bit for bit
    other_seed = uncertainty(MARES, workers=1, **dict(kw, seed=8))
    assert not np.array_equal(other_seed.samples, one.samples)


def test_uncertainty_cli_json_is_strict_and_names_its_sources(capsys):
    assert main(["uncertainty", str(SPHEROID), "--samples", "8", "--no-limits", "--json",
                 "--workers", "1", "--quiet"]) == 0
    out = capsys.readouterr().out

    def refuse(c):
        raise ValueError(c)

    data = json.loads(out, parse_constant=refuse)
    assert data["samples"] == 8 and data["shape_class"] == "revolution"
    assert {"nominal", "p2.5", "p50", "p97.5", "sd"} <= set(data["outputs"]["N_rdot"])
    assert all(s["reason"] for s in data["sources"])


@pytest.mark.parametrize("argv,needle", [
    (["--samples", "1"], "samples"),
    (["--output", "."], "--output"),
    pytest.param(["--scheduler", "tcp://127.0.0.1:1"], "scheduler", marks=pytest.mark.slow),
])
def test_uncertainty_cli_errors_are_one_line(argv, needle, capsys):
    assert main(["uncertainty", str(SPHEROID), "--no-limits", "--quiet", *argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and needle in err, err


# -- sweeps ----------------------------------------------------------------------------------

def test_sweep_over_two_keys_gives_the_grid(tmp_path):
    pytest.importorskip("pandas")
    frame = sweep(MARES, ["thrusters[0].max_forward=10:20:2", "mass.zones[0].density=900:1000:2"],
                  limits=False, strips=200, workers=1, progress=False)
    assert list(frame.columns[:2]) == ["thrusters[0].max_forward", "mass.zones[0].density"]
    assert len(frame) == 4
    assert sorted(set(frame["thrusters[0].max_forward"])) == [10.0, 20.0]
    # a denser zone makes a heavier vehicle; the thrust limit does not touch the added mass
    heavy = frame[frame["mass.zones[0].density"] == 1000.0]["mass"].to_numpy()
    light = frame[frame["mass.zones[0].density"] == 900.0]["mass"].to_numpy()
    assert np.all(heavy > light)
    assert frame["X_udot"].nunique() == 1


def test_sweep_cli_writes_a_table_and_a_plot(tmp_path, capsys):
    pytest.importorskip("pandas")
    pytest.importorskip("matplotlib")
    out, png = tmp_path / "sweep.csv", tmp_path / "sweep.png"
    assert main(["sweep", str(MARES), "--vary", "thrusters[0].max_forward=10:20:2",
                 "--vary", "thrusters[1].max_forward=10:20:2", "-o", str(out),
                 "--plot", str(png), "--workers", "1", "--quiet"]) == 0
    assert out.read_text().splitlines()[0].startswith("thrusters[0].max_forward,")
    assert png.stat().st_size > 0


@pytest.mark.parametrize("vary,needle", [
    ("hull.nosuchkey=1:2:3", "hull.nosuchkey"),
    ("name=1:2:3", "name"),
    ("mass.zones[0].density=1:x:3", "mass.zones[0].density"),
    ("mass.zones[0].density", "vary"),
])
def test_sweep_bad_keys_and_ranges_name_the_key(vary, needle, capsys):
    pytest.importorskip("pandas")
    assert main(["sweep", str(MARES), "--vary", vary, "--no-limits", "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and needle in err, err


def test_parse_vary():
    v = parse_vary("mass.mass=10:12:3")
    np.testing.assert_allclose(v.values, [10, 11, 12])


def test_sweep_says_why_a_limit_is_blank_and_plots_units(capsys):
    """A blank limit (NaN) of a grid point comes with its reason (``limits_note``, and one
    stderr line per reason from the CLI); the figure's axes carry units."""
    pytest.importorskip("pandas")
    pytest.importorskip("matplotlib")
    from stripcoef.study.plots import sweep_figure
    from stripcoef.study.sweep import blank_points
    frame = sweep(MARES, ["thrusters[0].max_forward=10:20:2"], strips=200, workers=1,
                  progress=False)
    blank = frame["sway_speed_max"].isna()
    assert blank.all()                      # MARES has no lateral thruster
    assert all("sway_speed_max" in n for n in frame["limits_note"][blank])
    assert sum(blank_points(frame).values()) == int(blank.sum())
    ax = sweep_figure(frame, ["thrusters[0].max_forward"], "surge_speed_max").axes[0]
    assert ax.get_xlabel() == "thrusters[0].max_forward [N]"
    assert ax.get_ylabel() == "surge_speed_max [m/s]"
    with pytest.raises(InputError, match="unknown output"):
        sweep_figure(frame, ["thrusters[0].max_forward"], "limits_note")
    assert main(["sweep", str(MARES), "--vary", "thrusters[0].max_forward=10:20:2",
                 "--workers", "1", "--quiet"]) == 0
    err = capsys.readouterr().err
    assert "2 of 2 grid points have blank limits: blank: sway_speed_max" in err


def test_coefficient_units_follow_the_matrix_entries():
    from stripcoef.views import coefficient_unit, key_unit
    assert coefficient_unit("X_udot") == "kg" and coefficient_unit("N_rdot") == "kg m^2"
    assert coefficient_unit("Y_rdot") == "kg m" and coefficient_unit("X_u") == "kg/s"
    assert coefficient_unit("X_uu") == "kg/m" and coefficient_unit("N_rr") == "kg m^2"
    assert coefficient_unit("Y_uv") == "kg/m" and coefficient_unit("N_uv") == "kg"
    assert coefficient_unit("Y_uudr") == "kg/m/rad" and coefficient_unit("mass") == "kg"
    assert coefficient_unit("u_max@R=5") == "m/s" and coefficient_unit("nonsense") == ""
    assert key_unit("hull.profile[1].radius") == "m" and key_unit("mass.zones[0].density") \
        == "kg/m^3"
