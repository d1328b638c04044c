"""Meshes as users have them (issue 32): textured OBJs with vertices split at seams, zero-area
faces inside a closed surface, overlapping parts united for the panel method, a wrong unit."""

import numpy as np
import pytest
import trimesh

from stripcoef.errors import ModelWarning
from stripcoef.geometry.mesh import EdgeTopology, load_mesh, mesh_body
from stripcoef.hull.panels import panel_added_mass

BOX = (0.46, 0.58, 0.25)


def split_vertex_obj(path, mesh, texture=True):
    """An OBJ as texturing tools write it: every face with its own three vertices (split at
    every seam), texture coordinates, and a material whose texture is not a readable image."""
    v = np.asarray(mesh.vertices)[np.asarray(mesh.faces)].reshape(-1, 3)
    lines = []
    if texture:
        lines.append("mtllib box.mtl")
        (path.parent / "box.mtl").write_text("newmtl m\nKd 1 1 1\nmap_Kd tex.png\n")
        (path.parent / "tex.png").write_bytes(b"\x89PNG\r\n\x1a\nnot an image")
    lines += ["v %.9g %.9g %.9g" % tuple(p) for p in v]
    lines += ["vt %.4f %.4f" % (i % 7 / 7, i % 5 / 5) for i in range(len(v))]
    if texture:
        lines.append("usemtl m")
    lines += [f"f {3 * k + 1}/{3 * k + 1} {3 * k + 2}/{3 * k + 2} {3 * k + 3}/{3 * k + 3}"
              for k in range(len(mesh.faces))]
    path.write_text("\n".join(lines) + "\n")
    return path


def test_split_vertex_textured_obj_is_merged_and_closed(tmp_path):
    box = trimesh.creation.box(BOX)
    path = split_vertex_obj(tmp_path / "box.obj", box)
    with pytest.warns(ModelWarning, match="merged"):
        body = load_mesh(path)
    assert EdgeTopology(body.mesh.faces).consistent
    assert len(body.mesh.vertices) == 8
    assert body.volume == pytest.approx(np.prod(BOX), rel=1e-9)
    assert body.n_bodies == 1


def test_zero_area_face_is_flipped_not_deleted():
    """A cap (a vertex on the opposite edge, a T-junction as CAD exports write): removing it
    would open the surface; the edge flip keeps it closed and the shape unchanged."""
    box = trimesh.creation.box(BOX)
    v, f = np.array(box.vertices), np.array(box.faces)
    a, b, x = f[0]
    m = len(v)
    v = np.vstack([v, 0.5 * (v[a] + v[b])])
    f = np.vstack([[[a, m, x], [m, b, x], [a, b, m]], f[1:]])     # the cap is (a, b, m)
    assert EdgeTopology(f).consistent
    body = mesh_body(trimesh.Trimesh(v, f, process=False))
    text = " ".join(body.repairs)
    assert "edge flips" in text and "removed" not in text
    assert EdgeTopology(body.mesh.faces).consistent
    assert len(body.mesh.faces) == len(f)
    assert body.volume == pytest.approx(np.prod(BOX), rel=1e-12)


def test_needle_face_is_collapsed():
    """A face with two corners a hair apart (not merged by position: 1e-6 of the size) is
    collapsed, not deleted; the surface stays closed."""
    ico = trimesh.creation.icosphere(subdivisions=2, radius=0.2)
    v, f = np.array(ico.vertices), np.array(ico.faces)
    a, b, x = f[0]
    # split vertex a: a copy a' 1e-11 m away takes the faces on one side of edge (a, b)
    v = np.vstack([v, v[a] + 1e-11])
    m = len(v) - 1
    f2 = f.copy()
    f2[0] = (m, b, x)
    f2 = np.vstack([f2, [[a, b, m]]])          # the needle closing the gap between a and a'
    # not merged by position at the loader's tolerance would leave it to the collapse
    body = mesh_body(trimesh.Trimesh(v, f2, process=False))
    assert EdgeTopology(body.mesh.faces).consistent
    assert body.volume == pytest.approx(ico.volume, rel=1e-9)


def test_overlapping_parts_united_for_the_panel_method():
    """Two boxes overlapping by half their length are one 1.5 m box for the panel method, not
    two boxes with a wall of panels inside each other: the two agree within their estimated
    errors on every term and within 2 % of the scale on all but the roll about the long axis
    (the box's slowest term, order 1 and a band of 5 % in the edge-graded references of
    reference_tables/bem/graded_boxes.csv; extrapolated at the edge's order, 2.5 % apart
    within estimates of 18 and 45 %)."""
    a = trimesh.creation.box([1.0, 0.2, 0.2])
    b = a.copy()
    b.apply_translation([0.5, 0.0, 0.0])
    two = mesh_body(trimesh.util.concatenate([a, b]), origin="file")
    one = trimesh.creation.box([1.5, 0.2, 0.2])
    one.apply_translation([0.25, 0.0, 0.0])
    ref = mesh_body(one, origin="file")
    with pytest.warns(ModelWarning, match="united 2 bodies"):
        m2, i2 = panel_added_mass(two, rho=1000.0, about=(0.25, 0, 0), panels=1600)
    m1, i1 = panel_added_mass(ref, rho=1000.0, about=(0.25, 0, 0), panels=1600)
    scale = np.sqrt(np.outer(np.diag(m1), np.diag(m1)))
    assert np.all(np.abs(m2 - m1) <= np.hypot(i1["error"], i2["error"]))
    off = np.abs(m2 - m1) / scale
    off[3, 3] = 0.0
    assert off.max() <= 0.02
    assert two.united().volume == pytest.approx(1.5 * 0.04, rel=1e-6)


def test_millimetre_file_read_as_metres_warns(tmp_path):
    box = trimesh.creation.box([150.0, 58.0, 25.0])       # mm, read as m
    path = tmp_path / "box.stl"
    box.export(path)
    with pytest.warns(ModelWarning, match="length-unit mm"):
        load_mesh(path)


def test_mesh_command_reports_repairs_and_writes_a_closed_copy(tmp_path, capsys):
    import json

    from stripcoef.cli import main

    path = split_vertex_obj(tmp_path / "box.obj", trimesh.creation.box(BOX))
    out = tmp_path / "fixed.stl"
    assert main(["mesh", str(path), "--repair", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "36 open" in text and "merged 28 vertices" in text and "closed" in text
    fixed = load_mesh(out)
    assert fixed.repairs == [] and fixed.volume == pytest.approx(np.prod(BOX), rel=1e-6)
    assert main(["mesh", str(out), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["open_edges_found"] == 0 and data["repairs"] == [] and data["watertight"]
    assert data["extent"] == pytest.approx(list(BOX), rel=1e-6)


def test_mesh_command_bad_options(tmp_path, capsys):
    from stripcoef.cli import main

    path = tmp_path / "box.stl"
    trimesh.creation.box(BOX).export(path)
    assert main(["mesh", str(path), "--repair"]) == 2
    assert "--repair and -o" in capsys.readouterr().err
    assert main(["mesh", str(tmp_path / "missing.stl")]) == 2
    assert main(["mesh", str(path), "--repair", "-o", str(tmp_path / "x.txt")]) == 2


def test_z_up_file_turned_into_frd():
    """A box with a skid on top of a z-up file (ROS REP 103) has the skid at body z < 0."""
    hull = trimesh.creation.box([0.5, 0.4, 0.2])
    skid = trimesh.creation.box([0.5, 0.1, 0.1])
    skid.apply_translation([0.0, 0.1, 0.15])            # up and to the left (+y is left in FLU)
    both = trimesh.boolean.union([hull, skid], engine="manifold")
    body = mesh_body(both, origin="file", z_up=True)
    v = np.asarray(body.mesh.vertices)
    assert v[:, 2].min() == pytest.approx(-0.2) and v[:, 2].max() == pytest.approx(0.1)
    top = v[v[:, 2] < -0.15]
    assert np.all(top[:, 1] < 0)                         # left is -y (port) in FRD


def _frame_rov():
    """An open frame as CAD exports it: two side plates, three cross tubes (one only at the
    front, so the frame is not fore-aft symmetric), overlapping parts."""
    parts = []
    for y in (-0.2, 0.2):
        parts.append(trimesh.creation.box([0.5, 0.02, 0.3],
                     transform=trimesh.transformations.translation_matrix([0, y, 0])))
    for x, z in ((-0.15, -0.1), (-0.15, 0.1), (0.2, 0.0)):
        tube = trimesh.creation.cylinder(radius=0.03, height=0.42, sections=16)
        tube.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [1, 0, 0]))
        tube.apply_translation([x, 0.0, z])
        parts.append(tube)
    return trimesh.util.concatenate(parts)


def test_symmetric_frame_couplings_exactly_zero():
    """Port-starboard and top-bottom mirror planes forbid every coupling but Y_rdot, Z_qdot
    (module stripcoef.assembly.symmetry): those are exactly zero in the model the exporters
    read, not 5 % of the diagonal scale."""
    import warnings

    from stripcoef.assembly import estimate
    from stripcoef.assembly.symmetry import allowed_couplings
    from stripcoef.geometry.vehicle import Vehicle

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        veh = Vehicle.from_mesh(_frame_rov(), name="frame")
        # 400 panels (the next test's frame): the couplings are zero by the mirrored solve at
        # any panel count (0.0 at 400 and 1600 alike; 1.3 instead of 2.4 s of CPU)
        model = estimate(veh, added_mass_method="panels", added_mass_panels=400)
    assert model.conditions["mirror_planes"] == "yz"
    forbidden = ~allowed_couplings({"y", "z"})
    assert np.all(model.added_mass[forbidden] == 0.0)
    assert np.all(model.added_mass_error[forbidden] == 0.0)
    assert abs(model.added_mass[1, 5]) > 0.0             # Y_rdot: the frame is fore-aft asymmetric
    assert np.all(np.diag(model.added_mass_error) > 0.0)


def test_unconverged_panels_warn_with_the_remedy_and_report_the_error(tmp_path, capsys,
                                                                     monkeypatch):
    """The frame at 400 panels: the levels disagree (roll 18 % of its value); never printed
    silently: a warning naming the panel count that resolves it, the estimated error of every
    term in the JSON and in the model file round trip.  Without the remesher (the two levels
    of the input; with it the levels are refined until converged)."""
    import json

    import stripcoef.hull.remesh
    from stripcoef.cli import main
    from stripcoef.model import HydroModel

    monkeypatch.setattr(stripcoef.hull.remesh, "available", lambda: False)

    path = tmp_path / "frame.stl"
    _frame_rov().export(path)
    assert main(["coefficients", str(path), "--added-mass-method", "panels",
                 "--added-mass-panels", "400", "--json"]) == 0
    cap = capsys.readouterr()
    assert "has not converged" in cap.err and "--added-mass-panels 800" in cap.err
    data = json.loads(cap.out)
    err = np.array(data["added_mass_error"])
    ma = np.array(data["added_mass"])
    assert err.shape == (6, 6) and np.all(err >= 0) and np.all(np.diag(err) > 0)
    assert data["conditions"]["added_mass_error_max"] > 0.05
    rel = err / np.sqrt(np.outer(np.diag(ma), np.diag(ma)))
    assert rel.max() == pytest.approx(data["conditions"]["added_mass_error_max"], rel=1e-9)
    assert data["conditions"]["added_mass_converged"] is False
    model = HydroModel.from_dict(data)
    np.testing.assert_array_equal(model.added_mass_error, err)
    # moved to another point: a bound that still covers every term
    moved = model.about([0.1, 0.0, 0.05])
    assert np.all(moved.added_mass_error >= 0)
    assert moved.added_mass_error[5, 5] >= err[5, 5]


def test_panels_beyond_the_face_count(monkeypatch):
    """A finely tessellated thin plate whose coarsening collapses it, with more faces than
    MAX_PANELS / 2.5: it used to be refused; now it is solved as it is and refined beyond its
    face count (MAX_PANELS lowered so that the test stays small)."""
    import stripcoef.hull.panels as panels

    monkeypatch.setattr(panels, "MAX_PANELS", 1200)
    b = trimesh.creation.box([0.3, 0.4, 0.01])
    v, f = trimesh.remesh.subdivide_to_size(b.vertices, b.faces, max_edge=0.06)
    body = mesh_body(trimesh.Trimesh(v, f))
    n_faces = len(body.mesh.faces)
    assert 1200 / 2.5 < n_faces <= 1200 / 1.5
    m, info = panels.panel_added_mass(body, rho=1000.0, panels=1000, family="input")
    assert info["panels"][0] == n_faces and info["panels"][1] >= 1.5 * n_faces
    assert info["panels"][1] > n_faces and info["panels"][1] <= 1200
    assert np.all(np.isfinite(m)) and np.all(np.diag(info["error"]) > 0)
