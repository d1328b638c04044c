"""``stripcoef sweep``: the model and the limits over a grid of vehicle-file values."""

from __future__ import annotations

import sys

from stripcoef.cli.uncertainty import add_execution_arguments
from stripcoef.errors import InputError


def add_parser(sub):
    p = sub.add_parser("sweep", help="the model and limits over a grid of vehicle-file values",
                       description="Set numbers of the vehicle file by key path "
                                   "(hull.profile[1].radius, thrusters[0].max_forward, "
                                   "mass.mass) over a grid and tabulate every coefficient and "
                                   "limit (docs/uncertainty.md).")
    p.add_argument("vehicle", metavar="VEHICLE", help="vehicle file (.yaml)")
    p.add_argument("--vary", action="append", required=True, metavar="KEY=LO:HI:N",
                   help="a key path and N values from LO to HI (repeat for a grid)")
    p.add_argument("--no-limits", dest="limits", action="store_false",
                   help="the model only (about 5x faster)")
    p.add_argument("-o", "--output", metavar="FILE.csv|FILE.parquet",
                   help="write the table (default: CSV on stdout)")
    p.add_argument("--plot", metavar="FILE.png", help="one output over the swept keys")
    p.add_argument("--plot-output", metavar="NAME", default=None,
                   help="the output to plot (default surge_speed_max, or X_udot without limits)")
    add_execution_arguments(p)
    p.set_defaults(func=run)
    return p


def run(args) -> int:
    from stripcoef.study.plots import sweep_figure
    from stripcoef.study.sweep import blank_points, parse_vary, sweep, write_table

    # --output and --plot are checked before any work (cli.app.check_outputs), and the
    # plot's format too: a long study must not end on a bad suffix
    if args.plot:
        from stripcoef.figures import check_plot_path
        check_plot_path(args.plot, key="--plot")
    axes = [parse_vary(v) for v in args.vary]
    if len(axes) > 2 and args.plot:
        raise InputError("a plot shows one or two swept keys", key="--plot",
                         value=len(axes), expected="--vary given once or twice with --plot")
    frame = sweep(args.vehicle, axes, limits=args.limits, workers=args.workers,
                  scheduler=args.scheduler, progress=getattr(args, "progress", None))
    for reason, count in blank_points(frame).items():
        print(f"sweep: {count} of {len(frame)} grid points have blank limits: {reason}",
              file=sys.stderr)
    if args.plot:
        output = args.plot_output or ("surge_speed_max" if args.limits else "X_udot")
        sweep_figure(frame, [a.key for a in axes], output, path=args.plot, key="--plot")
    if args.output:
        write_table(frame, args.output, key="--output")
    else:
        print(frame.to_csv(index=False), end="")
    return 0
