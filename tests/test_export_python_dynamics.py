"""The Python export runs: its state_derivative integrates to the trajectory of stripcoef
simulate (to 1e-6), and its Vehicle class has PythonVehicleSimulator's dynamics interface."""


import numpy as np
import pytest
from scipy.integrate import solve_ivp

from stripcoef.conventions import POSE, VELOCITIES
from stripcoef.export import write_export
from stripcoef.modelfile import load_model
from stripcoef.simulate import simulate
from conftest import load_module

COMMANDS = {"port": 150.0, "starboard": 120.0, "vertical": 60.0}
CURRENT = np.array([0.1, -0.05, 0.0])


def _module(path):
    return load_module(path)


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    from conftest import GEOMETRY
    from stripcoef.assembly import estimate

    # the strip model (its step errors are measured below; a bluff vehicle file's default added
    # mass is the panel method's since issue 32)
    model = estimate(GEOMETRY / "videoray_pro3.yaml", added_mass_method="strips")
    path = write_export(model, "python", tmp_path_factory.mktemp("py") / "videoray_model.py")
    return model, _module(path)


@pytest.mark.slow
def test_same_trajectory_as_simulate(exported):
    model, m = exported
    t = np.linspace(0.0, 20.0, 201)
    ref = simulate(model, t, commands=COMMANDS, current=CURRENT, rtol=1e-11, atol=1e-13)
    u = [COMMANDS.get(n, 0.0) for n in m.THRUSTERS]
    tau = m.B_THRUSTERS @ m.thrust(u)

    def rhs(_t, y):
        eta_dot, nu_dot = m.state_derivative(y[:6], y[6:], tau, CURRENT)
        return np.concatenate([eta_dot, nu_dot])

    sol = solve_ivp(rhs, (t[0], t[-1]), np.zeros(12), t_eval=t, rtol=1e-11, atol=1e-13)
    pose = np.column_stack([ref[k] for k in POSE])
    vel = np.column_stack([ref[k] for k in VELOCITIES])
    assert np.max(np.abs(sol.y[:6].T - pose)) < 1e-6
    assert np.max(np.abs(sol.y[6:].T - vel)) < 1e-6
    assert np.max(np.abs(pose[:, :3])) > 1.0            # it went somewhere
    # the thrust map is the model's
    for name, th in zip(m.THRUSTERS, model.thrusters):
        for n in (-300.0, -5.0, 0.0, 40.0, 250.0):
            assert m.thrust([n if k == name else 0.0 for k in m.THRUSTERS])[
                m.THRUSTERS.index(name)] == pytest.approx(th.thrust(n), rel=1e-14, abs=1e-15)


def test_vehicle_class_in_the_simulator_style(exported):
    model, m = exported
    v = m.Vehicle(current=CURRENT)
    assert v.dimU == len(m.THRUSTERS) and len(v.controls) == v.dimU
    u = np.array([COMMANDS.get(n, 0.0) for n in m.THRUSTERS])
    eta, nu = np.zeros(6), np.array([0.1, 0, 0, 0, 0, 0.02])
    nu1, ua = v.dynamics(eta, nu, u, u, 0.05)
    _, nu_dot = m.state_derivative(eta, nu, m.B_THRUSTERS @ m.thrust(u), CURRENT)
    assert np.allclose(nu1, nu + 0.05 * nu_dot, rtol=0, atol=1e-15)
    assert np.array_equal(ua, u)
    lagged = m.Vehicle(T_n=0.1).dynamics(eta, nu, np.zeros(v.dimU), u, 0.05)[1]
    assert np.allclose(lagged, 0.5 * u)

    # the simulator's main loop (Euler in nu, then eta): first order in the step
    t_end = 4.0
    ref = simulate(model, np.array([0.0, t_end]), commands=COMMANDS, current=CURRENT,
                   rtol=1e-11, atol=1e-13)
    want = np.array([ref[k][-1] for k in VELOCITIES])

    def run(dt):
        eta, nu, ua = np.zeros(6), np.zeros(6), u.copy()
        for _ in range(int(round(t_end / dt))):
            eta_dot, _ = m.state_derivative(eta, nu, np.zeros(6))
            nu_next, ua = v.dynamics(eta, nu, ua, u, dt)
            eta = eta + dt * eta_dot
            nu = nu_next
        return np.max(np.abs(nu - want))

    e1, e2 = run(0.01), run(0.005)
    assert e2 < 0.05 and 1.6 < e1 / e2 < 2.6          # measured 0.081, 0.034 (3 rad/s of yaw)


def test_flu_module_holds_data_only(tmp_path, exported):
    model, _ = exported
    m = _module(write_export(model, "python", tmp_path / "flu_model.py", axes="FLU"))
    assert m.AXES == "FLU" and not hasattr(m, "state_derivative") and m.M_A.shape == (6, 6)


@pytest.mark.slow
def test_vehicle_class_steers_with_rudders_and_elevators(tmp_path):
    """REMUS 100: the exported Vehicle takes the rudder and elevator deflections after the
    propeller command (as the simulator's remus100 does), clips them to MAX_DEFLECTION and
    integrates to the trajectory of stripcoef simulate with the same deflections."""
    from conftest import GEOMETRY
    model = load_model(GEOMETRY / "remus100.yaml")
    m = _module(write_export(model, "python", tmp_path / "remus_model.py"))
    v = m.Vehicle()
    n_th, n_cs = len(m.THRUSTERS), len(m.CONTROL_SURFACES)
    assert n_cs >= 2 and v.dimU == n_th + n_cs and len(v.controls) == v.dimU
    assert all("deflection" in c for c in v.controls[n_th:])
    rudder = next(i for i, c in enumerate(model.control_surfaces) if c.kind == "rudder")
    delta = np.zeros(n_cs)
    delta[rudder] = 0.05
    u = np.concatenate([np.full(n_th, 1000.0), delta])
    nu = np.array([1.5, 0, 0, 0, 0, 0])
    # a deflection past the stop is clipped
    big = u.copy()
    big[n_th + rudder] = 10.0
    _, ua = v.dynamics(np.zeros(6), nu, big, big, 0.01)
    assert ua[n_th + rudder] == pytest.approx(m.MAX_DEFLECTION[rudder])
    # the rudder's force is the model's u|u| derivative, and it turns the vehicle as simulate
    tau = v.forces(np.zeros(6), nu, u) - v.forces(np.zeros(6), nu, np.concatenate(
        [u[:n_th], np.zeros(n_cs)]))
    want = 1.5 * 1.5 * 0.05 * np.asarray(model.control_surfaces[rudder].derivative)
    assert np.allclose(tau, want, rtol=1e-12, atol=1e-12 * np.abs(want).max())
    t_end, dt = 5.0, 0.002
    cmd = {name: 1000.0 for name in m.THRUSTERS}
    ref = simulate(model, np.array([0.0, t_end]), commands=cmd, nu0=nu,
                   deflections={model.control_surfaces[rudder].name: 0.05},
                   rtol=1e-10, atol=1e-12)
    eta, x = np.zeros(6), nu.copy()
    for _ in range(int(round(t_end / dt))):
        eta_dot, _ = m.state_derivative(eta, x, v.forces(eta, x, u))
        x, _ = v.dynamics(eta, x, u, u, dt)
        eta = eta + dt * eta_dot
    want = np.array([ref[k][-1] for k in VELOCITIES])
    assert abs(want[5]) > 0.03                          # it turns
    assert np.allclose(x, want, rtol=0, atol=0.02 * np.abs(want).max())
