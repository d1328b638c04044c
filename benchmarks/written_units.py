"""Stored rows of ``benchmarks.diagnose_independent`` scored again with the magnitude rule in
the written model's units (issue 33, fresh33f).

Before fresh33f, :func:`benchmarks.diagnose_independent.magnitude_truth` expressed a force
effect at the thrust the written model gives the effect's DOF, :math:`s\\,g_w/g` (s the
fitted thrust scale, :math:`g_w` the written thrusters' gain there, g the truth's), but the
added mass only at :math:`s/g` and the thrust effectiveness as g: a change that moves a DOF's
mean written gain off 1 (the whole-log thruster gains with ``linked_gains``) was charged for
it. The rule now expresses both at the written gains too; a row records it as
``magnitude_units == "written"`` with its ``written_gain``. A row written before carries
neither; its :math:`g_w` is read from the row's own ``thruster_gains`` (the applied gains,
None when none were applied) with the benchmark's weights
(:func:`benchmarks.diagnose_independent.written_gain`), and its reference converted
(:func:`benchmarks.diagnose_independent.converted`):

- thrust effectiveness: :math:`g \\to g/g_w`;
- added mass: :math:`r \\to (r + M_0)\\,g_w - M_0`, :math:`M_0 = M_{RB,ii} + M_{A,ii}` of the
  prior (:func:`benchmarks.diagnose_independent.prior_inertia`), since
  :math:`r + M_0 = (M_{RB} + M_{A,true})\\,s/g`.

Force effects were already at :math:`g_w`. Second, a kept effect's value is the written
model's, which holds only the kept thrust scales, but the reference took every scale of the
DOF, a removed one too: a kept effect's reference (force effect or added mass) is now at the
kept scales (:func:`benchmarks.diagnose_independent.held_scales`), converted from the row's
``step_detail`` as :math:`r \\to (r + b)\\,\\rho - b`, :math:`\\rho` the kept scales' product
over every scale's, b the prior's own term (inertia, surge linear drag, net weight; 0 for a
tether or momentum drag). Every other row is left as it is. No diagnosis is run. Usage:

    python -m benchmarks.written_units OUTPUT[,OUTPUT...]

prints, per file, the rows whose reference changes (old -> new reference and error) and the
count within 15 % before and after.
"""

from __future__ import annotations

import argparse
import json

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

def main(argv=None) -> int:
    from benchmarks.diagnose_independent import converted_rows
    from stripcoef.files import read_text
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("outputs", help="comma-separated printed outputs of "
                                    "benchmarks.diagnose_independent (their 'row' lines)")
    args = ap.parse_args(argv)
    for path in args.outputs.split(","):
        rows = [json.loads(line.split(" row ", 1)[1])
                for line in read_text(path, kind="benchmark output").splitlines()
                if " row {" in line]
        got = converted_rows(rows)
        moved = [g for g in got if "magnitude_truth_before" in g]

        def within(r, key):
            return r.get(key) is not None and r[key] <= 0.15
        claimed = [g for g in moved if "estimate" in g]
        print(f"{path}: {len(rows)} rows, {len(moved)} converted ({len(claimed)} with an "
              f"estimate); within 15 %: {sum(within(g, 'magnitude_error_before') for g in claimed)}"
              f" -> {sum(within(g, 'magnitude_error') for g in claimed)}")
        for g in moved:
            if abs(g["magnitude_truth"] - g["magnitude_truth_before"]) < 1e-12:
                continue
            err = (f", error {100 * g['magnitude_error_before']:.1f} % -> "
                   f"{100 * g['magnitude_error']:.1f} %" if "estimate" in g else "")
            print(f"  {g['vehicle']} {g['category']} {g['seed']} {g['mode']}: g_w "
                  f"{g.get('written_gain', 1.0):.4f}, held scales / all "
                  f"{g['held_scale_ratio']:.4f}, reference {g['magnitude_truth_before']:+.4g} -> "
                  f"{g['magnitude_truth']:+.4g}" + (f", estimate {g['estimate']:+.4g}"
                                                    if "estimate" in g else "") + err)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
