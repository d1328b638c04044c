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

A thrust asymmetry found in a translation must also be identified apart from a buoyancy
change (:meth:`ThrusterParts.buoyancy_confounded`). Its column, the backward part
:math:`F^-_i` of the DOF's thrust, is largely a constant where the thrusters mostly push one
way to hold the vehicle against its restoring force (a BlueROV2's heave), so a buoyancy error
the prior does not carry (a real vehicle's displaced volume differs from its file's: trim,
foam, flooded volumes) is fitted as an asymmetry. A parameter is identified only by the part
of its column that the model's other columns do not span (a parameter is locally identified
when the information matrix is non-singular: Rothenberg 1971, Econometrica 39, 577-591,
Theorem 1; the information on one parameter given the others is the Schur complement of
theirs), so the asymmetry is refitted with the restoring force's column of a buoyancy change
(:func:`~stripcoef.effects.hydrodynamic.buoyancy_column`; Fossen 2011, eq. 4.6) free beside
it, as the tether is fitted (:class:`~stripcoef.effects.hydrodynamic.TetherDrag`), and must
still be ``MIN_Z`` standard deviations from zero, the z gate of every step. Issue 33, seed
29112051 of the independent benchmark: on BlueROV2-like logs 29213055 and 29213057 the heave
asymmetry's column was 75 % and 82 % (R^2) a constant plus the total thrust, and whole-log
runs named heave asymmetries eta-/eta+ - 1 of -5.3 % and -8.2 % (z 4.2, 4.0) where the
truth's thrusters give -0.01 % and +3.5 % on the same commands. Applied also where the DOF
already holds a buoyancy offset: the offset is a constant, a buoyancy change's restoring
force is not (:math:`-\Delta B\cos\theta\cos\phi` in heave, Fossen 2011, eq. 4.6), and
on a log whose attitude moves the difference :math:`\Delta B (1 - \cos\theta\cos\phi)`
is left for the asymmetry to take (issue 33, asym33s: fresh seed 1795929171, VideoRay-like
log 1795929178, pitch 9.6 deg RMS and up to 45 deg, the truth 0.53 N more buoyant than the
prior and no asymmetry: beside the offset the whole-log run named a heave asymmetry
eta_b / eta_f - 1 = -0.32, z 4.4; refitted with the buoyancy change free beside the offset
it is -0.17, z 1.4, and the buoyancy change is 0.54 +- 0.33 N, the truth's 0.53;
benchmarks/data/asym33s_trace.md). Not applied in the rotations (a buoyancy change's
moment there depends on the centre of buoyancy's position, a column not built here). The
identification argument does not depend on how many DOFs are diagnosed, so a one-DOF run
applies this test alone (:class:`OneDofParts`; it has no sibling DOFs to check): issue 33, fresh seed 1795929171, BlueROV2-like log 1795930174
(a buoyancy 0.58 N lighter than the prior's), the one-DOF heave diagnosis named a heave
asymmetry first (z 7.1; the validation then removed it) where the whole-log run names the
buoyancy; with the test it names the buoyancy first.

A thrust asymmetry found in a translation must, thirdly, be identified apart from the other
effect of each thruster's own map, its dead band, fitted beside the same buoyancy change
(:meth:`ThrusterParts.deadband_confounded`). The two are non-nested (neither law is a special
case of the other: the asymmetry scales every backward thrust, the dead band removes the thrust
of the small commands of both signs; Vuong 1989, Econometrica 57, 307-333), so the log tells
them apart only in the model that holds both (the comprehensive model, Atkinson 1970, J. R.
Stat. Soc. B 32, 323-353; Davidson & MacKinnon 1981, Econometrica 49, 781-793, the rule the
selection's competing effects already follow, :func:`~stripcoef.diagnose.select._competing`):
the dead band's width is profiled with the buoyancy change free beside it, and the asymmetry,
refitted beside that dead band with the buoyancy change free, must still be ``MIN_Z``
standard deviations from zero (Rothenberg 1971, Theorem 1, as above). The competing-effects
comparison of the selection does not see the pair when a buoyancy error the prior does not
carry hides the dead band at the first step, which is where the asymmetry takes both: issue
33, spur33d, fresh seed 1795929171, BlueROV2-like dead-band log 1795930177 (the truth's
thrusters all with a dead band of 0.252 of the full command, the truth 2.17 N heavier than the
prior): the whole-log heave diagnosis named an asymmetry eta_b / eta_f - 1 = -0.12 (z 16.3,
held-out error 0.573 N; buoyancy-free z 5.1) where the truth's thrusters give -0.003; the
dead band alone on the prior's buoyancy fits 0.05 (z 2.3); profiled with the buoyancy change
free it is 0.250 at a held-out error of 0.212 N, and beside it the asymmetry is 0.3 standard
deviations from zero (benchmarks/data/spur33d_trace.md). A true asymmetry is not a dead band:
its backward branch's change holds at every command, not only at small ones.

Depends on: diagnose.select, diagnose.settings, diagnose.fit, diagnose.crossscale, effects,
conventions.
"""

from __future__ import annotations


import numpy as np

from stripcoef.conventions import DOF
from stripcoef.diagnose.crossscale import cross_mass_confounded, refitted_z
from stripcoef.diagnose.fit import DEFAULTS, _evaluate
from stripcoef.diagnose.select import Siblings
from stripcoef.diagnose.settings import MIN_Z, DiagnoseSettings
from stripcoef.effects.base import THRUST_BAND, TRANSLATIONAL
from stripcoef.effects.hydrodynamic import buoyancy_column
from stripcoef.effects.thrust import Deadband, ThrustAsymmetry

#: The library's effects that are properties of each thruster's own map (checked in the parts)
PER_THRUSTER = ("thrust_asymmetry", "deadband")


class BuoyancyFreeAsymmetry(ThrustAsymmetry):
    r""":class:`~stripcoef.effects.thrust.ThrustAsymmetry` with a buoyancy change's column
    (:func:`~stripcoef.effects.hydrodynamic.buoyancy_column`, [N], free) beside the thrust
    scale in its nuisance: the identification test of :meth:`ThrusterParts.
    buoyancy_confounded` (module docstring). Never written, not in the registry."""

    nuisance_names = ("thrust_scale", "buoyancy_change")

    def nuisance(self, data, dof):
        return np.column_stack([super().nuisance(data, dof), buoyancy_column(data, dof)])

    def nuisance_sd(self, data, dof):
        # the thrust scale anchored at THRUST_BAND (ThrustAsymmetry), the buoyancy free
        return np.array([THRUST_BAND, np.inf])

    def lower_bounds(self, data, dof, hyper=None):
        return np.array([-0.9, -np.inf, -np.inf])


class BuoyancyFreeDeadband(Deadband):
    r""":class:`~stripcoef.effects.thrust.Deadband` with a buoyancy change's column
    (:func:`~stripcoef.effects.hydrodynamic.buoyancy_column`, [N], free) as its nuisance: its
    width profiled beside the buoyancy change, for the test of :meth:`ThrusterParts.
    deadband_confounded` (module docstring). Never written, not in the registry."""

    nuisance_names = ("buoyancy_change",)

    def nuisance(self, data, dof):
        return buoyancy_column(data, dof)[:, None]


class ThrusterParts(Siblings):
    """:class:`~stripcoef.diagnose.select.Siblings` that also checks a per-thruster effect
    (:data:`PER_THRUSTER`) of a DOF in the DOFs driven by parts of its thrusters alone
    (module docstring)."""

    def __init__(self, data, dofs, settings: DiagnoseSettings = DEFAULTS, **kwargs):
        super().__init__(data, dofs, settings, **kwargs)
        self._free = BuoyancyFreeAsymmetry()     # one instance: the fits cache its columns
        self._free_deadband = BuoyancyFreeDeadband()
        self._cross_free = {}                    # crossscale.CrossMassFreeScale by columns
        self._cross_test = settings.cross_mass_scale

    def parts(self, dof: int) -> list:
        """The diagnosed DOFs whose acting thrusters are a proper, non-empty subset of
        ``dof``'s."""
        act = set(self.data.acting(dof))
        return [j for j in self.configs
                if j != dof and set(self.data.acting(j)) and set(self.data.acting(j)) < act]

    def contradictions(self, trial: dict, dof: int) -> list:
        out = super().contradictions(trial, dof)
        why = (cross_mass_confounded(trial, dof, self._cross_free)   # a thrust scale
               if self._cross_test else "")
        if why:
            out = out + [why]
        if trial["effect"] not in PER_THRUSTER:
            return out
        out = out + [f"contradicted by {DOF[j]} (driven by a part of its thrusters alone): "
                     f"{why}" for j in self.parts(dof)
                     for why in [self.contradicted_in(trial, j)] if why]
        why = self.buoyancy_confounded(trial, dof) or self.deadband_confounded(trial, dof)
        return out + [why] if why else out

    def buoyancy_confounded(self, trial: dict, dof: int) -> str:
        """Why the thrust asymmetry ``trial`` of translation ``dof`` is not identified apart
        from a buoyancy change (module docstring): refitted with the buoyancy change's
        column free beside it, its own coefficient is under ``MIN_Z`` standard deviations
        from zero; '' when it is, or for another effect or a rotation. A DOF that holds a
        buoyancy offset is tested too: the offset is a constant, the buoyancy change's
        column is not (module docstring)."""
        cfg = trial.get("_cfg")
        if trial["effect"] != "thrust_asymmetry" or dof not in TRANSLATIONAL or cfg is None:
            return ""
        got = refitted_z(cfg, (self._free, cfg.terms[-1][1]))
        if got is None:
            return ""
        z = got[1]
        return "" if z >= MIN_Z else (
            f"not identified apart from a buoyancy change: with the restoring force's column "
            f"free beside it the asymmetry is {z:.1f} standard deviations from zero "
            f"(< {MIN_Z:g})")

    def deadband_confounded(self, trial: dict, dof: int) -> str:
        """Why the thrust asymmetry ``trial`` of translation ``dof`` is not identified apart
        from a dead band fitted beside a buoyancy change (module docstring): the dead band's
        width profiled with the buoyancy change free, the asymmetry refitted beside that dead
        band with the buoyancy change free is under ``MIN_Z`` standard deviations from zero;
        '' when it is not, for another effect or a rotation, or where no dead band applies."""
        cfg = trial.get("_cfg")
        if (trial["effect"] != "thrust_asymmetry" or dof not in TRANSLATIONAL or cfg is None
                or not self._free_deadband.applicable(cfg.data, dof)[0]):
            return ""
        head = list(cfg.terms[:-1])
        try:
            width = _evaluate(cfg.with_terms(head + [(self._free_deadband, None)]))["hyper"]
        except (np.linalg.LinAlgError, ValueError):
            return ""
        if width is None:
            return ""
        beside = cfg.with_terms(head + [(Deadband(), width), cfg.terms[-1]])
        got = refitted_z(beside, (self._free, cfg.terms[-1][1]))
        if got is None or got[1] >= MIN_Z:
            return ""
        return (f"not identified apart from a dead band: beside a dead band of "
                f"{float(np.atleast_1d(width)[0]):.3g} (its width fitted with a buoyancy "
                f"change free) and the buoyancy change, the asymmetry is {got[1]:.1f} "
                f"standard deviations from zero (< {MIN_Z:g})")


class OneDofParts(ThrusterParts):
    """A one-DOF run's check of a thruster effect: only the identification of a translation's
    thrust asymmetry apart from a buoyancy change (:meth:`ThrusterParts.buoyancy_confounded`,
    module docstring) and apart from a dead band beside it (:meth:`ThrusterParts.
    deadband_confounded`); a one-DOF run has no sibling DOFs, no parts and no other DOFs' added
    masses to refit beside a scale."""

    def contradictions(self, trial: dict, dof: int) -> list:
        why = self.buoyancy_confounded(trial, dof) or self.deadband_confounded(trial, dof)
        return [why] if why else []
