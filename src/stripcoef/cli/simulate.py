"""``stripcoef simulate VEHICLE --inputs INPUTS.csv --out LOG.csv``: a 6-DOF simulation.

INPUTS is a log-format CSV (:mod:`stripcoef.logfile`) with a time column ``t`` and thruster
commands ``n_<thruster>`` and/or generalized forces ``X Y Z K M N``; the output is a log
with the pose, the velocities, the applied forces and the commands at every input time
(or every ``--dt`` seconds; every :data:`DEFAULT_DT` seconds when the inputs have fewer than
:data:`FEW_ROWS` rows). ``--out -`` writes the log to stdout (the summary goes to stderr).
"""

from __future__ import annotations

import argparse
import sys
import warnings

import numpy as np

from stripcoef.conventions import FORCES
from stripcoef.errors import InputError, ModelWarning
from stripcoef.logfile import KNOWN_COLUMNS, read_log

#: Without --dt, inputs with fewer rows than this are resampled every DEFAULT_DT seconds
#: (a 2-row input would otherwise give a 2-row log).
FEW_ROWS = 100
DEFAULT_DT = 0.1   # [s]


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
    p.add_argument("-o", "--out", required=True, metavar="LOG.csv",
                   help="output log CSV ('-': stdout, the summary then goes to stderr)")
    p.add_argument("--current", metavar="U,V,W", default=None,
                   help="constant water current in the earth-fixed NED frame [m/s]")
    p.add_argument("--dt", type=float, default=None,
                   help="output sample period [s] (default: the inputs' times, or "
                        f"{DEFAULT_DT:g} s when the inputs have fewer than {FEW_ROWS} rows)")
    p.add_argument("--interpolation", choices=("previous", "linear"), default="previous",
                   help="inputs between samples: zero-order hold (default) or linear")
    p.add_argument("--rtol", type=float, default=1e-8, help="integrator relative tolerance")
    p.add_argument("--plot", metavar="FILE.png",
                   help="draw the trajectory and the velocities (.png/.pdf/.svg; matplotlib)")
    p.add_argument("--munk", action=argparse.BooleanOptionalAction, default=True,
                   help="keep the Munk moment in C_A(nu) (default: on; as in 'limits')")
    p.add_argument("--coriolis", action=argparse.BooleanOptionalAction, default=True,
                   help="keep C(nu) = C_RB + C_A (default: on; as in 'limits')")
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
    from stripcoef.simulate import simulate, summarize_motion

    if args.plot:
        from stripcoef.figures import check_plot_path
        check_plot_path(args.plot, key="--plot")
    log = read_log(args.inputs, required=("t",))
    model = load_model(args.vehicle)
    current = parse_vector(args.current, key="--current") if args.current else None
    times = None
    dt = args.dt
    if dt is not None and not (np.isfinite(dt) and dt > 0):
        raise InputError("not a positive time step", key="--dt", value=dt,
                         expected="a positive number of seconds")
    t_in = log.require("t")
    if dt is None and len(t_in) < FEW_ROWS:
        dt = DEFAULT_DT
    if dt is not None:
        times = np.arange(t_in[0], t_in[-1] + 0.5 * dt, dt)
        times = times[times <= t_in[-1] + 1e-12]
    times, forces, commands, channels = inputs_from_log(log, model, times,
                                                        interpolation=args.interpolation)
    out = simulate(model, times, forces=forces, commands=commands, current=current,
                   channels=channels, munk=args.munk, coriolis=args.coriolis,
                   interpolation=args.interpolation, rtol=args.rtol, atol=args.rtol * 1e-2)
    to_stdout = args.out == "-"
    if to_stdout:
        sys.stdout.write(out.to_csv_text())
    else:
        out.write_csv(args.out)
    if args.plot:
        from stripcoef.figures import motion_figure, save_figure
        save_figure(motion_figure(out, title=f"{model.name}: simulated trajectory and "
                                             "velocities", key="--plot"),
                    args.plot, key="--plot")
    summary = summarize_motion(out)
    print(format_summary(summary, args.out, out, dt=dt, default_dt=args.dt is None and dt),
          file=sys.stderr if to_stdout else sys.stdout)
    for text in summary.warnings:
        warnings.warn(text.replace("munk=False", "--no-munk"), ModelWarning, stacklevel=1)
    return 0


def format_summary(s, where, log, *, dt=None, default_dt=None) -> str:
    """What happened, in a few lines: samples, final speeds, distance, heading, attitude."""
    u, v, w, p, q, r = s.final_velocity
    t = log.require("t")
    target = "stdout" if where == "-" else where
    step = f", every {dt:g} s" if dt else ""
    why = f" (default for inputs of fewer than {FEW_ROWS} rows; --dt to change)" \
        if default_dt else ""
    dx, dy, dz = s.displacement
    return "\n".join([
        f"wrote {target}: {len(log)} samples, t = {t[0]:g} .. {t[-1]:g} s{step}{why}",
        f"  final speed {s.final_speed:.4g} m/s (u {u:.4g}, v {v:.4g}, w {w:.4g} m/s; "
        f"p {p:.3g}, q {q:.3g}, r {r:.3g} rad/s)",
        f"  distance travelled {s.distance:.4g} m; displacement north {dx:.4g}, east {dy:.4g}, "
        f"down {dz:.4g} m",
        f"  heading change {s.heading_change:.4g} rad ({np.degrees(s.heading_change):.4g} deg); "
        f"max |roll| {np.degrees(s.max_roll):.3g} deg, max |pitch| "
        f"{np.degrees(s.max_pitch):.3g} deg"])
