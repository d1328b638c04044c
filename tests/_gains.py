"""Test helper: how far a thruster-gain fit is from a truth's thruster coefficients."""

from __future__ import annotations

import numpy as np


def truth_contrasts(truth, prior, groups) -> np.ndarray:
    """Each truth thruster's factor over the file's map, divided by its group's mean [-]
    (the gains' fit determines contrasts within its groups only)."""
    thr = prior.to_dict()["thrusters"]
    g = np.array([t["ct_forward"] / (float(p.get("ct_forward", 1.0))
                                     * float(p.get("eta_forward", 1.0)))
                  for t, p in zip(truth.thrusters, thr)])
    out = g.copy()
    for members in groups:
        out[members] = g[members] / g[members].mean()
    return out


def fitted_groups(fit, alloc) -> list:
    """The groups whose contrasts ``fit`` estimated (thruster indices):
    :func:`stripcoef.diagnose.gains.thruster_groups` of ``alloc``, merged where the fit's
    record says two were linked (``linked_gains="identified"``, the default)."""
    from stripcoef.diagnose.gains import thruster_groups

    groups = thruster_groups(alloc)
    for link in fit.links or []:
        if link["linked"]:
            merged = sorted({int(i) for g in link["groups"] for i in g})
            groups = [g for g in groups if not set(g) & set(merged)] + [merged]
    return groups


def contrast_error(fit, truth, prior, alloc):
    """RMS [-] of the fitted gains minus the truth's contrasts within the fit's own groups
    (:func:`fitted_groups` of the allocation matrix ``alloc``)."""
    want = truth_contrasts(truth, prior, fitted_groups(fit, alloc))
    return float(np.sqrt(np.mean((np.array(fit.gains) - want) ** 2)))
