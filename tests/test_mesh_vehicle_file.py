"""A mesh appendage inside a vehicle file (the lead's `type: mesh`), through load_mesh."""

import warnings

import numpy as np
import pytest
import trimesh

from stripcoef.assembly.estimate import estimate
from stripcoef.geometry.mesh import load_mesh
from stripcoef.geometry.vehicle import load_vehicle


def test_vehicle_with_mesh_appendage(tmp_path):
    box = trimesh.creation.box([150.0, 60.0, 60.0])            # a sonar pod drawn in mm
    box.apply_translation([0.0, 0.0, 130.0])                   # below the hull (z down)
    box.export(tmp_path / "pod.stl")
    (tmp_path / "v.yaml").write_text(
        "name: t\n"
        "fluid: {density: 1000.0, kinematic_viscosity: 1.0e-6}\n"
        "hull:\n"
        "  profile:\n"
        "    - {type: ellipsoid_tail, x: [-0.75, 0.0], radius: 0.1}\n"
        "    - {type: ellipsoid_nose, x: [0.0, 0.75], radius: 0.1}\n"
        "appendages:\n"
        "  - {name: pod, type: mesh, mesh: pod.stl, length_unit: mm}\n")
    v = load_vehicle(tmp_path / "v.yaml")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = estimate(v, strips=200)
    hull_volume = 4 / 3 * np.pi * 0.75 * 0.01
    pod_volume = 0.15 * 0.06 * 0.06
    assert model.volume == pytest.approx(hull_volume + pod_volume, rel=2e-3)
    # the pod below the hull couples sway and roll (K_vdot), as a box appendage would
    assert abs(model.added_mass[1, 3]) > 0.0


def test_role_option(tmp_path):
    box = trimesh.creation.box([1.0, 0.2, 0.2])
    box.export(tmp_path / "b.stl")
    body = load_mesh(tmp_path / "b.stl", role="appendage")
    assert body.strips(10).parts[0].role == "appendage"
    from stripcoef.errors import InputError
    with pytest.raises(InputError, match="role"):
        load_mesh(tmp_path / "b.stl", role="wing")
