r"""The drag couplings of a moment DOF as calibration columns (issue 33, option
``drag_couplings``).

The prior builds every quadratic drag coupling :math:`D_Q[i, j]` (i a moment DOF roll,
pitch, yaw; j a translation surge, sway, heave) as the moment of the same member forces as
the translation's own drag :math:`D_Q[j, j]`: each strip's cross-flow force g and its moment
:math:`r \times g` (:mod:`stripcoef.assembly.damping`; Fossen 2011, sec. 6.4.3, cross-flow
drag as the sum of the strips' forces and their moments). A real vehicle's coupling
differs from its file's with its force (its drag coefficient) and with its lever (where the
force acts), so it is a coefficient of the prior like the others. A moment DOF's calibration
(:func:`~stripcoef.diagnose.fit._calibration`) held only its own M, D_L, D_Q and the other
DOFs' added masses: an error of :math:`D_Q[i, j]` was then a moment no column held
(benchmarks/data/roll33b_trace.md: on the BlueROV2-like log 29113031 the truth's
:math:`D_Q[\text{roll}, \text{sway}]` -3.835 against the file's -3.239, 0.082 N m RMS; roll's
own D_Q went to its bound 0 and a roll thrust scale took the rest).

With the option on, the calibration of a moment DOF i also holds each nonzero coupling
:math:`D_Q[i, j]` of a translation j whose velocity moves, named ``D_Q_<dof j>``: its window
column :math:`-\overline{\nu_j |\nu_j|}` (:func:`stripcoef.effects.windows.coefficient_column`),
its Gaussian prior's sd the relative band of DOF j's own quadratic drag (the force's family;
the lever is the geometry's) times :math:`|D_Q[i, j]|` (as every other column:
:class:`~stripcoef.diagnose.priors.PriorWidths`), and its value bounded to that band's
99.7 % range with the sign kept, :math:`|c_0| e^{\pm z\sigma}`, z =
:data:`~stripcoef.diagnose.priors.ADDED_MASS_BAND_Z` (the bound of an added mass,
:func:`~stripcoef.diagnose.priors.added_mass_bounds`): a coupling does not change sign (the
lever's side is the geometry's). The value calibrated is written into
:math:`D_Q[i, j]` (:func:`stripcoef.diagnose.calibrate.calibrated_model`): the model
simulated and written holds the coupling the fit used.

Depends on: conventions, diagnose.priors, effects.windows.
"""

from __future__ import annotations

import math

from stripcoef.conventions import DOF, parse_dof
from stripcoef.diagnose.priors import ADDED_MASS_BAND_Z
from stripcoef.effects.windows import COUPLING_PREFIX

#: The prefix of a coupling column's name (its window column's,
#: :func:`stripcoef.effects.windows.coefficient_column`).
PREFIX = COUPLING_PREFIX


def coupling_dof(name: str) -> int | None:
    """The translation j [index] of the coupling column ``name`` (``D_Q_<dof>``), None for
    any other calibration name (``M``, ``D_L``, ``D_Q``, ``M_<dof>``)."""
    if not name.startswith(PREFIX):
        return None
    return parse_dof(name[len(PREFIX):])


def coupling_keys(model, dof: int, moving) -> list:
    """The coupling names (``D_Q_<dof j>``) of moment DOF ``dof`` [index]: each translation j
    in ``moving`` (indices; None: all) with a nonzero :math:`D_Q[dof, j]`; none for a
    translation DOF."""
    if dof < 3:
        return []
    return [PREFIX + DOF[j] for j in range(3)
            if float(model.quadratic_damping[dof, j]) != 0.0
            and (moving is None or j in moving)]


def coupling_bounds(prior: float, band: float) -> tuple[float, float]:
    r"""``(lower, upper)`` of a coupling's change [N m s^2/m^2]: its value within
    :math:`|c_0| e^{\pm z b}` with the sign of the prior ``prior`` :math:`c_0`, b ``band``
    the relative 1-sigma band (sd of :math:`\ln c`) [-], z = ``ADDED_MASS_BAND_Z``."""
    lo, hi = math.exp(-ADDED_MASS_BAND_Z * band), math.exp(ADDED_MASS_BAND_Z * band)
    if prior >= 0.0:
        return prior * lo - prior, prior * hi - prior
    return prior * hi - prior, prior * lo - prior
