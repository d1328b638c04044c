"""UUV Simulator export parsed back with xml.etree and run through the plugin's own formulas.

Written from uuvsimulator/uuv_simulator uuv_gazebo_plugins/.../src/HydrodynamicModel.cc:
- HMFossen reads <added_mass> (36 values, GZ_ASSERT), <linear_damping>,
  <linear_damping_forward_speed>, <quadratic_damping> (6 or 36 values) in <hydrodynamic_model>
  with <type>fossen</type>, and <volume>, <center_of_buoyancy> in the link element;
- ApplyHydrodynamicForces: velRel = ToNED(link velocity) (flip y, z), tau = -D velRel -
  Ma acc - Ca velRel, wrench = FromNED(tau), applied at the CoG (AddRelativeForce);
- ComputeDampingMatrix: D = -DLin - u DLinFS - diag(DNonLin_ii |v_i|) (diagonal only);
- BuoyantObject.cc: buoyancy rho g V (world up) at <center_of_buoyancy> relative to the CoG.
"""

from __future__ import annotations

import re
import warnings
import xml.etree.ElementTree as ET

from dataclasses import replace

import numpy as np
import pytest
from _export_models import torpedo, warning_messages

from stripcoef.errors import InputError
from stripcoef.export import export_model

T = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])
READ_BY_PLUGIN = {"neutrally_buoyant", "volume", "center_of_buoyancy", "hydrodynamic_model",
                  "box", "metacentric_width", "metacentric_length", "submerged_height"}
READ_BY_FOSSEN = {"type", "added_mass", "linear_damping", "linear_damping_forward_speed",
                  "quadratic_damping"}


def numbers(el):
    return np.array([float(v) for v in el.text.split()])


def to_matrix(vals):
    """As HMFossen: 36 values row-major, or 6 on the diagonal."""
    assert vals.size in (6, 36)
    return vals.reshape(6, 6) if vals.size == 36 else np.diag(vals)


def parse(text):
    root = ET.fromstring(text)
    assert root.tag == "plugin"
    assert root.get("filename") == "libuuv_underwater_object_ros_plugin.so"
    link = root.find("link")
    assert {c.tag for c in link} <= READ_BY_PLUGIN
    hm = link.find("hydrodynamic_model")
    assert {c.tag for c in hm} <= READ_BY_FOSSEN
    assert hm.find("type").text == "fossen"
    ma = numbers(hm.find("added_mass"))
    assert ma.size == 36                                   # GZ_ASSERT in HMFossen
    return dict(root=root, link=link, rho=float(root.find("fluid_density").text),
                volume=float(link.find("volume").text), cob=numbers(link.find("center_of_buoyancy")),
                Ma=ma.reshape(6, 6), DLin=to_matrix(numbers(hm.find("linear_damping"))),
                DLinFS=to_matrix(numbers(hm.find("linear_damping_forward_speed"))),
                DNonLin=to_matrix(numbers(hm.find("quadratic_damping"))))


def plugin_wrench(p, vel_link, acc_link):
    """HMFossen::ApplyHydrodynamicForces without the Coriolis term, in the link frame."""
    vel = T * vel_link                      # ToNED on the linear and angular parts
    acc = T * acc_link
    d = -p["DLin"] - vel[0] * p["DLinFS"]
    d = d - np.diag(np.diag(p["DNonLin"]) * np.abs(vel))
    tau = -d @ vel - p["Ma"] @ acc
    return T * tau                          # FromNED


def test_tags_signs_and_plugin_force_equal_the_model_about_cg():
    model = torpedo()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        p = parse(export_model(model, "uuv", link_name="vehicle/base_link"))
        cg = model.about(model.center_of_gravity)
    assert p["link"].get("name") == "vehicle/base_link"
    assert np.all(np.diag(p["Ma"]) > 0)                  # positive added mass
    assert np.all(np.diag(p["DLin"]) < 0) and np.all(np.diag(p["DNonLin"]) < 0)
    np.testing.assert_allclose(p["Ma"], cg.added_mass, rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(p["DLin"], -cg.linear_damping, rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(np.diag(p["DNonLin"]), -np.diag(cg.quadratic_damping), rtol=1e-13)
    assert not np.any(p["DLinFS"])
    rng = np.random.default_rng(4)
    dq_diag = np.diag(np.diag(cg.quadratic_damping))
    for _ in range(5):
        vel_link, acc_link = rng.normal(size=6), rng.normal(size=6)
        nu, nu_dot = T * vel_link, T * acc_link        # FRD velocities at the CoG
        expected = -(cg.linear_damping + dq_diag * np.abs(nu)) @ nu - cg.added_mass @ nu_dot
        np.testing.assert_allclose(plugin_wrench(p, vel_link, acc_link), T * expected,
                                   rtol=1e-12, atol=1e-12)


def test_volume_and_center_of_buoyancy_give_the_restoring_moment():
    model = torpedo()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        p = parse(export_model(model, "uuv"))
        g_cg = model.about(model.center_of_gravity).restoring(np.zeros(6))
    assert p["volume"] == model.volume and p["rho"] == model.density
    b = p["rho"] * model.gravity * p["volume"]
    moment_link = np.cross(p["cob"], [0.0, 0.0, b])     # buoyancy (world up) at CoB, upright
    np.testing.assert_allclose(T[3:] * moment_link, -g_cg[3:], rtol=1e-12, atol=1e-12)


def test_quadratic_cross_terms_are_reported_as_dropped():
    model = torpedo()
    _, caught = warning_messages(export_model, model, "uuv")
    assert any(re.search(r"only the diagonal.*N_vv", m) for m in caught["SimulatorTrapWarning"])


def test_diagonal_model_has_no_trap():
    model = torpedo()
    model = replace(model,
                    quadratic_damping=np.diag(np.diag(model.quadratic_damping)),
                    reference_point=model.center_of_gravity.copy(),  # matrices taken as about the CG
                    added_mass=model.added_mass * 0.5)               # below the rigid-body terms
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        parse(export_model(model, "uuv"))


def test_point_must_be_cg_and_frd_link_flips_parameters():
    model = torpedo()
    with pytest.raises(InputError, match="CG"):
        export_model(model, "uuv", point="CB")
    with pytest.raises(InputError, match="CG"):
        export_model(model, "uuv", point=model.center_of_gravity)   # say CG, not numbers
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert export_model(model, "uuv", point="center_of_gravity") == export_model(model, "uuv")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        flu = parse(export_model(model, "uuv"))
        frd = parse(export_model(model, "uuv", axes="FRD"))
    # an FRD link frame: ToNED makes the parameters FLU
    np.testing.assert_allclose(frd["Ma"], np.diag(T) @ flu["Ma"] @ np.diag(T), atol=1e-15)
    np.testing.assert_allclose(frd["cob"], T[:3] * flu["cob"], atol=1e-15)


def test_added_mass_larger_than_rigid_body_is_a_trap():
    """The plugin applies added mass explicitly (HydrodynamicModel.cc, ComputeAcc)."""
    model = torpedo()                    # sway/heave M_A 35.5 kg > m = 31.9 kg
    _, caught = warning_messages(export_model, model, "uuv")
    assert any("sway (M_A 35.5 > M_RB 31.9)" in m for m in caught["SimulatorTrapWarning"])


def test_about_cg_and_back_gives_the_original():
    from stripcoef.conventions import transform_matrix
    model = torpedo()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        p = parse(export_model(model, "uuv"))
    for key, value in (("added_mass", p["Ma"]), ("linear_damping", -p["DLin"])):
        back = transform_matrix(value, from_point=model.center_of_gravity,
                                to_point=model.reference_point)      # parameters are FRD
        original = getattr(model, key)
        np.testing.assert_allclose(back, original, rtol=1e-12,
                                   atol=1e-12 * np.abs(original).max(), err_msg=key)


def _plugin_volume(box, volume, z):
    """BuoyantObject::GetBuoyancyForce (uuv_simulator bfb40cb, BuoyantObject.cc l. 82-120):
    the buoyant volume with the link origin at world z (up, surface at 0) [m^3]."""
    height = box["height"]
    if z + height / 2 > 0 and z < 0:
        return volume * (abs(z) + height / 2) / height
    return volume if z + height / 2 < 0 else 0.0


def test_box_is_the_body_extent_for_partial_submersion(geometry_dir):
    """``<box>`` (HydrodynamicModel.cc l. 67-84: width along x, length along y, height along
    z, centred on the link origin) carries L, B, H; with it the plugin's buoyancy is full at
    a depth of H/2, half with the CoG at the surface."""
    from stripcoef import estimate

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = estimate(geometry_dir / "remus100.yaml", strips=120)
        p = parse(export_model(model, "uuv"))
    box = {c.tag: float(c.text) for c in p["link"].find("box")}
    assert set(box) == {"width", "length", "height"}
    assert box["width"] == pytest.approx(model.conditions["length"], rel=1e-12)
    # REMUS 100: hull diameter 0.191 m, fins out to a span of 0.257 m (geometry/remus100.yaml)
    assert box["length"] == pytest.approx(box["height"], rel=1e-9)
    assert 0.19 < box["height"] < 0.30
    v = p["volume"]
    assert _plugin_volume(box, v, -box["height"]) == v
    assert _plugin_volume(box, v, -1e-12) == pytest.approx(v / 2, rel=1e-9)


def test_model_without_extents_has_no_box_and_says_so():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        text = export_model(torpedo(), "uuv")
    assert parse(text)["link"].find("box") is None
    assert "No <box>" in text
