"""Every class of bad vehicle file: a one-line error naming file, key, value and expectation,
exit code 2 from the CLI, and no output file."""

import copy

import pytest
import yaml

from stripcoef.cli import main

GOOD = {
    "name": "t",
    "hull": {"profile": [{"type": "ellipsoid_tail", "x": [-0.5, -0.3], "radius": 0.1},
                         {"type": "cylinder", "x": [-0.3, 0.3], "radius": 0.1},
                         {"type": "ellipsoid_nose", "x": [0.3, 0.5], "radius": 0.1}]},
}


def _mutate(path, value):
    data = copy.deepcopy(GOOD)
    node = data
    for k in path[:-1]:
        node = node[k]
    if value is _DELETE:
        del node[path[-1]]
    else:
        node[path[-1]] = value
    return data


_DELETE = object()

CASES = [
    ("unknown key", lambda: dict(GOOD, colour="red"), "colour", "unknown key"),
    ("missing hull", lambda: {"name": "t"}, "hull", "missing required key"),
    ("wrong type", lambda: _mutate(["hull", "profile", 1, "radius"], "big"),
     "hull.profile[1].radius", "expected a number"),
    ("negative size", lambda: _mutate(["hull", "profile", 1, "radius"], -0.1),
     "hull.profile[1].radius", "must be positive"),
    ("zero size", lambda: _mutate(["hull", "profile", 1, "radius"], 0),
     "hull.profile[1].radius", "must be positive"),
    ("nan", lambda: _mutate(["hull", "profile", 1, "radius"], float("nan")),
     "hull.profile[1].radius", "not finite"),
    ("gap", lambda: _mutate(["hull", "profile", 1, "x"], [-0.29, 0.3]), "hull.profile", "gap"),
    ("overlap", lambda: _mutate(["hull", "profile", 1, "x"], [-0.35, 0.3]), "hull.profile",
     "overlap"),
    ("unknown segment", lambda: _mutate(["hull", "profile", 1, "type"], "banana"),
     "hull.profile[1].type", "one of"),
    ("hole outside", lambda: dict(GOOD, holes=[{"axis": "z", "x": 0.9, "diameter": 0.05}]),
     "holes[0].x", "outside the hull"),
    ("hole too wide", lambda: dict(GOOD, holes=[{"axis": "z", "x": 0.0, "diameter": 0.5}]),
     "holes[0].diameter", "wider than the hull"),
    ("floating appendage", lambda: dict(GOOD, appendages=[
        {"name": "far", "type": "box", "center": [0, 2.0, 0], "size": [0.1, 0.1, 0.1]}]),
     "appendages[0]", "intersects nothing"),
    ("fin off the hull", lambda: dict(GOOD, appendages=[
        {"name": "f", "type": "fin", "center": [-0.4, 0, -0.12], "span_axis": "z", "span": 0.04,
         "chord": 0.05}]),
     "appendages[0].center", "does not touch the hull"),
    ("fin across the axis", lambda: dict(GOOD, appendages=[
        {"name": "f", "type": "fin", "center": [0.0, 0, 0.0], "span_axis": "z", "span": 0.4,
         "chord": 0.05}]),
     "appendages[0].span", "crosses the hull axis"),
    ("fin of zero span", lambda: dict(GOOD, appendages=[
        {"name": "f", "type": "fin", "center": [0.0, 0, 0.15], "span_axis": "z", "span": 0,
         "chord": 0.05}]),
     "appendages[0].span", "must be positive"),
    ("bad reference", lambda: dict(GOOD, reference_point="nose"), "reference_point",
     "center_of_buoyancy"),
    ("bad thruster", lambda: dict(GOOD, thrusters=[{"name": "a", "position": [0, 0, 0],
                                                   "direction": [0, 0, 0]}]),
     "thrusters[0].direction", "zero vector"),
    ("bad inertia", lambda: dict(GOOD, mass={"mass": 10, "inertia": [1, -1, 1]}),
     "mass.inertia", "positive definite"),
]


@pytest.mark.parametrize("label,make,key,text", CASES, ids=[c[0] for c in CASES])
def test_bad_vehicle_file(tmp_path, capsys, label, make, key, text):
    f = tmp_path / "bad.yaml"
    f.write_text(yaml.safe_dump(make()))
    out = tmp_path / "out.json"
    code = main(["coefficients", str(f), "--json", "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 2
    assert not out.exists()
    assert err.count("\n") == 1, err          # one line
    assert str(f) in err and key in err and text in err, err
    assert "Traceback" not in err


def test_invalid_yaml_names_the_line(tmp_path, capsys):
    f = tmp_path / "broken.yaml"
    f.write_text("name: x\nhull: [unclosed\n")
    assert main(["coefficients", str(f)]) == 2
    err = capsys.readouterr().err
    assert "invalid YAML" in err and "line" in err


def test_existing_output_untouched_on_error(tmp_path, capsys):
    out = tmp_path / "out.json"
    out.write_text("previous")
    f = tmp_path / "bad.yaml"
    f.write_text(yaml.safe_dump({"name": "t"}))
    assert main(["coefficients", str(f), "--json", "-o", str(out)]) == 2
    assert out.read_text() == "previous"


def test_missing_file_and_bad_extension(tmp_path, capsys):
    assert main(["coefficients", str(tmp_path / "none.yaml")]) == 2
    assert "file not found" in capsys.readouterr().err
    f = tmp_path / "v.txt"
    f.write_text("x")
    assert main(["coefficients", str(f)]) == 2
    assert "extension" in capsys.readouterr().err
