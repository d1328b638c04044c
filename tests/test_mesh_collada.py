"""COLLADA (.dae) meshes read directly (issue 32): the declared unit and up axis honoured, node
transforms applied and shells combined, a bad file refused in one line; a mesh still open after
hole filling refused naming the command that closes it, and that command's repair."""

import re

import numpy as np
import pytest
import trimesh

from stripcoef.errors import InputError, ModelWarning
from stripcoef.geometry.collada import TO_Z_UP
from stripcoef.geometry.mesh import EdgeTopology, load_mesh

HULL = (0.9, 0.3, 0.2)          # length (forward), breadth, height [m]


def _hull_with_fin():
    """A box hull with a fin on top: up and forward are both visible in the result."""
    hull = trimesh.creation.box(HULL)
    fin = trimesh.creation.box([0.2, 0.02, 0.1])
    fin.apply_translation([0.2, 0.0, 0.14])             # on top (z up), toward the bow
    return trimesh.boolean.union([hull, fin], engine="manifold")


def write_dae(path, shells, *, unit=1.0, up="Z_UP"):
    """A COLLADA file written with pycollada: one geometry per (mesh, 4x4 node transform),
    each instanced by its own scene node, with ``<unit meter>`` and ``<up_axis>``."""
    import collada
    from collada import geometry, material, scene, source

    c = collada.Collada()
    effect = material.Effect("effect0", [], "phong", diffuse=(0.5, 0.5, 0.5))
    mat = material.Material("material0", "grey", effect)
    c.effects.append(effect)
    c.materials.append(mat)
    nodes = []
    for k, (mesh, matrix) in enumerate(shells):
        src = source.FloatSource(f"verts{k}", np.asarray(mesh.vertices, float).ravel(),
                                 ("X", "Y", "Z"))
        geom = geometry.Geometry(c, f"geom{k}", f"shell{k}", [src])
        inputs = source.InputList()
        inputs.addInput(0, "VERTEX", f"#verts{k}")
        geom.primitives.append(geom.createTriangleSet(np.asarray(mesh.faces).ravel(), inputs,
                                                      "mat"))
        c.geometries.append(geom)
        gnode = scene.GeometryNode(geom, [scene.MaterialNode("mat", mat, inputs=[])])
        nodes.append(scene.Node(f"node{k}", children=[gnode], transforms=[
            scene.MatrixTransform(np.asarray(matrix, np.float32).ravel())]))
    sc = scene.Scene("scene", nodes)
    c.scenes.append(sc)
    c.scene = sc
    c.assetInfo.unitmeter = unit
    c.assetInfo.unitname = "unit"
    c.assetInfo.upaxis = up
    c.assetInfo.save()
    c.write(str(path))
    return path


def test_millimetre_y_up_dae_read_back_in_body_axes(tmp_path):
    """A hull with a fin on top, written in millimetres and Y_UP (the COLLADA default frame):
    read back with the same volume [m^3], its length along body x and the fin at body z < 0
    (FRD: up is -z)."""
    body_zup = _hull_with_fin()
    to_file = TO_Z_UP["Y_UP"].T                          # z-up frame -> the Y_UP file frame
    in_file = trimesh.Trimesh(1000.0 * np.asarray(body_zup.vertices) @ to_file.T,
                              body_zup.faces, process=False)
    text = write_dae(tmp_path / "hull.dae", [(in_file, np.eye(4))], unit=0.001, up="Y_UP")
    assert "Y_UP" in text.read_text() and 'meter="0.001"' in text.read_text()
    body = load_mesh(tmp_path / "hull.dae", origin="file")
    v = np.asarray(body.mesh.vertices)
    assert body.volume == pytest.approx(float(body_zup.volume), rel=1e-6)
    assert np.ptp(v, axis=0) == pytest.approx([0.9, 0.3, 0.29], rel=1e-6)
    fin = v[v[:, 2] < -0.11]                             # above the hull's top at -0.1
    assert len(fin) and np.all(fin[:, 0] > 0.05)        # toward the bow, +x
    assert v[:, 2].min() == pytest.approx(-0.19, abs=1e-6) and v[:, 2].max() == pytest.approx(0.1, abs=1e-6)


def test_scene_nodes_transformed_and_shells_combined(tmp_path):
    """Two nodes instancing a unit-scaled box each with its own transform (scale, rotation,
    translation): both shells are there, placed by their matrices."""
    box = trimesh.creation.box([1.0, 1.0, 1.0])
    rot = trimesh.transformations.rotation_matrix(np.pi / 2, [0, 0, 1])
    a = np.diag([0.8, 0.2, 0.1, 1.0])                              # 0.8 x 0.2 x 0.1 at 0
    b = trimesh.transformations.translation_matrix([0.0, 0.5, 0.0]) @ rot \
        @ np.diag([0.2, 0.4, 0.1, 1.0])                             # 0.4 x 0.2 x 0.1 at y 0.5
    path = write_dae(tmp_path / "two.dae", [(box, a), (box, b)])
    body = load_mesh(path, origin="file")
    assert body.n_bodies == 2
    assert body.volume == pytest.approx(0.8 * 0.2 * 0.1 + 0.4 * 0.2 * 0.1, rel=1e-6)
    v = np.asarray(body.mesh.vertices)
    # Z_UP: turned 180 deg about x into FRD, the second box at body y = -0.5
    assert v[:, 1].min() == pytest.approx(-0.6, abs=1e-6) and v[:, 1].max() == pytest.approx(0.1, abs=1e-6)
    assert v[:, 0].min() == pytest.approx(-0.4, abs=1e-6) and v[:, 0].max() == pytest.approx(0.4, abs=1e-6)


def test_body_along_the_file_y_axis_warns_and_axis_y_turns_about_up(tmp_path):
    """A glider-like body whose length lies along the z-up file's y axis (as the DAVE gliders
    come): a warning names the axis and the option; --axis y turns it about the up axis, so the
    fin stays on top (body z < 0)."""
    body_zup = _hull_with_fin()
    yaw = trimesh.transformations.rotation_matrix(np.pi / 2, [0, 0, 1])   # bow to +y
    path = write_dae(tmp_path / "glider.dae", [(body_zup, yaw)])
    with pytest.warns(ModelWarning, match=r"file's y axis .*--axis y"):
        load_mesh(path)
    body = load_mesh(path, axis="y", origin="file")
    v = np.asarray(body.mesh.vertices)
    assert np.ptp(v, axis=0) == pytest.approx([0.9, 0.3, 0.29], rel=1e-6)
    fin = v[v[:, 2] < -0.11]
    assert len(fin) and np.all(fin[:, 0] > 0.05)


def test_length_unit_overrides_the_declared_unit_with_a_warning(tmp_path):
    box = trimesh.creation.box([900.0, 300.0, 200.0])
    path = write_dae(tmp_path / "mm.dae", [(box, np.eye(4))], unit=1.0)   # wrongly declared
    with pytest.warns(ModelWarning, match="overrides the file's declared"):
        body = load_mesh(path, length_unit="mm")
    assert body.volume == pytest.approx(0.9 * 0.3 * 0.2, rel=1e-6)


@pytest.mark.parametrize("content, match", [
    ("this is not XML", "not a readable COLLADA file"),
    ('<?xml version="1.0"?><COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" '
     'version="1.4.1"><asset><up_axis>W_UP</up_axis></asset></COLLADA>', r"<up_axis>.*W_UP"),
    ('<?xml version="1.0"?><COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" '
     'version="1.4.1"><asset><unit meter="-1"/></asset></COLLADA>', r"<unit meter>"),
    ('<?xml version="1.0"?><COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" '
     'version="1.4.1"><asset/></COLLADA>', "no <scene>"),
])
def test_bad_dae_is_one_line_exit_2(tmp_path, capsys, content, match):
    from stripcoef.cli import main

    path = tmp_path / "bad.dae"
    path.write_text(content)
    assert main(["coefficients", str(path), "--rho", "1000"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "bad.dae" in err and "expected" in err
    assert re.search(match, err)


def _box_and_open_tube():
    """A closed box and a thruster tube without end caps beside it (an open part, as the
    collision meshes of simulators have them), every face written twice."""
    box = trimesh.creation.box([0.8, 0.3, 0.3])
    tube = trimesh.creation.cylinder(radius=0.05, height=0.3, sections=20)
    f = np.asarray(tube.faces)
    side = np.abs(np.asarray(tube.triangles_center)[:, 2]) < 0.149   # drop the end caps
    tube = trimesh.Trimesh(tube.vertices, f[side], process=False)
    tube.remove_unreferenced_vertices()
    tube.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0]))
    tube.apply_translation([0.0, 0.0, 0.3])              # above the box, apart
    both = trimesh.util.concatenate([box, tube])
    return trimesh.Trimesh(both.vertices, np.vstack([both.faces, both.faces]), process=False)


def test_open_part_refused_naming_the_repair_and_the_repair_closes_it(tmp_path, capsys):
    from stripcoef.cli import main

    path = tmp_path / "rov.stl"
    _box_and_open_tube().export(path)
    with pytest.raises(InputError) as err:
        load_mesh(path)
    text = str(err.value)
    assert "not watertight" in text and "1 of 2 parts open" in text
    assert "stripcoef mesh rov.stl --repair -o rov_closed.stl" in text
    assert main(["coefficients", str(path), "--rho", "1000"]) == 2
    assert len(capsys.readouterr().err.strip().splitlines()) == 1
    out = tmp_path / "rov_closed.stl"
    assert main(["mesh", str(path), "--repair", "-o", str(out)]) == 0
    report = capsys.readouterr().out
    assert "capped 2 holes of 1 open parts" in report and "refused (open parts)" in report
    fixed = load_mesh(out)
    assert EdgeTopology(fixed.mesh.faces).consistent and fixed.n_bodies == 2
    # the box and the tube capped into a 20-gon prism
    tube = 0.5 * 20 * 0.05**2 * np.sin(2 * np.pi / 20) * 0.3
    assert fixed.volume == pytest.approx(0.8 * 0.3 * 0.3 + tube, rel=1e-6)


def test_y_up_file_along_its_in_axis_names_the_axis_of_the_turned_frame(tmp_path):
    """A Y_UP body whose length lies along the file's z ("in") axis: after the turn to z-up
    that is the y axis, so the warning names --axis y, which reads it right way up."""
    body_zup = _hull_with_fin()
    yaw = trimesh.transformations.rotation_matrix(np.pi / 2, [0, 0, 1])[:3, :3]
    to_file = TO_Z_UP["Y_UP"].T @ yaw                    # bow along z-up y, then to Y_UP
    in_file = trimesh.Trimesh(np.asarray(body_zup.vertices) @ to_file.T, body_zup.faces,
                              process=False)
    path = write_dae(tmp_path / "hull.dae", [(in_file, np.eye(4))], up="Y_UP")
    with pytest.warns(ModelWarning, match=r"file's y axis \(turned z-up\).*--axis y"):
        load_mesh(path)
    v = np.asarray(load_mesh(path, axis="y", origin="file").mesh.vertices)
    assert np.ptp(v, axis=0) == pytest.approx([0.9, 0.3, 0.29], rel=1e-6)
    fin = v[v[:, 2] < -0.11]
    assert len(fin) and np.all(fin[:, 0] > 0.05)
