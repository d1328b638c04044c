"""Exception and warning classes.

Every error a user can cause says *where* (file, key path, column, row, strip),
*what* was received and *what was expected*.  The CLI turns any
:class:`StripcoefError` into one line on stderr and exit code 2; anything else
escaping to the user is a bug.
"""

from __future__ import annotations

from os import PathLike
from typing import Any


def _fmt_value(value: Any) -> str:
    """The value as the error shows it: a path whole (the user needs all of it to act), any
    other value cut to 80 characters (a bad cell, a long list), a text to 240."""
    if isinstance(value, PathLike):
        return repr(str(value))
    text = repr(value)
    limit = 240 if isinstance(value, str) else 80
    return text if len(text) <= limit else text[:limit - 3] + "..."


class StripcoefError(Exception):
    """Base class of every error a user can cause."""


class InputError(StripcoefError, ValueError):
    """Bad input: a file, key, column or argument with a wrong value.

    Parameters
    ----------
    what : str
        Short description, or the expected value when ``value`` is given.
    file : str, optional
        File name the value came from.
    key : str, optional
        Key path (``hull.profile[2].radius``), column or argument name.
    value : Any, optional
        The offending value (pass ``_MISSING`` to omit).
    expected : str, optional
        What was expected instead.
    """

    _MISSING = object()

    def __init__(self, what: str = "", *, file: str | None = None, key: str | None = None,
                 value: Any = _MISSING, expected: str | None = None):
        self.file = file
        self.key = key
        self.value = value
        self.expected = expected
        self.what = what
        where = ": ".join(p for p in (file, key) if p)
        parts = []
        if what:
            parts.append(what)
        if value is not InputError._MISSING:
            parts.append(f"got {_fmt_value(value)}")
        if expected:
            parts.append(f"expected {expected}")
        body = "; ".join(parts)
        super().__init__(f"{where}: {body}" if where else body)

    def with_key(self, key: str | None) -> "InputError":
        """The same error naming another key (the CLI names its flag for a parameter)."""
        return InputError(self.what, file=self.file, key=key, value=self.value,
                          expected=self.expected)


class UnreachableError(StripcoefError, RuntimeError):
    """A manoeuvre or computation that the model or thrusters cannot achieve."""


class ExternalToolError(StripcoefError, RuntimeError):
    """An external program (OpenFOAM) is missing, or failed on the input it was given."""


class ExtrapolationWarning(UserWarning):
    """A tabulated curve was evaluated outside the range of its data (value clamped)."""


class ModelWarning(UserWarning):
    """A modelling assumption or limitation the user should know about."""


class SamplingWarning(UserWarning):
    """A log stream sampled irregularly, with gaps or bursts, or off its stated rate."""


def unknown_name(kind: str, name: str, valid, *, file: str | None = None,
                 key: str | None = None) -> InputError:
    """Error for a name missing from a registry, listing the valid names."""
    return InputError(f"unknown {kind}", file=file, key=key, value=name,
                      expected="one of " + ", ".join(sorted(valid)))
