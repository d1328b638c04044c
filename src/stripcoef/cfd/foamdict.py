"""OpenFOAM dictionaries: a small writer and a reader for the subset stripcoef writes.

The maintained Python helpers for OpenFOAM case files (PyFoam, foamlib, fluidfoam) are GPL
licensed while stripcoef is MIT, so none of them can be a dependency: the case files are
written here from plain Python values, and read back (by the tests, and for the mesh size
OpenFOAM reports) by :func:`parse`.

Mapping of Python values to OpenFOAM syntax (OpenFOAM User Guide v1912, sec. 4.2 "Basic
input/output file format"):

- ``dict`` -> ``key { ... }`` for a dict value, ``key value;`` otherwise; a
  :class:`NamedList` -> ``key ( name { ... } name { ... } );``;
- ``list`` -> ``( a b c )`` (a vector is a list of three numbers; a list of dicts is a list
  of sub-dictionaries, as snappyHexMesh's ``features``);
- ``bool`` -> ``true``/``false``; ``int``/``float`` -> a number (``%.10g``);
- ``str`` -> written as it is (a word, ``"quoted"``, ``uniform (0 0 0)``, a ``#include``
  directive as a key with the value ``None``).
"""

from __future__ import annotations

import re

HEADER = ("/*--------------------------------*- C++ -*----------------------------------*\\\n"
          "  written by stripcoef (MIT); OpenFOAM v1912 syntax\n"
          "\\*---------------------------------------------------------------------------*/\n")


def number(value) -> str:
    """A number as OpenFOAM reads it (10 significant digits)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    return f"{float(value):.10g}"


class NamedList(dict):
    """A list of named dictionaries, ``( name { ... } name { ... } )`` (blockMesh's
    ``boundary``)."""


def value_text(value, indent: str = "") -> str:
    """The OpenFOAM text of one value (not a dictionary)."""
    if isinstance(value, NamedList):
        return f"\n{indent}(\n{entries(value, indent + '    ')}{indent})"
    if isinstance(value, (bool, int, float)):
        return number(value)
    if isinstance(value, str):
        return value
    if isinstance(value, (list, tuple)):
        if any(isinstance(v, dict) for v in value):
            inner = indent + "    "
            body = "".join(f"{inner}{{\n{entries(v, inner + '    ')}{inner}}}\n"
                           if isinstance(v, dict) else f"{inner}{value_text(v, inner)}\n"
                           for v in value)
            return f"\n{indent}(\n{body}{indent})"
        return "(" + " ".join(value_text(v, indent) for v in value) + ")"
    if hasattr(value, "tolist"):           # a numpy array or scalar
        return value_text(value.tolist(), indent)
    raise TypeError(f"no OpenFOAM text for {type(value).__name__}")


def entries(d: dict, indent: str = "") -> str:
    """The entries of a dictionary, one per line (sub-dictionaries indented)."""
    out = []
    for key, val in d.items():
        if key.startswith("(") or "|" in key:     # a regular expression key is quoted
            key = f'"{key}"'
        if isinstance(val, NamedList):
            out.append(f"{indent}{key} {value_text(val, indent)};\n")
        elif val is None:                     # a directive without argument
            out.append(f"{indent}{key}\n")
        elif key.startswith("#"):             # a directive: #includeEtc "file" (no ;)
            out.append(f"{indent}{key} {value_text(val, indent)}\n")
        elif isinstance(val, dict):
            out.append(f"{indent}{key}\n{indent}{{\n{entries(val, indent + '    ')}{indent}}}\n")
        else:
            out.append(f"{indent}{key} {value_text(val, indent)};\n")
    return "".join(out)


def foam_file(object_name: str, body: dict, *, cls: str = "dictionary",
              location: str | None = None) -> str:
    """A complete OpenFOAM file: the header, the ``FoamFile`` entry and ``body``."""
    head = {"version": 2.0, "format": "ascii", "class": cls, "object": object_name}
    if location is not None:
        head["location"] = f'"{location}"'
    return HEADER + entries({"FoamFile": head}) + "\n" + entries(body)


# ---------------------------------------------------------------------------- reading

_TOKEN = re.compile(r'\s+|//[^\n]*|/\*.*?\*/|"[^"]*"|[{}();]|[^\s{}();"]+', re.S)


def _tokens(text: str) -> list[str]:
    return [t for t in _TOKEN.findall(text)
            if t.strip() and not t.startswith("//") and not t.startswith("/*")]


def _atom(tok: str):
    try:
        return int(tok)
    except ValueError:
        pass
    try:
        return float(tok)
    except ValueError:
        return tok


def parse(text: str) -> dict:
    """Read an OpenFOAM dictionary file into nested ``dict``/``list`` values.

    Numbers become ``int``/``float``, words and quoted strings stay ``str`` (quotes kept);
    an entry of several values (``type fixedValue;`` has one, ``value uniform (1 0 0);``
    two) becomes a list of them when there are several; a list of named dictionaries
    (``( inlet { ... } outlet { ... } )``) a ``dict``. Enough for the files stripcoef
    writes and for OpenFOAM's own ``polyMesh/owner`` header; not a full OpenFOAM parser
    (no macro expansion, no ``#include``).
    """
    toks = _tokens(text)
    pos = 0

    def parse_list():
        nonlocal pos
        items = []
        pos += 1                                         # "("
        while toks[pos] != ")":
            if toks[pos] == "(":
                items.append(parse_list())
            elif toks[pos] == "{":
                pos += 1
                items.append(parse_dict("}"))
            else:
                items.append(_atom(toks[pos]))
                pos += 1
        pos += 1
        if items and len(items) % 2 == 0 and all(isinstance(k, str) for k in items[::2]) \
                and all(isinstance(v, dict) for v in items[1::2]):
            return dict(zip(items[::2], items[1::2]))     # ( name { } name { } )
        return items

    def parse_dict(end):
        nonlocal pos
        out = {}
        while pos < len(toks) and toks[pos] != end:
            key = toks[pos]
            pos += 1
            if key.startswith("#"):                      # a directive and its argument
                if pos < len(toks) and toks[pos].startswith('"'):
                    out[key] = toks[pos]
                    pos += 1
                    if pos < len(toks) and toks[pos] == ";":
                        pos += 1
                else:
                    out[key] = None
                continue
            if toks[pos] == "{":
                pos += 1
                out[key] = parse_dict("}")
                continue
            vals = []
            while toks[pos] != ";":
                if toks[pos] == "(":
                    vals.append(parse_list())
                else:
                    vals.append(_atom(toks[pos]))
                    pos += 1
            pos += 1
            out[key] = vals[0] if len(vals) == 1 else vals
        pos += 1
        return out

    return parse_dict(None)
