"""The reliability campaign: seeded malformed inputs through every command, outcomes classified.

Every case is a command line of ``stripcoef`` run in-process through :func:`stripcoef.cli.main`
on files written into a fresh folder: mutated vehicle files, meshes, model files, logs and
identification results, and bad option values. Each mutation says whether its input is
*invalid* (the command must end in a clean error) or only *odd* (it may succeed, but then
its output must be finite). A case's outcome is one of

- ``ok``: exit 0 on an odd input, every number written or printed finite;
- ``not reachable``: exit 2 and one line of an ``UnreachableError`` naming the degree of
  freedom or manoeuvre and the value that cannot be reached (an answer of the model, e.g.
  a vehicle whose thrusters cannot hold it still: not an input error);
- ``clean error``: exit 2 and one line ``stripcoef CMD: error: WHERE: ...`` naming the file,
  key, column or option and saying what was expected (argparse's usage errors name the
  option and the value);
- ``traceback``: an exception escaped ``main``;
- ``hang``: the case used more than its limit of CPU time (user + system, all threads of
  the process: a SIGPROF in the case), or more than :data:`WALL_FACTOR` times the limit of
  wall-clock time (a case blocked without computing: a SIGALRM). CPU time does not grow
  when other processes load the machine, so the rule holds on a busy CI runner;
- ``partial output``: after a failure an output file exists (or changed), a temporary file
  is left behind, or something was printed on stdout;
- ``exit 0 on invalid``: exit 0 for an input the mutation made invalid;
- ``exit 0 non-finite``: exit 0 with a NaN or an infinity in what was written or printed;
- ``vague error``: exit 2 whose line does not name where the problem is or what was
  expected; ``multi-line error``: more than one line besides warnings.

Full campaign (docs/performance.md has its counts)::

    python -m benchmarks.fuzz_campaign --cases 3400 --seed 0

``tests/test_fuzz.py`` runs a quick mode of a few hundred cheap cases in CI. Simulations run
with the time budgets of ``simulate`` and ``diagnose`` lowered to :data:`BUDGET` s, so a run
that a budget stops is told apart from a hang (the case limit, :data:`CASE_LIMIT`).
"""

from __future__ import annotations

import argparse
import contextlib
import copy
import io
import json
import os
import re
import shutil
import signal
import sys
import tempfile
import time
import traceback
import warnings
from collections import Counter, defaultdict
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import yaml

ROOT = Path(__file__).resolve().parent.parent

#: Per-case limit of CPU time [s]: past it the case is a hang (the issue's definition,
#: measured in the process's CPU time so that a loaded machine does not make hangs).
CASE_LIMIT = 60.0
#: A case also hangs past this many times its limit of wall-clock time (blocked, not
#: computing: CPU time would not grow).
WALL_FACTOR = 10.0
#: ``stripcoef.simulate.TIME_LIMIT`` and ``stripcoef.diagnose.pipeline.TIME_LIMIT`` during
#: the campaign [s] (defaults 120 s and 300 s): a run stopped by its budget is a clean error,
#: told apart from a hang by the case limit.
BUDGET = 10.0

OUTCOMES = ("ok", "clean error", "not reachable", "traceback", "hang", "partial output",
            "exit 0 on invalid", "exit 0 non-finite", "vague error", "multi-line error")
BAD = OUTCOMES[3:]


@dataclass
class Case:
    """One command line on files written into a fresh folder (``{d}`` in argv is the folder)."""

    command: str
    kind: str
    argv: list
    files: dict = field(default_factory=dict)   # name -> str or bytes
    invalid: bool = True                         # must end in a clean error
    outputs: tuple = ()                          # names of files the command may write


# ---------------------------------------------------------------------------
# base inputs (valid), built once
# ---------------------------------------------------------------------------

class Bases:
    """Valid inputs the mutations start from: vehicle files, models, logs, meshes."""

    def __init__(self):
        from stripcoef import estimate
        from stripcoef.export import export_model
        from stripcoef.logfile import Log

        geo = ROOT / "geometry"
        self.vehicles = {p.name: p.read_text() for p in sorted(geo.glob("*.yaml"))}
        # cheaper copies for the campaign: 200 strips (the mutations are what is tested)
        self.vehicles = {k: v + "\nstrips: 200\n" if "\nstrips:" not in v else v
                         for k, v in self.vehicles.items()}
        self.models = {}
        for name in ("mares.yaml", "videoray_pro3.yaml"):
            model = estimate(geo / name, strips=200)
            self.models[name.replace(".yaml", "")] = model
        self.model_json = {k: export_model(m, "json") for k, m in self.models.items()}
        self.model_yaml = {k: export_model(m, "yaml") for k, m in self.models.items()}
        # simulate inputs for mares: 20 s of thruster steps
        t = np.round(np.arange(0, 20.0 + 1e-9, 0.1), 6)
        step = np.where((t // 4) % 2 == 0, 1.0, -0.5)
        self.inputs = Log({"t": t, "n_P1": step, "n_P2": 0.8 + 0 * t, "n_V1": 0.2 + 0 * t,
                           "n_V2": 0 * t,
                           "X": 0.0 * t}).to_csv_text()
        # identification logs, as the tests make them
        from validation.experiments import (romeo_experiment, rov2_pendulum_log,
                                            rov2_torsion_log, videoray_yaw_log)
        pts, _ = romeo_experiment(2, seed=2)
        self.steady = Log({"w": pts.velocity, "Z": pts.force, "n_h": pts.n_h}).to_csv_text()
        self.yaw = videoray_yaw_log(0).to_csv_text()
        self.pend = rov2_pendulum_log(0).to_csv_text()
        self.tors = rov2_torsion_log(0).to_csv_text()
        from validation.synthetic import generate
        log, prior, _ = generate(None, seed=1, duration=80.0)
        self.diag_log = log.to_csv_text()
        self.diag_prior = export_model(prior, "yaml")
        self.identify_json = None
        # meshes
        import trimesh
        box = trimesh.creation.box(extents=(1.0, 0.3, 0.2))
        self.mesh_box = box.export(file_type="stl")
        self.mesh_capsule = trimesh.creation.capsule(height=0.8, radius=0.1, count=[16, 16])
        self.mesh_capsule.apply_transform(trimesh.transformations.rotation_matrix(
            np.pi / 2, [0, 1, 0]))
        self.mesh_capsule_stl = self.mesh_capsule.export(file_type="stl")
        self.mesh_obj = box.export(file_type="obj")

    def frame_stl(self) -> bytes:
        """An open frame of 12 square bars (a ROV skid), one closed surface: the bars' boolean
        union (manifold3d), else the bars merged where they overlap (which leaves the mesh
        not watertight: an error, so the case still runs)."""
        if getattr(self, "_frame", None) is None:
            import trimesh
            bars = []
            for y in (-0.3, 0.3):
                for z in (-0.2, 0.2):
                    bars.append(trimesh.creation.box(extents=(1.0, 0.04, 0.04)))
                    bars[-1].apply_translation([0, y, z])
            for x in (-0.48, 0.48):
                for z in (-0.2, 0.2):
                    bars.append(trimesh.creation.box(extents=(0.04, 0.64, 0.04)))
                    bars[-1].apply_translation([x, 0, z])
                for y in (-0.3, 0.3):
                    bars.append(trimesh.creation.box(extents=(0.04, 0.04, 0.44)))
                    bars[-1].apply_translation([x, y, 0])
            try:
                frame = trimesh.boolean.union(bars, engine="manifold")
            except Exception:  # noqa: BLE001 - manifold3d is an optional extra
                frame = trimesh.util.concatenate(bars)
            self._frame = frame.export(file_type="stl")
        return self._frame

    def pendulum_result(self) -> str:
        if self.identify_json is None:
            from stripcoef.cli import main
            from validation.experiments import ROV2_BUOYANCY, ROV2_LENGTH, ROV2_MASS
            with tempfile.TemporaryDirectory() as d:
                Path(d, "p.csv").write_text(self.pend)
                with contextlib.redirect_stdout(io.StringIO()), \
                        contextlib.redirect_stderr(io.StringIO()):
                    main(["identify", f"{d}/p.csv", "--method", "pendulum", "--mass",
                          str(ROV2_MASS), "--buoyancy", str(ROV2_BUOYANCY), "--length",
                          str(ROV2_LENGTH), "--json", "-o", f"{d}/r.json"])
                self.identify_json = Path(d, "r.json").read_text()
        return self.identify_json


# ---------------------------------------------------------------------------
# mutations of mappings (vehicle files, model files)
# ---------------------------------------------------------------------------

def _leaves(data, path=()):
    """(path, value) of every leaf and list of numbers in a parsed YAML/JSON document."""
    if isinstance(data, dict):
        for k, v in data.items():
            yield from _leaves(v, path + (k,))
    elif isinstance(data, list) and data and all(isinstance(x, (int, float)) and
                                                 not isinstance(x, bool) for x in data):
        yield path, data
    elif isinstance(data, list):
        for i, v in enumerate(data):
            yield from _leaves(v, path + (i,))
    else:
        yield path, data


def _mappings(data, path=()):
    if isinstance(data, dict):
        yield path, data
        for k, v in data.items():
            yield from _mappings(v, path + (k,))
    elif isinstance(data, list):
        for i, v in enumerate(data):
            yield from _mappings(v, path + (i,))


def _set(data, path, value):
    data = copy.deepcopy(data)
    ref = data
    for k in path[:-1]:
        ref = ref[k]
    ref[path[-1]] = value
    return data


NAN = float("nan")
INF = float("inf")


def _wrong_type(rng, value):
    """A value of a wrong type for ``value``'s key (always invalid)."""
    if isinstance(value, bool):
        pool = ["yes please", 1, None, [True]]
    elif isinstance(value, (int, float)):
        pool = ["abc", None, [1, 2], {"a": 1}, True, "1e3 m"]
    elif isinstance(value, str):
        pool = [123, None, [1, 2], {"a": 1}, 1.5]
    elif isinstance(value, list):
        pool = ["abc", None, 3.0, {"a": 1}]
    else:
        pool = ["abc", 1.0]
    return pool[rng.integers(len(pool))]


def _bad_vector(rng, vec):
    """A list of numbers with the wrong shape, a ragged nesting, a string or a non-finite."""
    options = [vec[:-1], vec + [0.0], [vec, [1.0]], "1, 2, 3", [NAN] + vec[1:],
               [INF] * len(vec), [str(v) for v in vec], []]
    if len(vec) == 1:
        options = options[1:]
    return options[rng.integers(len(options))]


_where: list = []     # the last mutated paths (for the failure report)

# vehicle-file keys that take any text (a mutation there proves nothing)
_FREE_KEYS = {"description"}


def mutate_mapping(rng, data, *, kind: str):
    """One structural mutation of a parsed document: (mutated data, kind, invalid)."""
    leaves = [(p, v) for p, v in _leaves(data) if not (set(p) & _FREE_KEYS)]
    choice = kind
    if choice == "type":
        p, v = leaves[rng.integers(len(leaves))]
        _where.append(p)
        return _set(data, p, _wrong_type(rng, v)), True
    if choice == "nonfinite":
        nums = [(p, v) for p, v in leaves if isinstance(v, (int, float, list))
                and not isinstance(v, bool)]
        p, v = nums[rng.integers(len(nums))]
        if isinstance(v, list):
            v = list(v)
            v[rng.integers(len(v))] = [NAN, INF, -INF][rng.integers(3)]
            return _set(data, p, v), True
        return _set(data, p, [NAN, INF, -INF][rng.integers(3)]), True
    if choice == "extreme":
        nums = [(p, v) for p, v in leaves if isinstance(v, (int, float)) and
                not isinstance(v, bool)]
        p, v = nums[rng.integers(len(nums))]
        new = [0, -1, -1e-9, 1e-30, 1e300, -1e300, 1e12, 1e-12, 7.5e6][rng.integers(9)]
        _where.append((p, new))
        return _set(data, p, new), False
    if choice == "shape":
        vecs = [(p, v) for p, v in leaves if isinstance(v, list)]
        if not vecs:
            return mutate_mapping(rng, data, kind="type")
        p, v = vecs[rng.integers(len(vecs))]
        return _set(data, p, _bad_vector(rng, list(v))), True
    if choice == "delete":
        maps = [(p, m) for p, m in _mappings(data) if m]
        p, m = maps[rng.integers(len(maps))]
        k = list(m)[rng.integers(len(m))]
        out = copy.deepcopy(data)
        ref = out
        for q in p:
            ref = ref[q]
        del ref[k]
        return out, False
    if choice == "unknown":
        maps = [(p, m) for p, m in _mappings(data)]
        p, _ = maps[rng.integers(len(maps))]
        out = copy.deepcopy(data)
        ref = out
        for q in p:
            ref = ref[q]
        ref["bogus_key_" + str(rng.integers(100))] = 1.0
        return out, True
    raise ValueError(choice)


def _dump_yaml(data) -> str:
    # PyYAML writes .nan/.inf for non-finite floats: exactly what a user could type
    return yaml.safe_dump(data, sort_keys=False, default_flow_style=None, width=200)


def _dump_json(data) -> str:
    return json.dumps(data)  # NaN / Infinity tokens for non-finite numbers


# ---------------------------------------------------------------------------
# text-level attacks
# ---------------------------------------------------------------------------

def alias_bomb() -> str:
    lines = ['hull: {profile: [{type: cylinder, x: [-0.5, 0.5], radius: 0.1}]}',
             'description: &a0 ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]']
    for i in range(1, 9):
        lines.append(f"a{i}: &a{i} [" + ",".join([f"*a{i - 1}"] * 9) + "]")
    return "\n".join(lines) + "\n"


def merge_bomb() -> str:
    """~70 kB: a mapping of 3,000 keys merged (``<<: *a``) into 5,000 mappings (1.5e7 nodes;
    55 s and 5.3 GB before the expansion was counted in true post-order, issue 36)."""
    big = "a: &a {" + ",".join(f"k{i}: 1" for i in range(3000)) + "}\n"
    return HULL + big + "b: [" + ",".join(["{<<: *a}"] * 5000) + "]\n"


def wide_bomb() -> str:
    """~100 kB: 20,000 references to one 5,000-item anchor, each in its own list."""
    seq = "a: &a [" + ",".join(["x"] * 5000) + "]\n"
    return HULL + seq + "b: [" + ",".join(["[*a]"] * 20000) + "]\n"


def recursive_alias(rng) -> str:
    return HULL + ["r: &r [1, *r]\n", "r: &r {a: *r}\n", "r: &r {<<: *r}\n"][rng.integers(3)]


def deep_yaml(depth=10_000) -> str:
    return "hull: " + "[" * depth + "]" * depth + "\n"


def deep_json(depth=100_000) -> str:
    return "[" * depth + "]" * depth


def garbage(rng, n=2000) -> bytes:
    return bytes(rng.integers(0, 256, n, dtype=np.uint8))


def truncate(rng, text):
    return text[: int(rng.integers(1, max(2, len(text) - 1)))]


# ---------------------------------------------------------------------------
# the generators, one per input family
# ---------------------------------------------------------------------------

HULL = ("hull:\n  profile:\n"
        "    - {type: ellipsoid_tail, x: [-0.75, -0.45], radius: 0.10}\n"
        "    - {type: cylinder, x: [-0.45, 0.55], radius: 0.10}\n"
        "    - {type: ellipsoid_nose, x: [0.55, 0.75], radius: 0.10}\nstrips: 200\n")
THRUSTER = "thrusters:\n  - {name: T, position: [-0.7, 0, 0], direction: [1, 0, 0], max_forward: 5}\n"

#: Named physical cases of the issue: (name, vehicle text, invalid)
PHYSICAL = [
    ("rudder behind the tail", HULL + "appendages:\n  - {name: r, type: fin, center: [-0.76, 0, 0],"
     " span_axis: z, span: 0.2, chord: 0.04}\n", False),
    ("boom 2 % longer than the hull", HULL + "appendages:\n  - {name: b, type: cylinder, axis: x,"
     " center: [0.0, 0, 0.1], diameter: 0.02, length: 1.53}\n", False),
    ("box appendage 10 km wide", HULL + "appendages:\n  - {name: b, type: box, center: [0, 0, 0],"
     " size: [0.1, 10000, 0.1]}\n", False),
    ("radius 1e12", HULL.replace("radius: 0.10}\n    - {type: ellipsoid_nose",
                                 "radius: 1.0e12}\n    - {type: ellipsoid_nose"), True),
    ("zero thruster direction", HULL + THRUSTER.replace("[1, 0, 0]", "[0, 0, 0]"), True),
    ("thruster position of 2 numbers", HULL + THRUSTER.replace("[-0.7, 0, 0]", "[-0.7, 0]"), True),
    ("ct a string", HULL + THRUSTER.replace("max_forward: 5", "ct: fast"), True),
    ("name a number", HULL + THRUSTER.replace("name: T", "name: 7"), True),
    ("max_forward null", HULL + THRUSTER.replace("max_forward: 5", "max_forward: null"), True),
    ("inertia violates the triangle inequality", HULL + "mass: {mass: 40, center_of_gravity: "
     "[0, 0, 0], inertia: [0.1, 5, 0.1]}\n", True),
    ("mass 1e-30 kg", HULL + "mass: {mass: 1.0e-30, center_of_gravity: [0, 0, 0], inertia: "
     "[1.0e-30, 1.0e-30, 1.0e-30]}\n", True),
    ("negative mass", HULL + "mass: {mass: -40}\n", True),
    ("density 1e-9", HULL + "fluid: {density: 1.0e-9, kinematic_viscosity: 1.0e-6}\n", True),
    ("water at -300 C", HULL + "fluid: {temperature: -300, salinity: 35}\n", True),
    ("water at 200 C", HULL + "fluid: {temperature: 200, salinity: 35}\n", True),
    ("viscosity zero", HULL + "fluid: {density: 1000, kinematic_viscosity: 0}\n", True),
    ("zone x with nan", HULL + "mass:\n  zones:\n    - {x: [.nan, 0.1], density: 1000}\n", True),
    ("Myring tail theta 720", "hull:\n  profile:\n    - {type: myring_tail, x: [-0.5, -0.2], "
     "radius: 0.1, theta_deg: 720}\n    - {type: cylinder, x: [-0.2, 0.5], radius: 0.1}\n"
     "strips: 200\n", True),
    ("reference point 1e300", HULL + "reference_point: [1.0e300, 0, 0]\n", True),
    ("duplicate key", HULL + "name: a\nname: b\n", True),
    # issue 36
    ("default_density alone", HULL + "mass: {default_density: 700}\n", False),
    ("default_density 0", HULL + "mass: {default_density: 0}\n", True),
    ("mass and default_density", HULL + "mass: {mass: 30, default_density: 700}\n", True),
    ("zone outside the body", HULL + "mass:\n  zones:\n    - {name: far, x: [5, 6], "
     "density: 900}\n", True),
    ("zone narrower than a strip", HULL + "mass:\n  zones:\n    - {name: thin, x: [0.0001, "
     "0.0002], density: 900}\n", True),
    ("massless zones", HULL + "mass:\n  default_density: 500\n  zones:\n    - {x: [-0.8, "
     "0.8], density: 0}\n", True),
    ("open frame along z", HULL + "appendages:\n  - {name: f, type: cylinder, axis: z, center: "
     "[0, 0, 0.3], diameter: 0.02, length: 0.5, inner_diameter: 0.018}\n", False),
]


def vehicle_case(rng, bases: Bases) -> Case:
    name = list(bases.vehicles)[rng.integers(len(bases.vehicles))]
    text = bases.vehicles[name]
    data = yaml.safe_load(text)
    r = rng.random()
    if r < 0.62:
        kind = ["type", "nonfinite", "extreme", "shape", "delete", "unknown"][rng.integers(6)]
        _where.clear()
        data, invalid = mutate_mapping(rng, data, kind=kind)
        content = _dump_yaml(data)
        kind = "vehicle:" + kind + (f"@{_where[-1]}" if _where else "")
    elif r < 0.82:
        pname, content, invalid = PHYSICAL[rng.integers(len(PHYSICAL))]
        kind = "vehicle:physical:" + pname
    else:
        attack = ["alias bomb", "deep nesting", "truncated", "garbage", "empty", "not a mapping",
                  "tabs", "NUL byte", "control character", "undecodable bytes",
                  "recursive alias", "merge-key bomb", "wide alias bomb"][rng.integers(13)]
        content, invalid = {
            "NUL byte": (HULL + "name: a\x00b\n", True),
            "control character": (HULL + "name: a\x07b\n", True),
            "undecodable bytes": (HULL.encode() + b"name: \xff\xfe\n", True),
            "recursive alias": (recursive_alias(rng), True),
            "merge-key bomb": (merge_bomb(), True),
            "wide alias bomb": (wide_bomb(), True),
            "alias bomb": (alias_bomb(), True),
            "deep nesting": (deep_yaml(), True),
            "truncated": (truncate(rng, text), False),
            "garbage": (garbage(rng), True),
            "empty": ("", True),
            "not a mapping": ("- 1\n- 2\n", True),
            "tabs": (text.replace("  ", "\t", 3), False),
        }[attack]
        kind = "vehicle:" + attack
    command = ["coefficients", "coefficients", "coefficients", "limits", "export",
               "simulate"][rng.integers(6)]
    files = {"v.yaml": content}
    if command == "coefficients":
        argv = ["coefficients", "{d}/v.yaml", *(["--json"] if rng.random() < 0.5 else []),
                "-o", "{d}/out.json"]
        outs = ("out.json",)
    elif command == "limits":
        argv = ["limits", "{d}/v.yaml", "--json", "--radii", "1:10:5"]
        outs = ()
        invalid = invalid or "thrusters" not in content
    elif command == "export":
        fmt = ["gazebo", "uuv", "mss", "python", "json", "yaml", "csv", "npz"][rng.integers(8)]
        ext = {"python": "py", "mss": "m", "gazebo": "sdf", "uuv": "yaml"}.get(fmt, fmt)
        argv = ["export", "{d}/v.yaml", "--to", fmt, "-o", f"{{d}}/out_model.{ext}"]
        outs = (f"out_model.{ext}",)
    else:
        files["in.csv"] = bases.inputs
        argv = ["simulate", "{d}/v.yaml", "--inputs", "{d}/in.csv", "--out", "{d}/out.csv"]
        outs = ("out.csv",)
        invalid = invalid or "thrusters" not in content  # the inputs command thrusters
    return Case(command, kind, argv, files, invalid, outs)


def _put(*path_value):
    *path, value = path_value

    def edit(d):
        node = d
        for k in path[:-1]:
            node = node[k]
        node[path[-1]] = value
    return edit


#: (name, edit) of a model file's parts that are invalid (issue 36)
MODEL_PARTS = [
    ("gravity nan", _put("gravity", NAN)), ("gravity 0", _put("gravity", 0)),
    ("gravity negative", _put("gravity", -9.81)),
    ("thrusters: position of 2 numbers", _put("thrusters", 0, "position", [1.0, 2.0])),
    ("thrusters: direction zeros", _put("thrusters", 0, "direction", [0, 0, 0])),
    ("thrusters: direction nan", _put("thrusters", 0, "direction", [NAN, 0, 0])),
    ("thrusters: ct_forward a string", _put("thrusters", 0, "ct_forward", "fast")),
    ("thrusters: ct_forward -1", _put("thrusters", 0, "ct_forward", -1)),
    ("thrusters: empty name", _put("thrusters", 0, "name", "")),
    ("effects a string", _put("effects", "tether_drag")),
    ("effect parameter a string", _put("effects", [{"name": "tether_drag", "dof": "surge",
                                                    "parameters": {"c_t": "abc"}}])),
    ("effect on DOF 7", _put("effects", [{"name": "tether_drag", "dof": 7,
                                          "parameters": {"c_t": 1.0}}])),
    ("kinematic viscosity negative", _put("kinematic_viscosity", -1e-6)),
]


def model_case(rng, bases: Bases) -> Case:
    name = list(bases.models)[rng.integers(len(bases.models))]
    as_json = rng.random() < 0.6
    data = json.loads(bases.model_json[name])
    r = rng.random()
    if r < 0.45:
        mats = ["added_mass", "linear_damping", "quadratic_damping", "rigid_body_mass"]
        key = mats[rng.integers(4)]
        i, j = int(rng.integers(6)), int(rng.integers(6))
        sub = ["entry type", "entry nan", "row dropped", "negative diagonal", "scalar",
               "missing key", "not positive definite", "huge"][rng.integers(8)]
        invalid = True
        if sub == "entry type":
            data[key][i][j] = ["abc", None, [1], {}][rng.integers(4)]
        elif sub == "entry nan":
            data[key][i][j] = [NAN, INF][rng.integers(2)]
        elif sub == "row dropped":
            data[key] = data[key][:-1]
        elif sub == "negative diagonal":
            key = ["linear_damping", "quadratic_damping"][rng.integers(2)]
            data[key][i][i] = -abs(data[key][i][i]) - 1.0
        elif sub == "scalar":
            k = ["mass", "volume", "density"][rng.integers(3)]
            data[k] = [0, -1, "heavy", None, NAN][rng.integers(5)]
        elif sub == "missing key":
            del data[["added_mass", "mass", "reference_point", "center_of_gravity"][
                rng.integers(4)]]
        elif sub == "not positive definite":
            data["rigid_body_mass"][3][3] = -1.0
        else:
            data[key] = (np.asarray(data[key]) * 1e300).tolist()
            invalid = False
        kind = "model:" + sub
        content = _dump_json(data) if as_json else _dump_yaml(data)
    elif r < 0.75:
        # issue 36: the parts beside the matrices, validated like a vehicle file
        sub, edit = MODEL_PARTS[rng.integers(len(MODEL_PARTS))]
        if name != "mares" and "thrusters" in sub and not data.get("thrusters"):
            sub, edit = MODEL_PARTS[0]
        edit(data)
        kind, invalid = "model:" + sub, True
        content = _dump_json(data) if as_json else _dump_yaml(data)
    elif r < 0.85:
        kind, content, invalid = "model:reference point far", None, False
        data["reference_point"] = [1e300, 0.0, 0.0]
        content = _dump_json(data) if as_json else _dump_yaml(data)
    else:
        attack = ["deep", "truncated", "garbage", "not an object"][rng.integers(4)]
        kind, invalid = "model:" + attack, True
        text = bases.model_json[name] if as_json else bases.model_yaml[name]
        content = {"deep": deep_json() if as_json else deep_yaml(),
                   "truncated": truncate(rng, text)[:-2], "garbage": garbage(rng),
                   "not an object": "[1, 2, 3]"}[attack]
    fname = "m.json" if as_json else "m.yaml"
    command = ["export", "export", "simulate", "limits", "diagnose"][rng.integers(5)]
    files = {fname: content}
    if command == "export":
        fmt = ["gazebo", "uuv", "mss", "python", "json", "yaml", "csv", "npz"][rng.integers(8)]
        ext = {"python": "py", "mss": "m", "gazebo": "sdf", "uuv": "yaml"}.get(fmt, fmt)
        argv = ["export", "{d}/" + fname, "--to", fmt, "-o", f"{{d}}/out_model.{ext}"]
        outs = (f"out_model.{ext}",)
    elif command == "simulate":
        files["in.csv"] = bases.inputs if name == "mares" else \
            "t,X,N\n" + "".join(f"{0.1 * k:.1f},{5.0},{0.1}\n" for k in range(100))
        argv = ["simulate", "{d}/" + fname, "--inputs", "{d}/in.csv", "--out", "{d}/out.csv"]
        outs = ("out.csv",)
    elif command == "limits":
        argv = ["limits", "{d}/" + fname, "--json", "--radii", "1:10:4"]
        outs = ()
    else:
        files["log.csv"] = bases.diag_log
        argv = ["diagnose", "{d}/log.csv", "--vehicle", "{d}/" + fname, "--no-resimulate",
                "--json", "--out", "{d}/cal.yaml"]
        outs = ("cal.yaml",)
    return Case(command, kind, argv, files, invalid, outs)


def _csv_mutation(rng, text, needed):
    """A mutated log: (text, kind, invalid). ``needed``: columns the command cannot do without."""
    lines = text.splitlines()
    header = lines[0].split(",")
    rows = lines[1:]
    sub = ["nan cell", "text cell", "10 MB cell", "one row", "header only", "empty",
           "1e300 column", "drop needed column", "ragged row", "duplicate time", "shuffled",
           "duplicate header", "inf cell", "garbage", "huge log", "nanosecond time",
           "millisecond time"][rng.integers(17)]
    if sub == "huge log" and rng.random() < 0.75:      # ~20 s each: a quarter as often
        return _csv_mutation(rng, text, needed)
    col = int(rng.integers(len(header)))
    k = int(rng.integers(len(rows)))
    invalid = True
    if sub in ("nan cell", "text cell", "inf cell", "10 MB cell"):
        cells = rows[k].split(",")
        cells[col] = {"nan cell": "nan", "text cell": "abc", "inf cell": "-inf",
                      "10 MB cell": "9" * 10_000_000}[sub]
        rows[k] = ",".join(cells)
    elif sub == "one row":
        rows = rows[:1]
        invalid = True
    elif sub == "header only":
        rows = []
    elif sub == "empty":
        return "", sub, True
    elif sub == "1e300 column":
        rows = [",".join("1e300" if j == col else c for j, c in enumerate(r.split(",")))
                for r in rows]
        invalid = True      # constant time, or a magnitude no vehicle log has (issue 36)
    elif sub == "drop needed column":
        cands = [h for h in header if h in needed]
        if not cands:
            return _csv_mutation(rng, text, needed)
        drop = header.index(cands[rng.integers(len(cands))])
        header = [h for j, h in enumerate(header) if j != drop]
        rows = [",".join(c for j, c in enumerate(r.split(",")) if j != drop) for r in rows]
    elif sub == "ragged row":
        rows[k] = rows[k] + ",1.0"
    elif sub == "duplicate time":
        if "t" not in header:
            return _csv_mutation(rng, text, needed)
        rows.insert(k, rows[k])
    elif sub == "shuffled":
        if "t" not in header:
            return _csv_mutation(rng, text, needed)
        rows = [rows[i] for i in rng.permutation(len(rows))]
    elif sub == "duplicate header":
        header[col] = header[(col + 1) % len(header)]
    elif sub == "garbage":
        return garbage(rng), sub, True
    elif sub in ("nanosecond time", "millisecond time"):
        if "t" not in header or len(rows) < 100:
            return _csv_mutation(rng, text, needed)
        j = header.index("t")
        out = []
        for r in rows:
            cells = r.split(",")
            t = float(cells[j])
            cells[j] = repr(t * 1e-9) if sub == "nanosecond time" else str(round(t * 1000))
            out.append(",".join(cells))
        rows = out
    elif sub == "huge log":
        if "t" not in header:
            return _csv_mutation(rng, text, needed)
        # 200k rows: the inputs jump at every row (a stiff restart at every sample)
        n = 200_000
        t = np.arange(n) * 0.01
        cols = [t] + [np.where(np.arange(n) % 2, 1.0, -1.0) for _ in header[1:]]
        body = "\n".join(",".join(f"{c[i]:.6g}" for c in cols) for i in range(n))
        return ",".join(header) + "\n" + body + "\n", sub, False
    return ",".join(header) + "\n" + "\n".join(rows) + "\n", sub, invalid


def log_case(rng, bases: Bases) -> Case:
    from validation.experiments import ROV2_BUOYANCY, ROV2_LENGTH, ROV2_MASS
    which = ["steady", "one-step", "pendulum", "torsion", "diagnose", "simulate"][rng.integers(6)]
    if which == "steady":
        text, needed = bases.steady, ("w", "Z")
        argv = ["identify", "{d}/log.csv", "--method", "steady", "--dof", "heave", "--json",
                "-o", "{d}/out.json"]
    elif which == "one-step":
        text, needed = bases.yaw, ("t", "r", "N")
        argv = ["identify", "{d}/log.csv", "--method", "one-step", "--dof", "yaw", "--json",
                "-o", "{d}/out.json"]
    elif which == "pendulum":
        text, needed = bases.pend, ("t", "theta_pendulum")
        argv = ["identify", "{d}/log.csv", "--method", "pendulum", "--mass", str(ROV2_MASS),
                "--buoyancy", str(ROV2_BUOYANCY), "--length", str(ROV2_LENGTH), "--json",
                "-o", "{d}/out.json"]
    elif which == "torsion":
        text, needed = bases.tors, ("t",)
        argv = ["identify", "{d}/log.csv", "--method", "torsion", "--stiffness", "0.05",
                "--inertia", "0.012", "--json", "-o", "{d}/out.json"]
    elif which == "diagnose":
        text, needed = bases.diag_log, ("t", "u")
        argv = ["diagnose", "{d}/log.csv", "--vehicle", "{d}/prior.yaml", "--dof", "surge",
                "--no-resimulate", "--json", "--out", "{d}/out.json"]
    else:
        text, needed = bases.inputs, ("t", "n_P1", "n_P2", "n_V1", "n_V2")
        argv = ["simulate", "geometry/mares.yaml", "--inputs", "{d}/log.csv", "--out",
                "{d}/out.json"]
        argv[1] = str(ROOT / "geometry" / "mares.yaml")
    content, sub, invalid = _csv_mutation(rng, text, needed)
    files = {"log.csv": content}
    if which == "diagnose":
        files["prior.yaml"] = bases.diag_prior
    command = "identify" if which in ("steady", "one-step", "pendulum", "torsion") else which
    return Case(command, f"log:{which}:{sub}", argv, files, invalid, ("out.json",))


#: A column map of a yaw log in chunk files and a second stream with its own clock
#: (issue 33): the navigation's chunks in nav/, the commands' stream aligned to it by the yaw
#: rate both record.
CHUNK_MAP = """\
streams:
  nav: {file: %(nav)s, time: {column: t%(retime)s}}
  cmd:
    file: cmd.csv
    time: {column: t}
    align: %(align)s
rates: {stream: nav, columns: [null, null, r]}
wrench: {stream: cmd, columns: [null, null, null, null, null, N]}
output: {rate: 30}
"""
CHUNK_OFFSET = 0.4       # the command logger's clock behind the navigation's [s]


def chunk_case(rng, bases: Bases) -> Case:
    """A yaw log as users have it (issue 33): chunk files named out of time order with
    overlaps, a command stream with a clock offset, and mutations of each part."""
    log = read_log_text(bases.yaw)
    t, r, n = (log[k].tolist() for k in ("t", "r", "N"))      # Python floats: repr is a number
    t_arr = np.asarray(t)
    sub = ["valid", "offset given", "glob", "nothing matches", "backwards in a chunk",
           "unknown align stream", "uncorrelated signal", "offset beyond max",
           "header-only chunk", "bursty receive times", "retime without column",
           "chunk of other columns"][rng.integers(12)]
    invalid = sub not in ("valid", "offset given", "glob", "bursty receive times")
    cuts = np.sort(rng.choice(np.arange(50, t_arr.size - 50), 3, replace=False)).tolist()
    bounds = [0, *cuts, t_arr.size]
    names = [f"nav/part_{c}.csv" for c in "dbca"]
    files = {}
    for i, (a, b) in enumerate(zip(bounds[:-1], bounds[1:])):
        a = max(0, a - int(rng.integers(0, 6))) if i else a          # overlapping rows
        rows = [f"{t[k]!r},{r[k]!r}" for k in range(a, b)]
        if sub == "backwards in a chunk" and i == 1:
            rows[2], rows[3] = rows[3], rows[2]
        files[names[i]] = "t,r\n" + "\n".join(rows) + "\n"
    if sub == "header-only chunk":
        files[names[2]] = "t,r\n"
    if sub == "chunk of other columns":
        files[names[3]] = files[names[3]].replace("t,r", "t,q")
    if sub == "bursty receive times":        # one file, stamps of bursts of 1-5 samples
        recv = t_arr.copy()
        k = 0
        while k < recv.size:
            m = int(rng.integers(1, 6))
            recv[k:k + m] = t_arr[min(k + m, recv.size) - 1]
            k += m
        recv = recv.tolist()
        files = {"nav/all.csv": "t,r\n" + "\n".join(f"{a!r},{b!r}" for a, b in zip(recv, r))
                 + "\n"}
    echo = rng.standard_normal(len(t)).tolist() if sub == "uncorrelated signal" else r
    files["cmd.csv"] = "t,N,r_echo\n" + "\n".join(
        f"{a - CHUNK_OFFSET!r},{b!r},{c!r}" for a, b, c in zip(t, n, echo)) + "\n"
    align = {"unknown align stream": "{to: dvl, signal: [r_echo, r]}",
             "offset beyond max": "{to: nav, signal: [r_echo, r], max: 0.1}",
             "offset given": f"{{offset: {CHUNK_OFFSET}}}"}.get(
        sub, "{to: nav, signal: [r_echo, r], max: 2}")
    files["map.yaml"] = CHUNK_MAP % {
        "nav": {"glob": "nav/part_*.csv", "nothing matches": "nav/x_*.csv"}.get(sub, "nav"),
        "retime": {"bursty receive times": ", retime: true"}.get(sub, ""), "align": align}
    if sub == "retime without column":
        files["map.yaml"] = files["map.yaml"].replace("{column: t}}", "{rate: 30, "
                                                      "retime: true}}")
    argv = ["identify", "{d}/nav", "--map", "{d}/map.yaml", "--method", "one-step", "--dof",
            "yaw", "--json", "-o", "{d}/out.json"]
    return Case("identify", f"chunks:{sub}", argv, files, invalid, ("out.json",))


def read_log_text(text):
    """A log from CSV text (the bases hold text)."""
    import tempfile

    from stripcoef.logfile import read_log

    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "log.csv"
        p.write_text(text)
        return read_log(p)


def mesh_case(rng, bases: Bases) -> Case:
    import trimesh
    sub = ["truncated", "garbage", "empty", "open", "nan vertex", "degenerate", "huge",
           "two intersecting bodies", "hull again as appendage", "transform a string",
           "transform ragged", "tiny", "options", "open frame"][rng.integers(14)]
    files, invalid, extra = {}, True, []
    box = trimesh.creation.box(extents=(1.0, 0.3, 0.2))
    name = "m.stl"
    if sub == "truncated":
        files[name] = bases.mesh_capsule_stl[: int(rng.integers(10, len(bases.mesh_capsule_stl)))]
    elif sub == "garbage":
        files[name] = garbage(rng)
    elif sub == "empty":
        files[name] = b""
    elif sub == "open":
        m = bases.mesh_capsule.copy()
        m.update_faces(np.arange(len(m.faces)) > 3)
        files[name] = m.export(file_type="stl")
        invalid = False
    elif sub == "nan vertex":
        name = "m.obj"
        files[name] = bases.mesh_obj.replace("v 0.5", "v nan", 1)
    elif sub == "degenerate":
        m = box.copy()
        m.vertices[:] = 0.0
        files[name] = m.export(file_type="stl")
    elif sub == "huge":
        m = bases.mesh_capsule.copy()
        m.apply_scale(1e12)
        files[name] = m.export(file_type="stl")
        invalid = False
    elif sub == "tiny":
        m = bases.mesh_capsule.copy()
        m.apply_scale(1e-9)
        files[name] = m.export(file_type="stl")
        invalid = False
    elif sub == "two intersecting bodies":
        b2 = box.copy()
        b2.apply_translation([0.3, 0.1, 0.05])
        files[name] = trimesh.util.concatenate([box, b2]).export(file_type="stl")
        invalid = False
    elif sub in ("hull again as appendage", "transform a string", "transform ragged"):
        files["hull.stl"] = bases.mesh_capsule_stl
        transform = {"hull again as appendage": "",
                     "transform a string": ", transform: rotate",
                     "transform ragged": ", transform: [[1, 0, 0], [0, 1], [0, 0, 1, 0]]"}[sub]
        files["v.yaml"] = (HULL + "appendages:\n  - {name: m, type: mesh, mesh: hull.stl"
                           + transform + "}\n")
        invalid = sub != "hull again as appendage"
        name = "v.yaml"
    elif sub == "open frame":
        # an open frame of 12 bars; along z its correction factor once went negative
        files[name] = bases.frame_stl()
        axis = ["x", "y", "z"][rng.integers(3)]
        extra, invalid, sub = ["--axis", axis], False, f"open frame --axis {axis}"
    else:  # mesh options
        files[name] = bases.mesh_capsule_stl
        opt = [["--origin", "nan,0,0"], ["--origin", "1,2"], ["--origin", "1e300,0,0"],
               ["--axis", "w"], ["--length-unit", "km"], ["--strips", "30000000"],
               ["--strips", "2"], ["--axis", "z"]][rng.integers(8)]
        extra = opt
        invalid = opt not in (["--origin", "1e300,0,0"], ["--axis", "z"])
        sub = "options " + " ".join(opt)
    argv = ["coefficients", "{d}/" + name, "--json", "--strips", "60", *extra,
            "-o", "{d}/out.json"]
    if "--strips" in extra:
        argv = ["coefficients", "{d}/" + name, "--json", *extra, "-o", "{d}/out.json"]
    return Case("coefficients", "mesh:" + sub, argv, files, invalid, ("out.json",))


#: (command, extra argv, invalid): options with bad values
OPTIONS = {
    "coefficients": [(["--strips", v], True) for v in ("0", "3", "-1", "30000000", "abc", "1e3")]
    + [(["--speed", v], True) for v in ("0", "-1", "nan", "inf", "-inf")]
    + [(["--speed", "1e300"], False), (["--speed", "1e-300"], False)]
    + [(["--reference-point", v], True) for v in ("nan,0,0", "1,2", "a,b,c", "inf,0,0")]
    + [(["--reference-point", "1e300,0,0"], False), (["--reference-point", "origin"], False)]
    + [(["--reference-point", ""], True)]
    + [(["--rho", v], True) for v in ("0", "-1", "nan", "inf")] + [(["--rho", "1e-9"], False)]
    + [(["--nu", v], True) for v in ("0", "-1e-6", "nan")]
    + [(["--water-temperature", t, "--salinity", s], inv) for t, s, inv in
       (("-300", "35", True), ("200", "35", True), ("nan", "35", True), ("20", "-5", True),
        ("20", "35", False), ("45", "35", False))]
    + [(["--water-temperature", "20"], True), (["--regime", "bogus"], True),
       (["-o", "{d}"], True), (["-o", "."], True), (["-o", "./"], True),
       (["-o", "{d}/missing/x.json"], True), (["--json", "--yaml"], True)],
    "limits": [(["--radii", v], True) for v in ("1:20:100000", "0:5:3", "5:1:3", "a", "1:2",
                                                 "nan:2:3", "1:inf:3", "1:2:-1", "1:2:0")]
    + [(["--radii", "1:1e300:3"], False), (["--radii", "1e-9:1e-8:2"], False)]
    + [(["--turn-speed", v], True) for v in ("0", "-1", "nan", "inf")]
    + [(["--plot", v], True) for v in ("{d}", ".", "{d}/no/p.png")],
    "export": [(["--to", v], True) for v in ("bogus", "")]
    + [(["--to", "gazebo", "--point", v], True) for v in ("abc", "1,2", "nan,0,0")]
    + [(["--to", "gazebo", "--point", "1e300,0,0"], False)]
    + [(["--to", "json", "--axes", "XYZ"], True), (["--to", "uuv", "--point", "CB"], True),
       (["--to", "gazebo", "--link", "a b"], True), (["--to", "npz"], True),
       (["--to", "json", "-o", "{d}"], True), (["--to", "json", "-o", "."], True),
       (["--to", "csv", "--link", "x"], True)],
    "simulate": [(["--rtol", v], True) for v in ("0", "-1", "nan", "inf", "10", "1e-300")]
    + [(["--dt", v], True) for v in ("0", "-1", "nan", "inf", "1e-12")]
    + [(["--current", v], True) for v in ("1e6,0,0", "a,b", "1,2", "nan,0,0", "inf,0,0")]
    + [(["--current", "0.5,0,0"], False), (["--dt", "0.5"], False), (["--rtol", "1e-3"], False)]
    + [(["--interpolation", "cubic"], True), (["--out", "{d}"], True)],
    "identify": [(["--method", "steady", "--dof", "heave", "--settle", v], True)
                 for v in ("-1", "nan", "inf")]
    + [(["--method", "steady", "--dof", "heave", "--trim", "-1"], True)]
    + [(["--method", "steady", "--dof", "heave", "--trim", "1000000000"], False)]  # a table: no-op
    + [(["--method", "steady", "--dof", v], True) for v in ("bogus", "")]
    + [(["--method", "one-step", "--dof", "yaw", "--inertia", v], True)
       for v in ("0", "-1", "nan", "inf")]
    + [(["--method", "pendulum", "--mass", m, "--buoyancy", "1", "--length", "1"], True)
       for m in ("0", "-1", "nan")]
    + [(["--method", "torsion", "--stiffness", v, "--inertia", "0.012"], True)
       for v in ("0", "-1", "nan", "inf")]
    + [(["--method", "pendulum", "--window", v], True) for v in ("0", "-1", "1", "100000000")]
    + [(["--method", "pendulum", "--order", v], True) for v in ("-1", "0", "1000")]
    + [(["--method", "bogus"], True), (["--method", "one-step", "--plot", "{d}"], True)],
    "diagnose": [(["--window", v], True) for v in ("0", "-1", "nan", "inf", "1e9", "1e-6")]
    + [(["--dof", "bogus"], True), (["--effects", "bogus"], True),
       (["--report", "{d}"], True), (["--out", "."], True)],
    # compare: the cases that must fail before the BEM starts (the BEM itself takes minutes)
    "compare": [(["--strips", v], True) for v in ("0", "30000000")]
    + [(["--max-faces", v], True) for v in ("0", "-5")]
    + [(["--speed", v], True) for v in ("0", "nan")]
    + [(["--rho", "-1"], True), (["--origin", "1,2"], True), (["-o", "{d}"], True),
       (["--garbage-mesh"], True)],
    "scale": [(["--ratio", v], True) for v in ("0", "-1", "nan", "inf")]
    + [(["--ratio", "1e300"], False), (["-o", "{d}"], True)],
}


def option_case(rng, bases: Bases) -> Case:
    command = list(OPTIONS)[rng.integers(len(OPTIONS))]
    extra, invalid = OPTIONS[command][rng.integers(len(OPTIONS[command]))]
    files = {}
    mares = str(ROOT / "geometry" / "mares.yaml")
    if command == "coefficients":
        files["v.yaml"] = bases.vehicles["mares.yaml"]
        argv = ["coefficients", "{d}/v.yaml", *extra]
    elif command == "limits":
        files["m.json"] = bases.model_json["mares"]
        argv = ["limits", "{d}/m.json", *extra]
    elif command == "export":
        files["m.json"] = bases.model_json["mares"]
        argv = ["export", "{d}/m.json", *extra]
    elif command == "simulate":
        files["m.json"] = bases.model_json["mares"]
        files["in.csv"] = bases.inputs
        argv = ["simulate", "{d}/m.json", "--inputs", "{d}/in.csv", *extra]
        if "--out" not in extra:
            argv += ["--out", "{d}/out.csv"]
    elif command == "identify":
        log = {"steady": bases.steady, "one-step": bases.yaw, "pendulum": bases.pend,
               "torsion": bases.tors}.get(extra[1], bases.yaw)
        files["log.csv"] = log
        argv = ["identify", "{d}/log.csv", *extra]
    elif command == "diagnose":
        files["log.csv"] = bases.diag_log
        files["prior.yaml"] = bases.diag_prior
        argv = ["diagnose", "{d}/log.csv", "--vehicle", "{d}/prior.yaml", "--no-resimulate",
                *extra]
    elif command == "compare":
        if extra == ["--garbage-mesh"]:
            files["m.stl"], extra = garbage(rng), []
        else:
            files["m.stl"] = bases.mesh_capsule_stl
        argv = ["compare", "{d}/m.stl", *extra]
    else:
        files["r.json"] = bases.pendulum_result()
        argv = ["scale", "{d}/r.json", *extra]
    del mares
    return Case(command, f"option:{command}:{' '.join(extra)}", argv, files, invalid,
                ("out.csv", "out.json", "p.png"))


def result_case(rng, bases: Bases) -> Case:
    """``scale`` on mutated identification results."""
    data = json.loads(bases.pendulum_result())
    r = rng.random()
    if r < 0.7:
        # the parameters are what scale reads: a wrong type or a non-finite one is invalid;
        # a parameter deleted or added may leave a scalable result
        kind = ["type", "nonfinite", "delete", "unknown"][rng.integers(4)]
        data["parameters"], invalid = mutate_mapping(rng, data["parameters"], kind=kind)
        if kind in ("delete", "unknown"):
            invalid = False
        content = _dump_json(data)
    else:
        kind = ["deep", "garbage", "empty", "list", "no method or dof"][rng.integers(5)]
        if kind == "no method or dof":
            data.pop("method", None)
            data.pop("dof", None)
        content = {"deep": deep_json(), "garbage": garbage(rng), "empty": "",
                   "list": "[1, 2]", "no method or dof": _dump_json(data)}[kind]
        invalid = True
    return Case("scale", "result:" + kind, ["scale", "{d}/r.json", "--ratio", "3.3", "--json",
                                            "-o", "{d}/out.json"],
                {"r.json": content}, invalid, ("out.json",))


GENERATORS = {"vehicle": (vehicle_case, 0.40), "model": (model_case, 0.17),
              "log": (log_case, 0.17), "mesh": (mesh_case, 0.08),
              "options": (option_case, 0.15), "result": (result_case, 0.03),
              "chunks": (chunk_case, 0.04)}
# (compare runs the BEM on valid input; only its failing cases are in the options family)


def generate_cases(n: int, seed: int, bases: Bases, *, families=None) -> list[Case]:
    rng = np.random.default_rng(seed)
    fams = families or list(GENERATORS)
    weights = np.array([GENERATORS[f][1] for f in fams])
    weights /= weights.sum()
    out = []
    for _ in range(n):
        fam = fams[rng.choice(len(fams), p=weights)]
        out.append(GENERATORS[fam][0](rng, bases))
    return out


# ---------------------------------------------------------------------------
# running and classifying
# ---------------------------------------------------------------------------

class _Hang(BaseException):
    pass


def _alarm(signum, frame):
    raise _Hang()


_NONFINITE = re.compile(r"(?<![A-Za-z_])(nan|inf|infinity)(?![A-Za-z_])", re.IGNORECASE)
_ERROR = re.compile(r"^stripcoef (\w+): error: (.+)$")


def _non_finite_text(text: str) -> bool:
    return bool(_NONFINITE.search(text))


def _npz_non_finite(path: Path) -> bool:
    with np.load(path, allow_pickle=False) as z:
        return any(z[k].dtype.kind in "fc" and not np.all(np.isfinite(z[k])) for k in z.files)


def classify_error(command: str, stderr: str) -> str:
    lines = [ln for ln in stderr.strip().splitlines() if not ln.startswith("warning:")]
    if len(lines) != 1:
        return "multi-line error"
    line = lines[0]
    if line.startswith("stripcoef") and ": error: argument " in line:
        return "clean error"          # argparse: names the option and the value
    if re.match(r"^stripcoef( \w+)?: error: ", line) and "the following arguments" in line:
        return "clean error"
    m = _ERROR.match(line)
    if not m:
        return "vague error"
    body = m.group(2)
    # WHERE: what; got VALUE; expected WHAT -- where and expected are required (a missing key
    # or file has no value to show)
    if ": " not in body or not ("expected" in body or "got" in body):
        return "vague error"
    return "clean error"


def run_case(case: Case, folder: Path, *, limit: float = CASE_LIMIT) -> tuple[str, str]:
    """Run one case in ``folder``; returns (outcome, detail)."""
    from stripcoef.cli import main

    for name, content in case.files.items():
        p = folder / name
        p.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, bytes):
            p.write_bytes(content)
        else:
            p.write_text(content)
    argv = [a.replace("{d}", str(folder)) for a in case.argv]
    before = {p.name: p.read_bytes() for p in folder.iterdir() if p.is_file()}
    out, err = io.StringIO(), io.StringIO()
    from stripcoef.cli import app
    raised = []
    in_cli_terms = app.in_cli_terms

    def spy(exc, parser):          # the type of the error main prints
        raised.append(type(exc).__name__)
        return in_cli_terms(exc, parser)
    app.in_cli_terms = spy
    old = signal.signal(signal.SIGALRM, _alarm)
    old_prof = signal.signal(signal.SIGPROF, _alarm)
    signal.setitimer(signal.ITIMER_PROF, limit)            # CPU time of the process
    signal.setitimer(signal.ITIMER_REAL, WALL_FACTOR * limit)
    rc = None
    showwarning = warnings.showwarning
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), \
                warnings.catch_warnings():
            warnings.simplefilter("default")
            try:
                rc = main(argv)
            except SystemExit as exc:                      # argparse
                rc = exc.code if isinstance(exc.code, int) else 2
    except _Hang:
        return "hang", f"over {limit:g} s of CPU time or {WALL_FACTOR * limit:g} s of wall time"
    except Exception as exc:  # noqa: BLE001 - the point: anything escaping is a traceback
        frames = traceback.extract_tb(exc.__traceback__)
        ours = [f for f in frames if "stripcoef" in f.filename]
        tb = (ours or frames)[-1]
        return "traceback", f"{type(exc).__name__}: {str(exc)[:120]} ({Path(tb.filename).name}:{tb.lineno})"
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGALRM, old)
        signal.signal(signal.SIGPROF, old_prof)
        warnings.showwarning = showwarning
        app.in_cli_terms = in_cli_terms
    stdout, stderr = out.getvalue(), err.getvalue()
    after = {p.name: p for p in folder.iterdir() if p.is_file()}
    leftovers = [p.name for p in folder.iterdir() if p.name.endswith(".tmp")]
    if leftovers:
        return "partial output", f"temporary file left: {leftovers[0]}"
    if rc != 0:
        changed = [n for n in after if n not in case.files and
                   (n not in before or after[n].read_bytes() != before[n])]
        if changed:
            return "partial output", f"exit {rc} but wrote {changed[0]}"
        if stdout.strip():
            return "partial output", f"exit {rc} but printed {stdout.strip()[:60]!r}"
        kind = classify_error(case.command, stderr)
        if kind == "vague error" and raised == ["UnreachableError"] and \
                re.search(r"error: [^:]+: .*\d", stderr):
            kind = "not reachable"
        return kind, stderr.strip().splitlines()[-1][:200] if stderr.strip() else "(no message)"
    # exit 0
    if case.invalid:
        return "exit 0 on invalid", stdout.strip()[:80]
    if _non_finite_text(stdout):
        return "exit 0 non-finite", "stdout: " + _NONFINITE.search(stdout).group(0)
    for n, p in after.items():
        if n in case.files:
            continue
        if n.endswith(".npz"):
            if _npz_non_finite(p):
                return "exit 0 non-finite", n
        elif n.endswith(".png"):
            continue
        else:
            text = p.read_text(errors="replace")
            if _non_finite_text(text):
                return "exit 0 non-finite", f"{n}: {_NONFINITE.search(text).group(0)}"
    return "ok", ""


def run_campaign(cases, *, limit: float = CASE_LIMIT, progress=None):
    """Run ``cases``; returns (counts per command and outcome, list of bad (case, detail))."""
    import stripcoef.diagnose.pipeline as diag
    import stripcoef.simulate as sim
    sim.TIME_LIMIT = diag.TIME_LIMIT = BUDGET
    counts = defaultdict(Counter)
    seconds = Counter()
    bad = []
    with tempfile.TemporaryDirectory(prefix="fuzz") as root:
        for k, case in enumerate(cases):
            folder = Path(root, f"c{k}")
            folder.mkdir()
            cwd = os.getcwd()
            t0 = time.monotonic()
            try:
                outcome, detail = run_case(case, folder, limit=limit)
            finally:
                os.chdir(cwd)
            seconds[case.command] += time.monotonic() - t0
            counts[case.command][outcome] += 1
            if outcome in BAD:
                bad.append((case, outcome, detail))
            if progress:
                progress(k, case, outcome, detail)
            shutil.rmtree(folder)
    run_campaign.seconds = seconds
    return counts, bad


def table(counts) -> str:
    cols = ("cases",) + OUTCOMES
    lines = ["| command | " + " | ".join(cols) + " |", "|---" * (len(cols) + 1) + "|"]
    total = Counter()
    for cmd in sorted(counts):
        c = counts[cmd]
        n = sum(c.values())
        total.update(c)
        lines.append(f"| {cmd} | {n} | " + " | ".join(str(c[o]) for o in OUTCOMES) + " |")
    n = sum(total.values())
    lines.append(f"| **total** | **{n}** | " + " | ".join(f"**{total[o]}**" for o in OUTCOMES)
                 + " |")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=3400)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--limit", type=float, default=CASE_LIMIT, help="per-case limit [s]")
    ap.add_argument("--families", default=None, help="comma-separated: " + ",".join(GENERATORS))
    ap.add_argument("--verbose", action="store_true")
    args = ap.parse_args(argv)
    t0 = time.time()
    bases = Bases()
    fams = args.families.split(",") if args.families else None
    cases = generate_cases(args.cases, args.seed, bases, families=fams)

    def progress(k, case, outcome, detail):
        if args.verbose or outcome in BAD:
            print(f"[{k}] {case.command} {case.kind}: {outcome} {detail}", flush=True)

    counts, bad = run_campaign(cases, limit=args.limit, progress=progress)
    print(table(counts))
    print("seconds per command:", {k: round(v) for k, v in run_campaign.seconds.items()})
    by_kind = Counter(f"{c.kind.split(':')[0]}/{o}" for c, o, _ in bad)
    if bad:
        print("failures by family:", dict(by_kind))
    print(f"{len(cases)} cases, seed {args.seed}, {time.time() - t0:.0f} s")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
