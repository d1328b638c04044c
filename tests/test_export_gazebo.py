"""Gazebo (gz-sim) export parsed back with xml.etree and checked against what the plugin reads.

The plugin side is written from the sources (not from the exporter):
- gz-sim src/systems/hydrodynamics/Hydrodynamics.cc, Configure(): tags "<{f}{V}>",
  "<{f}{V}abs{V}>", "<{f}Dot{V}>" for f in "xyzkmn", V in "UVWPQR", and "<link_name>";
- HydrodynamicsUtils.hh buildDampingMatrix + PreUpdate: applied force
  F_i = sum_j c_ij x_j + sum_jk c_ijk |x_k| x_j (x = link-origin velocity in the link frame);
  added mass: F = Ma * xdot with Ma(i,j) = <{f_i}Dot{V_j}>;
- sdformat sdf/1.11/inertial.sdf: the 21 <fluid_added_mass> elements, positive, about the
  link origin.
"""

from __future__ import annotations

import re
import warnings
import xml.etree.ElementTree as ET

from dataclasses import replace

import numpy as np
import pytest
from _export_models import torpedo, warning_messages

from stripcoef.export import SimulatorTrapWarning, export_model

F, V = "xyzkmn", "UVWPQR"
LINEAR = re.compile(r"^([xyzkmn])([UVWPQR])$")
QUAD_ABS = re.compile(r"^([xyzkmn])([UVWPQR])abs([UVWPQR])$")
DOT = re.compile(r"^([xyzkmn])Dot([UVWPQR])$")
FAM = ("xx", "xy", "xz", "xp", "xq", "xr", "yy", "yz", "yp", "yq", "yr", "zz", "zp", "zq", "zr",
       "pp", "pq", "pr", "qq", "qr", "rr")
T = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])     # FRD -> FLU sign per DOF


def parse(text):
    root = ET.fromstring(text)
    plugin = root.find("./model/plugin")
    assert plugin.get("filename") == "gz-sim-hydrodynamics-system"
    assert plugin.get("name") == "gz::sim::systems::Hydrodynamics"
    lin = np.zeros((6, 6))
    quad = np.zeros((6, 6, 6))
    dot = np.zeros((6, 6))
    seen_dot = False
    for el in plugin:
        tag = el.tag
        if tag == "link_name":
            continue
        if m := LINEAR.match(tag):
            lin[F.index(m[1]), V.index(m[2])] = float(el.text)
        elif m := QUAD_ABS.match(tag):
            quad[F.index(m[1]), V.index(m[2]), V.index(m[3])] = float(el.text)
        elif m := DOT.match(tag):
            dot[F.index(m[1]), V.index(m[2])] = float(el.text)
            seen_dot = True
        else:
            raise AssertionError(f"tag <{tag}> is not read by the Hydrodynamics plugin")
    fam_el = root.find("./model/link/inertial/fluid_added_mass")
    fam = None
    if fam_el is not None:
        assert sorted(c.tag for c in fam_el) == sorted(FAM)
        letters = "xyzpqr"
        fam = np.zeros((6, 6))
        for c in fam_el:
            i, j = letters.index(c.tag[0]), letters.index(c.tag[1])
            fam[i, j] = fam[j, i] = float(c.text)
    return root, plugin, lin, quad, (dot if seen_dot else None), fam


def plugin_damping_force(lin, quad, x):
    """The wrench the plugin applies for link velocity x (no added mass, no Coriolis)."""
    return lin @ x + np.einsum("ijk,k,j->i", quad, np.abs(x), x)


def point_velocity(nu_o, o, p):
    """FRD velocity of the body at point p given the velocity nu_o at point o."""
    w = nu_o[3:]
    return np.concatenate([nu_o[:3] + np.cross(w, np.asarray(p) - np.asarray(o)), w])


def wrench_about(tau_o, o, p):
    """The same wrench (given about o) about point p."""
    f = tau_o[:3]
    return np.concatenate([f, tau_o[3:] + np.cross(np.asarray(o) - np.asarray(p), f)])


def test_tags_are_the_plugins_and_signs_are_sname():
    model = torpedo()
    _, plugin, lin, quad, dot, fam = parse(export_model(model, "gazebo", axes="FRD"))
    assert plugin.find("link_name").text == "base_link"
    assert dot is None and fam is not None          # DART default: never both
    # About the CO in FRD, tags are exactly the SNAME derivatives: <xU> = X_u = -D_L[0,0]
    np.testing.assert_allclose(lin, -model.linear_damping, rtol=1e-14)
    for i in range(6):
        for j in range(6):
            assert quad[i, j, j] == pytest.approx(-model.quadratic_damping[i, j], rel=1e-14)
    assert np.count_nonzero(quad) == np.count_nonzero(model.quadratic_damping)
    assert lin[0, 0] < 0 and quad[0, 0, 0] < 0 and quad[5, 5, 5] < 0
    np.testing.assert_allclose(fam, model.added_mass, rtol=1e-14)
    assert all(fam[i, i] > 0 for i in range(6))


@pytest.mark.parametrize("point", ["CO", "CB", "CG", (0.3, -0.02, 0.05)])
def test_damping_force_in_link_frame_matches_model(point):
    """The plugin's force on FLU link-origin velocities equals the model's (FRD, at the CO)."""
    model = torpedo()
    model = replace(model, quadratic_damping=np.zeros((6, 6)))  # D_Q is moved approximately; checked at the CO below
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        text = export_model(model, "gazebo", point=point)
    _, _, lin, quad, _, _ = parse(text)
    p = {"CO": model.reference_point, "CB": model.center_of_buoyancy,
         "CG": model.center_of_gravity}.get(point, point) if isinstance(point, str) else point
    o = model.reference_point
    rng = np.random.default_rng(1)
    for _ in range(5):
        x_link = rng.normal(size=6)
        nu_p = T * x_link
        nu_o = point_velocity(nu_p, p, o)
        tau_o = -model.linear_damping @ nu_o
        expected = T * wrench_about(tau_o, o, p)
        np.testing.assert_allclose(plugin_damping_force(lin, quad, x_link), expected,
                                   rtol=1e-10, atol=1e-12)


def test_quadratic_force_in_flu_matches_model_at_co():
    model = torpedo()
    _, _, lin, quad, _, _ = parse(export_model(model, "gazebo"))
    rng = np.random.default_rng(2)
    for _ in range(5):
        x_link = rng.normal(size=6)
        nu = T * x_link
        expected = T * (-model.damping(nu) @ nu)
        np.testing.assert_allclose(plugin_damping_force(lin, quad, x_link), expected,
                                   rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("point", ["CO", "CG", (-0.4, 0.01, 0.03)])
def test_fluid_added_mass_about_link_origin_keeps_kinetic_energy(point):
    """<fluid_added_mass> about the link origin in FLU: same fluid kinetic energy as M_A at CO."""
    model = torpedo()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        _, _, _, _, _, fam = parse(export_model(model, "gazebo", point=point))
    p = {"CO": model.reference_point, "CG": model.center_of_gravity}.get(point, point) \
        if isinstance(point, str) else point
    rng = np.random.default_rng(3)
    for _ in range(5):
        x_link = rng.normal(size=6)
        nu_o = point_velocity(T * x_link, p, model.reference_point)
        assert x_link @ fam @ x_link == pytest.approx(nu_o @ model.added_mass @ nu_o, rel=1e-12)


def test_legacy_added_mass_tags_and_never_both():
    model = torpedo()
    text, caught = warning_messages(export_model, model, "gazebo", axes="FRD",
                                    legacy_added_mass=True)
    assert any("only the diagonal" in m for m in caught["SimulatorTrapWarning"])
    root, _, _, _, dot, fam = parse(text)
    assert fam is None and dot is not None
    # Hydrodynamics.cc applies +Ma*xdot: Ma = SNAME derivative = -M_A
    np.testing.assert_allclose(dot, -model.added_mass, rtol=1e-14)
    assert np.all(np.diag(dot) < 0)
    assert root.find("./model/link/inertial/fluid_added_mass") is None


def test_legacy_added_mass_larger_than_rigid_body_warns_issue_1923():
    model = torpedo(big_added_mass=True)      # sway M_A 106 kg > m = 31.9 kg
    _, caught = warning_messages(export_model, model, "gazebo", legacy_added_mass=True)
    assert any("1923" in m and "sway (M_A 106.5 > M_RB 31.9)" in m
               for m in caught["SimulatorTrapWarning"])
    with warnings.catch_warnings():
        warnings.simplefilter("error", SimulatorTrapWarning)
        # <fluid_added_mass> (DART): no trap (without the buoyancy box, whose own trap says
        # that gz-sim sums every collision of the link, and without the thrusters, whose
        # backward branch the Thruster system cannot hold)
        export_model(model, "gazebo", buoyancy_volume=False, thrusters=False)


def test_inertial_cg_pose_and_buoyancy_volume():
    model = torpedo()
    root, *_ = parse(export_model(model, "gazebo", link_name="hull"))
    link = root.find("./model/link")
    assert link.get("name") == "hull"
    assert root.find("./model/plugin/link_name").text == "hull"
    inertial = link.find("inertial")
    pose = np.array([float(v) for v in inertial.find("pose").text.split()])
    np.testing.assert_allclose(pose[:3], T[:3] * (model.center_of_gravity - model.reference_point))
    assert float(inertial.find("mass").text) == model.mass
    # inertia about the CG in FLU: the products with y flip sign (SDF uses -m x y entries)
    inertia = {c.tag: float(c.text) for c in inertial.find("inertia")}
    rg = model.center_of_gravity - model.reference_point
    s = np.array([[0, -rg[2], rg[1]], [rg[2], 0, -rg[0]], [-rg[1], rg[0], 0]])
    ig = model.rigid_body_mass[3:, 3:] + model.mass * s @ s          # I_g = I_o + m S^2
    t3 = np.diag(T[3:])
    ig_flu = t3 @ ig @ t3
    for tag, (a, b) in {"ixx": (0, 0), "ixy": (0, 1), "ixz": (0, 2), "iyy": (1, 1),
                        "iyz": (1, 2), "izz": (2, 2)}.items():
        assert inertia[tag] == pytest.approx(ig_flu[a, b], abs=1e-12)
    box = link.find("collision/geometry/box/size").text.split()
    assert np.prod([float(v) for v in box]) == pytest.approx(model.volume, rel=1e-12)
    cpose = np.array([float(v) for v in link.find("collision/pose").text.split()])
    np.testing.assert_allclose(cpose[:3], T[:3] * (model.center_of_buoyancy - model.reference_point),
                               atol=1e-15)


def test_asymmetric_added_mass_is_a_trap():
    model = torpedo()
    ma = np.array(model.added_mass)
    ma[1, 5] += 0.5
    model = replace(model, added_mass=ma)
    with pytest.warns(SimulatorTrapWarning, match="asymmetric"):
        export_model(model, "gazebo")


def test_about_cg_in_flu_and_back_gives_the_original():
    """Read the tags about the CG in FLU, undo axes and point with transform_matrix: the model."""
    from stripcoef.conventions import transform_matrix
    model = torpedo()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        _, _, lin, quad, _, fam = parse(export_model(model, "gazebo", point="CG"))
    assert not any(quad[i, j, k] for i in range(6) for j in range(6) for k in range(6) if k != j)
    read = {"added_mass": fam, "linear_damping": -lin,
            "quadratic_damping": -np.einsum("ijj->ij", quad)}
    for key, value in read.items():
        frd = transform_matrix(value, axes="FLU")
        back = transform_matrix(frd, from_point=model.center_of_gravity,
                                to_point=model.reference_point)
        original = getattr(model, key)
        np.testing.assert_allclose(back, original, rtol=1e-12,
                                   atol=1e-12 * np.abs(original).max(), err_msg=key)
