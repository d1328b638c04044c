r"""Inputs of the identification methods from a log and, optionally, a vehicle.

The applied generalized force along a DOF is the log's force column (``X``..``N``) or, from
thruster commands ``n_<name>`` and the vehicle's thruster map (Wang & Clark 2006, eq. 6,
:math:`T = C_t n|n|`, bench coefficients, efficiency 1 so that eta can be identified):

.. math:: \tau = \sum_j T_j(n_j)\, [d_j;\ (p_j - o) \times d_j]

about the model's reference point ``o`` (Fossen 2011, eq. 11.3).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from stripcoef.conventions import FORCES, parse_dof
from stripcoef.errors import InputError


def vehicle_model(path):
    """HydroModel of a vehicle file or a model file (JSON/YAML of ``HydroModel.to_dict``), as
    every model-consuming command reads it (:func:`stripcoef.modelfile.load_model`)."""
    from stripcoef.modelfile import load_model
    return load_model(path)


def applied_force(log, dof, model=None) -> tuple[np.ndarray, str]:
    """Applied force along ``dof`` [N or N m] and a description of where it came from.

    From the log column, else tau_i = sum_k B_ik T_k(n_k) with the bench thrust map
    T = C_t n|n| (eta = 1) and B_ik the i-th entry of the thruster's wrench column
    [-] or [m] (Wang & Clark 2006, eqs. 1 and 6; :mod:`stripcoef.thrusters`).
    """
    i = parse_dof(dof)
    name = FORCES[i]
    if name in log:
        return log[name], f"column {name}"
    cmds = log.commands()
    if model is None or not cmds:
        raise InputError("missing required column", file=log.source, key=name,
                         expected=f"a column {name!r} with the applied force, or thruster "
                         "commands n_<name> together with --vehicle (present: "
                         + ", ".join(log.names) + ")")
    known = {t.name: t for t in model.thrusters}
    unknown = sorted(set(cmds) - set(known))
    if unknown:
        raise InputError("command column for an unknown thruster", file=log.source,
                         key="n_" + unknown[0], expected="one of the vehicle's thrusters: "
                         + ", ".join("n_" + k for k in known))
    tau = np.zeros(len(log))
    for tname, n in cmds.items():
        th = dataclasses.replace(known[tname], eta_forward=1.0, eta_backward=1.0)
        col = th.wrench_column(model.reference_point)
        tau = tau + np.asarray(th.thrust(n)) * col[i]
    return tau, "thruster commands " + ", ".join("n_" + k for k in cmds) + " (bench map, eta = 1)"


def horizontal_command(log, model=None):
    """Mean |command| of the horizontal thrusters (``n_h`` of Indiveri 1998's eta-md model).

    n_h = (1/K) sum_k |n_k| over the K thrusters with no z component of direction
    [command units] (Indiveri 1998, sec. 3.3.1, momentum-drag regressor F_md = -alpha n_h w).
    """
    if "n_h" in log:
        return log["n_h"]
    if model is None:
        return None
    cols = [np.abs(log["n_" + t.name]) for t in model.thrusters
            if abs(float(np.asarray(t.direction)[2])) < 1e-9 and ("n_" + t.name) in log]
    return np.mean(cols, axis=0) if cols else None
