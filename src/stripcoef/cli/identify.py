"""``stripcoef identify``: coefficients and their error bars from a measured log.

Methods: ``steady`` (Indiveri 1998, eqs. 4.15-4.17 and the yaw model comparison), ``one-step``
(Wang & Clark 2006, eqs. 8-19), ``pendulum`` (Eng et al. 2009, eqs. 1-7) and ``torsion`` (Eng et al. 2009, eq. 12).
"""

from __future__ import annotations

import math

from stripcoef.cli.options import add_map_argument, read_log_from_args
from stripcoef.files import check_finite_output, json_text, write_text

from stripcoef.identify.api import METHODS


def add_parser(sub):
    p = sub.add_parser("identify", help="identify coefficients from a log (CSV)",
                       description="Least-squares identification with parameter standard "
                                   "deviations, relative errors, J_LS and information criteria.")
    p.add_argument("log", metavar="LOG",
                   help="log file (docs/identify.md: the log format), or with --map any CSV "
                        "or a ROS bag (docs/logs.md)")
    add_map_argument(p)
    p.add_argument("--method", required=True, choices=METHODS)
    p.add_argument("--dof", default=None, metavar="DOF",
                   help="surge..yaw or u..r (steady: heave, one-step: yaw, torsion: yaw)")
    p.add_argument("--model", default=None, metavar="NAME",
                   help="steady: standard, eta, eta-md, LQB, LQNB, LB, LNB or compare "
                        "(default standard); one-step: LQB (eq. 8), LQNB, LB, LNB")
    p.add_argument("--vehicle", metavar="VEHICLE",
                   help="vehicle file or model file (JSON/YAML of HydroModel.to_dict): "
                        "thruster map, mass, buoyancy and inertia")
    p.add_argument("--json", action="store_true", help="print the JSON result")
    p.add_argument("-o", "--output", metavar="FILE", help="write the output to FILE (atomically)")
    p.add_argument("--plot", metavar="FILE.png", help="data vs fit and residuals (matplotlib)")
    s = p.add_argument_group("steady")
    s.add_argument("--direction", choices=("both", "positive", "negative"), default="both",
                   help="fit one direction of motion only")
    s.add_argument("--settle", type=float, default=8.0, metavar="S",
                   help="seconds dropped at the start of each constant-input segment (8)")
    s.add_argument("--trim", type=int, default=0, metavar="N",
                   help="samples dropped at the end of each segment (Indiveri 1998: 70)")
    o = p.add_argument_group("one-step")
    o.add_argument("--inertia", type=float, metavar="KG_M2",
                   help="rigid-body mass or inertia about the DOF (default: from --vehicle)")
    o.add_argument("--covariance", choices=("ma1", "hac", "iid"), default=None,
                   help="covariance estimator (default ma1 for one-step)")
    d = p.add_argument_group("pendulum / torsion")
    d.add_argument("--mass", type=float, metavar="KG", help="model mass M (default: --vehicle)")
    d.add_argument("--buoyancy", type=float, metavar="N",
                   help="buoyancy force B [N] (default: --vehicle; 0 in air)")
    d.add_argument("--length", type=float, metavar="M", help="pendulum length r [m]")
    d.add_argument("--stiffness", type=float, metavar="NM_RAD", help="torsion spring K [N m/rad]")
    d.add_argument("--medium", choices=("water", "air"), default="water",
                   help="air: calibration run (pendulum gives r, torsion gives K or I)")
    d.add_argument("--window", type=int, metavar="N",
                   help="Savitzky-Golay window [samples] (default 0.4 of the period)")
    d.add_argument("--order", type=int, default=4, help="Savitzky-Golay order (4)")
    d.add_argument("--refine", action="store_true",
                   help="follow the paper's equation-error fit by an output-error fit")
    p.set_defaults(func=run)
    return p


def _fmt(v, digits=5):
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "-"
    return f"{v:.{digits}g}"


def format_fit(fit, *, source: str) -> str:
    """A table in the style of the papers: value, std, relative error, unit."""
    head = (f"{fit.method} identification, model {fit.model or '-'}"
            f"{', dof ' + fit.dof if fit.dof else ''}  ({source})")
    lines = [head, ""]
    rows = [("parameter", "value", "std", "100 sd/|value| [%]", "unit")]
    p, s, r = fit.parameters, fit.std, fit.relative_error_percent
    for n in p:
        rows.append((n, _fmt(p[n]), _fmt(s[n], 3), _fmt(r[n], 3), fit.units.get(n, "")))
    widths = [max(len(row[j]) for row in rows) for j in range(5)]
    for k, row in enumerate(rows):
        lines.append("  ".join(c.ljust(widths[j]) if j in (0, 4) else c.rjust(widths[j])
                               for j, c in enumerate(row)).rstrip())
        if k == 0:
            lines.append("  ".join("-" * w for w in widths))
    lines.append("")
    rms = fit.rms_error if fit.rms_error is not None else fit.residual_rms
    lines.append(f"J_LS = {_fmt(fit.cost)}   nu = N - p = {fit.degrees_of_freedom}   "
                 f"sigma = {_fmt(math.sqrt(fit.sigma2), 4)}   rms error = {_fmt(rms, 4)}")
    lines.append(f"AIC = {_fmt(fit.aic, 6)}   AICc = {_fmt(fit.aicc, 6)}   "
                 f"BIC = {_fmt(fit.bic, 6)}   covariance: {fit.covariance}")
    for k, v in fit.metrics.items():
        lines.append(f"{k} = {_fmt(v, 4)}")
    for note in fit.notes:
        lines.append(f"note: {note}")
    return "\n".join(lines) + "\n"


def format_comparison(cmp) -> str:
    """Indiveri's (1998) yaw tables: one column per model and direction, then the ranking."""
    lines = [f"steady-state model comparison, dof {cmp.dof}", ""]
    fits = cmp.single + [c.fits[0] for c in cmp.candidates if c.direction == "both"]
    names = []
    for f in fits:
        for n in f.names:
            if n not in names:
                names.append(n)
    header = ["", *[f.model for f in fits]]
    body = []
    for n in names:
        body.append([n, *[_fmt(f.parameters[n], 4) if n in f.names else "-" for f in fits]])
    for n in names:
        body.append([f"100 sd/|{n}| [%]",
                     *[_fmt(f.relative_error_percent[n], 3) if n in f.names else "-"
                       for f in fits]])
    body.append(["J_LS", *[_fmt(f.cost, 5) for f in fits]])
    body.append(["nu", *[str(f.degrees_of_freedom) for f in fits]])
    rows = [header] + body
    widths = [max(len(r[j]) for r in rows) for j in range(len(header))]
    for r in rows:
        lines.append("  ".join(c.rjust(widths[j]) if j else c.ljust(widths[j])
                               for j, c in enumerate(r)))
    lines += ["", "ranking over all the data (AICc; models fitted together or per direction):"]
    for k, c in enumerate(cmp.candidates, 1):
        lines.append(f"  {k}. {c.label:<22} AICc {c.aicc:9.3f}  BIC {c.bic:9.3f}  "
                     f"J_LS {c.cost:10.5g}  p {c.n_params}  max rel. err. "
                     f"{_fmt(c.max_relative_error, 3)} %")
    lines += ["", f"recommended: {cmp.recommended.label}", cmp.explanation]
    return "\n".join(lines) + "\n"


def run_identify(args):
    """Run the method; returns (fit, comparison or None)."""
    from stripcoef.identify.api import identify_log
    from stripcoef.identify.inputs import vehicle_model

    log = read_log_from_args(args.log, args)
    vehicle = vehicle_model(args.vehicle) if args.vehicle else None
    return identify_log(log, args.method, dof=args.dof, model=args.model, vehicle=vehicle,
                        direction=args.direction, settle=args.settle, trim=args.trim,
                        inertia=args.inertia, covariance=args.covariance, mass=args.mass,
                        buoyancy=args.buoyancy, length=args.length, stiffness=args.stiffness,
                        medium=args.medium, window=args.window, order=args.order,
                        refine=args.refine)


def run(args) -> int:
    fit, cmp = run_identify(args)
    check_finite_output({k: fit.to_dict().get(k) for k in ("parameters", "std")},
                        what="the identified model", file=args.log)
    if args.json:
        data = fit.to_dict()
        if cmp is not None:
            def num(x):
                return float(x) if math.isfinite(x) else None
            data["comparison"] = [
                {"label": c.label, "model": c.model, "direction": c.direction,
                 "aicc": num(c.aicc), "bic": num(c.bic), "cost": num(c.cost),
                 "n_params": c.n_params, "n_obs": c.n_obs,
                 "max_relative_error_percent": num(c.max_relative_error),
                 "problems": c.problems(),
                 "fits": [f.to_dict() for f in c.fits]} for c in cmp.candidates]
            data["recommended"] = cmp.recommended.label
            data["explanation"] = cmp.explanation
        text = json_text(data)
    else:
        text = format_comparison(cmp) if cmp is not None else ""
        text += ("\n" if cmp is not None else "") + format_fit(fit, source=args.log)
    if args.plot:
        from stripcoef.identify.plots import plot_fit
        plot_fit(fit, args.plot, key="--plot")
    if args.output:
        write_text(args.output, text, key="--output")
    else:
        print(text, end="")
    return 0
