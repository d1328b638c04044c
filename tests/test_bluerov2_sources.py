"""The shipped BlueROV2 Heavy is built from cited numbers (issue 32).

scripts/make_bluerov2_heavy.py tags every dimension with its source
(reference_tables/bluerov2/README.md); these tests hold the generator's constants and the
shipped vehicle file to the stored published values (reference_tables/bluerov2/dimensions.csv),
check the computed rows of the stored tables against their formulas, and that the validation
section reads the stored run.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
import yaml

from scripts import make_bluerov2_heavy as gen
from validation import reference as ref

ROOT = Path(__file__).resolve().parents[1]
GEOMETRY = ROOT / "geometry"
MM = 1e-3
KGF = 9.80665        # standard gravity [m/s^2]: 1 kgf in N (ISO 80000-4)


def pub(name: str) -> float:
    return ref.reference_value("bluerov2", name)["value"]


@pytest.fixture(scope="module")
def shipped() -> dict:
    return yaml.safe_load((GEOMETRY / "bluerov2_heavy.yaml").read_text())


def test_tables_load_and_computed_rows_recompute():
    for table in ("dimensions", "identified"):
        assert ref.table_caption("bluerov2", table)
        assert ref.load_table("bluerov2", table)
    computed = [r["name"] for r in ref.load_table("bluerov2", "dimensions")
                if r["provenance"] == "computed"]
    assert len(computed) >= 5
    for name in computed:
        assert ref.agrees(ref.reference_value("bluerov2", name),
                          ref.recompute("bluerov2", name)), name


def test_readme_names_every_table_and_source():
    text = (ROOT / "reference_tables" / "bluerov2" / "README.md").read_text()
    assert "Citation" in text and "Inconsistencies" in text
    folder = ROOT / "reference_tables" / "bluerov2"
    for csv_file in [*folder.glob("*.csv"), *folder.glob("runs/*.csv")]:
        name = csv_file.relative_to(folder).as_posix()
        assert f"`{name}`" in text, name
    for tag in ("BR-H", "BR-2", "BR-A", "BR-W", "BR-T", "SF", "IG", "CN", "AP"):
        assert f"| {tag} |" in text, tag
    script = (ROOT / "scripts" / "make_bluerov2_heavy.py").read_text()
    for tag in ("BR-H", "BR-2", "BR-A", "BR-W", "BR-T", "SF"):
        assert f"[{tag}" in script, tag


def test_generator_constants_are_the_published_values():
    assert gen.LENGTH == pytest.approx(pub("heavy.length") * MM)
    assert gen.HEIGHT == pytest.approx(pub("heavy.height") * MM)
    assert gen.WIDTH_HEAVY == pytest.approx(pub("heavy.width") * MM)
    assert gen.FRAME_WIDTH == pytest.approx(pub("base.width") * MM)
    assert gen.MASS == pytest.approx(pub("heavy.mass_in_air"))
    assert gen.SIDE_PLATE_PUBLISHED == pytest.approx(pub("side_panel.thickness") * MM)
    # the side panels as published (3/8"): modelled 1/2" until the foam's slot was closed
    assert gen.SIDE_PLATE == pytest.approx(gen.SIDE_PLATE_PUBLISHED)
    assert gen.PLATE == pytest.approx(pub("bottom_panel.thickness") * MM)
    assert gen.TUBE4_OD == pytest.approx(pub("tube4.outer_diameter") * MM)
    assert gen.TUBE4_TOTAL == pytest.approx(pub("tube4.total_length") * MM)
    assert gen.TUBE3_OD == pytest.approx(pub("tube3.outer_diameter") * MM)
    assert gen.BATTERY_LENGTH == pytest.approx(pub("battery_enclosure.length") * MM)
    assert gen.T200_D == pytest.approx(pub("t200.diameter") * MM)
    assert gen.T200_L == pytest.approx(pub("t200.length") * MM)
    assert gen.T200_VOLUME == pytest.approx(pub("t200.displaced_volume") * 1e-6)
    assert gen.T200_FORWARD == pytest.approx(pub("t200.max_forward_16V") * KGF)
    assert gen.T200_REVERSE == pytest.approx(pub("t200.max_reverse_16V") * KGF)
    # the duct ring's wall holds the published displacement: pi/4 (D^2 - d^2) L = V
    wall = math.pi / 4 * (gen.T200_D ** 2 - gen.T200_ID ** 2) * gen.T200_L
    assert wall == pytest.approx(gen.T200_VOLUME, rel=1e-12)


def test_thruster_places_are_the_public_models():
    """SF's places in x and y as printed, in z moved by its origin's height above its
    physical mesh's middle; the vertical ducts touch the side panels' outer faces (BR-H
    mounts them there) and sit within 4 mm of IG's independent places."""
    mid = pub("sf.origin_above_mid_height")
    assert gen.H_THRUSTER_X == pytest.approx((pub("sf.horizontal_fore.x"),
                                              pub("sf.horizontal_aft.x")))
    assert gen.H_THRUSTER_Y == pytest.approx(pub("sf.horizontal.y"))
    assert gen.H_THRUSTER_Z == pytest.approx(pub("sf.horizontal.z") - mid, abs=1e-4)
    assert gen.V_THRUSTER_X == pytest.approx(pub("sf.vertical.x"))
    assert gen.V_THRUSTER_Y == pytest.approx(pub("sf.vertical.y"))
    assert gen.V_THRUSTER_Z == pytest.approx(pub("sf.vertical.z") - mid, abs=1e-4)
    assert abs(gen.V_THRUSTER_X - pub("ig.vertical.x")) < 4e-3
    assert abs(gen.V_THRUSTER_Y - pub("ig.vertical.y")) < 4e-3
    inner_edge = gen.V_THRUSTER_Y - 0.5 * gen.T200_D
    assert 0 < 0.5 * gen.FRAME_WIDTH - inner_edge < 2e-3          # 1 mm into the panel


def test_shipped_vehicle_file_is_the_generator_output(shipped):
    """The shipped file carries the generator's numbers (what `python -m
    scripts.make_bluerov2_heavy` writes), so the tests above hold for it."""
    parts = {a["name"]: a for a in shipped["appendages"]}
    assert shipped["mass"]["mass"] == pytest.approx(gen.MASS)
    assert parts["post_fore_starboard"]["size"][1] == pytest.approx(gen.SIDE_PLATE, abs=1e-6)
    assert parts["post_fore_starboard"]["center"][1] + 0.5 * gen.SIDE_PLATE == pytest.approx(
        0.5 * gen.FRAME_WIDTH, abs=1e-6)
    assert parts["bottom_strip_fore"]["size"][2] == pytest.approx(gen.PLATE)
    assert parts["battery_tube"]["diameter"] == pytest.approx(gen.TUBE3_OD)
    assert parts["battery_tube"]["length"] == pytest.approx(gen.BATTERY_LENGTH, abs=1e-5)
    tube = shipped["hull"]["profile"][0]
    assert tube["x"][1] - tube["x"][0] == pytest.approx(gen.TUBE4_TOTAL)
    assert 2 * tube["radius"] == pytest.approx(gen.TUBE4_OD)
    assert shipped["hull"]["profile"][1]["x"][1] == pytest.approx(0.5 * gen.LENGTH)
    pos = {t["name"]: t["position"] for t in shipped["thrusters"]}
    assert pos["t1"] == pytest.approx([gen.H_THRUSTER_X[0], gen.H_THRUSTER_Y, gen.H_THRUSTER_Z])
    assert pos["t4"] == pytest.approx([gen.H_THRUSTER_X[1], -gen.H_THRUSTER_Y,
                                       gen.H_THRUSTER_Z])
    assert pos["t8"] == pytest.approx([-gen.V_THRUSTER_X, -gen.V_THRUSTER_Y, gen.V_THRUSTER_Z])
    for t in shipped["thrusters"]:
        assert t["max_forward"] == pytest.approx(gen.T200_FORWARD, abs=0.01)
        assert t["max_backward"] == pytest.approx(gen.T200_REVERSE, abs=0.01)


def test_shipped_mesh_size_and_volume():
    """Published length and height; the width is the frame plus the vertical ducts (the
    guards that make the published 571 mm are left out); the volume is the published mass
    at neutral buoyancy in fresh water (the foam block closes it on the vehicle file's
    strips, which count the parts' overlaps twice: within 1.5 %). The round parts' 16-sided
    polygons stand 0.65 mm out at their vertices."""
    mesh = trimesh.load(GEOMETRY / "bluerov2_heavy.stl", force="mesh")
    assert mesh.is_watertight
    width = 2 * (gen.V_THRUSTER_Y + 0.5 * gen.T200_D)
    np.testing.assert_allclose(np.ptp(mesh.vertices, axis=0),
                               [gen.LENGTH, width, gen.HEIGHT], atol=1.5e-3)
    assert width < gen.WIDTH_HEAVY
    assert mesh.volume * gen.RHO == pytest.approx(gen.MASS, rel=0.015)


def test_identified_models_are_stored_as_magnitudes():
    for model in ("vb2022", "wu2018"):
        for term in ("X_udot", "Y_vdot", "Z_wdot", "K_pdot", "M_qdot", "N_rdot"):
            row = ref.reference_value("bluerov2", f"{model}.{term}")
            assert row["value"] > 0 and "magnitude" in row["sign_convention"]
            assert row["provenance"] == "assumed (unverified)" and row["note"]


def test_validation_section_reads_the_stored_run():
    from validation import bluerov2

    text = bluerov2.section()
    assert text.startswith("## BlueROV2 Heavy")
    assert "BR-H" in text and "vb2022" in text
    if bluerov2.RUN.exists():
        command, rows = bluerov2.read_stored_run(bluerov2.RUN)
        assert command.startswith("OPENBLAS_NUM_THREADS=1 python -m validation.bluerov2")
        assert {r["label"] for r in rows} == {label for label, _, _ in bluerov2.FILES}
        assert len(rows) == 6 * len(bluerov2.FILES)
