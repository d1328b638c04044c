"""``stripcoef scale``: an identification result of a scaled model to full scale (similitude)."""

from __future__ import annotations

from pathlib import Path

from stripcoef.errors import InputError
from stripcoef.files import check_finite_output, json_text, load_json, read_text, write_text


def add_parser(sub):
    p = sub.add_parser("scale", help="scale identified coefficients to full size (similitude)",
                       description="Similitude of Eng et al. 2009 (eqs. 8-10): drag x lambda^2, "
                                   "rotational drag x lambda^5, added mass x lambda^3.")
    p.add_argument("result", metavar="RESULT.json", help="output of stripcoef identify --json")
    p.add_argument("--ratio", type=float, required=True, metavar="LAMBDA",
                   help="L_full / L_model (Eng et al. 2009: 1/0.3 = 3.333...)")
    kind = p.add_mutually_exclusive_group()
    kind.add_argument("--rotational", action="store_true", default=None,
                      help="treat as rotational (default: torsion results and roll/pitch/yaw)")
    kind.add_argument("--translational", dest="rotational", action="store_false")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.add_argument("-o", "--output", metavar="FILE", help="write to FILE (atomically)")
    p.set_defaults(func=run)
    return p


def run(args) -> int:
    from stripcoef.identify.scaling import scale_result
    path = Path(args.result)
    text = read_text(path, kind="identification result")
    data = load_json(text, file=str(path))
    check_finite_output(data, what="the identification result", file=str(path))
    if not isinstance(data, dict):
        raise InputError("not a JSON object", file=str(path),
                         expected="the output of stripcoef identify --json")
    out = scale_result(data, args.ratio, rotational=args.rotational, file=str(path))
    check_finite_output(out, what="the scaled result", file=str(path))
    if args.json:
        text = json_text(out)
    else:
        kind = "rotational" if out["rotational"] else "translational"
        lines = [f"similitude, lambda = {args.ratio:.6g} ({kind}), from {path}", "",
                 f"{'parameter':<10} {'model':>12} {'factor':>10} {'full scale':>12} {'std':>10}"]
        for n, v in out["parameters"].items():
            f = out["factors"][n]
            sd = out["std"][n]
            lines.append(f"{n:<10} {v / f:12.5g} {f:10.5g} {v:12.5g} "
                         f"{'-' if sd is None else format(sd, '10.3g'):>10}")
        lines += ["", "caveat: " + out["caveat"]]
        text = "\n".join(lines) + "\n"
    if args.output:
        write_text(args.output, text, key="--output")
    else:
        print(text, end="")
    return 0
