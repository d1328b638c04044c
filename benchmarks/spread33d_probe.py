"""Trace of the whole-log thrusters' gains against the truth's per-thruster spread (issue 33,
spread33d): the allocation matrix's rank, the gains' contrasts, each combination's
information ratio and the truth's value of it, on the independent simulator's logs.

``python -m benchmarks.spread33d_probe VEHICLE CATEGORY SEED [SEED...] [--default-groups]``
(300 s logs; the gains with ``linked_gains``, or with the default groups). A
trace, not a model change: benchmarks/data/spread33d_trace.md."""
from __future__ import annotations

import sys
import time
import warnings

import numpy as np

from benchmarks.diagnose_independent import _prior
from stripcoef.diagnose.gains import contrast_basis, fit_thruster_gains, thruster_groups
from stripcoef.diagnose.heldout import split
from stripcoef.diagnose.select import select_dofs
from stripcoef.diagnose.settings import VALIDATION_FRACTION, DiagnoseSettings
from stripcoef.effects.laws import model_window_data
from validation.independent import generate


def truth_gains(prior, truth) -> np.ndarray:
    """Each thruster's truth forward C_t over the prior's (C_t eta) [-]."""
    return np.array([t["ct_forward"] / (th.ct_forward * th.eta_forward)
                     for th, t in zip(prior.thrusters, truth.thrusters)])


def probe(vehicle: str, category: str, seed: int, settings=DiagnoseSettings(linked_gains=True)) -> None:
    prior = _prior(vehicle)
    log, truth = generate(prior.to_dict(), None if category == "clean" else category, seed,
                          duration=300.0)
    t0 = time.process_time()
    train, _ = split(log, VALIDATION_FRACTION, key="validation")
    data = model_window_data(train, prior, window=settings.window)
    excited, _ = select_dofs(data)
    alloc = data.alloc
    groups = thruster_groups(alloc, rows=excited, linked=settings.linked_gains)
    p = contrast_basis(groups, alloc.shape[1])
    sv = np.linalg.svd(alloc, compute_uv=False)
    print(f"{vehicle} {category} {seed}: B {alloc.shape}, rank {np.linalg.matrix_rank(alloc)}"
          f", singular values {np.round(sv, 4).tolist()}; groups {groups}; contrasts "
          f"{p.shape[1]}; null(B) dim {alloc.shape[1] - np.linalg.matrix_rank(alloc)}")
    g_true = truth_gains(prior, truth)
    print("  truth gains", np.round(g_true, 3).tolist())
    # the truth's contrasts: g_true / group mean - 1, projected on the contrasts
    rel = g_true.copy()
    for grp in groups:
        rel[grp] = g_true[grp] / g_true[grp].mean()
    gains = fit_thruster_gains(data, excited, settings, excited=excited)
    print(f"  fitted gains {np.round(gains.gains, 3).tolist()} prior_sd {gains.prior_sd:.3f}"
          f" p {gains.test['p_value']:.3g} k {gains.test['dof']} applied {gains.applied}: "
          f"{gains.reason}")
    print("  truth rel.  ", np.round(rel, 3).tolist())
    cmd = np.asarray(data.thrust)
    print("  thrust rms per thruster [N]", np.round(np.sqrt((cmd ** 2).mean(0)), 2).tolist())
    print("  thrust corr\n", np.round(np.corrcoef(cmd.T), 2))
    for c in gains.combinations:
        w = np.array([c["weights"][n] for n in gains.names])
        print(f"  combo ratio {c['information_ratio']:.3g} det {c['determined']} value "
              f"{c['value']:+.3f} +- {c['std']:.3f} truth {w @ (rel - 1.0):+.3f} w "
              f"{np.round(w, 2).tolist()}")
    print("  alloc\n", np.round(alloc, 3))
    g_fit = np.asarray(gains.gains)
    for i in range(6):
        tp = cmd @ alloc[i]
        if not np.any(np.abs(alloc[i]) > 1e-9):
            continue
        tt = cmd @ (alloc[i] * g_true)
        tg = cmd @ (alloc[i] * g_fit)
        print(f"  DOF {i}: truth/prior scale {tt @ tp / (tp @ tp) - 1:+.3f}, truth/gained "
              f"{tt @ tg / (tg @ tg) - 1:+.3f}, residual rms of truth minus scaled gained "
              f"{np.sqrt(np.mean((tt - (tt @ tg / (tg @ tg)) * tg) ** 2)):.3f} of "
              f"{np.sqrt(np.mean(tt ** 2)):.3f}")
    print(f"  CPU {time.process_time() - t0:.1f} s", flush=True)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        linked = "--default-groups" not in argv
        for s in [a for a in argv[2:] if a != "--default-groups"]:
            probe(argv[0], argv[1], int(s), DiagnoseSettings(linked_gains=linked))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
