r"""The lifting fins' Munk compensation as a part of the model of its own
(:attr:`stripcoef.model.HydroModel.fin_munk_lift`).

A fin's lift at its quarter chord carries the fin's Munk moment; C_A(nu) of the model's M_A
(Fossen 2011, eq. 3.46) adds it again, so the model takes the fins' share of it off with

.. math:: \Delta L = -L_M(M_A - M_A^{-})\ \text{(the moment rows of the lifting fins)},

force :math:`-u\,\Delta L\,\nu` (:func:`stripcoef.assembly.lift.fin_munk_compensation`, its
derivation and sources). :math:`\Delta L` is not lift: it belongs to C_A's Munk moment, so it is
kept apart from the lift matrix L, counted where C_A's Munk moment is counted and dropped
where it is dropped (``munk=False``, ``coriolis=False`` of
:meth:`~stripcoef.model.HydroModel.velocity_forces` and :meth:`~stripcoef.model.HydroModel.damping`;
``simulate``/``limits`` ``--no-munk``), and it follows M_A:

- an M_A swapped in after the estimate (:func:`stripcoef.assembly.methods.with_added_mass_of`)
  gets the compensation of its own method's fins' share (:func:`recompute`);
- M_A scaled by the method factors of a study (:mod:`stripcoef.study.evaluate`) scales it
  with the same factors (:func:`scaled`), while L takes the lift factor alone.

Every consumer that writes one matrix of u-terms beside a C_A with its Munk moment (the
coefficients ``Y_uv``..., every export, the model file's ``lift``) writes
:math:`L + \Delta L` (:attr:`~stripcoef.model.HydroModel.total_lift`), the same numbers as
when :math:`\Delta L` was folded into L; a model file holds :math:`\Delta L` again under
``fin_munk_lift``.
"""

from __future__ import annotations

import warnings
from dataclasses import replace

import numpy as np

from stripcoef.assembly.lift import fin_munk_compensation, lifting_fins
from stripcoef.errors import ModelWarning

#: The DOF of M_A whose row each moment row of :math:`\Delta L` copies: the yaw row (5) holds
#: :math:`-(M_A - M_A^-)_{1,:}` (sway), the pitch row (4) :math:`+(M_A - M_A^-)_{2,:}` (heave):
#: :math:`L_M[3{:}, j] = e_1 \times a_j` (:func:`stripcoef.assembly.lift.munk_lift_matrix`) [-].
SOURCE_ROW = {4: 2, 5: 1}


class NoFinSolve(Exception):
    """An added-mass method that cannot solve the vehicle without its lifting fins (the reason
    in ``args[0]``): raised by the ``added_mass_of`` given to :func:`recompute`."""


def recompute(model, vehicle, added_mass_of, *, method: str):
    r"""``model`` with :attr:`~stripcoef.model.HydroModel.fin_munk_lift` computed again from
    its own M_A, :math:`\Delta L = -L_M(M_A - M_A^{-})` with :math:`M_A^{-}` =
    ``added_mass_of(vehicle without its lifting fins)`` by the method that gave M_A (named
    ``method``), and its conditions ``lift.fin_munk`` with that share's summary and the method.

    Where that method cannot solve the vehicle without its fins (``added_mass_of`` raises
    :class:`NoFinSolve`), the compensation of the model is kept, with a :class:`ModelWarning`
    saying it is the fins' share by the estimate's method, not by ``method``. A vehicle without
    lifting fins gets none (zeros).

    References
    ----------
    :func:`stripcoef.assembly.lift.fin_munk_compensation` (Theodorsen 1935; Newman 1977,
    ch. 4; Fossen 2011, eq. 3.46).
    """
    fins = lifting_fins(vehicle)
    lift_info = dict(model.conditions.lift or {})
    try:
        delta, info = fin_munk_compensation(model.added_mass, added_mass_of, vehicle, fins)
    except NoFinSolve as exc:
        warnings.warn(f"{model.name}: the lifting fins' Munk compensation is kept from the "
                      f"estimate's added-mass method: {method} cannot solve the vehicle "
                      f"without its fins ({exc.args[0]})", ModelWarning, stacklevel=3)
        return model
    lift_info.pop("fin_munk", None)
    if info:
        lift_info["fin_munk"] = {**info, "method": method}
    conditions = replace(model.conditions, lift=lift_info or None)
    return replace(model, fin_munk_lift=delta, conditions=conditions)


def scaled(delta, factors) -> np.ndarray:
    r""":math:`\Delta L` of an M_A scaled DOF by DOF, :math:`M'_{ij} = M_{ij}\sqrt{f_i f_j}`
    (:func:`stripcoef.study.sources.scale_matrix`): its row k copies row r(k) of the fins'
    share of M_A (:data:`SOURCE_ROW`), so

    .. math:: \Delta L'_{kj} = \Delta L_{kj}\sqrt{f_{r(k)} f_j},

    the compensation of the scaled share, which the scaled C_A's Munk moment holds: the fins'
    Munk moment stays counted once under any factors. A coupling perturbation of M_A
    (:func:`stripcoef.study.sources.couple`) is not attributed to the fins (assumption: it is
    left out of :math:`\Delta L`). ``delta`` (6, 6) [kg/m, kg, kg m]; ``factors`` (6,) [-]."""
    f = np.sqrt(np.clip(np.asarray(factors, dtype=float), 0.0, None))
    out = np.asarray(delta, dtype=float).copy()
    for k, r in SOURCE_ROW.items():
        out[k] *= f[r] * f
    return out
