"""``python -m stripcoef``: the command-line interface."""

import sys

from stripcoef.cli import main

sys.exit(main())
