"""Test helper: how far a thruster-gain fit is from a truth's thruster coefficients."""

from __future__ import annotations

import numpy as np


def contrast_error(fit, truth, prior, groups):
    """RMS [-] of the fitted gains minus the truth's within-group contrasts (each group's
    truth gains divided by their mean: the gains' fit determines contrasts only)."""
    thr = prior.to_dict()["thrusters"]
    g = np.array([t["ct_forward"] / (float(p.get("ct_forward", 1.0))
                                     * float(p.get("eta_forward", 1.0)))
                  for t, p in zip(truth.thrusters, thr)])
    want = g.copy()
    for members in groups:
        want[members] = g[members] / g[members].mean()
    return float(np.sqrt(np.mean((np.array(fit.gains) - want) ** 2)))
