"""Sample data shipped in the wheel: the vehicles, a small mesh and logs with a known truth.

Reachable without a clone of the repository:

- Python: ``stripcoef.samples.path("mares.yaml")`` is the file's path; ``names()`` lists
  every sample.
- CLI: ``stripcoef samples`` lists them; any argument written ``sample:NAME`` (for example
  ``stripcoef coefficients sample:mares.yaml``) is that file.

The files are written by ``scripts/make_samples.py`` (the vehicles are copies of the
repository's ``geometry/`` folder, checked identical by a test). Each log's generating truth
and the command that recovers it are in ``truth.yaml`` beside the logs (docs/samples.md).
"""

from __future__ import annotations

from pathlib import Path

from stripcoef.errors import unknown_name

#: The folder of the sample files (inside the installed package).
FOLDER = Path(__file__).resolve().parent

#: The prefix of a sample in a command-line argument (``sample:mares.yaml``).
PREFIX = "sample:"

_SUFFIXES = (".yaml", ".json", ".csv", ".stl")


def names() -> list[str]:
    """Every sample's name (file name, with its suffix), sorted."""
    return sorted(p.name for p in FOLDER.iterdir()
                  if p.suffix in _SUFFIXES and not p.name.startswith("_"))


def path(name: str) -> Path:
    """The path of sample ``name`` (``"mares.yaml"``; ``"sample:mares.yaml"`` also works).

    An unknown name is an :class:`~stripcoef.errors.InputError` listing the samples.
    """
    name = str(name)
    if name.startswith(PREFIX):
        name = name[len(PREFIX):]
    if name not in names():
        raise unknown_name("sample", name, names())
    return FOLDER / name


def descriptions() -> dict[str, str]:
    """name -> one line saying what the sample is (from ``truth.yaml``)."""
    import yaml

    data = yaml.safe_load((FOLDER / "truth.yaml").read_text())
    return {n: data["samples"].get(n, "") for n in names()}


def truth(name: str) -> dict:
    """The generating truth of sample log ``name`` (``truth.yaml``): what it is, its
    generator, the true parameters as ``[value, unit]`` and the command that recovers them."""
    import yaml

    path(name)                                       # an unknown name lists the samples
    logs = yaml.safe_load((FOLDER / "truth.yaml").read_text())["logs"]
    name = str(name).removeprefix(PREFIX)
    if name not in logs:
        raise unknown_name("sample log", name, logs)
    return logs[name]


def resolve(argument: str) -> str:
    """A command-line argument with a ``sample:NAME`` form replaced by the sample's path;
    any other argument unchanged."""
    if isinstance(argument, str) and argument.startswith(PREFIX):
        return str(path(argument))
    return argument
