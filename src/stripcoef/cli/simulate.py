"""``stripcoef simulate VEHICLE --inputs INPUTS.csv --out LOG.csv``: a 6-DOF simulation.

INPUTS is a log-format CSV (:mod:`stripcoef.logfile`) with a time column ``t`` and thruster
commands ``n_<thruster>`` and/or generalized forces ``X Y Z K M N``; the output is a log
with the pose, the velocities, the applied forces and the commands at every input time
(or every ``--dt`` seconds).
"""

from __future__ import annotations

import numpy as np

from stripcoef.conventions import FORCES
from stripcoef.errors import InputError, UnreachableError
from stripcoef.files import check_finite_output
from stripcoef.logfile import KNOWN_COLUMNS, read_log


#: Fastest water current accepted [m/s]: the fastest tidal races run at ~5 m/s; a faster
#: "current" is a typo, and makes the equations so stiff that the integrator grinds.
MAX_CURRENT = 100.0
#: Most output samples of one run (a 1,000,000-row log is ~100 MB of CSV).
MAX_SAMPLES = 1_000_000


def add_parser(subparsers):
    p = subparsers.add_parser(
        "simulate", help="6-DOF time simulation of a vehicle or model file",
        description="Integrate M nu_dot + C(nu) nu + D(nu_r) nu_r + g(eta) = tau over the "
                    "inputs' time span and write a log CSV.")
    p.add_argument("vehicle", metavar="VEHICLE",
                   help="vehicle file (YAML, estimated by strip theory) or model file "
                        "(JSON/YAML from HydroModel.to_dict, e.g. diagnose --out)")
    p.add_argument("--inputs", required=True, metavar="INPUTS.csv",
                   help="log CSV with t and n_<thruster> commands and/or X Y Z K M N forces")
    p.add_argument("--out", required=True, metavar="LOG.csv", help="output log CSV")
    p.add_argument("--current", metavar="U,V,W", default=None,
                   help="constant water current in the earth-fixed NED frame [m/s]")
    p.add_argument("--dt", type=float, default=None,
                   help="output sample period [s] (default: the inputs' times)")
    p.add_argument("--interpolation", choices=("previous", "linear"), default="previous",
                   help="inputs between samples: zero-order hold (default) or linear")
    p.add_argument("--rtol", type=float, default=1e-8, help="integrator relative tolerance")
    p.set_defaults(func=run)
    return p


def parse_vector(text: str, *, key: str, size: int = 3) -> np.ndarray:
    parts = [s for s in str(text).replace(" ", "").split(",")]
    try:
        vec = np.array([float(s) for s in parts])
    except ValueError:
        vec = None
    if vec is None or vec.size != size or not np.all(np.isfinite(vec)):
        raise InputError("not a vector", key=key, value=text,
                         expected=f"{size} comma-separated finite numbers")
    return vec


def inputs_from_log(log, model, times=None, *, interpolation="previous"):
    """Times, forces (n,6) or None, commands and other channels (e.g. ``tether_length``)
    from an inputs log, resampled at ``times``."""
    t_in = log.require("t")
    if len(t_in) < 2:
        raise InputError("too few rows", file=log.source, key="t", value=len(t_in),
                         expected="at least 2 time samples")
    cmds = log.commands()
    force_cols = [f for f in FORCES if f in log]
    if not cmds and not force_cols:
        raise InputError("no inputs", file=log.source,
                         expected="thruster commands n_<name> (thrusters: "
                         + ", ".join(th.name for th in model.thrusters)
                         + ") and/or forces X Y Z K M N")
    names = [th.name for th in model.thrusters]
    for name in cmds:
        if name not in names:
            raise InputError("unknown thruster", file=log.source, key="n_" + name,
                             expected="one of " + ", ".join("n_" + n for n in names))
    if times is None:
        times = t_in

    def resample(values):
        if times is t_in:
            return values
        if interpolation == "linear":
            return np.interp(times, t_in, values)
        k = np.clip(np.searchsorted(t_in, times, side="right") - 1, 0, len(t_in) - 1)
        return values[k]

    forces = log.forces()
    forces = None if forces is None else np.column_stack([resample(c) for c in forces.T])
    commands = {k: resample(v) for k, v in cmds.items()}
    skip = set(KNOWN_COLUMNS) | {"n_" + k for k in cmds}
    channels = {k: resample(v) for k, v in log.columns.items() if k not in skip}
    return np.asarray(times, float), forces, commands, channels


def run(args) -> int:
    from stripcoef.modelfile import load_model
    from stripcoef.simulate import simulate

    log = read_log(args.inputs, required=("t",))
    model = load_model(args.vehicle)
    current = parse_vector(args.current, key="--current") if args.current else None
    if current is not None and np.linalg.norm(current) > MAX_CURRENT:
        raise InputError("current too fast", key="--current", value=args.current,
                         expected=f"a speed below {MAX_CURRENT:g} m/s (tidal races reach ~5 m/s)")
    times = None
    if args.dt is not None:
        if not (np.isfinite(args.dt) and args.dt > 0):
            raise InputError("not a positive time step", key="--dt", value=args.dt,
                             expected="a positive number of seconds")
        t_in = log.require("t")
        if (t_in[-1] - t_in[0]) / args.dt > MAX_SAMPLES:
            raise InputError("time step too small for the inputs' span", key="--dt",
                             value=args.dt, expected=f"at most {MAX_SAMPLES} output samples over "
                             f"{t_in[-1] - t_in[0]:g} s")
        times = np.arange(t_in[0], t_in[-1] + 0.5 * args.dt, args.dt)
        times = times[times <= t_in[-1] + 1e-12]
    times, forces, commands, channels = inputs_from_log(log, model, times,
                                                        interpolation=args.interpolation)
    try:
        out = simulate(model, times, forces=forces, commands=commands, current=current,
                       channels=channels,
                       interpolation=args.interpolation, rtol=args.rtol, atol=args.rtol * 1e-2)
    except UnreachableError as exc:     # a stopped run: name the model it was run on
        raise UnreachableError(f"{args.vehicle}: {exc}") from None
    check_finite_output(out.columns, what="the simulated log", file=str(args.vehicle))
    out.write_csv(args.out)
    print(f"wrote {args.out}: {len(out)} samples, t = {times[0]:g} .. {times[-1]:g} s, "
          f"final speed {np.linalg.norm(out.velocities()[-1, :3]):.4g} m/s")
    return 0
