"""One module per CLI subcommand (see stripcoef.cli)."""
