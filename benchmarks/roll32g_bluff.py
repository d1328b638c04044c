"""The bluff set's prism (``chamfer_box``, a 5-gon prism: the only right prism among the 24
shapes of ``benchmarks.bluff_shapes``) with the graded prism panels off and on, against its
edge-graded Capytaine reference (``reference_tables/bem/graded_bluff.csv``; issue 32, branch
roll32g).  Each diagonal term's error, the estimate, the CPU of the estimate.  Usage:

    python -m benchmarks.roll32g_bluff
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from benchmarks.bluff_shapes import chamfer_box  # noqa: E402
from stripcoef.hull import graded_panels as G  # noqa: E402
from stripcoef.hull import panels as P  # noqa: E402


def main(argv=None) -> int:
    from validation.graded_bodies import bluff_references

    ref = np.asarray(bluff_references()["chamfer_box"][0])
    ref = np.diag(ref) if ref.ndim == 2 else ref
    m = chamfer_box()
    saved = G.PRISMS
    try:
        for on in (False, True):
            G.PRISMS = on
            P._solved_level.cache_clear()
            c0 = time.process_time()
            a, info = P.panel_added_mass(m, rho=1000.0, about=m.center_mass, mirrors=("y",))
            cpu = time.process_time() - c0
            print(f"prisms {'on' if on else 'off'}: {info['family']}, panels {info['panels']}, "
                  f"CPU {cpu:.2f} s; diagonal error "
                  + " ".join(f"{100 * (x / r - 1):+.2f}" for x, r in zip(np.diag(a), ref))
                  + " %, estimate " + " ".join(f"{100 * e / x:.1f}" for e, x in
                                               zip(np.diag(info["estimate"]), np.diag(a)))
                  + " %")
    finally:
        G.PRISMS = saved
    return 0


if __name__ == "__main__":
    sys.exit(main())
