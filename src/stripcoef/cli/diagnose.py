"""``stripcoef diagnose LOG.csv --vehicle VEHICLE``: find the residual, trace it to the
effect the model lacks, add it, report before and after (see
:mod:`stripcoef.diagnose.pipeline`)."""

from __future__ import annotations

import json
import sys
from pathlib import Path

from stripcoef.errors import InputError


def add_parser(subparsers):
    p = subparsers.add_parser(
        "diagnose", help="trace a log's residual to the effects the model lacks",
        description="Predict the log with the vehicle's model, calibrate its coefficients "
                    "within their bands, add the significant effects of the library, and "
                    "report the error before and after each step.")
    p.add_argument("log", metavar="LOG.csv", help="time-series log (see docs/diagnose.md)")
    p.add_argument("--vehicle", required=True, metavar="VEHICLE",
                   help="vehicle file (YAML) or model file (JSON/YAML)")
    p.add_argument("--dof", default="all", help="DOF to diagnose (surge..yaw) or 'all'")
    p.add_argument("--json", action="store_true", help="print the JSON result")
    p.add_argument("--report", metavar="FILE.md", help="write a markdown report (+ plots)")
    p.add_argument("--out", metavar="CALIBRATED.yaml",
                   help="write the calibrated model (YAML or JSON model file)")
    p.add_argument("--window", type=float, default=None,
                   help="window of the one-step force residual [s] (default 4)")
    p.add_argument("--effects", default=None,
                   help="comma-separated candidate effects (default: the whole library)")
    p.add_argument("--no-resimulate", action="store_true",
                   help="skip the re-simulated velocity error (faster)")
    p.add_argument("--holdout", type=float, default=None, metavar="FRACTION",
                   help="keep the last FRACTION of the log out of the fit and report the "
                        "free-simulation error on it (prior, calibrated model as written, "
                        "hold-last-velocity)")
    p.add_argument("--validation", type=float, default=None, metavar="FRACTION",
                   help="fraction of the fitting log (its end) that validates each change by "
                        "free simulation (default 0.25; 0 keeps every change)")
    p.add_argument("--quiet", action="store_true",
                   help="no progress lines on stderr (they are printed only to a terminal)")
    p.set_defaults(func=run)
    return p


def run(args) -> int:
    from stripcoef.diagnose.pipeline import DEFAULT_WINDOW, diagnose, public
    from stripcoef.diagnose.report import markdown_report, text_summary
    from stripcoef.effects.laws import get_effect
    from stripcoef.logfile import read_log
    from stripcoef.export import write_export
    from stripcoef.modelfile import load_model

    if args.window is None:
        args.window = DEFAULT_WINDOW
    if not (args.window > 0):
        raise InputError("not a positive window", key="--window", value=args.window,
                         expected="a positive number of seconds")
    effects = None
    if args.effects:
        effects = [e.strip() for e in args.effects.split(",") if e.strip()]
        for e in effects:
            get_effect(e)
    for key, path in (("--out", args.out), ("--report", args.report)):
        if path:
            folder = Path(path).parent if str(Path(path).parent) else Path(".")
            if not folder.is_dir():
                raise InputError("folder does not exist", key=key, value=path,
                                 expected="a path in an existing, writable folder")
    from stripcoef.diagnose.pipeline import VALIDATION_FRACTION, heldout_errors

    for key, value in (("--holdout", args.holdout), ("--validation", args.validation)):
        if value is not None and not (0.0 <= value < 1.0):
            raise InputError("not a fraction", key=key, value=value,
                             expected="a number in [0, 1), e.g. 0.3")
    validation = VALIDATION_FRACTION if args.validation is None else args.validation
    progress = None
    if not args.quiet and sys.stderr.isatty():
        def progress(message):
            sys.stderr.write(f"diagnose: {message}\n")
            sys.stderr.flush()
    log = read_log(args.log, required=("t",))
    model = load_model(args.vehicle)
    result = diagnose(log, model, dof=args.dof, window=args.window, effects=effects,
                      resimulate=not args.no_resimulate, validation=validation or None,
                      holdout=args.holdout or None, progress=progress)
    if args.out:
        write_export(result["model"], "json" if str(args.out).lower().endswith(".json")
                     else "yaml", args.out)
        if result.get("holdout") is not None:
            # the held-out numbers printed are those of the file just written, read back
            result["holdout"] = heldout_errors(result, model, load_model(args.out))
            result["holdout"]["model_file"] = str(args.out)
    if args.report:
        markdown_report(result, args.report)
    if args.json:
        json.dump(public(result), sys.stdout, indent=1)
        sys.stdout.write("\n")
    else:
        sys.stdout.write(text_summary(public(result)))
    return 0
