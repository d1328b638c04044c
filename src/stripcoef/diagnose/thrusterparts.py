r"""Whole-log: an effect of each thruster found in a DOF that several groups of thrusters drive
must hold where parts of them act alone (issue 33).

A thrust asymmetry or a dead band is a property of each thruster's own map (Wang & Clark
2006, eq. 6 and Table I: each thruster's forward and backward thrust coefficients; Yoerger,
Cooke & Slotine 1990: its dead zone). :class:`~stripcoef.diagnose.select.Siblings` checks such
an effect in the other DOFs driven by the *same* thrusters. A DOF driven by several groups of
thrusters has none: the VideoRay's pitch is driven by the horizontal pair (their thrust 1 cm
below the reference point) and by the vertical thruster (0.9 cm ahead of it), and no other
DOF by all three. Its thrust is :math:`\tau_4 = \sum_k B_{4k} g_k T_k` with each thruster's
gain :math:`g_k` (Fossen 2011, sec. 11.2.1, eq. 11.14: :math:`\tau = T(\alpha) K u`); when the
groups' gains differ, the forward and backward branches of the DOF's thrust are different
mixes of the groups (the vertical thruster mostly holding the trim one way, the pair driven
both ways), so a per-DOF asymmetry of the pitch thrust fits the groups' gain ratio. Issue 33,
seed 5092026: 15 of the 22 whole-log runs with a step where the truth has none named a pitch
or heave thrust asymmetry on the VideoRay; traced on the tether log (pitch eta 1.026 forward,
0.946 backward, the truth's thrusters at 1.19, 0.95 and 1.24 of their maps and no asymmetry),
the step is not named when the prior carries the truth's thrust maps
(``python -m benchmarks.diagnose_independent --truth-maps``).

The rule: the per-DOF effect claims one law for every thruster acting in the DOF (the same
branches' ratio or dead zone: :class:`~stripcoef.effects.thrust.ThrustAsymmetry` scales the
forward and backward parts of the DOF's thrust of all of them), so it must hold in every
diagnosed DOF that a part of those thrusters drives alone (their acting thrusters a proper
subset of the DOF's). It is contradicted when such a DOF contradicts it by the siblings' own
test (:meth:`~stripcoef.diagnose.select.Siblings.contradicted_in`: at the effect's fitted
parameters it raises that DOF's held-out error by more than ``TIE`` and that DOF's own fit of
it differs by ``MIN_Z`` standard deviations or more), as a DOF driven by the same thrusters
does. A real asymmetry of every thruster holds in each part; one of a single group is named in
the DOFs that group drives, where it is not mixed with the others' thrust. On the tether log
above, surge (the horizontal pair alone) fits no asymmetry (8.0 standard deviations from the
pitch's) and the pitch's raises its held-out error by 136 %. No threshold is new.

Depends on: diagnose.select, conventions.
"""

from __future__ import annotations

from stripcoef.conventions import DOF
from stripcoef.diagnose.select import Siblings

#: The library's effects that are properties of each thruster's own map (checked in the parts)
PER_THRUSTER = ("thrust_asymmetry", "deadband")


class ThrusterParts(Siblings):
    """:class:`~stripcoef.diagnose.select.Siblings` that also checks a per-thruster effect
    (:data:`PER_THRUSTER`) of a DOF in the DOFs driven by parts of its thrusters alone
    (module docstring)."""

    def parts(self, dof: int) -> list:
        """The diagnosed DOFs whose acting thrusters are a proper, non-empty subset of
        ``dof``'s."""
        act = set(self.data.acting(dof))
        return [j for j in self.configs
                if j != dof and set(self.data.acting(j)) and set(self.data.acting(j)) < act]

    def contradictions(self, trial: dict, dof: int) -> list:
        out = super().contradictions(trial, dof)
        if trial["effect"] not in PER_THRUSTER:
            return out
        return out + [f"contradicted by {DOF[j]} (driven by a part of its thrusters alone): "
                      f"{why}" for j in self.parts(dof)
                      for why in [self.contradicted_in(trial, j)] if why]
