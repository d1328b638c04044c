"""How far this machine's outputs sit from the stored ones, as a fraction of their scale.

The snapshot tests (tests/test_golden.py, tests/test_samples.py,
tests/test_docs_export_examples.py) compare regenerated outputs with the stored files within
1e-9 of the scale of each number's array (``RTOL`` in tests/conftest.py). This script
regenerates the same outputs and prints, per file family, the largest |got - want| / scale
(0 where they are bit for bit the same): the margin that tolerance leaves on this machine's
CPU, BLAS thread count and numpy/scipy release.

Usage: python benchmarks/reproducibility.py
"""

import dataclasses
import importlib.util
import json
import tempfile
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _load(path: Path, name: str):
    import sys

    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module      # importable by the modules loaded after it
    spec.loader.exec_module(module)
    return module


def main() -> int:
    import numpy
    import scipy

    import stripcoef
    from stripcoef.export import write_export

    _load(ROOT / "tests" / "_shared_memo.py", "_shared_memo")     # conftest imports it
    conftest = _load(ROOT / "tests" / "conftest.py", "_stripcoef_conftest")
    golden = _load(ROOT / "tests" / "golden" / "make_golden.py", "_stripcoef_make_golden")
    make_samples = _load(ROOT / "scripts" / "make_samples.py", "_stripcoef_make_samples")
    examples = _load(ROOT / "scripts" / "make_export_examples.py", "_stripcoef_examples")
    print(f"numpy {numpy.__version__}, scipy {scipy.__version__}, tolerance {conftest.RTOL:g}")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        worst = (0.0, "")
        for name, argv in golden.cases(tmp):
            want = json.loads((ROOT / "tests" / "golden" / f"{name}.json").read_text())
            conftest.WORST["deviation"] = 0.0
            conftest.assert_same_tree(golden.run(argv), want, name, rtol=float("inf"))
            if conftest.WORST["deviation"] > worst[0]:
                worst = (conftest.WORST["deviation"], name)
        rows.append((f"golden coefficients --json (worst: {worst[1] or '-'})", worst[0]))
        worst = (0.0, "")
        for name, data in make_samples.build().items():
            stored = stripcoef.samples.path(name).read_bytes()
            conftest.WORST["deviation"] = 0.0
            conftest.assert_same_file(name, data, stored, rtol=float("inf"))
            if conftest.WORST["deviation"] > worst[0]:
                worst = (conftest.WORST["deviation"], name)
        rows.append((f"samples (worst: {worst[1] or '-'})", worst[0]))
        conftest.WORST["deviation"] = 0.0
        model = stripcoef.estimate(stripcoef.load_vehicle(ROOT / "geometry" / "mares.yaml"))
        model = dataclasses.replace(model, provenance={**model.provenance,
                                                       "source": "geometry/mares.yaml"})
        for name, fmt, options in examples.EXAMPLES:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                write_export(model, fmt, tmp / name, **options)
            conftest.assert_same_file(name, (tmp / name).read_text(),
                                      (examples.OUT / name).read_text(), rtol=float("inf"))
        rows.append(("export examples of MARES", conftest.WORST["deviation"]))
    for label, worst in rows:
        print(f"{label:45s} largest deviation {worst:.2e} of scale")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
