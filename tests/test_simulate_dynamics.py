"""Properties and exact solutions of the 6-DOF simulation (stripcoef.simulate)."""

import numpy as np
import pytest

from stripcoef.errors import InputError
from stripcoef.model import HydroModel, rigid_body_mass_matrix
from stripcoef.simulate import kinetic_energy, simulate
from stripcoef.thrusters import Thruster

RHO = 1000.0
G = 9.81


def make_model(*, damping=True, cg=(0.0, 0.0, 0.1), coupled=False, thrusters=()):
    """A neutrally buoyant 3.6 kg box-like ROV (VideoRay-sized), about its centre of buoyancy.

    The CG 10 cm below the CB gives a pitch restoring moment z_g W = 3.5 N m/rad, well above
    the destabilising Munk moment (Z_wdot - X_udot) u^2 = 1.1 N m/rad at 0.74 m/s (with 5 cm
    and this small pitch damping the vehicle loops at 0.74 m/s: the simulation shows it).
    """
    mass = 3.6
    inertia = np.diag([0.02275, 0.02391, 0.02532])
    mrb = rigid_body_mass_matrix(mass, cg, inertia)
    ma = np.diag([1.94, 6.06, 3.95, 0.033, 0.018, 0.032])
    if coupled:  # a full symmetric positive added-mass matrix (no symmetry assumed)
        rng = np.random.default_rng(3)
        a = rng.normal(scale=0.3, size=(6, 6))
        ma = ma + 0.05 * (a @ a.T)
    dl = np.diag([0.946, 5.87, 3.70, 0.01, 0.01, 0.023]) if damping else np.zeros((6, 6))
    dq = np.diag([6.04, 30.7, 26.4, 0.005, 0.007, 0.45]) if damping else np.zeros((6, 6))
    return HydroModel(name="box", reference_point=np.zeros(3), rigid_body_mass=mrb,
                      added_mass=ma, linear_damping=dl, quadratic_damping=dq, mass=mass,
                      volume=mass / RHO, center_of_gravity=np.asarray(cg, float),
                      center_of_buoyancy=np.zeros(3), density=RHO, gravity=G,
                      thrusters=list(thrusters))


def test_energy_conserved_without_damping_forcing_or_restoring():
    # CG = CB and W = B: g(eta) = 0, so only C(nu) acts and it does no work.
    model = make_model(damping=False, cg=(0.0, 0.0, 0.0), coupled=True)
    nu0 = np.array([0.4, -0.2, 0.1, 0.8, -0.5, 0.6])
    t = np.linspace(0.0, 20.0, 401)
    log = simulate(model, t, nu0=nu0, rtol=1e-10, atol=1e-12)
    e = kinetic_energy(model, log.velocities())
    assert e[0] == pytest.approx(kinetic_energy(model, nu0))
    assert np.max(np.abs(e - e[0])) / e[0] < 1e-7
    # the motion is not trivial: the velocity components exchange energy
    assert np.ptp(log["u"]) > 0.05


def test_total_energy_conserved_with_restoring_and_offset_cg():
    # No damping, W = B, CG off the CB in all three axes: kinetic + potential energy is
    # constant (the restoring moment is conservative; C_RB with r_g != 0 does no work).
    model = make_model(damping=False, cg=(0.01, -0.02, 0.05), coupled=True)
    t = np.linspace(0.0, 20.0, 401)
    log = simulate(model, t, nu0=[0.4, -0.2, 0.1, 0.8, -0.5, 0.6], rtol=1e-10, atol=1e-12)
    ke = kinetic_energy(model, log.velocities())
    phi, theta = log["phi"], log["theta"]
    down = np.column_stack([-np.sin(theta), np.cos(theta) * np.sin(phi),
                            np.cos(theta) * np.cos(phi)])  # NED z axis in body axes
    pe = -model.weight * down @ model.r_g + model.buoyancy * down @ model.r_b
    total = ke + pe
    assert np.ptp(ke) / ke[0] > 0.1  # energy does move between kinetic and potential
    assert np.ptp(total) / ke[0] < 1e-7


def test_coriolis_is_skew_symmetric_for_any_velocity():
    model = make_model(coupled=True, cg=(0.01, -0.02, 0.03))
    rng = np.random.default_rng(0)
    for _ in range(20):
        nu = rng.normal(size=6)
        c = model.coriolis(nu)
        np.testing.assert_allclose(c, -c.T, atol=1e-14)
        assert abs(nu @ c @ nu) < 1e-12


@pytest.mark.parametrize("thrust", [0.5, 1.8676, 4.0])
def test_constant_thrust_reaches_analytic_steady_speed(thrust):
    # X_u u + X_u|u| u|u| + T = 0 with SNAME signs: d_L u + d_Q u^2 = T (u > 0)
    model = make_model()
    t = np.linspace(0.0, 90.0, 181)
    forces = np.zeros(6)
    forces[0] = thrust
    log = simulate(model, t, forces=forces)
    dl, dq = model.linear_damping[0, 0], model.quadratic_damping[0, 0]
    u_ss = (-dl + np.sqrt(dl ** 2 + 4 * dq * thrust)) / (2 * dq)
    assert log["u"][-1] == pytest.approx(u_ss, rel=1e-6)
    np.testing.assert_allclose(log["X"], thrust)
    assert abs(log["v"][-1]) < 1e-9 and abs(log["psi"][-1]) < 1e-9


@pytest.mark.slow
def test_thruster_commands_forward_and_backward_maps():
    ct_f, ct_b = 2.5939e-4, 1.0086e-4  # Wang & Clark 2006, Table I (port/starboard)
    thr = [Thruster("port", np.array([0.0, -0.1, 0.0]), np.array([1.0, 0, 0]),
                    ct_forward=ct_f, ct_backward=ct_b),
           Thruster("starboard", np.array([0.0, 0.1, 0.0]), np.array([1.0, 0, 0]),
                    ct_forward=ct_f, ct_backward=ct_b)]
    model = make_model(thrusters=thr)
    t = np.linspace(0.0, 80.0, 801)
    n = np.where(t < 40.0, 60.0, -60.0)
    # Wang & Clark (2006) (sec. II.C) treats the DOFs as decoupled; with the Munk moment
    # (Y_vdot - X_udot) u v and this small yaw damping the straight run is directionally
    # unstable and a rounding-level asymmetry turns it into a circle, so drop it here.
    log = simulate(model, t, commands={"port": n, "starboard": n}, munk=False)
    dl, dq = model.linear_damping[0, 0], model.quadratic_damping[0, 0]
    for k, ct in ((399, ct_f), (800, ct_b)):
        thrust = 2 * ct * 3600.0
        u_ss = (-dl + np.sqrt(dl ** 2 + 4 * dq * thrust)) / (2 * dq)
        assert abs(log["u"][k]) == pytest.approx(u_ss, rel=1e-5)
        assert abs(log["X"][k]) == pytest.approx(thrust, rel=1e-12)
    assert log["u"][800] < 0
    np.testing.assert_array_equal(log["n_port"], n)
    assert abs(log["N"]).max() < 1e-12  # symmetric thrusters: no yaw moment


def test_thrust_limit_saturates_speed():
    thr = [Thruster("main", np.zeros(3), np.array([1.0, 0, 0]), ct_forward=1e-3,
                    max_forward=1.0)]
    model = make_model(thrusters=thr)
    t = np.linspace(0.0, 60.0, 301)
    log = simulate(model, t, commands={"main": np.full(t.size, 200.0)})
    assert log["X"][-1] == pytest.approx(1.0)


def test_passive_neutral_body_drifts_with_the_current():
    model = make_model()
    vc = np.array([0.3, -0.2, 0.0])  # NED [m/s]
    t = np.linspace(0.0, 120.0, 241)
    log = simulate(model, t, current=vc)
    # speed over ground tends to the current (the body may turn: Munk moment, no yaw spring)
    assert np.linalg.norm(log.velocities()[-1, :3]) == pytest.approx(np.linalg.norm(vc), abs=1e-4)
    vx = np.gradient(log["x"], t)[-1]
    vy = np.gradient(log["y"], t)[-1]
    vz = np.gradient(log["z"], t)[-1]
    np.testing.assert_allclose([vx, vy, vz], vc, atol=1e-4)
    assert log["X"].max() == 0.0  # nothing applied


@pytest.mark.slow
def test_current_on_a_turning_body_is_seen_in_body_axes():
    # Spinning in yaw in a uniform current: the relative velocity in body axes rotates,
    # and the body velocity over ground still tends to the current in NED.
    model = make_model()
    vc = np.array([0.2, 0.0, 0.0])
    t = np.linspace(0.0, 150.0, 301)
    forces = np.zeros(6)
    forces[5] = 0.02  # a small constant yaw moment
    log = simulate(model, t, current=vc, forces=forces)
    psi = log["psi"][-1]
    vel_ned = np.array([np.cos(psi) * log["u"][-1] - np.sin(psi) * log["v"][-1],
                        np.sin(psi) * log["u"][-1] + np.cos(psi) * log["v"][-1]])
    assert abs(log["r"][-1]) > 0.05
    np.testing.assert_allclose(vel_ned, vc[:2], atol=0.03)


def test_restoring_moment_gives_pendulum_period():
    # Small roll oscillation: (I_xx + K_pdot) p_dot = -z_g W phi  -> omega^2 = z_g W / I
    model = make_model(damping=False, cg=(0.0, 0.0, 0.02))
    t = np.linspace(0.0, 10.0, 2001)
    # at rest, the zero-order hold and the restoring moment alone
    log = simulate(model, t, eta0=[0, 0, 0, 0.01, 0, 0], rtol=1e-10, atol=1e-12)
    ixx = model.mass_matrix[3, 3] - model.mass_matrix[3, 1] ** 2 / model.mass_matrix[1, 1]
    omega = np.sqrt(0.02 * model.weight / ixx)  # Fossen (2011) eq. 4.38
    phi = log["phi"]
    crossings = t[1:][(phi[:-1] > 0) & (phi[1:] <= 0)]
    period = np.mean(np.diff(crossings))
    assert period == pytest.approx(2 * np.pi / omega, rel=2e-3)


def test_extra_force_hook_is_applied_but_not_logged():
    model = make_model()
    t = np.linspace(0.0, 90.0, 181)
    log = simulate(model, t, extra_force=lambda time, eta, nu, inp: np.array([1.0, 0, 0, 0, 0, 0]))
    dl, dq = model.linear_damping[0, 0], model.quadratic_damping[0, 0]
    assert log["u"][-1] == pytest.approx((-dl + np.sqrt(dl ** 2 + 4 * dq)) / (2 * dq), rel=1e-6)
    assert np.all(log["X"] == 0.0)


def test_linear_and_zero_order_hold_interpolation_differ_as_documented():
    model = make_model()
    t = np.array([0.0, 1.0, 2.0])
    f = np.zeros((3, 6))
    f[:, 0] = [0.0, 2.0, 2.0]
    zoh = simulate(model, t, forces=f, interpolation="previous")
    lin = simulate(model, t, forces=f, interpolation="linear")
    assert zoh["u"][1] == 0.0        # the step at t=1 acts from t=1 on
    assert lin["u"][1] > 0.0         # the ramp acts during [0, 1]


@pytest.mark.parametrize("kwargs, key", [
    ({"t": [0.0, 1.0, 1.0]}, "t"),
    ({"t": [0.0, np.nan]}, "t"),
    ({"t": [0.0, 1.0], "forces": np.full((2, 6), np.nan)}, "forces"),
    ({"t": [0.0, 1.0], "forces": np.zeros((3, 6))}, "forces"),
    ({"t": [0.0, 1.0], "commands": {"nope": [1.0, 1.0]}}, "n_nope"),
    ({"t": [0.0, 1.0], "interpolation": "cubic"}, "interpolation"),
])
def test_bad_input_names_the_key(kwargs, key):
    model = make_model()
    t = kwargs.pop("t")
    with pytest.raises(InputError) as exc:
        simulate(model, t, **kwargs)
    assert key in str(exc.value)


def test_saturated_thrusters_reach_the_limits_solvers_surge_speed():
    from stripcoef.limits.solver import surge_limit

    thr = [Thruster("port", np.array([-0.1, -0.1, 0.0]), np.array([1.0, 0, 0]),
                    ct_forward=2.5939e-4, ct_backward=1.0086e-4, max_forward=3.0,
                    max_backward=1.5),
           Thruster("starboard", np.array([-0.1, 0.1, 0.0]), np.array([1.0, 0, 0]),
                    ct_forward=2.5939e-4, ct_backward=1.0086e-4, max_forward=3.0,
                    max_backward=1.5),
           Thruster("vertical", np.zeros(3), np.array([0, 0, 1.0]), ct_forward=1.19e-4,
                    ct_backward=0.75e-4, max_forward=2.0, max_backward=1.5)]
    model = make_model(thrusters=thr)
    limit = surge_limit(model)
    t = np.linspace(0.0, 60.0, 121)
    full = np.full(t.size, 400.0)  # commands beyond saturation
    log = simulate(model, t, commands={"port": full, "starboard": full}, munk=False)
    assert log["u"][-1] == pytest.approx(limit.speed, rel=1e-5)


def test_controller_feedback_holds_a_speed_and_is_logged():
    # a proportional speed controller on one thruster: the logged command is the one applied
    thr = [Thruster("main", np.zeros(3), np.array([1.0, 0, 0]), ct_forward=1e-3,
                    ct_backward=1e-3)]
    model = make_model(thrusters=thr)
    t = np.linspace(0.0, 40.0, 401)

    def speed_hold(time, eta, nu, commands):
        return {"main": 100.0 * (0.3 - nu[0]) + 40.0}

    log = simulate(model, t, controller=speed_hold)
    assert log["n_main"][-1] == pytest.approx(100.0 * (0.3 - log["u"][-1]) + 40.0, rel=1e-9)
    # steady state: thrust = drag at the held speed
    u = log["u"][-1]
    thrust = 1e-3 * log["n_main"][-1] ** 2
    dl, dq = model.linear_damping[0, 0], model.quadratic_damping[0, 0]
    assert thrust == pytest.approx(dl * u + dq * u * u, rel=1e-4)
    with pytest.raises(InputError, match="thruster"):
        simulate(model, t[:5], controller=lambda *a: {"nope": 1.0})


def _spinning_top(inertia=(0.02275, 0.02391, 0.02532), added=(0.033, 0.018, 0.032)):
    """make_model without damping and restoring (CG = CB, W = B) and with the given rotational
    inertia [kg m^2] and added inertia [kg m^2]."""
    model = make_model(damping=False, cg=(0.0, 0.0, 0.0))
    import dataclasses
    return dataclasses.replace(
        model, rigid_body_mass=rigid_body_mass_matrix(3.6, (0.0, 0.0, 0.0), np.diag(inertia)),
        added_mass=np.diag([1.94, 6.06, 3.95, *added]))


def _attitude_error(log, expected):
    """Largest angle [rad] between the logged attitudes and the expected Rotations."""
    from scipy.spatial.transform import Rotation
    got = Rotation.from_euler("ZYX", np.column_stack([log["psi"], log["theta"], log["phi"]]))
    return float(np.max((got.inv() * expected).magnitude()))


def test_a_pure_pitch_rate_passes_through_90_degrees():
    """Rotation about a principal axis with no moment: q stays constant and the attitude is
    R_y(q t) (Fossen 2011 eq. 2.18). Euler angles are only the output: |theta| <= 90 deg, and
    the summary's largest pitch is 90 deg, not the integrated angle (issue 37: "450 deg")."""
    from scipy.spatial.transform import Rotation
    from stripcoef.simulate import summarize_motion

    q = 0.5
    t = np.linspace(0.0, 10.0, 201)                 # 5 rad: through 90, 180 and 270 deg
    log = simulate(_spinning_top(), t, nu0=[0, 0, 0, 0, q, 0], rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(log["q"], q, atol=1e-12)
    assert _attitude_error(log, Rotation.from_rotvec(np.outer(q * t, [0, 1, 0]))) < 1e-7
    assert np.max(np.abs(log["theta"])) <= np.pi / 2 + 1e-12
    assert np.max(np.abs(log["theta"])) > np.radians(89.0)
    assert summarize_motion(log).max_pitch <= np.pi / 2 + 1e-12


def test_any_constant_rate_of_a_symmetric_top_gives_the_closed_form_attitude():
    """Equal principal inertias: omega stays constant (omega x J omega = 0), so the attitude is
    R(t) = R(0) exp(S(omega) t) whatever the angles pass through; started at 75 deg of pitch
    the motion crosses the Euler angles' singularity (theta = +-90 deg)."""
    from scipy.spatial.transform import Rotation

    w = np.array([0.4, 0.7, -0.3])
    eta0 = [0.0, 0.0, 0.0, 0.2, np.radians(75.0), -0.4]
    t = np.linspace(0.0, 20.0, 401)
    log = simulate(_spinning_top((0.02, 0.02, 0.02), (0.01, 0.01, 0.01)), t,
                   eta0=eta0, nu0=[0, 0, 0, *w], rtol=1e-10, atol=1e-12)
    r0 = Rotation.from_euler("ZYX", eta0[5:2:-1])
    assert _attitude_error(log, r0 * Rotation.from_rotvec(np.outer(t, w))) < 1e-7
    np.testing.assert_allclose(log["phi"][0], 0.2, atol=1e-12)
    np.testing.assert_allclose(log["psi"][0], -0.4, atol=1e-12)



@pytest.mark.parametrize("munk", [True, False])
def test_right_hand_side_velocity_forces_are_the_models_matrices_times_nu(munk):
    """The right-hand side forms C_RB(nu) nu + C_A(nu_r) nu_r + D(nu_r) nu_r by
    HydroModel.velocity_forces (one table product per velocity); it equals the model's matrices
    times the velocities, C and D of coriolis() and damping(), for a full (non-diagonal) inertia
    matrix, with and without the Munk moment and a current, one velocity or many, to round-off."""
    model = make_model(coupled=True)            # a full added-mass matrix, CG off the origin
    rng = np.random.default_rng(4)
    nu = rng.normal(size=6)
    nu_r = nu - np.r_[rng.normal(size=3), 0.0, 0.0, 0.0]
    want = (model.coriolis(nu, added_mass=False) @ nu
            + model.coriolis(nu_r, rigid_body=False, munk=munk) @ nu_r
            + model.damping(nu_r) @ nu_r)
    scale = np.abs(want).max()
    got = model.velocity_forces(nu, nu_r, munk=munk)
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-13 * scale)
    rows = model.velocity_forces(np.vstack([nu, nu_r]), np.vstack([nu_r, nu_r]), munk=munk)
    np.testing.assert_allclose(rows[0], want, rtol=0, atol=1e-13 * scale)
    np.testing.assert_allclose(model.velocity_forces(nu_r, coriolis=False),
                               model.damping(nu_r) @ nu_r, rtol=0, atol=1e-13 * scale)
