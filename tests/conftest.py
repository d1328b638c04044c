import os
from functools import lru_cache
from pathlib import Path

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")   # small matrices: threads only add contention

import pytest

import _shared_memo

# before any test module imports the hull: its memoised functions shared by the run's processes
_shared_memo.install()

ROOT = Path(__file__).resolve().parent.parent
GEOMETRY = ROOT / "geometry"


@pytest.hookimpl(trylast=True)
def pytest_configure(config):
    """The run's shared folder (tests/_shared_memo.py): ``pytest-N/shared_memo``, the run's own
    temporary folder (new each run), the same for the xdist workers (their ``basetemp`` is
    ``pytest-N/popen-gwK``) and for the commands they start (the environment)."""
    base = config._tmp_path_factory.getbasetemp()
    root = (base.parent if hasattr(config, "workerinput") else base) / "shared_memo"
    os.environ[_shared_memo.ENV] = str(root)


def load_module(path, name=None, *, cache=False):
    """The Python file ``path`` as a module named ``name`` (default its stem): the model files
    the exporters write (benchmarks/ and scripts/ are packages: ``importlib.import_module``).
    ``cache``: load once per session, registered in sys.modules (a second call returns the same
    module)."""
    import importlib.util
    import sys

    name = name or Path(path).stem
    if cache and name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    if cache:
        sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


@lru_cache(maxsize=None)
def shipped_model(name: str):
    """``load_model(geometry/<name>)`` (warnings silenced) once per test run, shared by the
    xdist workers (tests/_shared_memo.py), for the tests that read the same shipped vehicle
    (the panelled BlueROV2 Heavy is about 8 s of CPU); a HydroModel is immutable, so sharing
    it is safe."""
    import warnings

    from stripcoef.modelfile import load_model

    def load():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return load_model(GEOMETRY / name)

    return _shared_memo.once(("load_model", name), load)


@lru_cache(maxsize=None)
def whole_log_parts(vehicle: str, dofs, effect, seed: int, duration: float, settings=None):
    """``(ThrusterParts, truth)``: the siblings of the DOFs ``dofs`` of an independent-simulator
    log (``validation.independent.generate`` of the shipped ``vehicle`` file) against the prior
    with the thrusters' gains fitted jointly first, as a whole-log diagnosis does (with
    ``settings``, a ``DiagnoseSettings``; None: the defaults)."""
    from stripcoef.diagnose.gains import fit_thruster_gains
    from stripcoef.diagnose.settings import DiagnoseSettings
    from stripcoef.diagnose.thrusterparts import ThrusterParts
    from stripcoef.effects.windows import window_data
    from validation.independent import generate

    prior = shipped_model(vehicle)
    log, truth = generate(prior.to_dict(), effect, seed, duration=duration)
    dofs = list(dofs)
    gains = fit_thruster_gains(window_data(log, prior), dofs, settings or DiagnoseSettings(),
                               excited=dofs)
    if gains is not None and gains.significant:
        prior = gains.model(prior)
    return ThrusterParts(window_data(log, prior), dofs), truth


def parts_trial(parts, name: str, dof: int) -> dict:
    """The selection's record of effect ``name`` fitted in ``dof`` of ``parts`` (a
    ``ThrusterParts``), as the selection leaves it."""
    from stripcoef.diagnose.fit import _evaluate
    from stripcoef.effects.laws import get_effect

    eff = get_effect(name)
    cfg = parts.configs[dof].with_terms([(eff, None)])
    ev = _evaluate(cfg)
    k = cfg.cal_cols.shape[1]
    nuis = eff.nuisance(cfg.data, dof)
    kn = 0 if nuis is None else nuis.shape[1]
    theta = ev["full"]["theta"]
    return {"effect": name, "parameters": eff.to_parameters(theta[k + kn:], None, theta[k:k + kn]),
            "_cfg": cfg, "_ev": ev}


def synthetic(effect, seed: int, **kw):
    """``validation.synthetic.generate(effect, seed=seed, **kw)``, generated once per test run
    for the tests that read the same log, in whichever worker asks first
    (tests/_shared_memo.py; a 240 s log is about 1 s of CPU to simulate) and kept in each
    worker.  The log, prior and truth are shared: read them, do not change them (the log's
    columns are read-only arrays, so an in-place change fails where it happens)."""
    def generate():
        from validation.synthetic import generate

        return generate(effect, seed=seed, **kw)

    log, prior, truth = _shared_memo.once(
        ("synthetic", repr(effect), repr(seed), repr(sorted(kw.items()))), generate)
    for column in log.columns.values():
        column.flags.writeable = False
    return log, prior, truth


@lru_cache(maxsize=None)
def synthetic_diagnosis(effect, seed: int, dof: str) -> dict:
    """``diagnose(log, prior, dof=dof).to_dict()`` of :func:`synthetic` ``(effect, seed)``
    with the default settings, once per test run for the tests that assert on the same
    diagnosis (tests/test_diagnose_detection.py and test_diagnose_select.py, often on two
    workers: tests/_shared_memo.py), kept in each worker (read it, do not change it)."""
    def run():
        from stripcoef.diagnose.pipeline import diagnose

        log, prior, _ = synthetic(effect, seed)
        return diagnose(log, prior, dof=dof).to_dict()

    return _shared_memo.once(("synthetic_diagnosis", repr(effect), repr(seed), dof), run)


@pytest.fixture(scope="session")
def run_once():
    """``once(key, compute)``: ``compute()`` once per test run for the results several test
    files read, shared by the xdist workers and kept in the process (tests/_shared_memo.py:
    the first worker to ask computes it and pickles it into the run's own temporary folder,
    ``pytest-N/``, new each run, holding a lock while it does; the others read it).  ``key``:
    a tuple of strings naming the computation exactly (e.g. the command line). Read the value,
    do not change it."""
    memo = {}

    def once(key, compute):
        if key not in memo:
            memo[key] = _shared_memo.once(("run_once",) + tuple(key), compute)
        return memo[key]

    return once


def shipped_model_once(once, name: str):
    """:func:`shipped_model` ``(name)``, shared by the xdist workers: the panelled BlueROV2
    Heavy of the Gazebo tests, about 8 s of CPU (``once``: kept for the tests that pass the
    :func:`run_once` fixture)."""
    return shipped_model(name)


def coefficients_json(once, *argv) -> dict:
    """``stripcoef coefficients ARGV --json`` parsed, as tests/golden/make_golden.py runs it
    (the provenance's absolute source path dropped), once per test run (:func:`run_once`):
    the golden case of a shipped vehicle file and the tests that read the same output. A copy
    of the shared value."""
    import copy

    argv = tuple(str(a) for a in argv)
    make_golden = load_module(ROOT / "tests" / "golden" / "make_golden.py", "make_golden",
                              cache=True)
    return copy.deepcopy(once(("coefficients --json",) + argv,
                              lambda: make_golden.run(list(argv))))


@pytest.fixture
def geometry_dir():
    return GEOMETRY


@pytest.fixture(scope="session")
def remus_file(tmp_path_factory):
    """REMUS 100 (a propeller, a rudder and an elevator) as a model file, estimated once."""
    import warnings

    from stripcoef.errors import ModelWarning
    from stripcoef.export import write_export
    from stripcoef.modelfile import load_model

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)          # REMUS is 7 % buoyant
        model = load_model(GEOMETRY / "remus100.yaml")
    path = tmp_path_factory.mktemp("remus") / "remus.json"
    write_export(model, "json", path)
    return path


def spheroid_vehicle(length, diameter, *, rho=1000.0, strips=400, **extra):
    """A spheroid vehicle dict (semi-axes a = L/2, b = D/2)."""
    from stripcoef.geometry.vehicle import parse_vehicle

    a, b = 0.5 * length, 0.5 * diameter
    data = {"name": f"spheroid L/D={length / diameter:g}",
            "fluid": {"density": rho, "kinematic_viscosity": 1e-6},
            "strips": strips,
            "hull": {"profile": [
                {"type": "ellipsoid_tail", "x": [-a, 0.0], "radius": b},
                {"type": "ellipsoid_nose", "x": [0.0, a], "radius": b}]}}
    data.update(extra)
    return parse_vehicle(data, file="<spheroid>")


def cylinder_vehicle(length, diameter, *, rho=1000.0, **extra):
    from stripcoef.geometry.vehicle import parse_vehicle

    data = {"name": "cylinder", "fluid": {"density": rho, "kinematic_viscosity": 1e-6},
            "hull": {"profile": [{"type": "cylinder", "x": [-0.5 * length, 0.5 * length],
                                  "radius": 0.5 * diameter}]}}
    data.update(extra)
    return parse_vehicle(data, file="<cylinder>")


# ---------------------------------------------------------------------------
# Regenerated outputs against stored ones (golden files, samples, export examples)
# ---------------------------------------------------------------------------

#: How far a regenerated number may sit from its stored value, as a fraction of the scale of
#: the array it belongs to (a matrix, a vector, a log column, a block of printed lines).
#: Another CPU, BLAS or numpy/scipy release rounds the last bits of a result differently:
#: measured up to 1.1e-11 of the matrix (the box mesh's M_A) and 1e-13 absolute in the
#: sample logs (docs/development.md), while a change of the physics moves a matrix by far
#: more than 1e-9 of its largest entry.  Each scalar by itself would not do: a coupling that
#: is zero up to round-off (7.99e-9 beside a 41 kg diagonal) has no digits of its own.
RTOL = 1e-9
#: The same for a number that estimates an error (``added_mass_error``, the panel levels'
#: estimated error of each term, and ``conditions.added_mass_error_max``, its largest ratio):
#: Eça & Hoekstra's free-order fit (:func:`stripcoef.hull.convergence._free_order_fit`)
#: places its order p at the minimum of a residual, and a minimum's location is determined
#: only to about sqrt(machine epsilon) = 1.5e-8 of it (the residual is flat there to second
#: order; Press et al., Numerical Recipes, 3rd ed., sec. 10.1): measured 1.8e-8 of the
#: estimate between two x86-64 machines whose M_A agreed to 5e-16 (the VideoRay's and the
#: box mesh's surge and sway). An estimated error is itself known to a few per cent, so a
#: change of the method moves it by far more than 1e-6 of its scale.
ESTIMATE_RTOL = 1e-6
#: The keys compared with :data:`ESTIMATE_RTOL` (in any dict of a compared tree).
ESTIMATE_KEYS = ("added_mass_error", "added_mass_error_max")

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"

#: The largest |got - want| / scale seen by the comparisons below since it was last reset
#: (benchmarks/reproducibility.py reports it).
WORST = {"deviation": 0.0}


def _deviation(got: float, want: float, scale: float) -> float:
    """|got - want| as a fraction of max(scale, |want|), recorded in :data:`WORST`."""
    base = max(scale, abs(want))
    d = abs(got - want) / base if base else (0.0 if got == want else float("inf"))
    WORST["deviation"] = max(WORST["deviation"], d)
    return d


def array_scale(value) -> float:
    """Largest magnitude of the numbers in ``value`` (nested lists; 0 for anything else)."""
    if isinstance(value, (list, tuple)):
        return max((array_scale(v) for v in value), default=0.0)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return abs(float(value))
    return 0.0


def coefficient_scales(doc: dict) -> dict:
    """Scale of each SNAME derivative of ``doc["coefficients"]``: the largest entry of the
    matrix it is read from (``X_udot`` from M_A, ``Y_v`` from D_L, ``Y_vv`` from D_Q, ``Y_uv``
    from the lift matrix, ``Y_uudr`` from the control derivatives)."""
    from stripcoef.conventions import (added_mass_name, linear_damping_name,
                                       quadratic_damping_name)
    from stripcoef.model import lift_names

    scales: dict = {}

    def add(name, scale):
        scales[name] = max(scales.get(name, 0.0), scale)

    for key, namer in (("added_mass", added_mass_name), ("linear_damping", linear_damping_name),
                       ("quadratic_damping", quadratic_damping_name)):
        s = array_scale(doc.get(key))
        for i in range(6):
            for j in range(6):
                add(namer(i, j), s)
    s = array_scale(doc.get("lift"))
    for name in lift_names().values():
        add(name, s)
    control = array_scale([c.get("derivative") for c in doc.get("control_surfaces") or []])
    return {name: scales.get(name, control) for name in doc.get("coefficients") or {}}


def band_scale(bound: float, doc: dict, name: str, scales: dict) -> float:
    """Scale of one bound of ``doc["coefficient_bands"][name]``: its matrix's scale times the
    bound's ratio to the coefficient's value. A lognormal band's bound is the value times
    exp(+-z sd), up to 129 times the value for a rotational term (the box mesh's K_pdot), so the
    value's round-off, small beside its matrix, is multiplied by that factor in the bound."""
    value = doc["coefficients"].get(name)
    scale = scales.get(name, abs(bound))
    if isinstance(value, (int, float)) and value:
        scale *= max(1.0, abs(bound / value))
    return scale


def assert_same_tree(got, want, path: str = "", *, rtol: float = RTOL, scale: float = 0.0):
    """Parsed JSON/YAML ``got`` equals ``want``: keys, strings, integers, booleans exactly;
    floats within ``rtol`` of the scale of their array (:data:`RTOL`), the ``coefficients``
    of a model by the scale of their matrix (:func:`coefficient_scales`), the bounds of its
    ``coefficient_bands`` by that scale times the bound's ratio to the value
    (:func:`band_scale`), an estimated error (:data:`ESTIMATE_KEYS`) within
    :data:`ESTIMATE_RTOL`."""
    if isinstance(want, dict):
        assert isinstance(got, dict) and list(got) == list(want), \
            f"{path}: keys {list(got) if isinstance(got, dict) else got!r} != {list(want)}"
        coefficients = coefficient_scales(want) if isinstance(want.get("coefficients"), dict) else {}
        for k in want:
            if k == "coefficients" and coefficients:
                assert list(got[k]) == list(want[k]), f"{path}.{k}: {list(got[k])} != {list(want[k])}"
                for name, w in want[k].items():
                    assert_same_tree(got[k][name], w, f"{path}.{k}.{name}", rtol=rtol,
                                     scale=coefficients[name])
            elif k == "coefficient_bands" and coefficients and isinstance(want[k], dict):
                assert list(got[k]) == list(want[k]), f"{path}.{k}: {list(got[k])} != {list(want[k])}"
                for name, bounds in want[k].items():
                    for i, bound in enumerate(bounds):
                        assert_same_tree(got[k][name][i], bound, f"{path}.{k}.{name}[{i}]",
                                         rtol=rtol, scale=band_scale(bound, want, name,
                                                                     coefficients))
            else:
                # an estimated error to ESTIMATE_RTOL (rtol 0 asks for bit-for-bit equality)
                tol = max(rtol, ESTIMATE_RTOL) if rtol and k in ESTIMATE_KEYS else rtol
                assert_same_tree(got[k], want[k], f"{path}.{k}", rtol=tol,
                                 scale=array_scale(want[k]))
    elif isinstance(want, (list, tuple)):
        assert isinstance(got, (list, tuple)) and len(got) == len(want), \
            f"{path}: {got!r} != {want!r}"
        for i, (g, w) in enumerate(zip(got, want)):
            assert_same_tree(g, w, f"{path}[{i}]", rtol=rtol, scale=scale)
    elif isinstance(want, float):
        import math
        assert isinstance(got, (int, float)) and not isinstance(got, bool), f"{path}: {got!r} != {want!r}"
        if math.isnan(want) or math.isinf(want):
            assert got == want or (math.isnan(got) and math.isnan(want)), f"{path}: {got!r} != {want!r}"
        else:
            d = _deviation(got, want, scale)
            assert d <= rtol, f"{path}: {got!r} != {want!r} ({d:.3g} of its scale > {rtol:g})"
    else:
        assert type(got) is type(want) and got == want, f"{path}: {got!r} != {want!r}"


def _text_blocks(text: str):
    """The numbers of ``text`` (as strings) and, for each, the index of its block: a run of
    consecutive lines that all hold numbers (a matrix printed a row or an element a line)."""
    import re

    numbers, blocks, block, previous = [], [], 0, False
    for line in text.splitlines():
        found = re.findall(_NUMBER, line)
        if found and not previous:
            block += 1
        previous = bool(found)
        numbers += found
        blocks += [block] * len(found)
    return numbers, blocks


def assert_same_text(name: str, got: str, want: str, *, rtol: float = RTOL, hint: str = ""):
    """Text ``got`` is ``want`` up to round-off: the words between the numbers equal with any
    run of whitespace read as one space (a longer number may wrap a line elsewhere), the same
    count of numbers, each within ``rtol`` of the largest magnitude of its block of lines in
    ``want`` (:func:`_text_blocks`)."""
    import re

    def words(text):
        return [" ".join(part.split()) for part in re.split(_NUMBER, text)]

    gw, ww = words(got), words(want)
    if gw != ww:
        first = next((k for k, (a, b) in enumerate(zip(gw, ww)) if a != b), min(len(gw), len(ww)))
        raise AssertionError(f"{name}: text differs near {ww[first] if first < len(ww) else 'the end'!r}"
                             f" (got {gw[first] if first < len(gw) else 'the end'!r}){hint}")
    g = [float(v) for v in re.findall(_NUMBER, got)]
    w_text, block = _text_blocks(want)
    w = [float(v) for v in w_text]
    assert len(g) == len(w), f"{name}: {len(g)} numbers != {len(w)}{hint}"
    scale: dict = {}
    for b, v in zip(block, w):
        scale[b] = max(scale.get(b, 0.0), abs(v))
    for k, (a, b) in enumerate(zip(g, w)):
        d = _deviation(a, b, scale[block[k]])
        assert d <= rtol, f"{name}: number {k} ({w_text[k]}): {a!r} != {b!r} " \
                          f"({d:.3g} of its scale > {rtol:g}){hint}"


def assert_same_csv(name: str, got: str, want: str, *, rtol: float = RTOL, hint: str = ""):
    """CSV ``got`` is ``want`` up to round-off: the same rows and columns, text cells equal,
    numbers within ``rtol`` of the largest magnitude of their column among the rows of the same
    quantity (the first cell when it is text: one matrix of an export; else the whole column:
    one signal of a log)."""
    import csv
    import io

    def number(cell):
        try:
            return float(cell)
        except ValueError:
            return None

    g = list(csv.reader(io.StringIO(got)))
    w = list(csv.reader(io.StringIO(want)))
    assert len(g) == len(w), f"{name}: {len(g)} rows != {len(w)}{hint}"

    def group(row):
        return row[0] if row and number(row[0]) is None else None

    scale: dict = {}
    for row in w:
        for j, cell in enumerate(row):
            v = number(cell)
            if v is not None:
                scale[group(row), j] = max(scale.get((group(row), j), 0.0), abs(v))
    for i, (a, b) in enumerate(zip(g, w)):
        assert len(a) == len(b), f"{name}: row {i + 1} has {len(a)} cells, not {len(b)}{hint}"
        for j, (x, y) in enumerate(zip(a, b)):
            vx, vy = number(x), number(y)
            if vy is None or vx is None:
                assert x == y, f"{name}: row {i + 1} column {j + 1}: {x!r} != {y!r}{hint}"
                continue
            d = _deviation(vx, vy, scale[group(b), j])
            assert d <= rtol, f"{name}: row {i + 1} column {j + 1}: {x} != {y} " \
                              f"({d:.3g} of its scale > {rtol:g}){hint}"


def assert_same_file(name: str, got, want, *, rtol: float = RTOL, hint: str = ""):
    """A regenerated file ``got`` (bytes or str) against the stored ``want``, by its suffix:
    JSON and YAML parsed (:func:`assert_same_tree`; a YAML file's comment lines as text), CSV
    by cell (:func:`assert_same_csv`), binary STL by its float32 records (within 4 float32 ulps
    of the mesh's size: the float64 geometry rounds to float32 on writing, so a last-bit change
    upstream may flip one rounding), any other text by :func:`assert_same_text`."""
    import json

    import numpy as np
    import yaml

    suffix = Path(name).suffix.lower()
    if suffix == ".stl" and isinstance(want, bytes) and not want[:5] == b"solid":
        assert isinstance(got, bytes) and len(got) == len(want), f"{name}: size differs{hint}"
        assert got[:84] == want[:84], f"{name}: header or face count differs{hint}"
        record = np.dtype([("f", "<f4", (12,)), ("attr", "<u2")])
        g = np.frombuffer(got, record, offset=84)
        w = np.frombuffer(want, record, offset=84)
        assert np.array_equal(g["attr"], w["attr"]), f"{name}: attributes differ{hint}"
        vg, vw = g["f"][:, 3:].astype(float), w["f"][:, 3:].astype(float)
        tol = max(rtol, 4 * float(np.finfo(np.float32).eps)) * float(np.abs(vw).max())
        assert np.abs(vg - vw).max() <= tol, f"{name}: vertices differ by {np.abs(vg - vw).max():.3g}{hint}"
        ng, nw = g["f"][:, :3].astype(float), w["f"][:, :3].astype(float)
        assert np.abs(ng - nw).max() <= 4 * float(np.finfo(np.float32).eps), \
            f"{name}: normals differ by {np.abs(ng - nw).max():.3g}{hint}"
        return
    got = got.decode() if isinstance(got, bytes) else got
    want = want.decode() if isinstance(want, bytes) else want
    if suffix in (".json", ".yaml", ".yml"):
        load = json.loads if suffix == ".json" else yaml.safe_load
        try:
            assert_same_tree(load(got), load(want), name, rtol=rtol)
        except AssertionError as error:
            raise AssertionError(f"{error}{hint}") from None
    if suffix in (".yaml", ".yml"):

        def comments(text):
            return "\n".join(line for line in text.splitlines() if line.lstrip().startswith("#"))
        assert_same_text(name, comments(got), comments(want), rtol=rtol, hint=hint)
    elif suffix == ".json":
        pass
    elif suffix == ".csv":
        assert_same_csv(name, got, want, rtol=rtol, hint=hint)
    else:
        assert_same_text(name, got, want, rtol=rtol, hint=hint)


def one_line_error(capsys, argv, *words):
    """Run the CLI: exit 2 and one line on stderr (warnings aside) holding every one of
    ``words``; returns that line."""
    from stripcoef.cli import main

    rc = main([str(a) for a in argv])
    _, err = capsys.readouterr()
    lines = [ln for ln in err.strip().splitlines() if not ln.startswith("warning:")]
    assert rc == 2, err
    assert len(lines) == 1 and "Traceback" not in err, err
    for w in words:
        assert w in lines[0], lines[0]
    return lines[0]


def pytest_collection_modifyitems(config, items):
    """Under xdist (two workers on two cores), the test files with ``slow`` tests run first,
    most slow tests first, each file's tests together and in order: the workers then end the
    run on the quick tests, not one of them on a minute of the documentation pages or the
    wheel while the other waits (with ``--dist worksteal`` an idle worker takes queued tests
    from the back of the other's queue, and a test already started cannot move). The files of
    one family (``test_lift_*.py``, ``test_diagnose_*.py``: the word after ``test_``) stay
    side by side, ranked by the family's slow tests, so that they share a worker and the
    models they cache in the process (measured with two workers: the SUBOFF models of
    ``validation.lift`` built on both workers, 7-8 s of CPU each time, when the lift files
    were spread between them). Run in this process (``-n0``), the order is the files' own."""
    if not hasattr(config, "workerinput"):
        return
    slow: dict = {}
    for item in items:
        slow.setdefault(item.nodeid.split("::")[0], 0)
        if item.get_closest_marker("slow") is not None:
            slow[item.nodeid.split("::")[0]] += 1

    def family(path: str) -> str:
        return Path(path).stem.removeprefix("test_").split("_")[0]

    family_slow: dict = {}
    for f, n in slow.items():
        family_slow[family(f)] = family_slow.get(family(f), 0) + n
    rank = {f: k for k, f in enumerate(sorted(slow, key=lambda f: (-family_slow[family(f)],
                                                                   family(f), -slow[f])))}
    items.sort(key=lambda item: rank[item.nodeid.split("::")[0]])
