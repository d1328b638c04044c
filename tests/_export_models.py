"""Hand-built HydroModel fixtures for the export tests (no dependence on the estimator).

A torpedo-like vehicle with every kind of term the exporters must carry: full symmetric
M_A with the couplings geometry creates (Y_rdot = N_vdot, Z_qdot = M_wdot, a roll coupling
from an off-axis appendage), off-diagonal linear damping (Y_r, N_v), quadratic cross terms
(N_vv, M_ww, Y_rr, Z_qq), CG and CB apart from the reference point, and two thrusters.
"""

from __future__ import annotations

import os
import shutil

import numpy as np
import pytest

from stripcoef.model import HydroModel, rigid_body_mass_matrix
from stripcoef.thrusters import Thruster


def torpedo(*, name: str = "torpedo", big_added_mass: bool = False) -> HydroModel:
    mass = 31.9
    rho = 1025.0
    ref = np.array([0.05, 0.0, 0.0])        # reference point (CO), FRD coordinates
    cg = np.array([0.03, 0.002, 0.02])
    cb = np.array([0.05, 0.0, -0.001])
    inertia_cg = np.array([[0.17, 0.001, -0.004], [0.001, 3.45, 0.002], [-0.004, 0.002, 3.45]])
    mrb = rigid_body_mass_matrix(mass, cg - ref, inertia_cg)
    ma = np.array([
        [0.93, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 35.5, 0.0, -0.12, 0.0, -1.93],
        [0.0, 0.0, 35.5, 0.0, 1.93, 0.0],
        [0.0, -0.12, 0.0, 0.0704, 0.0, 0.004],
        [0.0, 0.0, 1.93, 0.0, 4.88, 0.0],
        [0.0, -1.93, 0.0, 0.004, 0.0, 4.88],
    ])
    if big_added_mass:
        ma = ma * 3.0
    dl = np.diag([2.4, 9.0, 9.0, 0.2, 2.1, 2.1])
    dl[1, 5] = -1.1    # -Y_r
    dl[5, 1] = 0.6     # -N_v
    dl[2, 4] = 1.1
    dl[4, 2] = -0.6
    dq = np.diag([3.9, 131.0, 131.0, 0.013, 9.4, 9.4])
    dq[5, 1] = -4.2    # -N_v|v|
    dq[4, 2] = 4.2     # -M_w|w|
    dq[1, 5] = 0.63    # -Y_r|r|
    dq[2, 4] = -0.63   # -Z_q|q|
    thrusters = [
        Thruster(name="port", position=np.array([-0.7, -0.1, 0.0]),
                 direction=np.array([1.0, 0.0, 0.0]), ct_forward=0.0125, ct_backward=0.0091,
                 max_forward=40.0, max_backward=25.0),
        Thruster(name="vertical", position=np.array([0.2, 0.0, 0.0]),
                 direction=np.array([0.0, 0.0, 1.0]), ct_forward=0.011, ct_backward=0.008,
                 eta_backward=0.85),
    ]
    return HydroModel(name=name, reference_point=ref, rigid_body_mass=mrb, added_mass=ma,
                      linear_damping=dl, quadratic_damping=dq, mass=mass,
                      volume=mass / rho * 1.004, center_of_gravity=cg, center_of_buoyancy=cb,
                      density=rho, thrusters=thrusters,
                      conditions={"reference_speed": 1.5}, provenance={"method": "hand-built"})


def octave_or_skip() -> str:
    """Path of octave-cli; skip without it, unless STRIPCOEF_REQUIRE_OCTAVE=1 (CI): then fail."""
    exe = shutil.which("octave-cli")
    if exe is None:
        if os.environ.get("STRIPCOEF_REQUIRE_OCTAVE") == "1":
            pytest.fail("octave-cli not found but STRIPCOEF_REQUIRE_OCTAVE=1")
        pytest.skip("octave-cli not installed (set STRIPCOEF_REQUIRE_OCTAVE=1 to require it)")
    return exe


def warning_messages(func, *args, **kwargs):
    """Call func and return (result, {category name: [messages]}) of every warning it raised."""
    import warnings
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = func(*args, **kwargs)
    out: dict[str, list[str]] = {}
    for w in caught:
        out.setdefault(w.category.__name__, []).append(str(w.message))
    return result, out
