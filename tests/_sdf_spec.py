"""A check of an SDF file against the SDFormat 1.11 element descriptions
(reference_tables/sdformat_1_11, from gazebosim/sdformat at sdformat14_14.9.0), following
sdformat 14's parser (src/parser.cc: readXml, readAttributes); see that folder's README.

``problems(text)`` lists, one line each, what sdformat 14 would warn about or refuse:
undescribed elements and attributes, deprecated elements, missing required attributes,
missing required children of a joint, and values that do not read as their type; and,
stricter than the parser, a value element (one with a type) given twice (the parser keeps
both, the API reads the first). As in parser.cc, an ``<include>``'s own ``required`` is not
read: the included file's root element says it.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

SPEC = Path(__file__).resolve().parents[1] / "reference_tables" / "sdformat_1_11"


@dataclass
class Spec:
    """One element description: its name, type, required flag, attributes (name ->
    required), children (name -> Spec), and whether it takes any children (copy_data)."""

    name: str
    type: str | None = None
    required: str = "0"
    attributes: dict = field(default_factory=dict)
    children: dict = field(default_factory=dict)
    copy_data: bool = False


def _spec_of(node, files) -> Spec:
    if node.get("ref"):
        ref = _file(node.get("ref") + ".sdf", files)
        return Spec(ref.name, ref.type, node.get("required", "0"), ref.attributes,
                    ref.children, ref.copy_data)
    spec = Spec(node.get("name", ""), node.get("type"), node.get("required", "0"),
                copy_data=node.get("copy_data") == "true")
    files.setdefault("_pending", []).append((spec, node))
    return spec


def _fill(spec: Spec, node, files) -> None:
    for child in node:
        if child.tag == "attribute":
            spec.attributes[child.get("name")] = child.get("required") == "1"
        elif child.tag == "element":
            if child.get("copy_data") == "true" and not child.get("name"):
                spec.copy_data = True
                continue
            sub = _spec_of(child, files)
            spec.children[sub.name] = sub
        elif child.tag == "include":
            inc = _file(child.get("filename"), files)      # parser.cc initXml: the file's
            spec.children[inc.name] = inc                   # element, its own required


def _file(name: str, files) -> Spec:
    """The element a spec file describes (each file is read once, recursion by reference)."""
    if name in files:
        return files[name]
    node = ET.parse(SPEC / name).getroot()
    spec = Spec(node.get("name"), node.get("type"), node.get("required", "0"),
                copy_data=node.get("copy_data") == "true")
    files[name] = spec
    _fill(spec, node, files)
    while files.get("_pending"):
        sub, sub_node = files["_pending"].pop()
        _fill(sub, sub_node, files)
    return spec


@lru_cache(maxsize=1)
def root_spec() -> Spec:
    """The description of ``<sdf>`` (root.sdf) and everything below it."""
    return _file("root.sdf", {})


def _reads_as(kind: str | None, text: str) -> bool:
    """Whether ``text`` reads as an SDF value of type ``kind`` (sdformat's Param types)."""
    words = (text or "").split()
    def numbers(n):
        try:
            return len(words) == n and all(math.isfinite(float(w)) or w in ("inf", "-inf")
                                           for w in words)
        except ValueError:
            return False
    if kind in ("double", "float"):
        return numbers(1)
    if kind in ("int", "unsigned int"):
        try:
            value = int(words[0], 0) if len(words) == 1 else None    # 0xAB reads too
        except ValueError:
            return False
        return value is not None and (kind == "int" or value >= 0)
    if kind == "bool":
        return len(words) == 1 and words[0].lower() in ("true", "false", "1", "0")
    if kind == "vector3":
        return numbers(3)
    if kind == "vector2d":
        return numbers(2)
    if kind == "pose":
        return numbers(6) or numbers(7) or not words
    if kind == "color":
        return numbers(4) or numbers(3)
    return True        # string, time: any text


def problems(text: str) -> list[str]:
    """What sdformat 14 would report about the SDF ``text`` (module docstring); [] if clean."""
    body = text.split("?>", 1)[1] if text.lstrip().startswith("<?xml") else text
    root = ET.fromstring(body)
    out: list[str] = []
    if root.tag != "sdf":
        return [f"root element <{root.tag}>, expected <sdf>"]
    _check(root, root_spec(), "/sdf", out)
    return out


def _check(el, spec: Spec, path: str, out: list) -> None:
    for attr in el.attrib:
        if attr not in spec.attributes and not attr.startswith("{"):   # namespaced: custom
            out.append(f"{path}: attribute {attr!r} not defined in SDF 1.11")
    out += [f"{path}: required attribute {a!r} missing" for a, req in spec.attributes.items()
            if req and a not in el.attrib]
    if spec.type and not _reads_as(spec.type, el.text):
        out.append(f"{path}: value {el.text!r} does not read as {spec.type}")
    if spec.copy_data:
        return
    seen: dict[str, int] = {}
    for child in el:
        name = child.get("name")
        where = f"{path}/{child.tag}" + (f"[@name={name!r}]" if name else "")
        sub = spec.children.get(child.tag)
        if sub is None:
            if ":" not in child.tag:
                out.append(f"{where}: element not defined in SDF 1.11 under <{spec.name}>")
            continue
        seen[child.tag] = seen.get(child.tag, 0) + 1
        if sub.required == "-1":
            out.append(f"{where}: deprecated element")
        if sub.type and sub.required in ("0", "1") and seen[child.tag] == 2:
            out.append(f"{where}: value element <{child.tag}> given twice")
        _check(child, sub, where, out)
    if spec.name == "joint" and el.get("type") != "ball":
        out += [f"{path}: required element <{n}> missing" for n, s in spec.children.items()
                if s.required in ("1", "+") and n not in seen]
