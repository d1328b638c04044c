"""``stripcoef simulate VEHICLE --inputs INPUTS.csv --out LOG.csv``: a 6-DOF simulation.

INPUTS is a log-format CSV (:mod:`stripcoef.logfile`) with a time column ``t`` and thruster
commands ``n_<thruster>``, control-surface deflections ``delta_<surface>`` [rad] and/or
generalized forces ``X Y Z K M N`` (or, with ``--map``, any CSV or a ROS bag through a column
map, docs/logs.md); the output is a log with the pose, the velocities, the applied forces and
the commands at every input time (or every ``--dt`` seconds; every :data:`DEFAULT_DT` seconds
when the inputs have fewer than :data:`FEW_ROWS` rows). ``--out -`` writes the log to stdout
(the summary goes to stderr). ``--from-log LOG`` starts from the log's pose and velocity
instead of rest at the origin and, without ``--inputs``, free-simulates the log's own inputs
and prints the prediction error against the log. Inputs are read from a log by the one replay
rule of the library (:func:`stripcoef.logfile.log_inputs`: with thruster commands, a log's
``X..N`` are the record of the applied force, thrust included, and are not applied again).
"""

from __future__ import annotations

import argparse
import sys
import warnings

import numpy as np

from stripcoef.cli.options import add_map_argument, read_log_from_args
from stripcoef.conventions import VELOCITIES
from stripcoef.errors import InputError, ModelWarning, UnreachableError
from stripcoef.files import check_finite_output

#: Without --dt, inputs with fewer rows than this are resampled every DEFAULT_DT seconds
#: (a 2-row input would otherwise give a 2-row log).
FEW_ROWS = 100
DEFAULT_DT = 0.1   # [s]


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
    p.add_argument("--inputs", metavar="INPUTS",
                   help="log with t, n_<thruster> commands, delta_<surface> deflections [rad] "
                        "and/or X Y Z K M N forces "
                        "(default with --from-log: that log's inputs)")
    p.add_argument("--from-log", metavar="LOG", default=None,
                   help="start from this log's pose and velocity (at --start) instead of rest "
                        "at the origin; without --inputs, free-simulate its inputs and print "
                        "the error of the prediction against the log")
    add_map_argument(p)
    p.add_argument("--start", type=float, default=None, metavar="S",
                   help="with --from-log: start at this time of the log [s] (its first sample)")
    p.add_argument("--duration", type=float, default=None, metavar="S",
                   help="with --from-log: simulate this long [s] (to the end of the log)")
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


def _log_window(log, start, duration):
    """Rows of ``log`` with start <= t <= start + duration [s] (defaults: the whole log)."""
    t = log.require("t")
    if start is not None and not (t[0] <= start < t[-1]):
        raise InputError("start outside the log", key="start", value=start,
                         expected=f"a time in [{t[0]:g}, {t[-1]:g}) s")
    if duration is not None and not (np.isfinite(duration) and duration > 0):
        raise InputError("not a positive duration", key="duration", value=duration,
                         expected="a positive number of seconds")
    a = 0 if start is None else int(np.searchsorted(t, start - 1e-9))
    end = t[-1] if duration is None else t[a] + duration
    b = int(np.searchsorted(t, end + 1e-9, side="right"))
    if b - a < 2:
        raise InputError("fewer than 2 samples in the window", key="duration", value=duration,
                         expected="a window holding at least two of the log's samples")
    return log.slice(a, b)


def run(args) -> int:
    from stripcoef.modelfile import load_model
    from stripcoef.logfile import log_inputs
    from stripcoef.thrusters import check_command_columns
    from stripcoef.simulate import free_run_errors, initial_state, replay, simulate, summarize_motion

    if args.inputs is None and args.from_log is None:
        raise InputError("no inputs", key="inputs",
                         expected="--inputs INPUTS and/or --from-log LOG")
    if args.from_log is None and (args.start is not None or args.duration is not None):
        raise InputError("applies to --from-log only", key="start" if args.start is not None
                         else "duration", expected="--from-log LOG with it")
    if args.plot:
        from stripcoef.figures import check_plot_path
        check_plot_path(args.plot, key="--plot")
    eta0 = nu0 = None
    start_log = None
    if args.from_log is not None:
        start_log = _log_window(read_log_from_args(args.from_log, args, required=("t",)),
                                args.start, args.duration)
        eta0, nu0, missing = initial_state(start_log)
        if missing:
            warnings.warn(f"{start_log.source}: no column {', '.join(missing)}: the initial "
                          "state takes 0 for them", ModelWarning, stacklevel=2)
    log = start_log if args.inputs is None else \
        read_log_from_args(args.inputs, args, required=("t",))
    model = load_model(args.vehicle)
    current = parse_vector(args.current, key="--current") if args.current else None
    if current is not None and np.linalg.norm(current) > MAX_CURRENT:
        raise InputError("current too fast", key="--current", value=args.current,
                         expected=f"a speed below {MAX_CURRENT:g} m/s (tidal races reach ~5 m/s)")
    times = None
    dt = args.dt
    if dt is not None and not (np.isfinite(dt) and dt > 0):
        raise InputError("not a positive time step", key="--dt", value=dt,
                         expected="a positive number of seconds")
    t_in = log.require("t")
    if dt is None and len(t_in) < FEW_ROWS and start_log is None:
        dt = DEFAULT_DT
    if dt is not None:
        if (t_in[-1] - t_in[0]) / dt > MAX_SAMPLES:
            raise InputError("time step too small for the inputs' span", key="--dt",
                             value=dt, expected=f"at most {MAX_SAMPLES} output samples over "
                             f"{t_in[-1] - t_in[0]:g} s")
        times = np.arange(t_in[0], t_in[-1] + 0.5 * dt, dt)
        times = times[times <= t_in[-1] + 1e-12]
    elif start_log is not None and log is not start_log:
        times = start_log.require("t")              # predict at the logged times
    inputs = log_inputs(log, model)
    # every thruster has a column when any is commanded (a missing one is not "off": issue 36)
    check_command_columns(inputs.commands, model.thrusters, file=log.source)
    if times is not None:
        inputs = inputs.at(times, args.interpolation)
    _warn_not_replayed(inputs, log.source, args.vehicle)
    options = dict(current=current, munk=args.munk, coriolis=args.coriolis,
                   interpolation=args.interpolation, rtol=args.rtol, atol=args.rtol * 1e-2)
    try:
        if start_log is not None:
            out = replay(model, start_log, inputs=inputs, **options)
        else:
            out = simulate(model, inputs.t, **inputs.simulate_inputs(), **options)
    except UnreachableError as exc:     # a stopped run: name the model it was run on
        raise UnreachableError(f"{args.vehicle}: {exc}") from None
    check_finite_output(out.columns, what="the simulated log", file=str(args.vehicle))
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
    summary = summarize_motion(out, model=model, munk=args.munk and args.coriolis)
    report = sys.stderr if to_stdout else sys.stdout
    print(format_summary(summary, args.out, out, dt=dt, default_dt=args.dt is None and dt),
          file=report)
    for text in summary.warnings:
        warnings.warn(text.replace("munk=False", "--no-munk"), ModelWarning, stacklevel=1)
    if start_log is not None:
        same = len(start_log) == len(out) and np.allclose(start_log["t"], out["t"])
        if not same:
            print("prediction vs log: not compared (the output times are not the log's; "
                  "drop --dt)", file=report)
        else:
            errors = free_run_errors(start_log, out)
            print(f"free simulation from the logged state at t = {out['t'][0]:g} s "
                  f"({out['t'][-1] - out['t'][0]:g} s), RMS error vs the log "
                  "(and holding the initial velocity):", file=report)
            for c, e in errors.items():
                unit = "m/s" if VELOCITIES.index(c) < 3 else "rad/s"
                print(f"  {c}: {e['rms']:.4g} {unit}  (hold: {e['hold_initial_rms']:.4g})",
                      file=report)
    return 0


def _warn_not_replayed(inputs, source, vehicle) -> None:
    """Say which columns of the inputs the replay leaves out (:func:`stripcoef.logfile.log_inputs`,
    the one replay rule)."""
    if inputs.ignored:
        warnings.warn(f"{source}: {', '.join(inputs.ignored)} not applied: {vehicle} has no "
                      "control surfaces", ModelWarning, stacklevel=2)
    rec = inputs.recorded_forces
    scale = 1.0 if rec is None else max(1.0, float(np.max(np.abs(rec))))
    if rec is not None and inputs.thrust_mismatch > 1e-9 * scale:
        warnings.warn(f"{source}: X..N differ from the thrust of its n_ commands through "
                      f"{vehicle}'s thrusters by up to {inputs.thrust_mismatch:.4g} N or N m; "
                      "with thruster commands a log's X..N are the record of the applied force "
                      "(thrust included) and are not applied again", ModelWarning, stacklevel=2)


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
