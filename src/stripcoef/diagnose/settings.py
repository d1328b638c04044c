"""The diagnosis's thresholds, its options (:class:`DiagnoseSettings`) and its CPU-time
budget (:class:`Budget`): passed as arguments to every stage, never stashed on the data.

The thresholds of the selection are those of the method in :mod:`.pipeline`'s docstring
(docs/diagnose.md).

Depends on: errors, diagnose.heldout, diagnose.horizon.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

from stripcoef.diagnose.heldout import EACH
from stripcoef.errors import UnreachableError

#: 1-sigma relative bands on the prior's coefficients (:mod:`.pipeline`, step 2).
BANDS = {"translational": {"M": 0.3, "D_L": 0.6, "D_Q": 0.3},
         "rotational": {"M": 1.0, "D_L": 3.0, "D_Q": 3.0}}
MIN_HELD_OUT_GAIN = 0.10
MIN_DELTA_BIC = 10.0
MIN_Z = 3.0
TIE = 0.02
MIMIC_BANDS = 2.5
UNEXPLAINED_GAIN = 0.10
#: The residual is unexplained also when, after the best candidates, its held-out error
#: stays above this multiple of the noise floor F = M_ii sqrt(var(rate noise)) (the part of
#: the window residual the velocity noise alone makes; effects/windows.py): a model that
#: explained the log would leave about F (chi-square with one degree of freedom per window
#: exceeds 5^2 with probability < 1e-6, so noise alone never crosses it) -- provided the
#: generic basis predicts some of it (held-out gain > 0): the window residual also carries
#: the quadrature error of the window integrals on a jittered log, which no basis predicts
#: (measured: 7.4 floors on a 10 Hz log with 20 % jitter and 1-s windows diagnosed with its
#: own true model, tests/test_ingest_cli.py; a missing effect such as Coulomb friction is
#: partly predicted by the basis's sign column).
NOISE_FLOOR_FACTOR = 5.0
N_BLOCKS = 5
MAX_STEPS = 4
#: CPU-time budget (:func:`time.process_time`) of one diagnosis of up to :data:`BUDGET_ROWS` log rows [s]; past the
#: budget the diagnosis stops with an error saying so, instead of grinding.
TIME_LIMIT = 300.0
#: Log rows that :data:`TIME_LIMIT` covers: a longer log gets a budget in proportion to its
#: rows (:func:`default_time_limit`; issue 33: no log is refused for its length alone). The
#: cost of a diagnosis grows about linearly with the rows (window columns, the free
#: simulations of the validation); measured, a whole-log run of 72,000 rows takes well under
#: the 1,080 s this gives (docs/performance.md, benchmarks/diagnose_speed.py).
BUDGET_ROWS = 20_000


def default_time_limit(rows: int) -> float:
    """The default CPU-time budget of a diagnosis of a log of ``rows`` rows [s]:
    :data:`TIME_LIMIT`, times rows / :data:`BUDGET_ROWS` for a longer log."""
    return TIME_LIMIT * max(1.0, float(rows) / BUDGET_ROWS)
#: Plausible added mass as a factor of the prior's [-] (lower, upper): Wang & Clark 2006
#: Table I has analytical/experimental ratios up to 2.7 (N_rdot); strip theory's translational
#: added mass is closer (a factor 4 either way is an assumption that covers the synthetic
#: benchmark's 2-3x truths), rotation is barely constrained (a factor 5).
ADDED_MASS_FACTOR = {"translational": (0.25, 4.0), "rotational": (0.2, 5.0)}

#: Identifiability: a coefficient is calibrated only when sd_band / sd_data >=
#: MIN_INFORMATION_RATIO, with sd_data^2 = sigma^2 [(H^T H)^-1]_jj the conditional (Fisher)
#: variance given the other columns (Cramer-Rao bound of the linear model; Ljung 1999,
#: sec. 9.2, eq. 9.29). Below 0.3 the log adds less than 9 % (0.3^2) to the information of
#: the band: the MAP estimate would move by less than about a tenth of a band, noise rather
#: than a measurement, so the coefficient is kept exactly at the prior. (2.0 was tried
#: first: it froze every heave coefficient of the short ROMEO trials, Indiveri 1998, whose
#: data carry 0.4-0.9 of the band's information, and the thrust efficiency then absorbed
#: the inertia and drag errors.)
MIN_INFORMATION_RATIO = 0.3
#: ``linked_gains`` mode: the gains' groups linked through a shared DOF only where the log
#: identifies the contrast between them (:func:`stripcoef.diagnose.gains.identified_groups`).
LINKED_IDENTIFIED = "identified"
#: A DOF is excited when its velocity's standard deviation is this many times its noise
#: (the noise from second differences, :meth:`WindowData.rate_noise_variance`'s estimator)
#: and its applied force moves.
EXCITATION_SNR = 3.0
#: Fraction of the fitting log (its last part) kept to validate each change by free
#: simulation: a calibration or an effect stays only if it lowers the validation error.
VALIDATION_FRACTION = 0.25
#: Default window of the one-step residual [s]. Velocity noise of standard deviation
#: sigma_v enters the window residual as M_ii sqrt(2) sigma_v / T: 4 s windows halve the
#: noise floor of 2 s ones, while 60 windows in a 4-minute log still resolve 6-20 s steps
#: (measured: benchmarks/diagnose_detection.py --window 2 vs 4, docs/performance.md).
DEFAULT_WINDOW = 4.0
#: Velocity standard deviation above which ``dof="all"`` counts a DOF as excited [m/s, rad/s].
EXCITATION_STD = 1e-3
METRIC = "rms_window_force_residual"
METRIC_TEXT = ("RMS of the one-step force residual: the generalized force the model misses, "
               "averaged over non-overlapping windows [N or N m]")

#: Horizon of the re-simulated velocity error [s] (:data:`stripcoef.diagnose.heldout.HORIZON`).
RESIMULATION_HORIZON = 10.0


@dataclass(frozen=True)
class Budget:
    """The CPU-time budget of one diagnosis: :meth:`check` raises once it is spent.

    ``limit`` [s] (``inf``: none), ``rows`` and ``source`` (the log's, for the message) and
    ``at``, the :func:`time.process_time` deadline (None: no deadline). This process's CPU
    time, not the wall clock: a diagnosis that an idle machine finishes in its budget is not
    refused on the same machine loaded by other work (a test run beside others, a shared
    server). One is made per call of
    :func:`stripcoef.diagnose.pipeline.diagnose` (:meth:`start`) and passed to every fit."""

    limit: float = math.inf
    rows: int = 0
    source: str = ""
    at: float | None = None

    @classmethod
    def start(cls, limit: float, *, rows: int = 0, source: str = "") -> Budget:
        """A budget of ``limit`` seconds from now."""
        limit = float(limit)
        return cls(limit, int(rows), str(source),
                   time.process_time() + limit if math.isfinite(limit) else None)

    def check(self) -> None:
        """Raise :class:`~stripcoef.errors.UnreachableError` once past the deadline."""
        if self.at is not None and time.process_time() > self.at:
            raise UnreachableError(
                f"{self.source}: diagnosis stopped, over its time budget of {self.limit:g} s; "
                f"got {self.rows} log rows; expected a log this machine can fit in time "
                "(resample it, e.g. to 10 Hz, or cut it into parts)")


#: No deadline (the fits of :func:`stripcoef.diagnose.fit.fit_effects` and of a report).
UNLIMITED = Budget()


#: The ways the validation's free simulations move the DOFs a diagnosis does not diagnose
#: (:attr:`DiagnoseSettings.validation_others`). "logged": as the log (the equation
#: decoupling of output-error identification, the measured states of the equations not
#: under test entering as inputs), so that a DOF's change is judged on its own DOF and not
#: on the prior's errors in the others, which reach it through C(nu) nu and the attitude
#: (issue 33: on a BlueROV2-like log with the thrust 0.76 of the map, the prior simulates
#: roll and pitch 0.82 and 0.76 rad/s off on the validation part, and even the truth's own
#: surge coefficients and thrust scale on the prior simulate surge 0.108 m/s against the
#: prior's 0.114: the right surge scale was removed; with roll, pitch and the rest logged,
#: 0.059 against 0.138). "simulated": every DOF by the model, as before. Only a one-DOF
#: diagnosis takes the others from the log: in a whole-log one the DOFs not diagnosed are
#: those the log hardly moves, while diagnosed ones whose changes the validation removes
#: (a VideoRay's pitch, a BlueROV2's roll and pitch) still reach the others at the prior;
#: logging the undiagnosed ones there (measured on the 24 whole-log rows of seeds 5092026
#: and 5469, benchmarks/data/diagnose_independent_detect33.md) gave the error cut >= 3x in
#: 14 rows instead of 12 (three up, one down: a deadband cut 22.1 -> 1.03) and kept a
#: spurious pitch thrust asymmetry (0 -> 1 of 16): not adopted. One-DOF rows: 8 -> 13 of
#: 22 on the same logs, none lower. "each" (an option, issue 33, benchmarks/data/
#: val33_trace.md): every diagnosed DOF simulated alone, the five others logged
#: (:data:`stripcoef.diagnose.heldout.EACH`), a whole-log diagnosis included: on the
#: BlueROV2-like log 29113033 the truth's own model simulates roll and pitch 0.64 and 0.92
#: rad/s off with every DOF simulated (worse than the prior in three DOFs), 0.035 and 0.034
#: with the others logged. With "each" a whole-log diagnosis validates the thrusters' gains
#: by the joint simulation (:meth:`DiagnoseSettings.gains_logged_dofs`: judged each DOF
#: alone they reached what the selection names, three spurious steps on seed 29112026) and
#: keeps a DOF's own changes only where its decoupled simulation beats the trivial
#: predictors (:func:`stripcoef.diagnose.validate.validate_changes`; a held DOF replayed
#: open loop has no skill; each33c, benchmarks/data/each33c_trace.md). Alone it was not
#: adopted (the error cut >= 3x, up on seed 29112026's measured whole-log rows, fell 3 -> 2
#: of 4 on a fresh seed, 1795929820); the default with five others since adopt33h
#: (:data:`ADOPTED_TOGETHER`).
VALIDATION_OTHERS = ("logged", "simulated", EACH)

#: The closed loop's validation defaults adopted together (adopt33h, stop 56), each an option
#: before: ``validation_others="each"``, ``validation_horizon="correlation"``,
#: ``validation_judge="own"``, ``validation_reference="combination"``,
#: ``noise_with_bias=True``, ``linked_gains="identified"``. Each was built on traced rows and
#: failed the adoption rule alone on one seed; together, on every row of the independent
#: simulator's benchmark (``python -m benchmarks.diagnose_independent``, 88 library-effect,
#: 8 clean and 8 dry-friction diagnoses per seed, both modes) of the five seeds they were
#: built and measured on (benchmarks/data/closed_loop_options_5seeds.md), pooled of 440:
#: named first 384 -> 386, after the background 399 -> 397, magnitude within 15 % 373 ->
#: 379, error cut >= 3x 342 -> 401, whole-log runs with a spurious step named 26 -> 16 of
#: 220 and kept 9 -> 7, clean logs with an effect 3 -> 2 of 40, dry friction 40/40; on the
#: unseen sixth seed, drawn after that measurement and run with and without them before
#: anything was traced on it (benchmarks/data/closed_loop_options_seed6.md, the rule written
#: down first): better or equal on every criterion (named first 76 -> 77 of 88, error cut
#: >= 3x 68 -> 81, spurious kept 2 -> 0 of 44); pooled over the six seeds every criterion
#: better or equal but named first after the background, 480 -> 479 of 528.
ADOPTED_TOGETHER = ("validation_others", "validation_horizon", "validation_judge",
                    "validation_reference", "noise_with_bias", "linked_gains")
#: Their values before adopt33h (``diagnose(..., **BEFORE_ADOPTED)`` runs the rule before;
#: the tests of mechanisms built under it pass it).
BEFORE_ADOPTED = MappingProxyType({
    "validation_others": "logged", "validation_horizon": RESIMULATION_HORIZON,
    "validation_judge": "all", "validation_reference": "trivial", "noise_with_bias": False,
    "linked_gains": False})

#: The rules of :attr:`DiagnoseSettings.one_added_mass`: off (False), a DOF's fit more than
#: ``MIN_Z`` of its own sd from a diagnosed DOF's written added mass (True), or more than
#: ``MIN_Z`` sd of the difference of the two estimates (``"difference"``). Issue 33
#: (benchmarks/data/one_added_mass.md).
ONE_ADDED_MASS = (False, True, "difference")


@dataclass(frozen=True)
class DiagnoseSettings:
    r"""The options of one diagnosis, passed to every stage (:func:`diagnose`'s arguments).

    Attributes
    ----------
    window : float
        Window of the one-step residual [s]
    effects : tuple of str or None
        Candidate effects (None: the whole library)
    resimulate : bool
        Also compute the re-simulated velocity error
    bands : mapping or None
        Relative 1-sigma bands given by the caller (:data:`BANDS`' form), overriding
        ``prior_widths``
    max_steps : int
        Most effects added per DOF
    validation, holdout : float or None
        Fractions of the log kept to validate the changes and never fitted (None: none)
    added_mass_sd : (6,) array or None
        1-sigma method uncertainty of the prior's added mass, sd of ln M_ii [-]
    prior_widths : PriorWidths or None
        The method table's widths of the calibration's priors (a vehicle file)
    validation_others : str
        How the validation's free simulations (:func:`~stripcoef.diagnose.validate.
        validate_changes`) move the DOFs that are not diagnosed: ``"logged"`` (in a
        one-DOF diagnosis their velocities, and the attitude when roll and pitch both
        are, follow the log) or ``"simulated"`` (the model, the prior's where nothing
        was diagnosed; a whole-log diagnosis always) or ``"each"`` (default since adopt33h,
        :data:`ADOPTED_TOGETHER`: every diagnosed DOF alone, the other five logged,
        whole-log too) (:data:`VALIDATION_OTHERS`)
    one_added_mass : bool or str
        Whole-log: a DOF whose fit holds a diagnosed DOF's added mass more than ``MIN_Z``
        sd from that DOF's own (written) value is selected again with it at the prior and
        written refitted with the written value
        (:func:`stripcoef.diagnose.calibrate.contradicted`); ``"difference"``: more than
        ``MIN_Z`` sd of the two estimates' difference (:data:`ONE_ADDED_MASS`). Off by
        default: it wins the VideoRay-like issue-16 real-style log's held-out cells back
        but, paired on 30 whole-log logs of the independent simulator, wins 2 and loses 5
        (benchmarks/data/one_added_mass.md, section 5)
    not_determined : bool
        One DOF: a step found only with the thrusters' gains free (a tether) is named with
        its value not determined by one DOF and not written
        (:mod:`stripcoef.diagnose.undetermined`; on by default). False: written from the
        fit with the prior's thrust map, as before (its c_t +88 % on an independent
        BlueROV2-like log; the written model's validation error 0.9-20 % lower on the
        three such logs measured, docs/performance.md, ``tether33e``)
    gains_beside_current : bool or str
        Whole-log: the thrusters' gains, fitted before any effect, fitted again beside the
        water current the DOFs found, and the DOFs diagnosed again on them
        (:mod:`stripcoef.diagnose.regains`: the omitted-variable bias of the first fit).
        ``True``: the current held at the DOFs' value; ``"joint"``: the current free beside
        the gains (linearised), and the gains withdrawn with the current when the validation
        removes it; ``"test"``: the gains (fitted without a current) and the current
        (without gains) compared as two non-nested explanations of the prior's residual
        (Vuong 1989; not identified apart where the log does not turn, Rothenberg 1971),
        the gains kept when the log chooses them, mode ``"joint"`` when it chooses the
        current and gains beside it (Schwarz 1978), else withdrawn. Off by default: measured on the
        real-style logs (benchmarks/data/real33_trace.md, benchmarks/data/real33c_trace.md) and,
        ``True`` with the six closed-loop options and ``validation_choice="best_visited"``, on
        the independent benchmark's current, clean and tether logs only (real-style logs 29 -> 36
        of 44, no criterion worse there: benchmarks/data/real33h_trace.md, section 5). Alone
        beside the defaults (stop 57), by a rule written before the result: real-style logs
        29 -> 36 of 44, but named first 80 -> 79 of 88 on an unseen seed (a thrust
        effectiveness named before the current, then removed), so still off
        (benchmarks/data/gains_beside_current_1795981337.md)
    dof_gains : bool
        One DOF: the thrusters' gains (:mod:`stripcoef.diagnose.gains`, their contrasts
        within each group of thrusters) fitted in the diagnosed DOF's balance alone, as a
        whole-log diagnosis fits them over its DOFs, and kept as the prior of the rest of
        the diagnosis when significant, within the physical bound (``gains.MIN_GAIN``) and
        validated. On by default (``gains33c``): on every one-DOF row of the independent
        simulator's seed 29112026 named first 39 -> 40 of 44, magnitude within 15 % 34 -> 38,
        error cut >= 3x 31 -> 38, clean logs and dry friction unchanged; a fresh seed's six
        logs (1795929680) named first 5 -> 5, cut 4 -> 5 (docs/performance.md;
        benchmarks/data/gains33c_trace.md). A tether found on the
        gained map is written when it is identified apart from the gains
        (:mod:`stripcoef.diagnose.undetermined`'s one rule). False: the prior's map
    cross_mass_scale : bool
        Whole-log: a thrust scale must stay ``MIN_Z`` sd from 1 with the other DOFs' added
        masses its calibration holds free beside it (:mod:`stripcoef.diagnose.crossscale`;
        a closed loop's Coriolis feed-forward, issue 33; on by default). False: not tested
    drag_couplings : bool
        A moment DOF's calibration also holds its quadratic drag couplings
        :math:`D_Q[i, j]` to the translations that move (the moments of their drag forces;
        :mod:`stripcoef.diagnose.couplings`), written into the model. Off by default:
        measured in benchmarks/data/drag33c_trace.md
    restoring_free : bool
        The linear drag's test in surge and sway repeated, when it fails on its statistics,
        with the buoyancy change's restoring force free beside it
        (:class:`~stripcoef.effects.hydrodynamic.LinearDragBiasFree`, a nuisance parameter:
        Cox & Reid 1987; Fossen 2011 eq. 4.6; Indiveri 1998 sec. 3.3.1).
        Measured in benchmarks/data/named33d_trace.md
    scale_choice_unforced : bool
        When no candidate of a step passes and both a thrust scale and an added-mass release
        are contenders (:func:`~stripcoef.diagnose.scalechoice.contender`), the model holding
        both decides (:func:`~stripcoef.diagnose.scalechoice.unforced`). On by default
        (named33d): the fresh seed's BlueROV2 thrust effectiveness 1795930181 named in both
        modes (magnitude 6 %), every other row of the thrust-effectiveness, added-mass, clean
        and dry-friction logs of seeds 29112026 and 1795929171 unchanged
        (benchmarks/data/named33d_trace.md). False: the choice runs only when one of the
        two passed its gates
    heldout_rise : str
        When a thrust scale or a released coefficient "raises the held-out error"
        (:mod:`stripcoef.diagnose.heldoutrise`): ``"tie"`` (default, beyond ``TIE``) or
        ``"diebold_mariano"`` (the one-sided Diebold-Mariano test of the cross-validated
        window losses rejects at ``ALPHA``). Off by default: on the thrust-effectiveness,
        added-mass and clean logs of seeds 1795938998 and 1795929171 (48 diagnoses) named
        first +1 (VideoRay 1795939008 both modes named, BlueROV2 1795930181 whole-log lost to
        the cross-mass test the tie gate had shadowed), error cut >= 3x -1 and spurious kept
        +1 (the validation removes the scale with the calibration fitted beside it):
        benchmarks/data/named33f_trace.md
    validation_horizon : float or str
        Horizon of the validation's segments [s] (:func:`~stripcoef.diagnose.validate.
        validate_changes`; the thrusters' gains keep the free simulation's):
        ``"correlation"`` (default since adopt33h, :data:`ADOPTED_TOGETHER`), each
        DOF's the integral time scale of its logged velocity on the validation part, a
        k-step-ahead prediction error for a log flown in closed loop
        (:mod:`stripcoef.diagnose.horizon`; :meth:`validation_horizons`; built with
        ``"each"``, benchmarks/data/closed33d_trace.md), or a number of seconds
        (:data:`~stripcoef.diagnose.heldout.HORIZON`, 10 s, the free simulation's, the
        default before)
    validation_judge : str
        The DOFs whose validation errors judge removing a change
        (:func:`~stripcoef.diagnose.validate.validate_changes`' ``judge``): ``"own"``
        (default since adopt33h, :data:`ADOPTED_TOGETHER`: those of the changes removed,
        the equation decoupling, for ``validation_others="each"``) or ``"all"`` (the
        summed score over every DOF, the default before). Measured alone, with ``"each"``
        and the correlation horizon, the whole-log error cut >= 3x
        rose 4 -> 15 of 17 rows of seed 29112026 and 13 -> 18 of 22 of the fresh seed
        1795929171, but the fresh seed's spurious steps kept went 1 -> 3 of 22 (a pitch
        thrust scale imitating the level hold, a heave asymmetry; seed 29112026 2 -> 1):
        benchmarks/data/closed33d_trace.md, docs/performance.md. ``"coupled"``: as ``"own"``
        and also on the other DOFs whose prior simulation has skill, the outputs a change
        written into the thrusters, the restoring force or an added mass moves too (an
        option: on seed 1795938998's 15 rows where it matters it removes a kept spurious heave
        bias but loses 3 of the 13 cuts >= 3x that ``"own"`` gains: benchmarks/data/
        adopt33g_trace.md)
    linked_gains : bool or str
        The thrusters' gains' contrasts taken within each group of thrusters linked through
        the diagnosed DOFs they act in (:func:`stripcoef.diagnose.gains.thruster_groups`,
        ``linked``): a gain common to such a group is exactly a per-DOF thrust scale, so on a
        BlueROV2 Heavy the vertical four's common gain against the vectored four's (both act
        in roll and pitch) is fitted. Off by default: the groups are the thrusters with the
        same set of DOFs. Measured in benchmarks/data/spread33d_trace.md. ``"identified"``
        (:data:`LINKED_IDENTIFIED`): the groups linked through a shared DOF only where the
        log identifies their contrast (:func:`stripcoef.diagnose.gains.identified_groups`):
        the default since adopt33h (:data:`ADOPTED_TOGETHER`). Measured alone, on the
        whole-log rows of seeds 1795938998 and 1795929171 the error cut >= 3x
        rose 55 -> 58 of 88, spurious named 13 -> 12 and the clean logs 7/8 -> 8/8, but
        magnitude within 15 % fell on both seeds (73 -> 71; two BlueROV2 logs whose contrast
        the log determines and an omitted effect biases) and named first 76 -> 75
        (benchmarks/data/linked33f_trace.md)
    gains_validation : str
        How the thrusters' gains are validated (:mod:`stripcoef.diagnose.gaingate`):
        ``"consecutive"`` (consecutive 10-s segments, sum of squared error ratios at most
        the DOFs' number) or ``"rolling"`` (10-s segments restarted every 2 s, judged by
        the changes' score: no DOF worse, then that sum) or ``"rolling_test"`` (on those
        segments, kept only when better than the prior by the one-sided Diebold-Mariano
        test of the pooled loss). Measured in benchmarks/data/real33f_trace.md
    validation_reference : str
        The skill veto's reference forecast under ``validation_others="each"``
        (:func:`~stripcoef.diagnose.validate.validate_changes`' ``reference``):
        ``"combination"`` (default since adopt33h, :data:`ADOPTED_TOGETHER`: where the
        prior has no skill, the least-squares combination of the prior and the trivial
        predictors, :mod:`stripcoef.diagnose.combination`; built in
        benchmarks/data/cut33f_trace.md) or ``"trivial"`` (the best of them, the default
        before)
    gains_judge : str
        How a significant one-DOF gain fit is validated (:mod:`stripcoef.diagnose.gainjudge`):
        ``"written"`` (default since gains33f) inside the written model after the selection
        (the DOF diagnosed with and without the gains, the better written model on the
        validation log kept: on every one-DOF row of the independent benchmark's four seeds
        named first 311 -> 315 of 352, magnitude within 15 % 295 -> 302, cut 269 -> 270,
        benchmarks/data/gains33f_trace.md, docs/performance.md); ``"prior"``: alone on the prior before the
        selection (:func:`stripcoef.diagnose.gains.validated`, the rule before); ``"none"``:
        applied unvalidated. Whole-log diagnoses always use ``"prior"``'s rule unless
        ``"none"`` or ``"written_all"`` (the whole-log gains judged inside the written model
        too, an option: benchmarks/data/real33g_trace.md); ``"off"``: the gains not fitted
    noise_with_bias : bool
        The calibration's identifiability (:func:`~stripcoef.diagnose.fit._identifiability`)
        judged with the window residual's noise level fitted with a free constant beside
        the calibration's columns (:func:`~stripcoef.diagnose.fit.sigma_beside_bias`: a
        constant force the prior misses is not noise, Ljung 1999 sec. 9.2). On by default
        since adopt33h (:data:`ADOPTED_TOGETHER`; built in benchmarks/data/spur33f_trace.md);
        False: the residual's own level, the rule before
    buoyancy_carry : bool
        Heave's buoyancy offset written as one change of the buoyancy B (the model's volume),
        acting in every DOF through the restoring force (Fossen 2011, eq. 4.6), and in a
        whole-log diagnosis heave diagnosed first and the change carried into the other
        DOFs' fits (:mod:`stripcoef.diagnose.buoyancy`). Off by default: on the four seeds'
        linear-drag, tether and clean whole-log logs, magnitude within 15 % 16 -> 21 of 32,
        error cut >= 3x 17 -> 20, one clean log's surge tether gone, one spurious roll thrust
        scale kept more (seed 1795938998; benchmarks/data/buoy33g_trace.md)
    gains_beside_timing : bool
        The thrusters' gains, fitted before any effect, fitted again beside the lag or delay
        the DOFs found and the DOFs diagnosed again on them
        (:mod:`stripcoef.diagnose.timinggains`: a backfitting cycle, Hastie & Tibshirani
        1990 sec. 4.4). Off by default: on the lag and delay logs of four seeds error cut
        >= 3x 46 -> 52 of 64, but one seed names one more spurious step and another loses a
        magnitude (benchmarks/data/calib33g_trace.md)
    retest_scales : bool
        Whole-log: a thrust scale or an added-mass release (the steps judged with the bands)
        judged again in the model the shared fits (lag, delay, current) wrote into its DOF, as
        every other own step is (:func:`stripcoef.diagnose.stepwise.retest_steps`; Efroymson
        1960). Off by default: on the six logs of five seeds it reaches it removes four
        spurious steps named (a BlueROV2 roll scale 1.78 fitted before the shared lag, kept
        by the six whole-log options) but withdraws the right heave scale of the unseen seed's
        VideoRay lag log 1796060454 (0.744, the truth's 0.802: the scale-or-inertia confound),
        whose cut falls 3.94 -> 1.60 (benchmarks/data/adopt33g_trace.md)
    validation_choice : str
        The validation's final model (:func:`~stripcoef.diagnose.validate.validate_changes`'
        ``choice``): ``"greedy"`` (default, the set the backward elimination and the veto
        end with) or ``"best_visited"`` (the best on the validation data of the prior and
        every set they scored, so that the written model never scores worse than the prior
        there by the rule that judges its changes; Hastie, Tibshirani & Friedman 2009, sec.
        7.2). Off by default: with the six closed-loop options, real-style logs 29 of 44 cells
        either way (the current log's reverse split writes the prior instead of a model worse
        than it in every held-out DOF); on the whole-log current, clean and tether rows of
        seeds 29112026 and 1795938998 held by the written model 12 -> 13 of 16 but error cut
        >= 3x 12 -> 11 (benchmarks/data/real33h_trace.md); with ``gains_beside_current`` on
        every whole-log row of seed 1795971241 held by the written model 37 -> 34 of 44 and
        cut >= 3x 40 -> 38: it wrote a set other than the greedy one, or the prior, over a
        right buoyancy offset or lag on four logs (a choice among many sets on the same
        validation data, benchmarks/data/closed_loop_choice_seed6.md)
    """

    window: float = DEFAULT_WINDOW
    effects: tuple | None = None
    resimulate: bool = False
    bands: Mapping | None = None
    max_steps: int = MAX_STEPS
    validation: float | None = None
    holdout: float | None = None
    added_mass_sd: np.ndarray | None = None
    prior_widths: object = None
    validation_others: str = EACH
    one_added_mass: bool | str = False
    not_determined: bool = True
    gains_beside_current: bool | str = False
    dof_gains: bool = True
    cross_mass_scale: bool = True
    drag_couplings: bool = False
    restoring_free: bool = False
    scale_choice_unforced: bool = True
    heldout_rise: str = "tie"
    validation_horizon: float | str = "correlation"     # horizon.CORRELATION (no import cycle)
    validation_judge: str = "own"
    linked_gains: bool | str = LINKED_IDENTIFIED
    gains_validation: str = "consecutive"
    validation_reference: str = "combination"
    gains_judge: str = "written"
    noise_with_bias: bool = True
    buoyancy_carry: bool = False
    gains_beside_timing: bool = False
    retest_scales: bool = False
    validation_choice: str = "greedy"

    def validation_horizons(self, val_log, dofs):
        """The validation's horizon of each DOF of ``dofs`` [s]: None for the default
        (:data:`~stripcoef.diagnose.heldout.HORIZON`), a number as given, or with
        ``"correlation"`` :func:`stripcoef.diagnose.horizon.correlation_horizons` of the
        validation log ``val_log``."""
        from stripcoef.diagnose.horizon import CORRELATION, correlation_horizons

        if self.validation_horizon == CORRELATION:
            return correlation_horizons(val_log, dofs)
        if float(self.validation_horizon) == RESIMULATION_HORIZON:
            return None
        return [float(self.validation_horizon)] * len(dofs)

    def logged_dofs(self, dofs) -> list:
        """The DOFs (indices) the validation's free simulations take from the log: in a
        one-DOF diagnosis (``dofs`` one index) with ``validation_others`` ``"logged"``,
        every other DOF; with ``"each"``, :data:`stripcoef.diagnose.heldout.EACH` (each DOF
        alone, the others logged); else none (:data:`VALIDATION_OTHERS`)."""
        dofs = [int(i) for i in dofs]
        if self.validation_others == EACH:     # every DOF alone
            return EACH
        if self.validation_others != "logged" or len(dofs) != 1:
            return []
        return [j for j in range(6) if j not in dofs]

    def gains_logged_dofs(self, dofs):
        """The DOFs the thrusters' gains' validation (:func:`stripcoef.diagnose.gains.
        validated`) takes from the log: :meth:`logged_dofs`, except that with ``"each"`` a
        whole-log diagnosis judges the gains by the joint simulation of every DOF (none
        logged). A change of each DOF's own equation (its calibration, its effects) is judged
        on that DOF simulated alone; the gains are fitted jointly over the DOFs (one
        multiresponse fit, :mod:`stripcoef.diagnose.gains`) before any DOF is selected and
        are the prior of every DOF's selection, so that with each DOF alone the validation
        would reach what the selection names: on seed 29112026 of the independent benchmark
        the gains judged DOF by DOF were kept on two BlueROV2-like logs and removed on a
        VideoRay-like one where the joint simulation did the opposite, and the selection on
        the other prior named three spurious steps the default does not name (roll and
        pitch thrust scales, a heave thrust asymmetry, a yaw buoyancy offset;
        benchmarks/data/each33c_trace.md). Judged jointly, ``"each"`` changes what the
        validation keeps, never what the selection names."""
        dofs = [int(i) for i in dofs]
        if self.validation_others == EACH and len(dofs) > 1:
            return []
        return self.logged_dofs(dofs)

    @property
    def widths(self):
        """The :class:`~stripcoef.diagnose.priors.PriorWidths` the calibration uses: None
        when bands are given (they override the method table)."""
        return self.prior_widths if self.bands is None else None

    def band_table(self) -> Mapping:
        """The relative 1-sigma bands of the calibration: those given, else the method
        table's (:attr:`widths`), else :data:`BANDS`."""
        widths = self.widths
        return self.bands or (widths.bands if widths is not None else BANDS)

    def band_sd(self, dof: int):
        """The 1-sigma method uncertainty of DOF ``dof``'s added mass (sd of ln M_ii), or
        None."""
        sd = self.added_mass_sd
        return None if sd is None else float(sd[dof])
