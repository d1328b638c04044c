"""Hand-built HydroModels for the limits tests (no strip theory involved)."""

from __future__ import annotations

import numpy as np

from stripcoef.fluid import G
from stripcoef.model import HydroModel, rigid_body_mass_matrix
from stripcoef.thrusters import Thruster


def make_model(*, mass=50.0, rho=1000.0, buoyancy_ratio=1.0, added=(2.0, 40.0, 40.0, 0.1, 5.0, 5.0),
               linear=(2.0, 5.0, 5.0, 0.5, 1.0, 1.0), quadratic=(20.0, 150.0, 150.0, 1.0, 20.0, 20.0),
               inertia=(0.5, 8.0, 8.0), z_g=0.02, thrusters=None, name="test"):
    """A slender, xz-symmetric AUV about its CB; diagonal M_A, D_L, D_Q.

    ``buoyancy_ratio`` = B/W.  Default thrusters: two horizontal at y = +-0.1 m
    (port 'P1', starboard 'P2'), two vertical at x = +-0.4 m, 10 N each way.
    """
    volume = buoyancy_ratio * mass / rho
    rg = np.array([0.0, 0.0, z_g])
    if thrusters is None:
        thrusters = horizontal_pair(10.0) + vertical_pair(10.0)
    return HydroModel(
        name=name, reference_point=np.zeros(3),
        rigid_body_mass=rigid_body_mass_matrix(mass, rg, np.diag(inertia)),
        added_mass=np.diag(added), linear_damping=np.diag(linear),
        quadratic_damping=np.diag(quadratic), mass=mass, volume=volume,
        center_of_gravity=rg, center_of_buoyancy=np.zeros(3), density=rho, gravity=G,
        thrusters=list(thrusters))


def horizontal_pair(tmax, *, y=0.1, backward=None, x=-0.6):
    b = tmax if backward is None else backward
    return [Thruster("P1", np.array([x, -y, 0.0]), np.array([1.0, 0, 0]),
                     max_forward=tmax, max_backward=b),
            Thruster("P2", np.array([x, y, 0.0]), np.array([1.0, 0, 0]),
                     max_forward=tmax, max_backward=b)]


def vertical_pair(tmax, *, x=0.4):
    return [Thruster("V1", np.array([x, 0, 0.0]), np.array([0, 0, 1.0]),
                     max_forward=tmax, max_backward=tmax),
            Thruster("V2", np.array([-x, 0, 0.0]), np.array([0, 0, 1.0]),
                     max_forward=tmax, max_backward=tmax)]
