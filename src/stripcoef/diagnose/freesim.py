r"""Many short free simulations of one model at once: the segments of
:func:`stripcoef.diagnose.heldout.free_simulation_errors`, integrated side by side.

The held-out and validation errors re-simulate a log in segments of ``horizon`` seconds,
each started from the logged state (:mod:`stripcoef.diagnose.heldout`). The segments are
independent, so they are one system of S x 13 states, :math:`x_s = [p_s;\ q_s;\ \nu_s]`,
with the state equation of :class:`stripcoef.simulate.RightHandSide` evaluated for all of
them in one vectorised call:

.. math::
    M\dot\nu = \tau - C_{RB}(\nu)\nu - C_A(\nu)\nu - D(\nu)\nu - g(\eta) + \tau_{extra},
    \qquad \dot p = R(q)\,v,\qquad
    \dot\varepsilon = \tfrac12 (q_0\omega + \varepsilon\times\omega),\quad
    \dot q_0 = -\tfrac12 \varepsilon^T\omega

(Fossen 2011, eqs. 2.86, 3.46, 6.43, 7.190; no current: the replay of a log has none).
Step k of every segment runs over that segment's own sample interval
:math:`[t_{a_s+k}, t_{a_s+k+1}]`, with the inputs of its sample held (zero-order hold, the
replay rule of :func:`stripcoef.simulate.replay`: the integrator restarts at each sample and
never steps across an input jump). Each interval is integrated by the Dormand-Prince 5(4) pair
(Dormand & Prince 1980, J. Comput. Appl. Math. 6, 19-26; the tableau of
:class:`scipy.integrate.RK45`, the method ``simulate`` uses through ``solve_ivp``) on the
normalised time :math:`s \in [0, 1]` of the interval, with the error control of Hairer,
Norsett & Wanner (1993), Solving ODEs I, sec. II.4 (eq. 4.11: the RMS of the error over
``atol + rtol |x|``, here the largest over the segments, so every segment meets it). The
first step of an interval is the one the error control proposed at the end of the previous
one (as a solver that did not restart would take it); starting each interval with the whole
interval took one step more per interval on the 240-s synthetic logs (19 evaluations of the
right-hand side per interval against 13, the same errors to within the tolerance).

The calibrated effects of the model (``model.effects``) keep their scalar force laws: each
segment gets its own (:func:`stripcoef.effects.laws.effect_forces`; a lag has a state),
called with the hook ``simulate`` gives them.

Depends on: simulate (initial state, inputs), effects, model.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import RK45

from stripcoef.model import restoring_from_down

#: Most integration steps per sample interval before a segment set counts as diverged (a
#: smooth interval takes one or two; ``simulate``'s budget is 1e6 evaluations per run).
MAX_STEPS_PER_INTERVAL = 2000


def _quadratic_form() -> np.ndarray:
    """The (16, 9) table W with R(q) = (q q^T : W) / |q|^2 (:func:`_quat_matrices`)."""
    w = np.zeros((4, 4, 3, 3))
    x, y, z, s = range(4)
    for (i, j), terms in {(0, 0): [(1, x, x), (-1, y, y), (-1, z, z), (1, s, s)],
                          (1, 1): [(-1, x, x), (1, y, y), (-1, z, z), (1, s, s)],
                          (2, 2): [(-1, x, x), (-1, y, y), (1, z, z), (1, s, s)],
                          (0, 1): [(2, x, y), (-2, z, s)], (1, 0): [(2, x, y), (2, z, s)],
                          (0, 2): [(2, x, z), (2, y, s)], (2, 0): [(2, x, z), (-2, y, s)],
                          (1, 2): [(2, y, z), (-2, x, s)],
                          (2, 1): [(2, y, z), (2, x, s)]}.items():
        for c, a, b in terms:
            w[a, b, i, j] += c
    w = w.reshape(16, 9)
    w.flags.writeable = False
    return w


#: :func:`_quadratic_form`, built once (read-only).
_QUAT_FORM = _quadratic_form()


def _quat_matrices(q):
    r"""(S, 3, 3) R(q) of (S, 4) quaternions (x, y, z, w), normalised (Fossen 2011, eq. 2.72;
    the R(q) of :class:`stripcoef.simulate.RightHandSide`, vectorised). Each entry of R of a unit
    quaternion is a quadratic form in q, e.g. :math:`R_{11} = 1 - 2(y^2 + z^2) = x^2 - y^2 -
    z^2 + w^2`, so that :math:`R(q/|q|) = (q q^T : W_{ij}) / |q|^2` with constant W
    (:func:`_quadratic_form`): one product of the (S, 16) outer products with a (16, 9) table
    instead of some twenty operations on (S,) columns (a fifth of the time at S = 24; the
    same matrix to round-off, 4e-16)."""
    n2 = np.einsum("ij,ij->i", q, q)
    qq = (q[:, :, None] * q[:, None, :]).reshape(-1, 16)
    return ((qq @ _QUAT_FORM) / n2[:, None]).reshape(-1, 3, 3)


def _quaternion_rate_table() -> np.ndarray:
    r"""The (12, 4) table T with :math:`\dot q = (\omega q^T)_{flat}\,T` (:func:`_quat_matrices`'
    order, q = (x, y, z, w)): :math:`\dot\varepsilon = \tfrac12 (q_0\omega + \varepsilon\times
    \omega)`, :math:`\dot q_0 = -\tfrac12 \varepsilon^T\omega` (Fossen 2011, eq. 2.86), each
    entry bilinear in omega and q."""
    t = np.zeros((3, 4, 4))           # [omega index, q index, rate index]
    for i in range(3):
        t[i, 3, i] += 0.5             # q0 omega_i
        t[i, i, 3] -= 0.5             # -eps_i omega_i
    for a, b, c in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        t[c, b, a] += 0.5             # (eps x omega)_a = eps_b omega_c - eps_c omega_b
        t[b, c, a] -= 0.5
    t = t.reshape(12, 4)
    t.flags.writeable = False
    return t


#: :func:`_quaternion_rate_table`, built once (read-only).
_QUAT_RATE = _quaternion_rate_table()


class BatchRightHandSide:
    r"""The state equation of S segments at once (module docstring); ``tau`` (S, 6) [N, N m]
    the held applied force of each segment's current sample, set by the caller.

    :math:`C_{RB}(\nu)\nu + C_A(\nu)\nu + D(\nu)\nu` of every segment by
    :meth:`stripcoef.model.HydroModel.velocity_forces` (Fossen 2011, eq. 7.190; no current in
    a replay, so :math:`\nu_r = \nu`).

    The model's effects that are not held, in the model's order: ``batch`` holds, per
    effect, its law for all segments at once (an effect's ``batch_force_law``, called with
    the times, ``rows`` the sample each segment holds and ``last`` the last sample of its
    input history, both set by the caller) or None, where ``terms`` (per segment, a list
    with a scalar force law at that place) and ``hooks`` (per segment, the hook of its
    current sample) give it segment by segment. Without ``batch`` every place is scalar."""

    def __init__(self, model, hooks=None, terms=None, batch=None):
        self.model = model
        self.m_inv_t = np.linalg.inv(model.mass_matrix).T
        # g(eta) is linear in the down axis k (restoring_from_down): g = k G, G (3, 6) its
        # values at the unit axes, one product per evaluation for all segments
        self.g_table = restoring_from_down(np.eye(3), weight=float(model.weight),
                                           buoyancy=float(model.buoyancy),
                                           r_g=tuple(map(float, model.r_g)),
                                           r_b=tuple(map(float, model.r_b))).T
        self.terms = terms or []     # per segment: a list of scalar force laws
        self.hooks = hooks           # per segment: the hook of the current sample
        self.batch = list(batch or [])
        self.tau = self.rows = self.last = None
        self.logged, self.slope = [], None       # prescribed DOFs (:meth:`prescribe`)

    def prescribe(self, dofs) -> None:
        r"""Make the velocities of ``dofs`` (indices) follow the log: their rate is the
        logged one, ``slope`` (S, len(dofs)) set by the caller for each sample interval,
        and the others' rates solve :math:`M_{ff}\dot
u_f = F_f - M_{fl}\dot
u_l`, the
        partition of :math:`M\dot
u = F` with the logged rates known (the equation
        decoupling of output-error identification: measured states of the equations not
        being tested enter as inputs)."""
        self.logged = sorted(int(i) for i in dofs)
        free = [i for i in range(6) if i not in self.logged]
        m = np.asarray(self.model.mass_matrix, float)
        self.free = free
        self.m_ff_inv_t = np.linalg.inv(m[np.ix_(free, free)]).T
        self.m_fl_t = m[np.ix_(free, self.logged)].T

    def __call__(self, times, x):
        quat, nu = x[:, 3:7], x[:, 7:]
        rmat = _quat_matrices(quat)
        force = self.tau - self.model.velocity_forces(nu) - rmat[:, 2] @ self.g_table
        places = self.batch or [None] * max((len(t) for t in self.terms), default=0)
        eta = None
        for p, law in enumerate(places):
            if law is not None:          # all segments at once, the same numbers
                force += law(times, self.rows, self.last)
                continue
            if eta is None:
                phi = np.arctan2(rmat[:, 2, 1], rmat[:, 2, 2])
                theta = np.arcsin(np.clip(-rmat[:, 2, 0], -1.0, 1.0))
                psi = np.arctan2(rmat[:, 1, 0], rmat[:, 0, 0])
                eta = np.column_stack([x[:, :3], phi, theta, psi])
                when = times.tolist()
            # rows as lists of views, the times as floats: one indexing per segment
            for laws, hook, t_s, eta_s, nu_s, f_s in zip(self.terms, self.hooks, when, eta,
                                                        nu, force):
                hook["nu_r"] = nu_s              # no current in a replay: nu_r = nu
                f_s += laws[p](t_s, eta_s, nu_s, hook)
        out = np.empty_like(x)
        out[:, :3] = np.einsum("sij,sj->si", rmat, nu[:, :3])
        out[:, 3:7] = (nu[:, 3:, None] * quat[:, None, :]).reshape(-1, 12) @ _QUAT_RATE
        if self.logged:
            out[:, 7 + np.array(self.logged)] = self.slope
            out[:, 7 + np.array(self.free)] = ((force[:, self.free] - self.slope @ self.m_fl_t)
                                              @ self.m_ff_inv_t)
        else:
            out[:, 7:] = force @ self.m_inv_t
        return out


def integrate_interval(f, t0, h, x, rtol, atol, ds=1.0):
    """Integrate every segment over its own interval [t0_s, t0_s + h_s] (Dormand-Prince
    5(4) on the normalised time, module docstring), with ``ds`` the first step tried (a
    fraction of the interval). Returns the states at the ends and the step the error
    control proposes next, or None when the steps shrink past
    :data:`MAX_STEPS_PER_INTERVAL` or leave the finite numbers."""
    a, b, c, e = RK45.A, RK45.B, RK45.C, RK45.E
    hs = h[:, None]
    s, steps = 0.0, 0
    k = np.empty((7,) + x.shape)
    k[0] = f(t0, x) * hs
    while s < 1.0 - 1e-12:
        steps += 1
        if steps > MAX_STEPS_PER_INTERVAL:
            return None
        step = min(ds, 1.0 - s)
        flat = k.reshape(7, -1)
        for i in range(1, 6):
            xi = x + step * (a[i, :i] @ flat[:i]).reshape(x.shape)
            k[i] = f(t0 + (s + c[i] * step) * h, xi) * hs
        x_new = x + step * (b @ flat[:6]).reshape(x.shape)
        k[6] = f(t0 + (s + step) * h, x_new) * hs
        if not np.all(np.isfinite(x_new)):
            return None
        err = step * (e @ flat).reshape(x.shape)
        scale = atol + rtol * np.maximum(np.abs(x), np.abs(x_new))
        norm = float(np.max(np.sqrt(np.mean((err / scale) ** 2, axis=1))))
        if norm <= 1.0:
            s += step
            x = x_new
            k[0] = k[6]
            # the next step: grown from this one, or the step proposed before this one was
            # cut short by the end of the interval
            ds = max(ds if step < ds else 0.0,
                     step * (10.0 if norm == 0.0 else min(10.0, 0.9 * norm ** -0.2)))
        else:
            ds = step * max(0.2, 0.9 * norm ** -0.2)
    return x, ds


def batch_free_velocities(model, log, bounds, inputs, *, tolerances=(1e-5, 1e-7),
                          logged=()):
    """The re-simulated velocities of every segment ``(a, b)`` of ``bounds`` of ``log``,
    each from the logged state at its row a with the inputs ``inputs``
    (:func:`stripcoef.logfile.log_inputs` of the whole log): a list of (b - a, 6) arrays
    [m/s, rad/s], or None when a simulation diverges. Only for a model without control
    surfaces (:func:`supported`). The effects with a state (a thruster lag, an actuation
    delay) read the input history from the log's first sample: their state at a segment's
    start is the one the logged inputs before it set (a first-order lag of the logged
    commands, Fossen 2011 sec. 9.3), not an equilibrium with the segment's first input.

    ``logged``: DOFs (indices) whose velocity follows the log instead
    (:meth:`BatchRightHandSide.prescribe`): at each sample its logged value, in between the
    logged rate of the interval (linear between the samples); when roll and pitch both
    follow the log the attitude is the logged one at each sample (the restoring moments
    read it). A DOF without its velocity column in the log is simulated."""
    from stripcoef.effects.laws import effect_entries
    from stripcoef.simulate import (InputSampler, attitude_quaternion, initial_state,
                                    state_vector)

    t = np.asarray(log["t"], float)
    history = bool(model.effects)
    sampler = InputSampler(model, t, forces=inputs.forces, commands=inputs.commands or None,
                           deflections=None, channels=inputs.channels or None, current=None,
                           interpolation="previous", history=True)
    tau_all = sampler.tau_history                               # (n, 6) applied force
    starts = np.array([a for a, _ in bounds])
    lengths = np.array([b - a for a, b in bounds])
    x = np.array([state_vector(*initial_state(log, int(a))[:2]) for a in starts])
    out = np.empty((len(bounds), int(lengths.max()), 6))
    out[:, 0] = x[:, 7:]
    terms = hooks = held = None
    batch, held_batch, scalar = [], [], False
    if history:
        names = sampler.names
        thrust_all = (np.column_stack([np.asarray(th.thrust(sampler.cmd[:, j]), float)
                                       .reshape(-1) for j, th in enumerate(sampler.thrusters)])
                      if sampler.nthr else np.zeros((t.size, 0)))
        alloc = sampler.alloc
        # the laws of all segments at once where the effect has them (the same numbers as
        # its scalar law, Effect.batch_force_law), else each segment its own scalar laws (a
        # lag has a state); those of held effects (Effect.held: constant between samples)
        # evaluated once per sample, the others at every evaluation of the right-hand side
        entries = effect_entries(model)
        shared = {"t": t, "tau": tau_all, "allocation": alloc,
                  "thrust": thrust_all if sampler.nthr and model.thrusters else None}
        unique = len(set(names)) == len(names)
        made = [eff.batch_force_law(params, dof, shared)
                if unique and hasattr(eff, "batch_force_law") else None
                for eff, dof, params in entries]
        batch = [g for (eff, _, _), g in zip(entries, made) if not eff.held]
        held_batch = [g for (eff, _, _), g in zip(entries, made) if eff.held]
        scalar = any(g is None for g in made)
        if scalar:
            laws = [[None if g is not None else eff.force_law(params, dof)
                     for (eff, dof, params), g in zip(entries, made)] for _ in bounds]
            terms = [[law for (eff, _, _), law in zip(entries, row) if not eff.held]
                     for row in laws]
            held = [[law for (eff, _, _), law in zip(entries, row) if eff.held]
                    for row in laws]
        hooks = [None] * len(bounds)
    f = BatchRightHandSide(model, hooks, terms, batch)
    from stripcoef.conventions import VELOCITIES
    logged = [int(i) for i in logged if VELOCITIES[int(i)] in log]
    if logged:
        f.prescribe(logged)
        nu_log = log.velocities()[:, logged]
        att = None
        if 3 in logged and 4 in logged:
            from stripcoef.conventions import POSE
            eta = np.column_stack([log.get(c, np.zeros(t.size)) for c in POSE])
            att = attitude_quaternion(eta)
    rtol, atol = tolerances
    ds = 1.0
    ends = starts + lengths - 1                 # the last sample of each segment's history
    for k in range(int(lengths.max()) - 1):
        act = np.nonzero(lengths > k + 1)[0]
        rows = starts[act] + k
        f.tau = tau_all[rows]
        f.rows, f.last = rows, ends[act]
        if scalar:
            f.terms = [terms[s] for s in act]
            f.hooks = [{"commands": dict(zip(names, sampler.cmd[r])),
                        "thrust": dict(zip(names, thrust_all[r])), "tau": tau_all[r],
                        "nu_c": np.zeros(6), "nu_r": None, "model": model,
                        "allocation": alloc,
                        # from the log's first sample: the state of a lag or a delay at
                        # the segment's start is set by the logged inputs before it
                        "input_history": (t[:starts[s] + lengths[s]],
                                          tau_all[:starts[s] + lengths[s]]),
                        "columns": ({n: float(v) for n, v in zip(
                            sampler.chan_names, sampler.chan_series[r])}
                            if sampler.chan_names else {})}
                       for s, r in zip(act, rows)]
        for p, g in enumerate(held_batch):      # the held laws, in the model's order
            if g is not None:
                f.tau = f.tau + g(None, rows, f.last)
                continue
            for j, (s, r) in enumerate(zip(act, rows)):
                hook = f.hooks[j]
                hook["nu_r"] = x[s, 7:]          # the state is not read by a held law
                f.tau[j] = f.tau[j] + held[s][p](t[r], np.zeros(6), x[s, 7:], hook)
        h = t[rows + 1] - t[rows]
        if logged:
            x[np.ix_(act, 7 + np.array(logged))] = nu_log[rows]
            f.slope = (nu_log[rows + 1] - nu_log[rows]) / h[:, None]
            if att is not None:
                x[act, 3:7] = att[rows]
        got = integrate_interval(f, t[rows], h, x[act], rtol, atol, ds)
        if got is None:
            return None
        xa, ds = got
        ds = min(ds, 1.0)
        x[act] = xa
        out[act, k + 1] = xa[:, 7:]
    return [out[s, :lengths[s]] for s in range(len(bounds))]


def supported(model, inputs) -> bool:
    """Whether :func:`batch_free_velocities` replays these inputs of this model: sampled
    inputs held between samples, no control surfaces deflected."""
    return not inputs.deflections and not callable(inputs.forces)
