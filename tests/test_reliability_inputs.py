"""Reliability, issue 36: each reproducing input of the issue ends in one line naming the
file, the key or column, the value and what was expected, with exit code 2 (or, for an odd
but valid input, a correct answer); nothing is written after a failure.

One test per class of the issue: YAML read safely; model files validated like vehicle files;
vehicle files' mass; estimators on ill-conditioned or non-finite problems; logs; writes;
options.
"""

from __future__ import annotations

import copy
import json
import time
from pathlib import Path

import numpy as np
import pytest

from conftest import one_line_error as _one_line

from stripcoef.cli import main
from stripcoef.errors import InputError

ROOT = Path(__file__).resolve().parent.parent
GEO = ROOT / "geometry"
HULL = ("hull:\n  profile:\n"
        "    - {type: ellipsoid_tail, x: [-0.75, -0.45], radius: 0.10}\n"
        "    - {type: cylinder, x: [-0.45, 0.55], radius: 0.10}\n"
        "    - {type: ellipsoid_nose, x: [0.55, 0.75], radius: 0.10}\nstrips: 100\n")


# -- YAML read safely -------------------------------------------------------------------

@pytest.mark.parametrize("text, words", [
    (HULL + "name: a\x00b\n", ("line 7", "a character YAML does not allow", "'\\x00'")),
    (HULL + "name: a\x07b\n", ("line 7", "a character YAML does not allow")),
    ("hull: &a\n  profile: [*a]\n", ("line 1", "recursive alias", "&a")),
    ("a: &x [1, *x]\n" + HULL, ("line 1", "recursive alias", "&x")),
    ("a: &m {<<: *m}\n" + HULL, ("recursive alias",)),
])
def test_unprintable_text_and_recursive_aliases(text, words, tmp_path, capsys):
    f = tmp_path / "v.yaml"
    f.write_text(text)
    _one_line(capsys, ["coefficients", f], str(f), *words)


def test_undecodable_bytes_name_the_file_and_the_byte(tmp_path, capsys):
    f = tmp_path / "v.yaml"
    f.write_bytes(HULL.encode() + b"name: \xff\xfe\n")
    _one_line(capsys, ["coefficients", f], str(f), "not UTF-8", "0xff", "line 7")


def _wide_bombs():
    """Aliases that are cheap to write and expensive to build: (name, text)."""
    big = "a: &a {" + ",".join(f"k{i}: 1" for i in range(3000)) + "}\n"
    yield "merge keys", big + "b: [" + ",".join(["{<<: *a}"] * 5000) + "]\n"
    seq = "a: &a [" + ",".join(["x"] * 5000) + "]\n"
    yield "wide sequence", seq + "b: [" + ",".join(["*a"] * 20000) + "]\n"
    # shared nodes met in an order that a pre-order walk counts wrongly
    yield "late references", seq + "b: [" + ",".join(["[*a]"] * 20000) + "]\n"


@pytest.mark.parametrize("name, text", list(_wide_bombs()))
def test_wide_alias_bomb_is_refused_quickly(name, text, tmp_path, capsys):
    """A ~100 kB document that expands to millions of nodes: refused before it is built
    (the issue: 55 s and 5.3 GB before the fix)."""
    from stripcoef.files import load_yaml

    assert len(text) < 120_000
    t0 = time.process_time()
    with pytest.raises(InputError, match="too large once its aliases are expanded"):
        load_yaml(text, file="bomb.yaml")
    assert time.process_time() - t0 < 10.0


def test_shared_anchors_are_counted_once_per_reference():
    """The expansion count is exact: a node referenced n times counts n times."""
    from stripcoef.files import _expanded_size, _yaml_loader

    loader = _yaml_loader("f")("a: &a [1, 2, 3]\nb: [*a, *a, [*a]]\n")
    node = loader.get_single_node()
    # root 1 + (key a 1 + [1,2,3] 4) + (key b 1 + list 1 + 4 + 4 + (1 + 4)) = 21
    assert _expanded_size(node, 10_000, "f") == 21


# -- model files validated like vehicle files ------------------------------------------

@pytest.fixture(scope="module")
def mares_model_dict():
    from stripcoef import estimate

    return estimate(GEO / "mares.yaml", strips=100).to_dict()


def _set(key, value):
    def edit(d):
        node = d
        for k in key[:-1]:
            node = node[k]
        node[key[-1]] = value
    return edit


MODEL_CASES = [
    ("gravity nan", _set(["gravity"], float("nan")), ("gravity", "nan", "finite")),
    ("gravity 0", _set(["gravity"], 0), ("gravity", "got 0", "> 0")),
    ("gravity negative", _set(["gravity"], -9.81), ("gravity", "-9.81", "> 0")),
    ("position of 2 numbers", _set(["thrusters", 0, "position"], [1.0, 2.0]),
     ("thrusters[0].position", "[1.0, 2.0]", "3 numbers")),
    ("direction zeros", _set(["thrusters", 0, "direction"], [0, 0, 0]),
     ("thrusters[0].direction", "zero vector", "non-zero")),
    ("direction nan", _set(["thrusters", 0, "direction"], [float("nan"), 0, 0]),
     ("thrusters[0].direction", "finite")),
    ("ct_forward a string", _set(["thrusters", 0, "ct_forward"], "fast"),
     ("thrusters[0].ct_forward", "'fast'", "a number")),
    ("ct_forward -1", _set(["thrusters", 0, "ct_forward"], -1),
     ("thrusters[0].ct_forward", "-1", "> 0")),
    ("empty thruster name", _set(["thrusters", 0, "name"], ""),
     ("thrusters[0].name", "empty name")),
    ("duplicated thruster name", _set(["thrusters", 1, "name"], "P1"),
     ("thrusters[1].name", "'P1'", "unique")),
    ("unknown thruster key", _set(["thrusters", 0, "ct_foward"], 2.0),
     ("thrusters[0].ct_foward", "unknown key")),
    ("effects a string", _set(["effects"], "tether_drag"),
     ("effects", "'tether_drag'", "a list")),
    ("effect parameter a string", _set(["effects"], [
        {"name": "tether_drag", "dof": "surge", "parameters": {"c_t": "abc"}}]),
     ("effects[0].parameters.c_t", "'abc'", "a number")),
    ("effect on DOF 7", _set(["effects"], [
        {"name": "tether_drag", "dof": 7, "parameters": {"c_t": 1.0}}]),
     ("effects[0].dof", "got 7", "surge")),
    # effects checked against the effects library (stripcoef.effects.laws.EFFECTS)
    ("unknown effect", _set(["effects"], [
        {"name": "teather_drag", "dof": "surge", "parameters": {"c_t": 1.0}}]),
     ("effects[0].name", "'teather_drag'", "tether_drag")),
    ("unknown effect parameter", _set(["effects"], [
        {"name": "tether_drag", "dof": "surge", "parameters": {"c_t": 1.0, "ct": 2.0}}]),
     ("effects[0].parameters.ct", "unknown parameter", "c_t [N s^2/m^3]")),
    ("effect parameter missing", _set(["effects"], [
        {"name": "thrust_asymmetry", "dof": "surge", "parameters": {"eta_forward": 1.0}}]),
     ("effects[0].parameters.eta_backward", "missing", "eta_forward")),
    ("effect parameter out of range", _set(["effects"], [
        {"name": "tether_drag", "dof": "surge", "parameters": {"c_t": -1.0}}]),
     ("effects[0].parameters", "-1.0", "c_t > 0")),
    ("current of 1e6 m/s", _set(["effects"], [
        {"name": "current", "dof": "surge",
         "parameters": {"current_north": 1e6, "current_east": 0.0}}]),
     ("effects[0].parameters", "1000000.0", "< 5 m/s")),
    ("effect in a DOF it does not act in", _set(["effects"], [
        {"name": "tether_drag", "dof": "yaw", "parameters": {"c_t": 1.0}}]),
     ("effects[0].dof", "'yaw'", "surge, sway, heave")),
    ("effect in all DOFs", _set(["effects"], [
        {"name": "tether_drag", "dof": "all", "parameters": {"c_t": 1.0}}]),
     ("effects[0].dof", "'all'", "does not act in all")),
    ("kinematic viscosity negative", _set(["kinematic_viscosity"], -1e-6),
     ("kinematic_viscosity", "-1e-06", "> 0")),
    ("lift of 5 rows", lambda d: d.__setitem__("lift", d["lift"][:5]), ("lift", "6 entries")),
    ("control surface without derivative", _set(["control_surfaces"], [
        {"name": "r", "type": "rudder", "max_deflection": 0.3}]),
     ("control_surfaces[0].derivative", "missing")),
]


@pytest.mark.parametrize("command", ["export", "simulate", "limits"])
@pytest.mark.parametrize("name, edit, words", MODEL_CASES, ids=[c[0] for c in MODEL_CASES])
def test_model_file_errors(name, edit, words, command, mares_model_dict, tmp_path, capsys):
    """Each invalid model file of the issue: one line from every command that reads it
    (today some ran with NaN, the thruster off or a traceback)."""
    d = copy.deepcopy(mares_model_dict)
    edit(d)
    f = tmp_path / "m.json"
    f.write_text(json.dumps(d))
    if command == "export":
        argv = ["export", f, "--to", "gazebo", "-o", tmp_path / "o.sdf"]
    elif command == "simulate":
        (tmp_path / "in.csv").write_text("t,n_P1,n_P2,n_V1,n_V2\n0,1,1,0,0\n1,1,1,0,0\n")
        argv = ["simulate", f, "--inputs", tmp_path / "in.csv", "--out", tmp_path / "o.csv"]
    else:
        argv = ["limits", f, "--json", "--radii", "1:10:3"]
    _one_line(capsys, argv, str(f), *words)
    assert sorted(p.name for p in tmp_path.iterdir()) in (["m.json"], ["in.csv", "m.json"])


def test_model_file_effects_of_the_library_are_read(mares_model_dict):
    """Entries the effects library admits load, ``all`` where the law acts in all DOFs."""
    from stripcoef.modelfile import model_from_dict

    d = copy.deepcopy(mares_model_dict)
    d["effects"] = [
        {"name": "tether_drag", "dof": "heave", "parameters": {"c_t": 3.0}, "std": {}},
        {"name": "thrust_effectiveness", "dof": "all", "parameters": {"scale": 0.6}},
        {"name": "thruster_lag", "dof": "surge", "parameters": {"time_constant": 0.2}},
        {"name": "tether_drag", "dof": 1, "parameters": {"c_t": 3.0}}]    # a DOF index
    model = model_from_dict(d, file="m.json")
    assert [e["name"] for e in model.effects] == ["tether_drag", "thrust_effectiveness",
                                                  "thruster_lag", "tether_drag"]
    from stripcoef.effects.laws import effect_forces

    assert len(effect_forces(model)) == 4        # the simulation reads every entry


def test_model_file_direction_is_normalised_as_in_a_vehicle_file(mares_model_dict):
    """A direction that is not a unit vector is its direction (as in a vehicle file), not a
    thrust scale."""
    from stripcoef.modelfile import model_from_dict

    d = copy.deepcopy(mares_model_dict)
    d["thrusters"][0]["direction"] = [2.0, 0.0, 0.0]
    model = model_from_dict(d, file="m.json")
    np.testing.assert_allclose(model.thrusters[0].direction, [1.0, 0.0, 0.0], atol=1e-15)
    assert model_from_dict(mares_model_dict).to_dict()["thrusters"] == \
        mares_model_dict["thrusters"]


def test_model_file_yaml_with_unlimited_thrust_reads_back(mares_model_dict):
    """A thruster without a limit (``null``, or JSON's Infinity) stays valid."""
    from stripcoef.modelfile import model_from_dict

    d = copy.deepcopy(mares_model_dict)
    d["thrusters"][0]["max_forward"] = None
    d["thrusters"][1]["max_forward"] = float("inf")
    model = model_from_dict(d)
    assert model.thrusters[0].max_forward == model.thrusters[1].max_forward == float("inf")


# -- vehicle files: density -------------------------------------------------------------

def _cylinder(mass):
    from stripcoef.geometry.vehicle import parse_vehicle

    return parse_vehicle({"name": "c", "fluid": {"density": 1000.0, "kinematic_viscosity": 1e-6},
                          "strips": 200,
                          "hull": {"profile": [{"type": "cylinder", "x": [-1.0, 1.0],
                                                "radius": 0.1}]},
                          "mass": mass}, file="c.yaml")


def test_default_density_without_zones_is_honoured():
    """A uniform body of ``default_density``: m = rho V, exactly for a cylinder [kg] (it was
    the fluid's density, silently)."""
    from stripcoef import estimate
    from stripcoef.errors import ModelWarning

    with pytest.warns(ModelWarning, match="weight and buoyancy differ by -50.0 %"):
        m = estimate(_cylinder({"default_density": 500.0}))
    volume = np.pi * 0.1 ** 2 * 2.0
    assert m.volume == pytest.approx(volume, rel=1e-9)
    assert m.mass == pytest.approx(500.0 * volume, rel=1e-9)
    np.testing.assert_allclose(m.center_of_gravity, m.center_of_buoyancy, atol=1e-12)
    # the inertia of a solid rod of that mass: Iyy = m (L^2/12 + R^2/4) [kg m^2] (the
    # strips' midpoint sum of a uniform rod is exact up to the dx^2/12 term they include)
    iyy = m.mass * (2.0 ** 2 / 12 + 0.1 ** 2 / 4)
    r_g = m.center_of_gravity - m.reference_point
    assert m.rigid_body_mass[4, 4] - m.mass * (r_g[0] ** 2 + r_g[2] ** 2) == \
        pytest.approx(iyy, rel=1e-6)


@pytest.mark.parametrize("mass, words", [
    ({"default_density": 0}, ("mass.default_density", "got 0", "> 0")),
    ({"mass": 30.0, "default_density": 800.0}, ("mass.default_density", "both mass and")),
    ({"zones": [{"name": "far", "x": [5.0, 6.0], "density": 900.0}]},
     ("mass.zones[0].x", "'far' entirely outside the body", "[5.0, 6.0]", "-1 to 1 m")),
    ({"zones": [{"name": "thin", "x": [0.0001, 0.0002], "density": 900.0}]},
     ("mass.zones[0].x", "'thin' covers no strip", "more strips")),
    ({"default_density": 1000.0, "zones": [{"x": [-1.0, 1.0], "density": 0.0}]},
     ("mass.zones", "massless")),
])
def test_density_errors(mass, words, tmp_path, capsys):
    import yaml

    f = tmp_path / "v.yaml"
    f.write_text(HULL.replace("-0.75", "-1.0").replace("0.75", "1.0")
                 + yaml.safe_dump({"mass": mass}))
    text = f.read_text().replace("ellipsoid_tail, x: [-1.0, -0.45]", "cylinder, x: [-1.0, -0.45]")
    f.write_text(text.replace("ellipsoid_nose, x: [0.55, 1.0]", "cylinder, x: [0.55, 1.0]"))
    _one_line(capsys, ["coefficients", f, "-o", tmp_path / "o.json"], str(f), *words)
    assert not (tmp_path / "o.json").exists()


# -- estimators: ill-conditioned or non-finite problems -----------------------------------

def test_lstsq_refuses_an_overflowing_regression():
    """One value of -1e300 among ordinary ones (a LinAlgError before): a named refusal."""
    from stripcoef.identify.estimators import linear_lstsq

    rng = np.random.default_rng(3)
    h = np.column_stack([np.ones(40), rng.normal(size=40)])
    y = h @ [1.0, 2.0] + 0.01 * rng.normal(size=40)
    assert np.allclose(linear_lstsq(h, y, ["a", "b"]).theta, [1.0, 2.0], atol=0.02)
    y[7] = -1e300
    with pytest.raises(InputError, match=r"overflows.*-1e\+300 at observation 7.*units"):
        linear_lstsq(h, y, ["a", "b"], what="points")
    h[5, 1] = 1e300
    with pytest.raises(InputError, match="overflows"):
        linear_lstsq(h, h @ [1.0, 2.0], ["a", "b"])


@pytest.mark.parametrize("a, b, c", [(1e308, -1e308, 0.0), (10.0, 0.0, -1e150)])
def test_pendulum_decay_blow_up_is_nan_not_a_math_domain_error(a, b, c):
    """sin(inf) inside a Runge-Kutta step raised 'math domain error' (a 200k-row log's fit)."""
    from stripcoef.identify.pendulum import simulate_decay

    out = simulate_decay(np.linspace(0.0, 1.0, 50), 1.0, 0.0, a, b, c)
    assert out[0] == 1.0 and np.all(np.isnan(out[1:]))


# -- logs: absurd magnitudes and units -----------------------------------------------------

def _steady_log(tmp_path, edit=None):
    from stripcoef.logfile import Log
    from validation.experiments import romeo_experiment

    pts, _ = romeo_experiment(2, seed=2)
    cols = {"w": pts.velocity.copy(), "Z": pts.force.copy(), "n_h": pts.n_h.copy()}
    if edit:
        edit(cols)
    f = tmp_path / "steady.csv"
    f.write_text(Log(cols).to_csv_text())
    return f


@pytest.mark.parametrize("column, value, words", [
    ("Z", -1e300, ("Z:", "row 5", "-1e+300", "|Z| <= 1e+09")),
    ("w", 1e300, ("w:", "row 5", "|w| <= 100 m/s")),
    ("n_h", 1e300, ("n_h:", "row 5", "1e+12")),
])
def test_steady_log_with_an_absurd_value(column, value, words, tmp_path, capsys):
    f = _steady_log(tmp_path, lambda c: c[column].__setitem__(3, value))
    _one_line(capsys, ["identify", f, "--method", "steady", "--dof", "heave", "--json"],
              str(f), *words)


def _yaw_log(tmp_path, scale=1.0, value=None):
    from validation.experiments import videoray_yaw_log

    log = videoray_yaw_log(0)
    cols = dict(log.columns)
    cols["t"] = cols["t"] * scale
    if value is not None:
        cols["r"] = cols["r"].copy()
        cols["r"][5] = value
    f = tmp_path / "yaw.csv"
    from stripcoef.logfile import Log
    f.write_text(Log(cols).to_csv_text())
    return f


def test_time_squeezed_to_nanoseconds_or_a_1e300_value(tmp_path, capsys):
    """The fits gave 'null' error bars with exit 0 on these logs."""
    f = _yaw_log(tmp_path, scale=1e-9)
    _one_line(capsys, ["identify", f, "--method", "one-step", "--dof", "yaw"], str(f), "t:",
              "not in seconds", "3.33e-11")
    f = _yaw_log(tmp_path, value=1e300)
    _one_line(capsys, ["identify", f, "--method", "one-step", "--dof", "yaw"], str(f), "r:",
              "1e+300", "rad/s")
    assert main(["identify", str(_yaw_log(tmp_path)), "--method", "one-step", "--dof",
                 "yaw"]) == 0


def test_time_in_milliseconds_is_named(tmp_path, capsys):
    """simulate ran 20,000 s (and stopped at its 120 s budget) on a 20 s log in ms."""
    t = np.arange(0, 20001, 100)
    f = tmp_path / "in.csv"
    f.write_text("t,n_P1,n_P2,n_V1,n_V2\n" + "".join(f"{x},1,1,0,0\n" for x in t))
    t0 = time.time()
    _one_line(capsys, ["simulate", GEO / "mares.yaml", "--inputs", f, "--out",
                       tmp_path / "o.csv"], str(f), "t:", "milliseconds", "divide by 1000")
    assert time.time() - t0 < 30
    assert not (tmp_path / "o.csv").exists()


def test_magnitude_bounds_leave_real_logs_alone():
    """The shipped sample logs pass the magnitude checks."""
    from stripcoef import samples
    from stripcoef.logfile import read_log

    for name in ("heave_steady.csv", "pendulum.csv", "rov_tether.csv", "yaw_onestep.csv"):
        read_log(samples.path(name))


@pytest.mark.parametrize("header, words", [
    ("t,n_P1,n_P2,n_V1", ("n_V2:", "no command column for thruster 'V2'", "zeros")),
    ("t,n_P1,n_P2,n_V1,n_V3", ("n_V3:", "unknown thruster", "n_V2")),
])
def test_simulate_inputs_missing_or_renamed_thruster_column(header, words, tmp_path, capsys):
    """A thruster without its column ran switched off, silently."""
    f = tmp_path / "in.csv"
    cells = ",".join(["1"] * (header.count(",")))
    f.write_text(f"{header}\n0,{cells}\n1,{cells}\n")
    _one_line(capsys, ["simulate", GEO / "mares.yaml", "--inputs", f, "--out",
                       tmp_path / "o.csv"], str(f), *words)
    assert not (tmp_path / "o.csv").exists()


# -- writes that fail cleanly -------------------------------------------------------------

def _disk_full(monkeypatch):
    """Every text or byte write fails as on a full disk (ENOSPC)."""
    import errno

    def full(self, *a, **k):
        raise OSError(errno.ENOSPC, "No space left on device", str(self))
    monkeypatch.setattr(Path, "write_text", full)
    monkeypatch.setattr(Path, "write_bytes", full)


@pytest.mark.parametrize("argv", [
    ["coefficients", GEO / "sphere.yaml", "--strips", "40", "--json", "-o", "{d}/out.json"],
    ["export", GEO / "sphere.yaml", "--to", "json", "-o", "{d}/out.json"],
])
def test_full_disk_is_one_line_and_keeps_the_old_file(argv, tmp_path, capsys, monkeypatch):
    old = tmp_path / "out.json"
    old.write_text("previous\n")
    argv = [str(a).replace("{d}", str(tmp_path)) for a in argv]
    _disk_full(monkeypatch)
    _one_line(capsys, argv, "cannot write (No space left on device", "kept", str(old))
    monkeypatch.undo()
    assert old.read_text() == "previous\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.json"]


def test_output_onto_an_installed_sample_is_refused(capsys):
    from stripcoef import samples

    before = samples.path("sphere.yaml").read_bytes()
    _one_line(capsys, ["coefficients", "sample:sphere.yaml", "--strips", "40", "-o",
                       "sample:sphere.yaml"], "-o", "installed sample is read-only")
    assert samples.path("sphere.yaml").read_bytes() == before


def test_output_set_is_all_new_or_all_old(tmp_path):
    """Outputs of one run (a model, a report and its plot): renamed together after all were
    written; an error while writing the second leaves both old files and no temporary."""
    from stripcoef.files import OutputSet

    a, b = tmp_path / "model.yaml", tmp_path / "sub" / "report.md"
    b.parent.mkdir()
    a.write_text("old model\n")
    b.write_text("old report\n")
    with pytest.raises(RuntimeError):
        with OutputSet() as outs:
            outs.path(a, key="out").write_text("new model\n")
            staged = outs.path(b, key="report")
            staged.with_name("report_plot.png").write_text("png")   # a writer's side file
            raise RuntimeError("killed while writing the report")
    assert a.read_text() == "old model\n" and b.read_text() == "old report\n"
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["model.yaml", "report.md", "sub"]
    with OutputSet() as outs:
        outs.path(a, key="out").write_text("new model\n")
        staged = outs.path(b, key="report")
        staged.write_text("new report\n")
        staged.with_name("report_plot.png").write_text("png")
        assert a.read_text() == "old model\n"                   # nothing moved before commit
    assert a.read_text() == "new model\n" and b.read_text() == "new report\n"
    assert (b.parent / "report_plot.png").read_text() == "png"
    assert sorted(p.name for p in tmp_path.rglob("*")) == [
        "model.yaml", "report.md", "report_plot.png", "sub"]
    with pytest.raises(InputError, match="the same file twice"):
        with OutputSet() as outs:
            outs.path(a)
            outs.path(tmp_path / "sub" / ".." / "model.yaml")


def test_output_set_full_disk_names_the_output(tmp_path, monkeypatch):
    from stripcoef.files import OutputSet, write_text

    a = tmp_path / "cal.yaml"
    a.write_text("old\n")
    _disk_full(monkeypatch)
    with pytest.raises(InputError, match=r"out: cannot write \(No space left.*cal.yaml'"):
        with OutputSet() as outs:
            write_text(outs.path(a, key="out"), "new\n", key="x")
    monkeypatch.undo()
    assert a.read_text() == "old\n" and [p.name for p in tmp_path.iterdir()] == ["cal.yaml"]


@pytest.mark.slow
def test_diagnose_writes_its_model_and_report_as_a_set(tmp_path, capsys, monkeypatch):
    """A failure while writing the report (after the model was written) leaves the earlier
    model and report: never a new model beside an old report."""
    import stripcoef.diagnose.report as report
    from stripcoef.export import export_model
    from conftest import synthetic

    log, prior, _ = synthetic(None, 1, duration=80.0)       # shared: read only
    (tmp_path / "log.csv").write_text(log.to_csv_text())
    (tmp_path / "prior.yaml").write_text(export_model(prior, "yaml"))
    (tmp_path / "cal.yaml").write_text("old model\n")
    (tmp_path / "r.md").write_text("old report\n")

    def broken(result, path):
        Path(path).write_text("half a rep")
        raise OSError(28, "No space left on device", str(path))
    monkeypatch.setattr(report, "markdown_report", broken)
    argv = ["diagnose", tmp_path / "log.csv", "--vehicle", tmp_path / "prior.yaml",
            "--no-resimulate", "--dof", "surge", "--out", tmp_path / "cal.yaml",
            "--report", tmp_path / "r.md"]
    _one_line(capsys, argv, "--report", "No space left", "r.md")
    assert (tmp_path / "cal.yaml").read_text() == "old model\n"
    assert (tmp_path / "r.md").read_text() == "old report\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cal.yaml", "log.csv", "prior.yaml",
                                                          "r.md"]
    monkeypatch.undo()
    assert main([str(a) for a in argv]) == 0
    capsys.readouterr()
    assert (tmp_path / "cal.yaml").read_text() != "old model\n"
    assert (tmp_path / "r.md").read_text() != "old report\n"


# -- options and meshes ---------------------------------------------------------------------

def test_empty_reference_point_is_an_error(capsys):
    """--reference-point '' was taken as not given."""
    _one_line(capsys, ["coefficients", GEO / "sphere.yaml", "--strips", "40",
                       "--reference-point", ""], "--reference-point", "got ''", "X,Y,Z")


def test_diagnose_window_shorter_than_the_sampling(tmp_path, capsys):
    """--window 1e-6 was widened to one sample without a word."""
    from stripcoef.export import export_model
    from conftest import synthetic

    log, prior, _ = synthetic(None, 1, duration=80.0)       # shared: read only
    (tmp_path / "log.csv").write_text(log.to_csv_text())
    (tmp_path / "prior.yaml").write_text(export_model(prior, "yaml"))
    _one_line(capsys, ["diagnose", tmp_path / "log.csv", "--vehicle", tmp_path / "prior.yaml",
                       "--no-resimulate", "--window", "1e-6"], "--window", "1e-06",
              "sampling intervals")


def test_scale_of_a_result_without_method_or_dof(tmp_path, capsys):
    """Without its method and DOF a result was scaled as translational, silently."""
    f = tmp_path / "r.json"
    f.write_text(json.dumps({"parameters": {"m_a": 1.0, "K_L": 2.0},
                             "std": {"m_a": 0.1, "K_L": 0.2}}))
    _one_line(capsys, ["scale", f, "--ratio", "3.3"], str(f), "method",
              "--rotational or --translational")
    assert main(["scale", str(f), "--ratio", "3.3", "--translational", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["parameters"]["m_a"] == pytest.approx(3.3 ** 3)


@pytest.mark.parametrize("suffix", ["stl", "obj"])
def test_mesh_with_nan_vertices_names_the_nan(suffix, tmp_path, capsys):
    """trimesh dropped the faces of the NaN vertex and the repair closed the hole: a
    different body with a warning (or an error blaming watertightness)."""
    trimesh = pytest.importorskip("trimesh")
    box = trimesh.creation.box(extents=(1.0, 0.3, 0.2))
    v = np.array(box.vertices)
    v[3, 1] = np.nan
    f = tmp_path / f"nan.{suffix}"
    data = trimesh.Trimesh(vertices=v, faces=box.faces, process=False).export(file_type=suffix)
    f.write_bytes(data if isinstance(data, bytes) else data.encode())
    _one_line(capsys, ["coefficients", f, "--strips", "40"], str(f), "non-finite vertex",
              "nan", "expected finite coordinates")


def test_reference_speed_beyond_any_vehicle_is_named(tmp_path, capsys):
    """A reference speed of 7.5e6 m/s was accepted; the limits then said only that no speed
    could be held (the campaign's one vague error)."""
    f = tmp_path / "v.yaml"
    f.write_text(HULL + "reference_speed: 7500000.0\n")
    _one_line(capsys, ["limits", f, "--json", "--radii", "1:10:5"], str(f), "reference_speed",
              "7500000.0", "<= 100 m/s")
    _one_line(capsys, ["coefficients", GEO / "sphere.yaml", "--strips", "40", "--speed",
                       "1e300"], "--speed", "<= 100 m/s")


def test_a_huge_log_is_refused_up_front(tmp_path, capsys):
    """A log over files.MAX_TEXT_BYTES (a 1 GB CSV) is refused before any byte is read: one
    line with its size and the remedy, at once and in no memory (the file here is sparse)."""
    import resource

    from stripcoef.files import MAX_TEXT_BYTES

    big = tmp_path / "huge.csv"
    with open(big, "wb") as fh:
        fh.write(b"t,u\n0,0\n")
        fh.truncate(MAX_TEXT_BYTES * 4)            # 1 GiB, no disk used
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    _one_line(capsys, ["identify", str(big), "--method", "steady", "--dof", "surge"],
              "huge.csv", "too large to read (1024 MiB", "split it")
    assert resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before < 200_000   # kB


@pytest.mark.parametrize("segment, key", [
    ("{type: ellipsoid_nose, x: [0.5, 1.0], radius: 1.0e+300}", "hull.profile[0].radius"),
    ("{type: cylinder, x: [0.0, 1.0e+300], radius: 0.1}", "hull.profile[0].x"),
    ("{type: cone, x: [0.0, 1.0], radius: [0.1, 5000.0]}", "hull.profile[0].radius"),
])
def test_absurd_lengths_are_refused_before_the_geometry_libraries(segment, key, tmp_path,
                                                                     capsys):
    """A 1e300 m radius reached shapely's overlay (GEOSException traceback, fuzz campaign
    seed 3927): lengths beyond geometry.vehicle.MAX_DIMENSION are one-line errors."""
    f = tmp_path / "v.yaml"
    f.write_text(f"name: big\nhull:\n  profile:\n    - {segment}\n")
    _one_line(capsys, ["coefficients", f], str(f), key, "too large", "2000 m")
