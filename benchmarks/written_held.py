"""What a diagnosis's written model holds of a library effect, and the independent benchmark's
"held by the written model" counted by it (issue 33, mag33g;
benchmarks/data/mag33g_trace.md).

Until mag33g the benchmark counted a magnitude "held by the written model" when the named
step was within 15 % of the truth and the validation kept the step. The written model can
hold the effect without the step (the calibration's own inertia after an added-mass release
is removed; a dead band another DOF's kept step wrote on the same thrusters) and can lack it
with the step's flag set; :func:`written_magnitude` reads it from the model itself.
"""

from __future__ import annotations

import numpy as np


#: The effects a diagnosis's calibration can also carry: the DOF's inertia (its ``M``) and
#: its linear drag (``D_L``); the written model may hold such an effect's change when the
#: validation removed its step (:func:`written_magnitude`)
CALIBRATED = ("added_mass_error", "linear_drag")


def written_magnitude(written, prior, category: str, dof_name: str) -> float | None:
    r"""The magnitude of effect ``category`` in DOF ``dof_name`` that the written model
    ``written`` (a diagnosis's calibrated model, :class:`stripcoef.model.HydroModel`) holds
    against its prior ``prior``, in the units of the effect's ``magnitude`` (issue 33,
    mag33g: what the written model holds, whichever change wrote it):

    - added-mass error: :math:`M_{A,ii}^{written} - M_{A,ii}^{prior}` [kg or kg m^2]: the
      calibration's and the step's changes of the one inertia (Fossen 2011 eq. 6.2);
    - linear drag: :math:`D_{L,ii}^{written} - D_{L,ii}^{prior}` [N s/m or N m s/rad];
    - thrust effectiveness: the product of the written ``thrust_effectiveness`` scales of
      the DOF (:func:`stripcoef.diagnose.written.thrust_scale`), 1 without one [-];
    - dead band: the mean change of the dead band of the thrusters acting in the DOF [command
      units] (a thruster's property: a dead band named in another DOF that shares them is
      written on them too);
    - buoyancy offset: the written net weight's change :math:`(W - B)^{written} -
      (W - B)^{prior}` plus a written ``buoyancy_offset`` entry's own value [N] (Fossen
      2011 eq. 4.6 at small angles);
    - any other library effect: the effect's ``magnitude`` of its written entry in the DOF
      or of the thrusters' shared one (``dof: all``: the lag, the delay, the current), or of
      a native effect's applied parameters (the model's ``provenance.diagnose`` record,
      :func:`stripcoef.diagnose.written.written_effects`); 0 when the model holds none.

    None for a category that is not a library effect (clean, outside the library)."""
    from stripcoef.conventions import parse_dof
    from stripcoef.diagnose.written import thrust_scale, written_effects
    from stripcoef.effects import get_effect
    from validation.independent import GRAVITY, STRENGTHS
    if category not in STRENGTHS:
        return None
    i = parse_dof(dof_name)
    if category == "added_mass_error":
        return float(written.added_mass[i, i] - prior.added_mass[i, i])
    if category == "linear_drag":
        return float(written.linear_damping[i, i] - prior.linear_damping[i, i])
    if category == "thrust_effectiveness":
        return float(thrust_scale(written, dof_name))
    if category == "deadband":
        # a thruster's property: the mean dead band of the thrusters acting in the DOF, which
        # a dead band named in another DOF sharing them writes too (Deadband.apply: each
        # acting thruster's the larger of its own and the step's)
        b = written.allocation()[i]
        act = [th.deadband for k, th in enumerate(written.thrusters) if abs(b[k]) > 1e-9]
        before = [th.deadband for k, th in enumerate(prior.thrusters) if abs(b[k]) > 1e-9]
        return float(np.mean(act) - np.mean(before)) if act else 0.0
    eff = get_effect(category)
    effects = written_effects(written, dof_name)
    entries = [e for e in written.effects if isinstance(e, dict)
               and e.get("name") == category and e.get("dof") in (dof_name, "all")]
    value = (float(eff.magnitude(entries[0]["parameters"])) if entries
             else float(eff.magnitude(effects[category])) if category in effects else 0.0)
    if category == "buoyancy_offset":
        def net(m):
            return (float(m.mass) - float(m.density) * float(m.volume)) * GRAVITY
        value += net(written) - net(prior)
    return value


def held(row: dict) -> bool:
    """Whether a row's effect is named with its magnitude within 15 % and the written model
    holds it within 15 % too (the summary's "held by the written model"): by the written
    model's own magnitude (``written_magnitude_error``, :func:`written_magnitude` against the
    truth at the written model's thrust scales) where the row has it; a row written before
    mag33g by its step's ``magnitude_written`` (kept by the validation)."""
    if row.get("magnitude_error", float("inf")) > 0.15:
        return False
    if row.get("written_magnitude_error") is not None:
        return row["written_magnitude_error"] <= 0.15
    return bool(row.get("magnitude_written", True))
