"""The Gazebo Harmonic export (SDF 1.11) against the SDFormat 1.11 specification.

Debian's sdformat 12 cannot parse SDF 1.11 and sdformat 14 is not packaged here, so the
file is checked against the specification files themselves (reference_tables/sdformat_1_11,
gazebosim/sdformat at sdformat14_14.9.0) the way sdformat 14's parser reads them
(tests/_sdf_spec.py): every element and attribute described under its parent, required
attributes present, single elements once, a joint's required children present, typed values
readable. The legacy (Fortress) file is SDF 1.9 and is parsed by sdformat 12 itself
(test_export_gazebo_fortress.py).
"""

import warnings

import pytest
from _sdf_spec import problems, root_spec


from stripcoef.export import export_model

# the REMUS (a thruster and control surfaces) in the quick loop, the others marked slow (the
# BlueROV2's eight thrusters: its vehicle file is panelled, about 8 s of CPU)
VEHICLES = [pytest.param(v, marks=[] if v.startswith("remus") else [pytest.mark.slow])
            for v in ("bluerov2_heavy.yaml", "mares.yaml", "remus100.yaml",
                      "videoray_pro3.yaml")]


class _Models(dict):
    def __init__(self, once):
        super().__init__()
        self.once = once

    def __missing__(self, name):
        from conftest import shipped_model_once     # shared with the other export tests

        self[name] = shipped_model_once(self.once, name)
        return self[name]


@pytest.fixture(scope="module")
def models(run_once):
    """Vehicle file name -> its model, estimated on first use (once per run)."""
    return _Models(run_once)


def _export(model, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return export_model(model, "gazebo", **kw)


@pytest.mark.parametrize("world", [False, True], ids=["model", "world"])
@pytest.mark.parametrize("vehicle", VEHICLES)
def test_harmonic_file_follows_the_sdf_1_11_specification(models, vehicle, world):
    text = _export(models[vehicle], world=world)
    assert '<sdf version="1.11">' in text
    assert problems(text) == []
    if models[vehicle].thrusters:
        assert "gz-sim-thruster-system" in text


def test_the_spec_is_read_whole():
    root = root_spec()
    assert set(root.children) == {"world", "model", "actor", "light"}
    model = root.children["model"]
    assert model.children["model"].children is model.children      # nested models (ref)
    assert model.children["plugin"].copy_data                        # any child in a plugin
    fam = model.children["link"].children["inertial"].children["fluid_added_mass"]
    assert len(fam.children) == 21 and all(s.type == "double" for s in fam.children.values())
    # an <include>'s required is the included file's (parser.cc initXml), not the tag's
    assert root.children["world"].children["physics"].required == "1"  # world.sdf says "+"
    assert root.children["actor"].children["link"].required == "*"     # actor.sdf says "+"


@pytest.mark.slow      # the BlueROV2 model fixture: its vehicle file is panelled (8 s)
@pytest.mark.parametrize("edit, expected", [
    (lambda t: t.replace("<mass>", "<masse>", 1).replace("</mass>", "</masse>", 1),
     "/sdf/model[@name='BlueROV2 Heavy']/link[@name='base_link']/inertial/masse: "
     "element not defined in SDF 1.11 under <inertial>"),
    (lambda t: t.replace('<link name="base_link">', '<link name="base_link" kind="x">', 1),
     "attribute 'kind' not defined"),
    (lambda t: t.replace('<plugin filename="gz-sim-thruster-system"', "<plugin", 1),
     "required attribute 'filename' missing"),
    (lambda t: t.replace("<child>thruster_t1</child>", "", 1),
     "required element <child> missing"),
    (lambda t: t.replace("<mass>11.5</mass>", "<mass>11.5 kg</mass>", 1),
     "does not read as double"),
    (lambda t: t.replace("<mass>11.5</mass>", "<mass>11.5</mass><mass>1</mass>", 1),
     "<mass> given twice"),
], ids=["element", "attribute", "required attribute", "joint child", "value", "twice"])
def test_the_check_finds_what_sdformat_reports(models, edit, expected):
    text = _export(models["bluerov2_heavy.yaml"])
    assert problems(text) == []
    found = problems(edit(text))
    assert len(found) == 1 and expected in found[0], found
