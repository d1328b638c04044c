r"""The added masses of the DOFs a log moves but does not diagnose: which DOF's calibration
holds each (issue 33).

A diagnosed DOF i feels the added mass :math:`M_{jj}` of every other DOF j through the
added-mass Coriolis and centripetal force :math:`C_A(\nu)\nu` (Fossen 2011, eq. 6.43: in
surge :math:`M_{22}\,v r - M_{33}\,w q`), whenever j's velocity moves, whether or not a
thruster pushes in j. A DOF with no thruster (a VideoRay's sway) is not diagnosed
(:func:`~stripcoef.diagnose.select.select_dofs`: no applied force, so its own force balance
has no scale), yet it slips sideways in every turn, and its added mass's error (strip
theory's, or the vehicle's difference from its file) is then a force in the surge residual
that no calibration column took up: on the independent benchmark's VideoRay-like tether
logs (issue 33, seeds 12, 481516 and 581516, 300 s) a sway added mass 8-23 % off left a
surge residual of 0.11-0.24 N RMS beside a tether force of 0.07 N, and the tether's test
failed (z 0.9-2.2); with ``M_sway`` calibrated the residual fell to 0.04-0.06 N and the
tether's z rose to 5-6 on two of the three.

So a DOF's calibration (:func:`~stripcoef.diagnose.fit._calibration`) may hold the added
mass of every DOF whose velocity moves (:func:`moving_dofs`); its Fisher information still
decides whether the log determines it (:func:`~stripcoef.diagnose.fit._identifiability`,
Ljung 1999 eq. 9.29). Where that DOF is diagnosed itself, its own calibration's value is
written, and the others keep the value they fitted; with the option ``one_added_mass`` a
DOF whose fit contradicts the written value is selected again without it and refitted with
it (:func:`stripcoef.diagnose.calibrate.contradicted`,
:func:`~stripcoef.diagnose.calibrate.consistent_fits`, :func:`with_known`).
One coefficient has one value: in a whole-log diagnosis several diagnosed DOFs may each
calibrate such an added mass (a VideoRay's sway added mass reaches surge through
:math:`M_{22} v r` and yaw through the Munk moment :math:`(M_{22} - M_{11}) u v`); the
model written holds their inverse-variance weighted mean (:func:`shared_value`,
:func:`stripcoef.diagnose.calibrate.calibrated_model`), and every value reported about it
is read back from that model (:mod:`.written`). (Tried: each such added mass held by the
one diagnosed DOF that determines it best; on the VideoRay tether log of seed 481516 that
was yaw, and the surge residual kept the sway added mass's error.)

Depends on: effects (windows), diagnose.settings.
"""

from __future__ import annotations

import copy
import math

import numpy as np

from stripcoef.conventions import VELOCITIES
from stripcoef.diagnose.settings import EXCITATION_SNR, EXCITATION_STD
from stripcoef.effects.windows import coefficient_column, white_noise_sd


def velocity_snr(data, i: int) -> tuple:
    r"""``(std, noise, snr)`` of DOF ``i``'s velocity [m/s or rad/s, -]: its standard
    deviation, its white noise :math:`\sigma_{v,i}` estimated from second differences,
    :math:`\mathrm{var}(\Delta^2\nu) = 6\sigma_v^2`, by the median absolute deviation
    (:func:`~stripcoef.effects.windows.white_noise_sd`), and their ratio (infinite for a
    noise-free velocity that varies, 0 for a constant one). The one rule of a velocity that
    moves, read by :func:`moving_dofs` and :func:`stripcoef.diagnose.select.select_dofs`."""
    v = data.nu[:, i]
    noise = white_noise_sd(v)
    std = float(np.std(v))
    snr = std / noise if noise > 0 else (math.inf if std > 1e-12 else 0.0)
    return std, noise, snr


def moving_dofs(data) -> list:
    r"""The DOFs whose velocity moves in the log [indices]: the column is there, its standard
    deviation is above ``EXCITATION_STD`` [m/s or rad/s] and at least ``EXCITATION_SNR``
    times its white noise (:func:`velocity_snr`), the velocity rules of
    :func:`~stripcoef.diagnose.select.select_dofs` without its applied-force rule. The DOFs
    whose added mass the calibration of a diagnosed DOF may hold (a diagnosed DOF's own is
    its calibration's ``M``).
    """
    out = []
    for i in range(6):
        if VELOCITIES[i] not in data.log:
            continue
        std, _, snr = velocity_snr(data, i)
        if std > EXCITATION_STD and snr >= EXCITATION_SNR:
            out.append(i)
    return out


def with_known(data, dof: int, values: dict, nu=None):
    r"""A copy of the window data ``data`` whose residual in DOF ``dof`` has the force of the
    other DOFs' added-mass changes ``values`` ({``M_<dof>``: change [kg or kg m^2]}) taken
    out as a known force, :math:`e_0 - \sum_j \Delta M_{jj} (C_A[E_{jj}](\nu)\nu)_i` (the
    calibration column of ``M_<dof>``, :func:`~stripcoef.effects.windows.coefficient_column`,
    at the velocity ``nu`` relative to the water when given), recorded in its
    ``known_added_mass`` (added to what it held). The copy shares the log and the cached
    designs (they do not depend on the residual)."""
    out = copy.copy(data)
    out.e0 = np.array(data.e0, float)
    known = dict(data.known_added_mass)
    for key, value in values.items():
        if value != 0.0:
            out.e0[:, dof] -= coefficient_column(data, dof, key, nu) * float(value)
        known[key] = known.get(key, 0.0) + float(value)
    out.known_added_mass = known
    return out


def shared_value(estimates) -> tuple:
    r"""``(value, sd)`` of one coefficient estimated in several DOFs' calibrations,
    ``estimates`` a list of (value, sd): the inverse-variance weighted mean
    :math:`\hat x = \sum_k x_k / s_k^2 / \sum_k 1 / s_k^2`, sd
    :math:`(\sum_k 1/s_k^2)^{-1/2}` (the combination of independent estimates, e.g.
    Bevington & Robinson 2003, Data Reduction and Error Analysis, eq. 4.17); an estimate
    without a finite positive sd is left out unless none has one (then the plain mean)."""
    est = [(float(v), float(s)) for v, s in estimates]
    good = [(v, s) for v, s in est if np.isfinite(s) and s > 0.0]
    if not good:
        return float(np.mean([v for v, _ in est])), float("nan")
    w = np.array([1.0 / s ** 2 for _, s in good])
    x = np.array([v for v, _ in good])
    return float(w @ x / w.sum()), float(1.0 / np.sqrt(w.sum()))
