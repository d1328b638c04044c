"""MARES: hydrodynamic model exported by stripcoef 0.1.0 to format 'python'.

reference point: CO = [0.00436665486209404, 0, 0.0013222979649128548] m (FRD body coordinates of the source model)
axes: FRD (x forward, y starboard, z down)
mass 41.32106391636393 kg, volume 0.04169631394247401 m^3, density 998.2063193823999 kg/m^3

Fossen's convention: M_A, D_L, D_Q positive; hydrodynamic force
-M_A nu_dot - C_A(nu) nu - (D_L + D_Q diag|nu|) nu. Units SI, radians.
"""

import numpy as np

NAME = 'MARES'
AXES = 'FRD'
POINT = 'CO'
DOF = ('surge', 'sway', 'heave', 'roll', 'pitch', 'yaw')
REFERENCE_POINT = np.array([0.00436665486209404, 0, 0.0013222979649128548])  # [m], FRD coordinates of the source model
MASS = 41.32106391636393  # [kg]
VOLUME = 0.04169631394247401  # [m^3]
DENSITY = 998.2063193823999  # [kg/m^3]
GRAVITY = 9.81  # [m/s^2]
KINEMATIC_VISCOSITY = 1.0035619398114109e-06  # [m^2/s]
R_G = np.array([-0.0004234878459554864, -2.7025640964143323e-19, 0.001607830407052056])  # CG relative to the reference point [m]
R_B = np.array([0, 0, 0])  # CB relative to the reference point [m]

# Rigid-body mass [kg, kg m, kg m^2]
M_RB = np.array([
    [41.32106391636393, 0, 0, 0, 0.06643726301647145, 0],
    [0, 41.32106391636393, 0, -0.06643726301647145, 0, -0.017498968350529935],
    [0, 0, 41.32106391636393, 0, 0.017498968350529935, 0],
    [0, -0.06643726301647145, 0, 0.2280629775480152, 0, -0.02369302548573914],
    [0.06643726301647145, 0, 0.017498968350529935, 0, 6.551275412100456, 0],
    [0, -0.017498968350529935, 0, -0.023693025485739143, 0, 6.553724319663196],
])

# Added mass, positive (M_A[0, 0] = -X_udot) [kg, kg m, kg m^2]
M_A = np.array([
    [3.9080205335022757, 0, 0, 0, -0.002031868498488919, 0],
    [0, 41.036429297212806, 0, 0.003975713912744219, 0, 0.15571599365549155],
    [0, 0, 36.91390605313635, 0, 0.00805582597421888, 0],
    [0, 0.003975713912744219, 0, 0.027790670034328287, 0, -0.009278143896206813],
    [-0.002031868498488919, 0, 0.00805582597421888, 0, 4.824341228959663, 0],
    [0, 0.15571599365549155, 0, -0.009278143896206813, 0, 5.293744731778096],
])

# Linear damping, positive (D_L[0, 0] = -X_u) [kg/s, kg m/s, kg m^2/s]
D_L = np.array([
    [0, 0, 0, 0, 0, 0],
    [0, 0.7501885810374327, 0, 0.0005118397209968547, 0, -0.004819820893470568],
    [0, 0, 0.7301727363055358, 0, 0.005733206876093822, 0],
    [0, 0.0005118397209968547, 0, 0.00034693782180132216, 0, -0.00010030328636826275],
    [0, 0, 0.005733206876093822, 0, 0.12415684895144302, 0],
    [0, -0.004819820893470568, 0, -0.00010030328636826277, 0, 0.1266566013908442],
])

# Quadratic damping, positive: force_i = -sum_j D_Q[i, j] |nu_j| nu_j
D_Q = np.array([
    [6.0012083844558894, 0, 0, 0, 0.019969773115173384, 0],
    [0, 119.57559739437953, 0, -0.05285886418027026, 0, -1.1998235201929406],
    [0, 0, 116.54437764317548, 0, 1.2966503361901387, 0],
    [0, -0.25848912889531994, 0, 0.020955683648977017, 0, -0.018312212079145233],
    [0.14891737561184415, 0, 2.092129463170924, 0, 10.620700850353032, 0],
    [0, -1.9538053670317983, 0, -0.010385274551659671, 0, 10.76299097350171],
])

# Lift (forward-speed) terms, positive: force = -u L nu (L[1, 1] = -Y_uv)
# [kg/m, kg, kg m] (body and fin lift, Prestero 2001 sec. 3.6)
L = np.array([
    [0, 0, 0, 0, 0, 0],
    [0, 0, 0, 0, 0, 0],
    [0, 0, 0, 0, 0, 0],
    [0, 0, 0, 0, 0, 0],
    [0, 0, 0, 0, 0, 0],
    [0, 0, 0, 0, 0, 0],
])

M = M_RB + M_A

CONTROL_SURFACES = ()
# Control surfaces: force = u |u| B_DELTA @ deflections [rad] (Prestero 2001 sec. 3.7)
B_DELTA = np.zeros((6, 0))
MAX_DEFLECTION = np.array([])  # [rad]

THRUSTERS = ('P1', 'P2', 'V1', 'V2')
# Thruster allocation: tau = B_THRUSTERS @ thrusts [N]
B_THRUSTERS = np.array([
    [1, 1, 0, 0],
    [0, 0, 0, 0],
    [0, 0, 1, 1],
    [0, 0, 0, 0],
    [-0.0013222979649128548, -0.0013222979649128548, 0.304366654862094, -0.395633345137906],
    [0.13, -0.13, 0, 0],
])

# SNAME derivatives (signed) in AXES
COEFFICIENTS = {
    'X_udot': -3.9080205335022757,
    'X_qdot': 0.002031868498488919,
    'Y_vdot': -41.036429297212806,
    'Y_pdot': -0.003975713912744219,
    'Y_rdot': -0.15571599365549155,
    'Z_wdot': -36.91390605313635,
    'Z_qdot': -0.00805582597421888,
    'K_vdot': -0.003975713912744219,
    'K_pdot': -0.027790670034328287,
    'K_rdot': 0.009278143896206813,
    'M_udot': 0.002031868498488919,
    'M_wdot': -0.00805582597421888,
    'M_qdot': -4.824341228959663,
    'N_vdot': -0.15571599365549155,
    'N_pdot': 0.009278143896206813,
    'N_rdot': -5.293744731778096,
    'Y_v': -0.7501885810374327,
    'Y_p': -0.0005118397209968547,
    'Y_r': 0.004819820893470568,
    'Z_w': -0.7301727363055358,
    'Z_q': -0.005733206876093822,
    'K_v': -0.0005118397209968547,
    'K_p': -0.00034693782180132216,
    'K_r': 0.00010030328636826275,
    'M_w': -0.005733206876093822,
    'M_q': -0.12415684895144302,
    'N_v': 0.004819820893470568,
    'N_p': 0.00010030328636826277,
    'N_r': -0.1266566013908442,
    'X_uu': -6.0012083844558894,
    'X_qq': -0.019969773115173384,
    'Y_vv': -119.57559739437953,
    'Y_pp': 0.05285886418027026,
    'Y_rr': 1.1998235201929406,
    'Z_ww': -116.54437764317548,
    'Z_qq': -1.2966503361901387,
    'K_vv': 0.25848912889531994,
    'K_pp': -0.020955683648977017,
    'K_rr': 0.018312212079145233,
    'M_uu': -0.14891737561184415,
    'M_ww': -2.092129463170924,
    'M_qq': -10.620700850353032,
    'N_vv': 1.9538053670317983,
    'N_pp': 0.010385274551659671,
    'N_rr': -10.76299097350171,
}

THRUSTER_MAPS = (
    # P1: thrust = eta C_t n|n| [N], clipped to [-max_backward, max_forward]
    {'name': 'P1', 'ct_forward': 1, 'ct_backward': 1, 'eta_forward': 1, 'eta_backward': 1, 'max_forward': 8, 'max_backward': 6, 'deadband': 0},
    # P2: thrust = eta C_t n|n| [N], clipped to [-max_backward, max_forward]
    {'name': 'P2', 'ct_forward': 1, 'ct_backward': 1, 'eta_forward': 1, 'eta_backward': 1, 'max_forward': 8, 'max_backward': 6, 'deadband': 0},
    # V1: thrust = eta C_t n|n| [N], clipped to [-max_backward, max_forward]
    {'name': 'V1', 'ct_forward': 1, 'ct_backward': 1, 'eta_forward': 1, 'eta_backward': 1, 'max_forward': 8, 'max_backward': 6, 'deadband': 0},
    # V2: thrust = eta C_t n|n| [N], clipped to [-max_backward, max_forward]
    {'name': 'V2', 'ct_forward': 1, 'ct_backward': 1, 'eta_forward': 1, 'eta_backward': 1, 'max_forward': 8, 'max_backward': 6, 'deadband': 0},
)

def skew(a):
    """S(a), S(a) b = a x b (Fossen 2011, eq. 2.10)."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def coriolis(mass, nu):
    """C(nu) of a 6x6 inertia matrix [kg/s, kg m/s, kg m^2/s] (Fossen 2011, eqs. 3.46, 6.43)."""
    a = mass[:3, :3] @ nu[:3] + mass[:3, 3:] @ nu[3:]
    b = mass[3:, :3] @ nu[:3] + mass[3:, 3:] @ nu[3:]
    c = np.zeros((6, 6))
    c[:3, 3:] = -skew(a)
    c[3:, :3] = -skew(a)
    c[3:, 3:] = -skew(b)
    return c


def rotation(phi, theta, psi):
    """R(Theta), body to NED, zyx Euler angles [rad] (Fossen 2011, eq. 2.18)."""
    cf, sf, ct, st, cp, sp = (np.cos(phi), np.sin(phi), np.cos(theta), np.sin(theta),
                              np.cos(psi), np.sin(psi))
    return np.array([[cp * ct, -sp * cf + cp * st * sf, sp * sf + cp * cf * st],
                     [sp * ct, cp * cf + sf * st * sp, -cp * sf + st * sp * cf],
                     [-st, ct * sf, ct * cf]])


def kinematics(eta):
    """J(eta): eta_dot = J(eta) nu (Fossen 2011, eqs. 2.18 and 2.29)."""
    phi, theta = eta[3], eta[4]
    cf, sf, ct, tt = np.cos(phi), np.sin(phi), np.cos(theta), np.tan(theta)
    t = np.array([[1.0, sf * tt, cf * tt], [0.0, cf, -sf], [0.0, sf / ct, cf / ct]])
    j = np.zeros((6, 6))
    j[:3, :3] = rotation(*eta[3:6])
    j[3:, 3:] = t
    return j


def restoring(eta):
    """g(eta) [N, N m], the force is -g (Fossen 2011, eq. 4.6)."""
    w, b = MASS * GRAVITY, DENSITY * GRAVITY * VOLUME
    phi, theta = eta[3], eta[4]
    sf, cf, st, ct = np.sin(phi), np.cos(phi), np.sin(theta), np.cos(theta)
    (xg, yg, zg), (xb, yb, zb) = R_G, R_B
    return np.array([(w - b) * st, -(w - b) * ct * sf, -(w - b) * ct * cf,
                     -(yg * w - yb * b) * ct * cf + (zg * w - zb * b) * ct * sf,
                     (zg * w - zb * b) * st + (xg * w - xb * b) * ct * cf,
                     -(xg * w - xb * b) * ct * sf - (yg * w - yb * b) * st])


def thrust(commands):
    """Thrusts [N] of the thrusters for their commands (sequence in THRUSTERS order):
    T = eta C_t n|n| (forward/backward values), 0 inside the dead band, clipped to the limits
    (Wang & Clark 2006, eq. 6)."""
    out = np.zeros(len(THRUSTER_MAPS))
    for k, (t, n) in enumerate(zip(THRUSTER_MAPS, np.asarray(commands, dtype=float))):
        fwd = n >= 0.0
        ct = t["ct_forward"] * t["eta_forward"] if fwd else t["ct_backward"] * t["eta_backward"]
        value = 0.0 if abs(n) <= t["deadband"] else ct * n * abs(n)
        out[k] = min(max(value, -t["max_backward"]), t["max_forward"])
    return out


def state_derivative(eta, nu, tau, current=(0.0, 0.0, 0.0)):
    """(eta_dot, nu_dot) of the 6-DOF model [m/s, rad/s; m/s^2, rad/s^2].

    M nu_dot = tau - C_RB(nu) nu - C_A(nu_r) nu_r - D(nu_r) nu_r - g(eta) + M_A nu_c_dot,
    D(nu_r) = D_L + u_r L + D_Q diag|nu_r| (L: body and fin lift, 0 without fins),
    eta_dot = J(eta) nu, nu_r = nu - nu_c, nu_c = [R^T V_c; 0], nu_c_dot = [-S(w) R^T V_c; 0]
    (Fossen 2011, eqs. 7.190 and 10.1). eta [m, rad] NED pose, nu [m/s, rad/s] body
    velocity over ground (about the reference point, FRD), tau [N, N m] applied force,
    current V_c [m/s] constant in NED. Control-surface forces are part of tau:
    u_r |u_r| B_DELTA @ deflections [N, N m] for deflections [rad].
    """
    eta = np.asarray(eta, dtype=float)
    nu = np.asarray(nu, dtype=float)
    vc = rotation(*eta[3:6]).T @ np.asarray(current, dtype=float)
    nu_c = np.concatenate([vc, np.zeros(3)])
    nu_c_dot = np.concatenate([-skew(nu[3:]) @ vc, np.zeros(3)])
    nu_r = nu - nu_c
    force = (np.asarray(tau, dtype=float) - coriolis(M_RB, nu) @ nu
             - coriolis(M_A, nu_r) @ nu_r - (D_L + nu_r[0] * L + D_Q * np.abs(nu_r)) @ nu_r
             - restoring(eta) + M_A @ nu_c_dot)
    return kinematics(eta) @ nu, np.linalg.solve(M, force)


class Vehicle:
    """The model as a vehicle of Fossen's PythonVehicleSimulator (same interface).

    ``u_control`` and ``u_actual`` are the thruster commands (THRUSTERS order) followed by the
    control-surface deflections [rad] (CONTROL_SURFACES order: rudders, elevators), as the
    simulator's ``remus100`` takes its rudder and stern-plane angles beside the propeller.
    ``T_n`` [s] is a first-order lag of the actual thruster commands and ``T_delta`` [s] of
    the actual deflections (0: none, as in stripcoef simulate); the deflections are clipped
    to +-MAX_DEFLECTION; ``current`` [m/s] a constant NED current.
    """

    def __init__(self, controlSystem="stepInput", T_n=0.0, current=(0.0, 0.0, 0.0),
                 T_delta=0.0):
        self.name = NAME + " (stripcoef export)"
        self.L = None
        self.controls = ([f"{n} command" for n in THRUSTERS]
                         + [f"{n} deflection (rad)" for n in CONTROL_SURFACES])
        self.dimU = len(THRUSTERS) + len(CONTROL_SURFACES)
        self.controlMode = controlSystem
        self.controlDescription = "Step inputs of the thruster commands and deflections"
        self.nu = np.zeros(6)
        self.u_actual = np.zeros(self.dimU)
        self.T_n = float(T_n)
        self.T_delta = float(T_delta)
        self.current = np.asarray(current, dtype=float)
        self.u_step = np.zeros(self.dimU)

    def forces(self, eta, nu, u_actual):
        """tau [N, N m] of the actual inputs: B_THRUSTERS thrust(commands) plus the
        control surfaces' u_r |u_r| B_DELTA delta (u_r: surge speed through the water)."""
        u_actual = np.asarray(u_actual, dtype=float)
        n = len(THRUSTERS)
        tau = B_THRUSTERS @ thrust(u_actual[:n]) if n else np.zeros(6)
        if CONTROL_SURFACES:
            vc = rotation(*np.asarray(eta, dtype=float)[3:6]).T @ self.current
            u_r = float(nu[0]) - vc[0]
            tau = tau + u_r * abs(u_r) * (B_DELTA @ u_actual[n:])
        return tau

    def dynamics(self, eta, nu, u_actual, u_control, sampleTime):
        """One forward-Euler step of sampleTime [s]: returns (nu, u_actual) at the next sample."""
        u_actual = np.asarray(u_actual, dtype=float)
        _, nu_dot = state_derivative(eta, nu, self.forces(eta, nu, u_actual), self.current)
        target = np.asarray(u_control, dtype=float).copy()
        n = len(THRUSTERS)
        target[n:] = np.clip(target[n:], -MAX_DEFLECTION, MAX_DEFLECTION)
        lag = np.array([self.T_n] * n + [self.T_delta] * len(CONTROL_SURFACES))
        step = np.where(lag > 0.0, sampleTime / np.where(lag > 0.0, lag, 1.0), 1.0)
        u_actual = u_actual + np.minimum(step, 1.0) * (target - u_actual)
        return np.asarray(nu, dtype=float) + sampleTime * nu_dot, u_actual

    def stepInput(self, t):
        """The inputs of a step input at time t [s] (constant ``u_step``)."""
        return self.u_step.copy()
