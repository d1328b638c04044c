"""Mesh input: formats, units, axes, origin, defects and bad input."""

import numpy as np
import pytest
import trimesh

from stripcoef.errors import InputError, ModelWarning
from stripcoef.geometry.mesh import load_mesh, mesh_body, revolved_mesh


def spheroid(a=0.75, b=0.1, n_ax=60, n_circ=48):
    t = np.linspace(0.0, np.pi, n_ax + 1)[::-1]
    return revolved_mesh(a * np.cos(t), b * np.sin(t), sections=n_circ)


@pytest.mark.parametrize("ext", [".stl", ".obj", ".ply", ".glb"])
def test_formats_round_trip(tmp_path, ext):
    m = spheroid()
    path = tmp_path / f"body{ext}"
    m.export(path)
    body = load_mesh(path)
    assert body.volume == pytest.approx(m.volume, rel=1e-6)
    np.testing.assert_allclose(body.centroid, 0.0, atol=1e-9)
    assert body.x_extent() == pytest.approx((-0.75, 0.75), abs=1e-6)


def test_units_axis_and_origin(tmp_path):
    m = spheroid()
    ref = mesh_body(m)
    # same body in millimetres, lying along the file's z axis, offset
    m2 = m.copy()
    m2.vertices = np.asarray(m2.vertices)[:, [1, 2, 0]] * 1000.0 + [10.0, 20.0, 30.0]
    path = tmp_path / "body_mm.stl"
    m2.export(path)
    body = load_mesh(path, axis="z", length_unit="mm")
    assert body.volume == pytest.approx(ref.volume, rel=1e-6)       # STL stores float32
    assert body.x_extent() == pytest.approx(ref.x_extent(), abs=1e-6)
    # origin at a given point (file coordinates and unit): the nose tip
    nose = np.array([10.0, 20.0, 30.0 - 750.0])
    b2 = load_mesh(path, axis="z", length_unit="mm", origin=nose)
    assert b2.x_extent() == pytest.approx((0.0, 1.5), abs=1e-6)


def test_transform_applied():
    m = spheroid()
    rot = trimesh.transformations.rotation_matrix(np.pi / 2, [0, 0, 1])  # x -> y
    m2 = m.copy()
    m2.apply_transform(np.linalg.inv(rot))
    body = mesh_body(m2, transform=rot)
    assert body.x_extent() == pytest.approx((-0.75, 0.75), abs=1e-6)


def test_clean_mesh_reports_nothing():
    assert mesh_body(spheroid()).repairs == []


def test_flipped_normals_repaired():
    m = spheroid()
    m.invert()
    body = mesh_body(m)
    assert body.volume > 0
    assert any("flipped" in r for r in body.repairs)


def test_degenerate_and_duplicate_faces_removed():
    m = spheroid()
    v = np.vstack([m.vertices, [[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.2, 0.0, 0.0]]])
    n = len(m.vertices)
    f = np.vstack([m.faces, [[n, n + 1, n + 2]], m.faces[:3]])
    body = mesh_body(trimesh.Trimesh(v, f, process=False))
    text = " ".join(body.repairs)
    assert "degenerate" in text and "duplicate" in text
    assert body.volume == pytest.approx(m.volume, rel=1e-9)


def test_small_hole_filled():
    m = spheroid()
    keep = np.ones(len(m.faces), bool)
    keep[len(m.faces) // 2] = False
    m2 = trimesh.Trimesh(m.vertices, m.faces[keep], process=False)
    assert not m2.is_watertight
    body = mesh_body(m2)
    assert any("holes" in r for r in body.repairs)
    assert body.volume == pytest.approx(m.volume, rel=1e-3)


def test_non_manifold_open_mesh_refused():
    box = trimesh.creation.box([1.0, 0.2, 0.2])
    # a loose fin: a single triangle sharing a box edge, giving a non-manifold edge
    e = box.edges_unique[0]
    v = np.vstack([box.vertices, [[0.0, 0.0, 1.0]]])
    f = np.vstack([box.faces, [[e[0], e[1], len(box.vertices)]]])
    with pytest.raises(InputError, match="watertight"):
        mesh_body(trimesh.Trimesh(v, f, process=False))


def test_several_bodies_reported_and_sliced_together():
    a = trimesh.creation.icosphere(subdivisions=3, radius=0.1)
    b = a.copy()
    b.apply_translation([0.0, 0.5, 0.0])
    body = mesh_body(trimesh.util.concatenate([a, b]))
    assert any("2 separate bodies" in r for r in body.repairs)
    st = body.strips(20)
    assert len(st.parts) == 1
    assert all(len(c) == 2 for c in st.parts[0].contours)
    assert st.parts[0].half_breadth[10] == pytest.approx(0.35, rel=2e-2)


def test_overlapping_bodies_united():
    a = trimesh.creation.box([1.0, 0.2, 0.2])
    b = trimesh.creation.box([0.4, 0.2, 0.6])           # a fin crossing the hull
    body = mesh_body(trimesh.util.concatenate([a, b]))
    with pytest.warns(ModelWarning, match="double counts"):
        st = body.strips(50)
    p = st.parts[0]
    mid = np.argmin(abs(st.x))
    assert p.area[mid] == pytest.approx(0.2 * 0.6, rel=1e-6)
    assert p.area[0] == pytest.approx(0.2 * 0.2, rel=1e-6)
    assert float(np.sum(p.area * st.dx)) == pytest.approx(0.2 * 0.2 * 1.0 + 0.4 * 0.2 * 0.4, rel=1e-6)
    assert any("overlapping" in r for r in body.repairs)


def test_gap_along_axis_is_an_error():
    a = trimesh.creation.icosphere(subdivisions=2, radius=0.1)
    b = a.copy()
    b.apply_translation([0.5, 0.0, 0.0])
    body = mesh_body(trimesh.util.concatenate([a, b]))
    with pytest.raises(InputError, match="strip .* cuts no material"):
        body.strips(20)


def test_duct_ring_sections_have_holes():
    ring = trimesh.creation.annulus(r_min=0.15, r_max=0.17, height=0.1, sections=64)
    body = mesh_body(ring, axis="z")
    st = body.strips(10)
    p = st.parts[0]
    assert all(len(c) == 2 for c in p.contours)
    area_64gon = 0.5 * 64 * np.sin(2 * np.pi / 64) * (0.17 ** 2 - 0.15 ** 2)
    np.testing.assert_allclose(p.area, area_64gon, rtol=1e-9)
    np.testing.assert_allclose(p.half_breadth, 0.17, rtol=1e-3)


def test_section_properties_of_a_box():
    box = trimesh.creation.box([1.0, 0.4, 0.2])
    box.apply_translation([0.0, 0.1, -0.3])
    body = mesh_body(box, origin=(0.0, 0.0, 0.0))
    p = body.strips(8).parts[0]
    np.testing.assert_allclose(p.area, 0.08)
    np.testing.assert_allclose(p.y, 0.1, atol=1e-12)
    np.testing.assert_allclose(p.z, -0.3, atol=1e-12)
    np.testing.assert_allclose(p.half_breadth, 0.2)
    np.testing.assert_allclose(p.half_height, 0.1)
    np.testing.assert_allclose(p.iyy, 0.2 * 0.4 ** 3 / 12)
    np.testing.assert_allclose(p.izz, 0.4 * 0.2 ** 3 / 12)
    assert p.rounded is False


def test_strip_volume_matches_mesh_volume():
    body = mesh_body(spheroid(n_ax=200, n_circ=64))
    st = body.strips(200)
    assert float(np.sum(st.parts[0].area * st.dx)) == pytest.approx(body.volume, rel=1e-3)


# ------------------------------------------------------------------ bad input

def test_not_a_mesh(tmp_path):
    p = tmp_path / "junk.stl"
    p.write_text("this is not a mesh\n")
    with pytest.raises(InputError, match="junk.stl"):
        load_mesh(p)


def test_unknown_extension(tmp_path):
    p = tmp_path / "model.step"
    p.write_text("x")
    with pytest.raises(InputError, match="extension"):
        load_mesh(p)


def test_missing_file(tmp_path):
    with pytest.raises(InputError, match="not found"):
        load_mesh(tmp_path / "nope.stl")


def test_empty_mesh(tmp_path):
    p = tmp_path / "empty.ply"
    trimesh.Trimesh(vertices=np.zeros((0, 3)), faces=np.zeros((0, 3), int)).export(p)
    with pytest.raises(InputError, match="empty|no triangle|not a readable"):
        load_mesh(p)


def test_zero_volume():
    sheet = trimesh.Trimesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
                            [[0, 1, 2], [0, 2, 3], [0, 2, 1], [0, 3, 2]], process=False)
    with pytest.raises(InputError, match="no volume"):
        mesh_body(sheet)


def test_kilometres_long(tmp_path):
    p = tmp_path / "big.stl"
    m = spheroid()
    m.apply_scale(1000.0)          # a model drawn in mm ...
    m.export(p)
    with pytest.raises(InputError, match="length-unit"):
        load_mesh(p)               # ... read as metres


def test_no_extent_along_axis():
    plate = trimesh.creation.box([1.0, 1.0, 1.0])
    plate.vertices[:, 0] = 0.0     # flattened along x
    with pytest.raises(InputError, match="no extent along"):
        mesh_body(trimesh.Trimesh(plate.vertices, plate.faces, process=False))


@pytest.mark.parametrize("kw,match", [({"axis": "w"}, "axis"), ({"length_unit": "km"}, "unit"),
                                      ({"origin": "nose"}, "origin"),
                                      ({"transform": np.eye(3)}, "transform")])
def test_bad_options(kw, match):
    with pytest.raises(InputError, match=match):
        mesh_body(spheroid(), **kw)


def test_glb_scene_nodes_are_merged_with_their_transforms(tmp_path):
    scene = trimesh.Scene()
    box = trimesh.creation.box([1.0, 0.2, 0.2])
    scene.add_geometry(box, node_name="hull")
    pod = trimesh.creation.box([0.2, 0.1, 0.1])
    scene.add_geometry(pod, node_name="pod",
                       transform=trimesh.transformations.translation_matrix([0.0, 0.5, 0.0]))
    path = tmp_path / "scene.glb"
    scene.export(path)
    with pytest.warns(ModelWarning, match="2 separate bodies"):
        body = load_mesh(path, origin="file")
    assert body.n_bodies == 2
    assert body.bbox()[1, 1] == pytest.approx(0.55, abs=1e-6)
    assert body.volume == pytest.approx(0.04 + 0.002, rel=1e-6)


def test_box_mesh_drag_through_the_section_registry():
    """A sharp box section gets the rectangular-cylinder coefficient via sections.section_drag."""
    from stripcoef.sections import drag, section_drag
    body = mesh_body(trimesh.creation.box([1.0, 0.4, 0.2]))
    p = body.strips(10).parts[0]
    cd_y, cd_z = section_drag(p, np.full(10, 1e5), np.full(10, 1e5))
    np.testing.assert_allclose(cd_y, float(drag.rectangle_cd(2.0)))     # d/h = 0.4/0.2
    np.testing.assert_allclose(cd_z, float(drag.rectangle_cd(0.5)))
