"""The typed, immutable results and the registries of the layout (docs/architecture.md).

Properties that can fail: a HydroModel cannot be changed in place (fields, arrays, the
caller's arrays stay writable), a changed model is a new one; the estimate options give the
same model as the keywords; the typed conditions read as the JSON's mapping, in its order;
the registries hold frozen specs and refuse unknown names with the list of valid ones.
"""

import copy
import json
import pickle
import re
from dataclasses import FrozenInstanceError, fields, replace
from pathlib import Path

import numpy as np
import pytest

import stripcoef
from stripcoef.assembly import EstimateOptions, estimate
from stripcoef.assembly.methods import (ADDED_MASS_METHODS, AddedMassMethod, choose_method,
                                        estimate_choices, get_method)
from stripcoef.effects import EFFECTS, get_effect
from stripcoef.errors import InputError
from stripcoef.export import FORMATS, ExportFormat, get_format
from stripcoef.geometry.shapes import GEOMETRY, ShapeGeometry, built_from_half_sizes, shape_geometry
from stripcoef.model import Conditions
from stripcoef.sections import SHAPES, SectionShape, get_shape
from stripcoef.strips import Part

ROOT = Path(__file__).resolve().parents[1]
GOLDEN = ROOT / "tests" / "golden"


@pytest.fixture(scope="module")
def sphere():
    return estimate(ROOT / "geometry" / "sphere.yaml", strips=100)


def test_model_fields_and_arrays_cannot_be_changed(sphere):
    with pytest.raises(FrozenInstanceError):
        sphere.added_mass = np.zeros((6, 6))
    for name in ("reference_point", "rigid_body_mass", "added_mass", "linear_damping",
                 "quadratic_damping", "center_of_gravity", "center_of_buoyancy"):
        with pytest.raises(ValueError, match="read-only"):
            getattr(sphere, name)[0] = 1.0
    assert isinstance(sphere.thrusters, tuple) and isinstance(sphere.effects, tuple)
    with pytest.raises(TypeError):
        sphere.provenance["method"] = "x"
    with pytest.raises(TypeError):
        sphere.conditions["regime"] = "x"


def test_model_copies_the_callers_arrays(sphere):
    ma = np.array(sphere.added_mass)
    m = replace(sphere, added_mass=ma)
    assert ma.flags.writeable and m.added_mass is not ma
    ma[0, 0] += 1.0
    assert m.added_mass[0, 0] == sphere.added_mass[0, 0]


def test_changed_models_are_new_ones(sphere):
    entry = {"name": "buoyancy_offset", "dof": "heave", "parameters": {"b": 1.0}}
    m = sphere.with_effects(entry)
    assert sphere.effects == () and m.effects == (entry,)
    p = sphere.with_provenance(note="x")
    assert "note" not in sphere.provenance and p.provenance["note"] == "x"
    d = get_effect("linear_drag").apply(sphere, 0, {"d_L": 2.0})
    assert d.linear_damping[0, 0] == sphere.linear_damping[0, 0] + 2.0
    assert sphere.linear_damping[0, 0] != d.linear_damping[0, 0]


def test_pickle_and_deepcopy_round_trip(sphere):
    for m in (pickle.loads(pickle.dumps(sphere)), copy.deepcopy(sphere)):
        assert json.dumps(m.to_dict()) == json.dumps(sphere.to_dict())
        assert not m.added_mass.flags.writeable


def test_estimate_options_equal_the_keywords():
    path = ROOT / "geometry" / "spheroid.yaml"
    by_kw = estimate(path, strips=120, corrections=False, speed=0.8)
    opts = EstimateOptions(strips=120, corrections=False, speed=0.8)
    assert json.dumps(estimate(path, opts).to_dict()) == json.dumps(by_kw.to_dict())
    # keywords beside options replace their fields
    again = estimate(path, EstimateOptions(strips=120, speed=0.8), corrections=False)
    assert json.dumps(again.to_dict()) == json.dumps(by_kw.to_dict())
    assert stripcoef.EstimateOptions is EstimateOptions
    with pytest.raises(TypeError):
        estimate(path, {"strips": 120})
    with pytest.raises(TypeError):
        EstimateOptions(strip=10)
    with pytest.raises(FrozenInstanceError):
        opts.strips = 10


@pytest.mark.parametrize("name", ["mares", "mares_no_corrections", "box_mesh"])
def test_conditions_read_as_the_json_in_its_order(name):
    want = json.loads((GOLDEN / f"{name}.json").read_text())["conditions"]
    c = Conditions.from_dict(want)
    assert list(c) == list(want) and c.to_dict() == want and dict(c) == want
    assert c.extra == {}
    for key, value in want.items():
        assert c[key] == value == getattr(c, key)
    missing = next(k for k in ("k1", "end_correction_sway") if k not in want)
    assert missing not in c and c.get(missing) is None
    with pytest.raises(KeyError):
        c[missing]


def test_conditions_keep_unknown_keys_of_a_model_file():
    c = Conditions.from_dict({"note": "hand-built", "reference_speed": 1.5, "zeta": 2})
    assert list(c) == ["reference_speed", "note", "zeta"]
    assert c.reference_speed == 1.5 and c["note"] == "hand-built"
    assert Conditions.from_dict(c.to_dict()) == c


def test_correction_factors_are_frozen():
    from stripcoef.hull.corrections import hull_corrections
    v = stripcoef.load_vehicle(ROOT / "geometry" / "spheroid.yaml")
    st = v.cut(80)
    c = hull_corrections(st, rho=1025.0, center=(0.0, 0.0, 0.0), panels=40)
    with pytest.raises(FrozenInstanceError):
        c.axial_added_mass = 0.0
    with pytest.raises(ValueError, match="read-only"):
        c.scale[1] = 1.0
    assert (c.translation, c.rotation, c.coupling) == (c.scale[1], c.scale[5], c.coupling_26)


def test_section_shape_spec_carries_its_geometry():
    # one shape = one geometry entry (below sections) + one coefficient entry, same names
    assert set(SHAPES) == set(GEOMETRY)
    for name, spec in SHAPES.items():
        assert isinstance(spec, ShapeGeometry)
        for f in fields(ShapeGeometry):
            assert getattr(spec, f.name) is getattr(GEOMETRY[name], f.name)
    # no shape name is tested outside the registries
    src = Path(stripcoef.__file__).parent
    pattern = re.compile(r"(shape|section)\s*[!=]=\s*[\"'](" + "|".join(SHAPES) + r")[\"']")
    hits = [f"{p.relative_to(src)}:{i}" for p in src.rglob("*.py")
            for i, line in enumerate(p.read_text().splitlines(), 1) if pattern.search(line)]
    assert hits == []


def test_section_shape_geometry_is_exact():
    part = Part(name="p", shape="rectangle", index=[0], y=0.1, z=-0.2, half_breadth=0.3,
                half_height=0.05, area=0.06)
    ring = get_shape("rectangle").outline(part, 0, 8)[0]
    assert ring.shape == (5, 2) and np.allclose(ring[0], ring[-1])
    assert np.isclose(get_shape("rectangle").outer_area(part)[0], 4 * 0.3 * 0.05)
    assert np.isclose(get_shape("rectangle").wetted_perimeter(part)[0], 4 * 0.35)
    part = replace(part, shape="ellipse")
    ring = get_shape("ellipse").outline(part, 0, 400)[0]
    area = 0.5 * abs(np.sum(ring[:-1, 0] * ring[1:, 1] - ring[1:, 0] * ring[:-1, 1]))
    assert np.isclose(area, np.pi * 0.3 * 0.05, rtol=1e-3)
    assert np.isclose(get_shape("ellipse").half_chord(0.3, 0.05, 0.15), 0.05 * np.sqrt(0.75))
    assert built_from_half_sizes() == ("ellipse", "rectangle")
    with pytest.raises(InputError, match="polygon"):
        shape_geometry("hexagon")


def test_registries_hold_frozen_specs_and_list_valid_names():
    assert all(isinstance(s, SectionShape) and s.name == k for k, s in SHAPES.items())
    assert all(isinstance(f, ExportFormat) and f.name == k for k, f in FORMATS.items())
    assert all(e.name == k for k, e in EFFECTS.items())
    with pytest.raises(FrozenInstanceError):
        SHAPES["ellipse"].name = "x"
    with pytest.raises(FrozenInstanceError):
        FORMATS["json"].binary = True
    with pytest.raises(FrozenInstanceError):
        EFFECTS["current"].name = "x"
    assert all(isinstance(m, AddedMassMethod) and m.name == k
               for k, m in ADDED_MASS_METHODS.items())
    with pytest.raises(FrozenInstanceError):
        ADDED_MASS_METHODS["strips"].in_estimate = False
    for lookup, names in ((get_shape, SHAPES), (get_format, FORMATS), (get_effect, EFFECTS),
                          (get_method, ADDED_MASS_METHODS)):
        with pytest.raises(InputError) as err:
            lookup("no-such-thing")
        assert all(n in str(err.value) for n in names)


def test_added_mass_methods_registry_drives_the_option_and_the_cli(sphere):
    from stripcoef.cli.app import build_parser
    from stripcoef.geometry.vehicle import load_vehicle

    assert set(ADDED_MASS_METHODS) == {"strips", "panels", "bem"}
    assert estimate_choices() == ("auto", "panels", "strips")     # the BEM runs after
    sub = build_parser()._subparsers._group_actions[0].choices["coefficients"]
    flag = next(a for a in sub._actions if a.dest == "added_mass_method")
    assert tuple(flag.choices) == estimate_choices()
    veh = load_vehicle(ROOT / "geometry" / "sphere.yaml")
    assert choose_method("auto", veh, veh.cut(40)).name == "strips"   # no mesh
    assert sphere.provenance["method"] == ADDED_MASS_METHODS["strips"].provenance
    # a vehicle file is panelled on its united surface; the BEM runs after the estimate
    assert choose_method("panels", veh, veh.cut(40)).name == "panels"
    with pytest.raises(InputError, match="panels or strips or auto"):
        choose_method("bem", veh, veh.cut(40))
