"""Write the golden outputs of ``stripcoef coefficients --json`` (tests/test_golden.py).

Run only when a change of the matrices is intended and explained in its commit:

    .venv/bin/python tests/golden/make_golden.py

The cases: every shipped vehicle file, with and without the 3D corrections, and a box
mesh (trimesh's box primitive, deterministic) through the mesh path, by strip theory and by
the default method (auto: the panel method for this box).
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")   # as the CLI does: threaded BLAS changes the last bits

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent


def cases(tmp: Path | None):
    """(name, argv) for every golden case; writes the box mesh into ``tmp`` (``None``: the
    cases' names only, no file written)."""
    import trimesh

    out = []
    for vehicle in sorted((ROOT / "geometry").glob("*.yaml")):
        out.append((vehicle.stem, [str(vehicle)]))
        out.append((vehicle.stem + "_no_corrections", [str(vehicle), "--no-corrections"]))
    box = (tmp or Path(".")) / "box.stl"
    if tmp is not None:
        trimesh.creation.box(extents=(0.46, 0.58, 0.25)).export(box)
    # strip theory on the box (its golden numbers since the house move), and the default
    # (auto: the 3D panel method for a body neither round nor slender)
    out.append(("box_mesh", [str(box), "--rho", "1000", "--added-mass-method", "strips"]))
    out.append(("box_mesh_auto", [str(box), "--rho", "1000"]))
    return out


def run(argv) -> dict:
    import contextlib
    import io

    from stripcoef.cli import main

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        code = main(["coefficients", *argv, "--json"])
    if code:
        raise SystemExit(f"coefficients {argv} exited {code}")
    data = json.loads(buf.getvalue())
    data.get("provenance", {}).pop("source", None)   # an absolute path: differs per checkout
    return data


if __name__ == "__main__":
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        for name, argv in cases(Path(tmp)):
            (HERE / f"{name}.json").write_text(json.dumps(run(argv), indent=1) + "\n")
            print("wrote", name, file=sys.stderr)
