"""``stripcoef limits VEHICLE``: steady-state manoeuvre limits (a thin layer over
:func:`stripcoef.limits.solver.solve_limits`)."""

from __future__ import annotations

import argparse
import math
import sys

from stripcoef.errors import InputError
from stripcoef.files import check_finite_output, json_text
from stripcoef.modelfile import load_model


def add_parser(subparsers) -> None:
    p = subparsers.add_parser(
        "limits", help="maximum speeds, yaw rate and turning circle the thrusters allow",
        description="Steady-state manoeuvre limits: maximum surge, dive, sway speed, yaw rate "
                    "on the spot and the fastest steady turn for each radius (the method of "
                    "the MARES AUV paper, Ferreira et al. 2009 sec. V; see docs/limits.md).")
    p.add_argument("vehicle", metavar="VEHICLE",
                   help="vehicle file (YAML) or a model file written by stripcoef "
                        "(JSON/YAML of HydroModel.to_dict())")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p.add_argument("--plot", metavar="FILE.png", help="draw u_max, drift angle and thrusts vs R")
    p.add_argument("--radii", metavar="R1:R2:N", default=None,
                   help="turning radii [m]: N values from R1 to R2 (default 0.5:20:40)")
    p.add_argument("--munk", action=argparse.BooleanOptionalAction, default=True,
                   help="include the Munk moment (default: on; Ferreira et al. 2009 neglects it)")
    p.add_argument("--coriolis", action=argparse.BooleanOptionalAction, default=True,
                   help="include the Coriolis and centripetal terms C(nu) (default: on)")
    p.add_argument("--turn-speed", type=float, default=None, metavar="U",
                   help="surge speed [m/s] for the minimum turning radius "
                        "(default: half the straight-line maximum)")
    p.set_defaults(func=run)


def format_table(result, surfaces=()) -> str:
    """Readable summary and turning-circle table."""
    d = result.to_dict()
    opts = (f"Munk moment {'on' if result.options.munk else 'off'}, "
            f"Coriolis {'on' if result.options.coriolis else 'off'}")
    lines = [f"{result.name}: steady manoeuvre limits ({opts})", ""]

    def row(label, value, unit, m=None, extra=""):
        sat = f"  saturates: {', '.join(m.at_limit) or m.saturated}" if m is not None else ""
        if m is not None and abs(m.nu[1]) > 1e-9 and m is not result.sway:
            sat += f"; sway drift v = {m.nu[1]:.4f} m/s"
        if m is not None:
            for k, a in m.trim.items():
                if abs(a) > 1e-6:
                    sat += f"; {k} trim {math.degrees(a):.2f} deg"
        lines.append(f"  {label:<28s} {value:>9s} {unit:<6s}{extra}{sat}")

    row("surge speed max", f"{result.surge_speed_max:.4f}", "m/s", result.surge)
    if result.heave is None:
        row("dive (heave) speed max", "-", "", None, "  (unreachable, see notes)")
    else:
        row("dive (heave) speed max", f"{result.heave_speed_max:.4f}", "m/s", result.heave)
    if result.yaw is None:
        row("yaw rate max (on the spot)", "-", "", None, "  (unreachable, see notes)")
    else:
        row("yaw rate max (on the spot)", f"{result.yaw_rate_max:.4f}", "rad/s", result.yaw,
            f" ({math.degrees(result.yaw_rate_max):.1f} deg/s)")
    if result.sway is None:
        row("sway speed max", "-", "", None, "  (no thruster gives sway)")
    else:
        row("sway speed max", f"{result.sway_speed_max:.4f}", "m/s", result.sway)
    if d["min_turning_radius"] is None:
        row("min turning radius", "-", "m")
    else:
        row("min turning radius", f"{d['min_turning_radius']:.3f}", "m", None,
            f"  at u = {d['min_turning_radius_speed']:.3f} m/s")
    for note in result.notes:
        lines.append(f"  note: {note}")
    if result.steering is not None:
        lines += steering_table(result.steering, surfaces)
    if result.turning:
        names = list(result.turning[0].thrust)
        lines += ["", "  steady starboard turn at the thrust limit (drift > 0: nose into the "
                  "circle)", ""]
        head = (f"  {'R [m]':>8s} {'u_max [m/s]':>11s} {'v [m/s]':>9s} {'r [rad/s]':>9s} "
                f"{'drift [deg]':>11s} " + " ".join(f"{n + ' [N]':>9s}" for n in names)
                + "  saturated")
        lines.append(head)
        for p in result.turning:
            lines.append(f"  {p.radius:8.3f} {p.u_max:11.4f} {p.v:9.4f} {p.yaw_rate:9.4f} "
                         f"{math.degrees(p.drift_angle):11.2f} "
                         + " ".join(f"{p.thrust[n]:9.3f}" for n in names)
                         + f"  {p.saturated}")
    return "\n".join(lines)


def steering_table(steer, surfaces=()) -> list[str]:
    """Trim, turning circle, dive and climb of a rudder/elevator-steered vehicle
    (``surfaces``: the model's control surfaces, to tell rudders from elevators)."""
    deg = math.degrees
    lines = ["", f"  straight flight: top speed {steer.surge_speed_max:.4f} m/s; slowest level "
             + ("-" if steer.level_speed_min is None else f"{steer.level_speed_min:.4f} m/s")]
    if steer.trim:
        lines += ["", "  trim (pitch, heel and elevator the vehicle needs; dz/dt > 0 down: 0 in "
                  "level flight)", "",
                  f"  {'u [m/s]':>8s} {'pitch [deg]':>11s} {'heel [deg]':>10s} "
                  f"{'w [m/s]':>8s} {'elevator [deg]':>14s} {'dz/dt [m/s]':>11s} "
                  f"{'thrust load':>11s}"]
        for f in steer.trim:
            el = [v for k, v in f.deflections.items()
                  if any(s.name == k and s.kind == "elevator" for s in surfaces)]
            elev = f"{deg(max(el, key=abs)):14.2f}" if el else f"{'-':>14s}"
            lines.append(f"  {f.u:8.3f} {deg(f.pitch):11.2f} {deg(f.roll):10.2f} {f.nu[2]:8.4f} "
                         f"{elev} {f.depth_rate:11.4f} {f.load:11.3f}")
    if steer.turning:
        lines += ["", "  turning circle at full rudder (positive rudder: turn to port)", "",
                  f"  {'u [m/s]':>8s} {'R [m]':>8s} {'r [rad/s]':>9s} {'drift [deg]':>11s} "
                  f"{'rudder [deg]':>12s} {'thrust load':>11s}"]
        for f in steer.turning:
            rud = max([v for k, v in f.deflections.items()
                       if any(s.name == k and s.kind == "rudder" for s in surfaces)], key=abs)
            lines.append(f"  {f.u:8.3f} {f.radius:8.3f} {f.yaw_rate:9.4f} "
                         f"{deg(f.drift_angle):11.2f} {deg(rud):12.2f} {f.load:11.3f}")
    for title, rows in (("steepest steady dive", steer.dive), ("steepest steady climb",
                                                                 steer.climb)):
        if rows:
            lines += ["", f"  {title} (elevator and thrust within limits; depth rate > 0 "
                      "down)", "",
                      f"  {'u [m/s]':>8s} {'pitch [deg]':>11s} {'dz/dt [m/s]':>11s} "
                      f"{'elevator [deg]':>14s} {'thrust load':>11s}"]
            for f in rows:
                el = max([v for k, v in f.deflections.items()
                          if any(s.name == k and s.kind == "elevator" for s in surfaces)],
                         key=abs)
                lines.append(f"  {f.u:8.3f} {deg(f.pitch):11.2f} {f.depth_rate:11.4f} "
                             f"{deg(el):14.2f} {f.load:11.3f}")
    return lines


def run(args) -> int:
    from stripcoef.limits.plots import plot_limits
    from stripcoef.limits.solver import check_model, solve_limits

    radii = parse_radii(args.radii) if args.radii is not None else None
    if args.turn_speed is not None and not (args.turn_speed > 0 and math.isfinite(args.turn_speed)):
        raise InputError("turning speed must be positive", key="--turn-speed",
                         value=args.turn_speed, expected="a speed > 0 [m/s]")
    # --plot is checked before any work (cli.app.check_outputs)
    model = load_model(args.vehicle)            # shared with the other model commands
    check_model(model, file=str(args.vehicle))
    result = solve_limits(model, radii=radii, munk=args.munk, coriolis=args.coriolis,
                          turn_speed=args.turn_speed)
    check_finite_output(result.to_dict(), what="the limits", file=str(args.vehicle))
    if args.plot is not None:
        plot_limits(result, args.plot, key="--plot")
    if args.json:
        sys.stdout.write(json_text(result.to_dict()))
    else:
        print(format_table(result, model.control_surfaces))
    return 0


def parse_radii(text: str):
    """``--radii "R1:R2:N"`` -> N radii evenly spaced from R1 to R2 [m] (checked)."""
    import numpy as np

    from stripcoef.limits.solver import MAX_RADII, check_radii

    parts = str(text).split(":")
    try:
        if len(parts) != 3:
            raise ValueError
        r1, r2, n = float(parts[0]), float(parts[1]), int(parts[2])
    except ValueError:
        raise InputError("cannot read radii", key="--radii", value=text,
                         expected="R1:R2:N, e.g. 0.5:20:40") from None
    if n < 1:
        raise InputError("number of radii must be positive", key="--radii", value=text,
                         expected="R1:R2:N with N >= 1")
    if n > MAX_RADII:
        raise InputError("too many turning radii", key="--radii", value=text,
                         expected=f"R1:R2:N with N <= {MAX_RADII}")
    if r1 <= 0.0:
        raise InputError("turning radius must be positive", key="--radii", value=text,
                         expected="R1 > 0 [m]")
    if n > 1 and r2 <= r1:
        raise InputError("turning radii are not increasing", key="--radii", value=text,
                         expected="R2 > R1")
    return check_radii(np.linspace(r1, r2, n) if n > 1 else [r1])
