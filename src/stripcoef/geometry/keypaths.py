"""Key paths into a vehicle file's data, and the uncertain values a file declares.

A key path names one value of the vehicle file the way the error messages do:
``mass.mass``, ``hull.profile[1].radius``, ``thrusters[0].max_forward``. Sweeps set values
by key path; uncertainty studies read the values a file declares as uncertain:

.. code-block:: yaml

    mass:
      mass: {value: 11.5, sd: 0.2}       # normal, 1 sigma [kg]
      center_of_gravity: [0.0, 0.0, {value: 0.02, tol: 0.005}]   # uniform +-tol [m]

:func:`nominal` replaces every such mapping by its ``value`` (what the model is built from);
:func:`uncertain_values` lists them.
"""

from __future__ import annotations

import copy
import math
import re
from dataclasses import dataclass

from stripcoef.errors import InputError

_TOKEN = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)|\[(\d+)\]")
#: The keys of a mapping that declares an uncertain value.
UNCERTAIN_KEYS = ({"value", "sd"}, {"value", "tol"})


def parse_path(path: str, *, file: str | None = None) -> tuple:
    """``"hull.profile[1].radius"`` -> ``("hull", "profile", 1, "radius")``."""
    text = str(path).strip()
    out, pos = [], 0
    while pos < len(text):
        if text[pos] == "." and out:
            pos += 1
        m = _TOKEN.match(text, pos)
        if m is None:
            raise InputError("not a key path", file=file, key=str(path),
                             expected="dotted keys and [index], e.g. hull.profile[1].radius")
        out.append(m.group(1) if m.group(1) is not None else int(m.group(2)))
        pos = m.end()
    if not out:
        raise InputError("empty key path", file=file, key=str(path),
                         expected="e.g. mass.mass or thrusters[0].max_forward")
    return tuple(out)


def format_path(tokens) -> str:
    """Inverse of :func:`parse_path`."""
    text = ""
    for t in tokens:
        text += f"[{t}]" if isinstance(t, int) else (f".{t}" if text else t)
    return text


def get_value(data, path, *, file: str | None = None):
    """The value at ``path`` (a key path or its tokens); an error names the missing key."""
    tokens = parse_path(path, file=file) if isinstance(path, str) else tuple(path)
    node = data
    for i, t in enumerate(tokens):
        ok = (isinstance(t, int) and isinstance(node, list) and 0 <= t < len(node)) or \
             (isinstance(t, str) and isinstance(node, dict) and t in node)
        if not ok:
            raise InputError("no such key in the vehicle file", file=file,
                             key=format_path(tokens[:i + 1]),
                             expected="a key path to an existing value (docs/vehicle-file.md)")
        node = node[t]
    return node


def set_value(data, path, value, *, file: str | None = None):
    """A deep copy of ``data`` with the number at ``path`` replaced by ``value``.

    The key must exist and hold a number (or an uncertain-value mapping): a sweep cannot add
    keys the file does not have, and cannot turn a list or a name into a number.
    """
    tokens = parse_path(path, file=file) if isinstance(path, str) else tuple(path)
    old = get_value(data, tokens, file=file)
    if not (_is_number(old) or _is_uncertain(old)):
        raise InputError("not a number in the vehicle file", file=file, key=format_path(tokens),
                         value=old if not isinstance(old, (dict, list)) else type(old).__name__,
                         expected="a key path to a numeric value")
    out = copy.deepcopy(data)
    node = out
    for t in tokens[:-1]:
        node = node[t]
    node[tokens[-1]] = float(value)
    return out


@dataclass(frozen=True)
class UncertainValue:
    """A value the vehicle file declares as uncertain.

    ``kind`` is ``"normal"`` (``spread`` = 1 sigma) or ``"uniform"`` (``spread`` = half-width
    ``tol``), in the value's own unit.
    """

    path: str
    value: float
    kind: str
    spread: float

    @property
    def sd(self) -> float:
        """Standard deviation [value's unit]: sigma, or tol/sqrt(3) for a uniform spread."""
        return self.spread if self.kind == "normal" else self.spread / math.sqrt(3.0)


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _is_uncertain(v) -> bool:
    return isinstance(v, dict) and set(v) in UNCERTAIN_KEYS


def _check(node, path: str, file: str | None) -> UncertainValue:
    value, key = node["value"], "sd" if "sd" in node else "tol"
    spread = node[key]
    for k, v in (("value", value), (key, spread)):
        if not _is_number(v) or not math.isfinite(v):
            raise InputError("not a finite number", file=file, key=f"{path}.{k}", value=v,
                             expected="a number")
    if spread < 0:
        raise InputError("negative spread", file=file, key=f"{path}.{key}", value=spread,
                         expected=f"{key} >= 0")
    return UncertainValue(path, float(value), "normal" if key == "sd" else "uniform",
                          float(spread))


def uncertain_values(data, *, file: str | None = None) -> list[UncertainValue]:
    """Every ``{value, sd}`` / ``{value, tol}`` mapping of the data, in file order."""
    found = []

    def walk(node, tokens):
        if _is_uncertain(node):
            found.append(_check(node, format_path(tokens), file))
        elif isinstance(node, dict):
            for k, v in node.items():
                walk(v, tokens + (k,))
        elif isinstance(node, list):
            for i, v in enumerate(node):
                walk(v, tokens + (i,))

    walk(data, ())
    return found


def nominal(data, *, file: str | None = None):
    """The data with every uncertain-value mapping replaced by its ``value``.

    Returns ``data`` itself when it declares nothing uncertain (no copy).
    """
    declared = uncertain_values(data, file=file)
    if not declared:
        return data
    out = data
    for u in declared:
        out = set_value(out, u.path, u.value, file=file)
    return out
