"""Do the references fall inside the stated 95 % bands as often as the bands claim?

For each reference value (an exact solution, a converged BEM, a measurement) the uncertainty
study of its vehicle (method error only: no inputs are declared) gives a 95 % band
[P2.5, P97.5] of the same coefficient; the benchmark counts how many references fall inside.
Well-calibrated bands hold about 95 %; many more means the bands are too wide, fewer too
narrow. The references are stored data, not recomputed fits:

- Lamb's exact added mass of prolate spheroids (L/D 3, 5, 7.5, 10): X_udot, Y_vdot, N_rdot;
- the converged Capytaine run of the 1.5 m x 0.2 m capsule (reference_tables/capytaine_anchor);
- the VideoRay Pro III's measured (experimental) coefficients of Wang & Clark 2006, Table I
  (reference_tables/videoray_pro3): the drag, the linear damping and the yaw added mass.

Run: python benchmarks/band_coverage.py [--samples 64]   (about 1-2 min)
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402
import yaml  # noqa: E402

from stripcoef.hull.lamb import spheroid_added_mass  # noqa: E402
from stripcoef.study.uncertainty import uncertainty  # noqa: E402
from validation.reference import load_table  # noqa: E402

NAMES = {0: "X_udot", 1: "Y_vdot", 5: "N_rdot"}


def spheroid_file(folder: Path, ld: float) -> Path:
    a, b = 0.75, 0.75 / ld
    data = {"name": f"spheroid L/D {ld:g}", "fluid": {"density": 1000.0, "kinematic_viscosity": 1e-6},
            "strips": 1000,
            "hull": {"profile": [{"type": "ellipsoid_tail", "x": [-a, 0.0], "radius": b},
                                 {"type": "ellipsoid_nose", "x": [0.0, a], "radius": b}]}}
    path = folder / f"spheroid_{ld:g}.yaml"
    path.write_text(yaml.safe_dump(data))
    return path


def references(folder: Path):
    """(label, vehicle file, output name, reference value in SNAME sign)."""
    out = []
    for ld in (3.0, 5.0, 7.5, 10.0):
        exact = spheroid_added_mass(0.75, 0.75 / ld, rho=1000.0)
        path = spheroid_file(folder, ld)
        for i, name in NAMES.items():
            out.append((f"spheroid L/D {ld:g} vs Lamb", path, name, -float(exact[i])))
    capsule = ROOT / "geometry" / "capsule.yaml"
    for row in load_table("capytaine_anchor", "capsule"):
        name = {"m11": "X_udot", "m22": "Y_vdot", "m33": "Z_wdot", "m55": "M_qdot",
                "m66": "N_rdot"}[row["name"]]
        out.append(("capsule vs Capytaine", capsule, name, -row["value"]))
    videoray = ROOT / "geometry" / "videoray_pro3.yaml"
    for table in ("table1_added_mass", "table1_quadratic_drag", "table1_linear_drag"):
        for row in load_table("videoray_pro3", table):
            if not row["name"].endswith(".experimental"):
                continue
            out.append(("VideoRay vs Wang & Clark 2006 Table I (measured)", videoray,
                        row["name"].split(".")[0], -row["value"]))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=64)
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        refs = references(Path(tmp))
        studies = {}
        rows, inside = [], 0
        for label, path, name, ref in refs:
            if path not in studies:
                studies[path] = uncertainty(path, samples=args.samples, seed=0, limits=False,
                                            workers=1, progress=False)
            res = studies[path]
            s = res.summary()[name]
            lo, hi = s["p2.5"], s["p97.5"]
            ok = min(lo, hi) <= ref <= max(lo, hi)
            inside += ok
            rows.append((label, res.shape_class, name, ref, s["nominal"], lo, hi, ok))
    print("| reference | class | term | reference | nominal | P2.5 | P97.5 | inside |")
    print("|---|---|---|---|---|---|---|---|")
    for label, cls, name, ref, nom, lo, hi, ok in rows:
        print(f"| {label} | {cls} | {name} | {ref:.4g} | {nom:.4g} | {lo:.4g} | {hi:.4g} | "
              f"{'yes' if ok else '**no**'} |")
    print(f"\n{inside} of {len(rows)} references inside their 95 % band "
          f"({100 * inside / len(rows):.0f} %; {args.samples} samples per vehicle)")


if __name__ == "__main__":
    main()
