"""``benchmarks.diagnose_independent`` run with the oracle of a rule not adopted (issue 33,
spur33d): the calibration's identifiability judged with the window residual's noise level fitted
with a free constant beside its columns (:func:`benchmarks.spur33d_trace.noise_with_bias`).

``python -m benchmarks.spur33d_bias_run [diagnose_independent's arguments] --jobs 1``
(one job: the swap holds in this process only). Measured text: benchmarks/data/spur33d_trace.md.
"""
from __future__ import annotations

import sys


def main(argv=None) -> int:
    from benchmarks import diagnose_independent
    from benchmarks.spur33d_trace import noise_with_bias

    argv = sys.argv[1:] if argv is None else argv
    with noise_with_bias():
        return diagnose_independent.main(argv)


if __name__ == "__main__":
    raise SystemExit(main())
