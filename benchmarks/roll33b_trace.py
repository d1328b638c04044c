"""The whole-log thruster gains of a BlueROV2-Heavy-like log against the truth's own
per-thruster factors (issue 33, roll33b; benchmarks/data/roll33b_trace.md).

``python -m benchmarks.roll33b_trace SEED CATEGORY GAINS_JSON``: GAINS_JSON the row's
``thruster_gains`` of ``benchmarks.diagnose_independent``. The fit holds contrasts only
(:func:`stripcoef.diagnose.gains.contrast_basis`: within each group of thrusters driving the
same DOFs the gains sum to their count), so the truth's factors f_k = C_t,truth / C_t,prior
are compared divided by their group's mean; the group's mean is the DOFs' thrust
effectiveness (``benchmarks.diagnose_independent.thrust_gain``)."""
from __future__ import annotations

import json
import sys

import numpy as np

from benchmarks.diagnose_independent import _prior, thrust_gain
from stripcoef.diagnose.gains import thruster_groups
from stripcoef.effects.windows import window_data
from validation.independent import generate


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    seed, cat, gains = int(argv[0]), argv[1], json.loads(argv[2])
    prior = _prior("bluerov2_heavy")
    pd = prior.to_dict()
    log, truth = generate(pd, cat, seed, duration=300.0)
    names = [t["name"] for t in truth.thrusters]
    c0 = np.array([float(p.get("ct_forward", 1.0)) * float(p.get("eta_forward", 1.0))
                   for p in pd["thrusters"]])
    f = np.array([t["ct_forward"] for t in truth.thrusters]) / c0
    g = np.array([float(gains[n]) for n in names])
    print("the truth's thrust per unit of the prior's map, per DOF:",
          {d: round(float(thrust_gain(truth, pd, i)), 4) for i, d in
           enumerate(("surge", "sway", "heave", "roll", "pitch", "yaw"))})
    for members in thruster_groups(window_data(log, prior).alloc):
        idx = list(members)
        fm = f[idx].mean()
        print(f"group {[names[k] for k in idx]}: the truth's mean factor {fm:.4f}")
        for k in idx:
            print(f"  {names[k]}: truth f/mean {f[k] / fm:.4f}, fitted {g[k]:.4f}, "
                  f"difference {g[k] - f[k] / fm:+.4f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
