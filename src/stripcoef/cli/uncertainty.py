"""``stripcoef uncertainty``: percentiles of every coefficient and limit, with their sources."""

from __future__ import annotations

import json

from stripcoef.files import write_text


def add_parser(sub):
    p = sub.add_parser("uncertainty", help="uncertainty bands of the model and the limits",
                       description="Propagate strip theory's method error and the vehicle "
                                   "file's {value, sd} / {value, tol} inputs by quasi-Monte "
                                   "Carlo (seeded scrambled Sobol) to every coefficient and "
                                   "manoeuvre limit (docs/uncertainty.md).")
    p.add_argument("vehicle", metavar="VEHICLE", help="vehicle file (.yaml)")
    p.add_argument("--samples", type=int, default=256, metavar="N",
                   help="number of samples (default 256; a power of two is best)")
    p.add_argument("--seed", type=int, default=0, help="seed of the sampling (default 0)")
    p.add_argument("--no-limits", dest="limits", action="store_false",
                   help="the model only (about 5x faster)")
    p.add_argument("--no-method", dest="method", action="store_false",
                   help="leave strip theory's method error out (declared inputs only)")
    p.add_argument("--json", action="store_true", help="print the JSON result")
    p.add_argument("-o", "--output", metavar="FILE", help="write the output to FILE")
    p.add_argument("--plot", metavar="FILE.png", help="u_max(R) with its bands")
    add_execution_arguments(p)
    p.set_defaults(func=run)
    return p


def add_execution_arguments(p):
    """--workers, --scheduler (shared with ``sweep``; -q/--quiet is every command's)."""
    g = p.add_argument_group("execution")
    g.add_argument("--workers", type=int, metavar="N",
                   help="local processes (default: the cores of this machine)")
    g.add_argument("--scheduler", metavar="ADDRESS",
                   help="run on a Dask distributed scheduler (tcp://host:8786) instead")
    return g


def format_table(result) -> str:
    s = result.summary()
    lines = [f"{result.vehicle}: {result.samples.shape[0]} samples (seed {result.seed}), "
             f"shape class {result.shape_class}", "", "sources:"]
    for src in result.sources:
        lines.append(f"  {src.kind:6s} {src.name:32s} {src.distribution:9s} "
                     f"{src.spread:<8.4g} {src.reason}")
    lines += ["", f"{'output':26s} {'nominal':>11s} {'P2.5':>11s} {'P50':>11s} "
                  f"{'P97.5':>11s} {'sd':>10s}"]
    for name, e in s.items():
        if "p50" not in e:
            lines.append(f"{name:26s} {e['nominal']:11.4g} {'unreachable':>11s}")
            continue
        lines.append(f"{name:26s} {e['nominal']:11.4g} {e['p2.5']:11.4g} {e['p50']:11.4g} "
                     f"{e['p97.5']:11.4g} {e['sd']:10.3g}")
    return "\n".join(lines) + "\n"


def run(args) -> int:
    from stripcoef.study.uncertainty import plot_band, uncertainty

    # --output and --plot are checked before any work (cli.app.check_outputs), and the
    # plot's format too: a long study must not end on a bad suffix
    if args.plot:
        from stripcoef.figures import check_plot_path
        check_plot_path(args.plot, key="--plot")
    result = uncertainty(args.vehicle, samples=args.samples, seed=args.seed,
                         limits=args.limits, method=args.method, workers=args.workers,
                         scheduler=args.scheduler, progress=getattr(args, "progress", None))
    text = json.dumps(result.to_dict(), indent=2, allow_nan=False) + "\n" if args.json \
        else format_table(result)
    if args.plot:
        plot_band(result, path=args.plot, key="--plot")
    if args.output:
        write_text(args.output, text, key="--output")
    else:
        print(text, end="")
    return 0
