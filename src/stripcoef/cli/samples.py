"""``stripcoef samples``: the sample data shipped with the package (vehicles, a mesh, logs)."""

from __future__ import annotations

from stripcoef.errors import InputError


def add_parser(sub):
    p = sub.add_parser("samples", help="list the shipped sample vehicles, mesh and logs",
                       description="The sample files installed with stripcoef. Any command "
                                   "takes one as sample:NAME (e.g. 'stripcoef coefficients "
                                   "sample:mares.yaml'); the logs' generating truth and the "
                                   "command recovering it are in sample:truth.yaml.")
    p.add_argument("name", nargs="?", metavar="NAME",
                   help="print this sample's path (and, for a log, its truth)")
    p.set_defaults(func=run)
    return p


def run(args) -> int:
    from stripcoef import samples

    if args.name:
        path = samples.path(args.name)
        print(path)
        try:
            truth = samples.truth(args.name)
        except InputError:  # not a log: the path is the whole answer
            return 0
        print(f"  {truth['what']}")
        for k, (value, unit) in truth["truth"].items():
            print(f"  truth {k} = {value:.6g} [{unit}]")
        print(f"  recover: {truth['recover']}")
        return 0
    desc = samples.descriptions()
    width = max(len(n) for n in desc)
    print(f"samples in {samples.FOLDER} (use as sample:NAME):")
    for name, text in desc.items():
        print(f"  {name:<{width}}  {text}")
    return 0
