"""``stripcoef diagnose LOG.csv --vehicle VEHICLE``: find the residual, trace it to the
effect the model lacks, add it, report before and after (see
:mod:`stripcoef.diagnose.pipeline`)."""

from __future__ import annotations

import sys

from stripcoef.cli.options import add_map_argument, read_log_from_args
from stripcoef.errors import InputError
from stripcoef.files import check_finite_output


def add_parser(subparsers):
    p = subparsers.add_parser(
        "diagnose", help="trace a log's residual to the effects the model lacks",
        description="Predict the log with the vehicle's model, calibrate its coefficients "
                    "within their bands, add the significant effects of the library, and "
                    "report the error before and after each step.")
    p.add_argument("log", metavar="LOG",
                   help="time-series log: a log CSV (docs/diagnose.md), or with --map any CSV "
                        "or a ROS bag (docs/logs.md)")
    p.add_argument("--vehicle", required=True, metavar="VEHICLE",
                   help="vehicle file (YAML) or model file (JSON/YAML)")
    add_map_argument(p)
    p.add_argument("--dof", default="all",
                   help="DOF to diagnose (surge..yaw) or 'all' (every excited DOF; it says "
                        "which it drops and why)")
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
    p.add_argument("--validation-choice", default="greedy",
                   choices=("greedy", "best_visited"),
                   help="the validation's final model: the set its backward elimination "
                        "ends with (greedy, default) or the best on the validation part of "
                        "the prior and every set it scored (best_visited)")
    p.set_defaults(func=run)
    return p


def run(args) -> int:
    from dataclasses import replace

    from stripcoef.diagnose.pipeline import (DEFAULT_WINDOW, VALIDATION_FRACTION, diagnose,
                                             heldout_errors, load_prior)
    from stripcoef.diagnose.report import markdown_report, text_summary
    from stripcoef.effects.laws import get_effect
    from stripcoef.export import write_export
    from stripcoef.files import OutputSet, json_text
    from stripcoef.modelfile import load_model

    if args.window is None:
        args.window = DEFAULT_WINDOW
    if not (0 < args.window < float("inf")):
        raise InputError("not a positive window", key="--window", value=args.window,
                         expected="a positive number of seconds")
    effects = None
    if args.effects:
        effects = [e.strip() for e in args.effects.split(",") if e.strip()]
        for e in effects:
            get_effect(e)
    # --out and --report are checked before any work (cli.app.check_outputs); --holdout and
    # --validation by diagnose (its keys are reworded to the flags by cli.app)
    validation = VALIDATION_FRACTION if args.validation is None else args.validation
    log = read_log_from_args(args.log, args, required=("t",))
    # a vehicle file: the method uncertainty of its shape class sets the widths of the
    # calibration's priors and bounds the added mass (a model file: the fixed bands)
    model, widths = load_prior(args.vehicle)
    result = diagnose(log, model, dof=args.dof, window=args.window, effects=effects,
                      resimulate=not args.no_resimulate, validation=validation,
                      holdout=args.holdout, prior_widths=widths,
                      validation_choice=args.validation_choice)
    check_finite_output(result.model.to_dict(), what="the calibrated model", file=str(args.log))
    with OutputSet() as outs:       # the model and the report: all new or all old
        if args.out:
            staged = outs.path(args.out, key="out")
            write_export(result.model, "json" if str(args.out).lower().endswith(".json")
                         else "yaml", staged)
            if result.holdout is not None:
                # the held-out numbers printed are those of the file just written, read back
                hold = dict(heldout_errors(result, model, load_model(staged)),
                            model_file=str(args.out))
                result = replace(result, holdout=hold)
        if args.report:
            markdown_report(result, outs.path(args.report, key="report"))
    if args.json:
        sys.stdout.write(json_text(result.to_dict(), indent=1))
    else:
        sys.stdout.write(text_summary(result))
    return 0
