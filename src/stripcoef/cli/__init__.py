"""Command-line interface: a thin layer over the Python API (``stripcoef COMMAND``).

:mod:`.app` builds the parser and is the only place that turns errors into exit codes;
each command is one module here with ``add_parser(subparsers)`` and ``run(args)``;
:mod:`.options` holds the options several commands share.

Depends on: everything below it; nothing imports it.
"""

from stripcoef.cli.app import build_parser, main

__all__ = ["build_parser", "main"]
