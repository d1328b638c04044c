"""Command-line interface: a thin layer over the Python API.

Each subcommand lives in ``stripcoef.cli.<name>`` and exposes
``add_parser(subparsers)`` and ``run(args) -> int``.  This module is the only
place that turns errors into exit codes: a :class:`StripcoefError` (bad input,
unreachable manoeuvre) prints one line and exits 2.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
import warnings
from pathlib import Path

# The matrices here are small (strips, panels): threaded BLAS only adds contention, and on a
# loaded 2-core machine makes a 160x160 solve 100x slower (docs/performance.md). Set before
# numpy is imported by the subcommands; a user's own setting wins.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from stripcoef.errors import InputError, StripcoefError
from stripcoef.files import check_output_path

#: Options that name a file a command writes: checked before any work (a folder, ``.``, a
#: missing or unwritable folder is a one-line error, not a failure after minutes of work).
OUTPUT_OPTIONS = ("output", "out", "report", "plot")

#: Subcommands, in the order of the pipeline.
COMMANDS = ("mesh", "coefficients", "limits", "export", "simulate", "identify", "scale", "compare",
            "diagnose", "uncertainty", "sweep", "cfd", "samples")


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # argparse's usage errors: one line, exit 2
        self.exit(2, f"{self.prog}: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="stripcoef",
                     description="Hydrodynamic models of underwater vehicles by strip theory.")
    from stripcoef import __version__
    parser.add_argument("--version", action="version", version=f"stripcoef {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True
    for name in COMMANDS:
        module = importlib.import_module(f"stripcoef.cli.{name}")
        module.add_parser(sub)
    for command in sub.choices.values():
        add_progress_arguments(command)
    return parser


def add_progress_arguments(parser) -> None:
    """--quiet/--verbose on every command: progress bars on long work (stripcoef.progress)."""
    g = parser.add_mutually_exclusive_group()
    g.add_argument("-q", "--quiet", dest="progress", action="store_const", const=False,
                   help="no progress bars (default: bars when stderr is a terminal)")
    g.add_argument("-v", "--verbose", dest="progress", action="store_const", const=True,
                   help="progress bars even when stderr is not a terminal")


def _showwarning(message, category, filename, lineno, file=None, line=None):
    print(f"warning: {message}", file=sys.stderr)


def in_cli_terms(exc: StripcoefError, parser: argparse.ArgumentParser) -> StripcoefError:
    """The library names a parameter (``radii``); the user typed a flag (``--radii``).

    An :class:`InputError` that names no file and whose key is the destination of one of the
    command's options is reworded to name that option's flag (a key of a file, such as a
    vehicle file's ``reference_point``, stays the file's); any other error is returned as it is.
    """
    if not isinstance(exc, InputError) or not exc.key or exc.file:
        return exc
    for action in parser._actions:
        if action.dest == exc.key and action.option_strings:
            return exc.with_key(max(action.option_strings, key=len))
    return exc


def check_outputs(args) -> None:
    """Every output option of the command names a writable file path (before any work)."""

    from stripcoef import samples

    for dest in OUTPUT_OPTIONS:
        path = getattr(args, dest, None)
        if path is not None:
            check_output_path(path, key=dest)
            if path != "-" and Path(path).resolve().parent == samples.FOLDER:
                raise InputError("an installed sample is read-only", key=dest, value=str(path),
                                 expected="a path outside the package's samples (the sample "
                                          "is read as sample:NAME; write a copy elsewhere)")


def main(argv=None) -> int:
    parser = build_parser()
    argv = list(sys.argv[1:] if argv is None else argv)
    warnings.showwarning = _showwarning
    try:
        # sample:NAME is the shipped sample's path (stripcoef.samples), in any argument
        from stripcoef.samples import resolve
        argv = [resolve(a) for a in argv]
    except StripcoefError as exc:
        print(f"stripcoef: error: {exc}", file=sys.stderr)
        return 2
    args = parser.parse_args(argv)
    from stripcoef import progress
    try:
        check_outputs(args)
        with progress.bars(getattr(args, "progress", None)):
            return int(args.func(args) or 0)
    except MemoryError:  # a resource limit missed by the input checks: say so, in one line
        print(f"stripcoef {args.command}: error: out of memory; expected inputs of a size this "
              "machine can hold (fewer strips, radii or log rows)", file=sys.stderr)
        return 2
    except StripcoefError as exc:
        exc = in_cli_terms(exc, parser._subparsers._group_actions[0].choices[args.command])
        print(f"stripcoef {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:  # output piped into a command that stopped reading (e.g. head)
        sys.stderr.close()
        return 0
