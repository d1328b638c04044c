"""The diagnosis' options as command-line flags: one registry for every benchmark that runs
:func:`stripcoef.diagnose.diagnose` (``benchmarks.diagnose_independent``,
``benchmarks.real_logs`` and their traces).

Every flag's default is ``None``: an option left out is diagnose's own default
(:class:`stripcoef.diagnose.settings.DiagnoseSettings`, read there and nowhere else), so a
benchmark run without flags measures what a user gets. :func:`given` turns the parsed
arguments into diagnose's keyword arguments, :func:`command_text` writes them back as the
flags that reproduce a run.

Use::

    ap = argparse.ArgumentParser(...)
    add_flags(ap)
    options = given(ap.parse_args(argv))      # diagnose(log, prior, **options)
"""

from __future__ import annotations

import argparse

#: (flag, keyword of diagnose, argparse keywords); several flags may set one keyword
#: (``--noise-with-bias`` / ``--no-noise-with-bias``). Every default is None.
FLAGS = (
    ("--validation-others", "validation_others",
     {"choices": ("logged", "simulated", "each"),
      "help": "how the validation's free simulations move the DOFs not diagnosed "
              "(validation_others)"}),
    ("--validation-horizon", "validation_horizon",
     {"metavar": "SECONDS|correlation",
      "help": "the validation's segments [s], or 'correlation': each DOF's velocity's "
              "integral time scale (validation_horizon)"}),
    ("--validation-judge", "validation_judge",
     {"choices": ("all", "own", "coupled"),
      "help": "'own': a removal judged on the DOFs of the changes it removes; 'coupled': "
              "and on the other DOFs whose prior simulation has skill (validation_judge)"}),
    ("--validation-reference", "validation_reference",
     {"choices": ("trivial", "combination"),
      "help": "'combination': in a DOF the prior does not predict, the skill veto's "
              "reference is the prior combined with the trivial predictors "
              "(validation_reference)"}),
    ("--validation-choice", "validation_choice",
     {"choices": ("greedy", "best_visited"),
      "help": "'best_visited': the validation's final model the best on the validation "
              "part of the prior, the kept set and every set the elimination scored "
              "(validation_choice)"}),
    ("--noise-with-bias", "noise_with_bias",
     {"action": "store_true",
      "help": "the calibration's identifiability judged with the noise level fitted beside "
              "a free constant (noise_with_bias)"}),
    ("--no-noise-with-bias", "noise_with_bias",
     {"action": "store_false", "help": "noise_with_bias=False (the rule before adopt33h)"}),
    ("--linked-gains", "linked_gains",
     {"nargs": "?", "const": True, "choices": (True, "identified", "off"),
      "help": "the thrusters' gains' contrasts within groups linked through the diagnosed "
              "DOFs they act in; 'identified': only where the log identifies the groups' "
              "contrast; 'off': not linked (linked_gains)"}),
    ("--one-added-mass", "one_added_mass",
     {"action": "store_true",
      "help": "whole-log: a DOF whose fit contradicts a diagnosed DOF's own added mass "
              "selected again (one_added_mass)"}),
    ("--dof-gains", "dof_gains",
     {"action": "store_true",
      "help": "one DOF: the thrusters' gains fitted in the DOF's balance (dof_gains)"}),
    ("--no-dof-gains", "dof_gains",
     {"action": "store_false", "help": "one DOF on the prior's thrust map (dof_gains=False)"}),
    ("--gains-beside-current", "gains_beside_current",
     {"nargs": "?", "const": True, "choices": (True, "joint", "test"),
      "metavar": "joint|test",
      "help": "whole-log: the thrusters' gains fitted again beside the current the DOFs "
              "found; 'joint': with the current free beside them; 'test': the gains and the "
              "current compared as two explanations, Vuong 1989 (gains_beside_current)"}),
    ("--gains-beside-timing", "gains_beside_timing",
     {"action": "store_true",
      "help": "the thrusters' gains fitted again beside the lag or delay the DOFs found "
              "(gains_beside_timing)"}),
    ("--gains-validation", "gains_validation",
     {"choices": ("consecutive", "rolling", "rolling_test"),
      "help": "'rolling': the thrusters' gains validated on 10-s segments restarted every "
              "2 s (gains_validation, stripcoef.diagnose.gaingate)"}),
    ("--gains-judge", "gains_judge",
     {"choices": ("prior", "written", "none", "written_all"),
      "help": "'written': a significant one-DOF gain fit judged inside the written model "
              "after the selection; 'written_all': a whole-log fit too (gains_judge)"}),
    ("--drag-couplings", "drag_couplings",
     {"action": "store_true",
      "help": "a moment DOF's calibration holds its drag couplings to the translations "
              "(drag_couplings)"}),
    ("--restoring-free", "restoring_free",
     {"action": "store_true",
      "help": "the linear drag's test in surge and sway repeated with the buoyancy change "
              "free (restoring_free)"}),
    ("--no-scale-choice-unforced", "scale_choice_unforced",
     {"action": "store_false",
      "help": "a scale and an added-mass release, both contenders of a step none passes, "
              "left undecided (scale_choice_unforced=False: the rule before named33d)"}),
    ("--heldout-rise", "heldout_rise",
     {"choices": ("tie", "diebold_mariano"),
      "help": "'diebold_mariano': a scale or a released coefficient refused for a held-out "
              "rise only when the Diebold-Mariano test of the window losses rejects "
              "(heldout_rise)"}),
    ("--retest-scales", "retest_scales",
     {"action": "store_true",
      "help": "whole-log: a thrust scale or an added-mass release judged again beside the "
              "shared fits (retest_scales)"}),
    ("--buoyancy-carry", "buoyancy_carry",
     {"action": "store_true",
      "help": "heave's buoyancy offset written as one change of B, acting in every DOF, and "
              "carried whole-log (buoyancy_carry)"}),
)


def add_flags(ap: argparse.ArgumentParser) -> None:
    """Add every flag of :data:`FLAGS` to ``ap``, each defaulting to None (diagnose's own
    default)."""
    for flag, key, kw in FLAGS:
        ap.add_argument(flag, dest=key, default=None, **kw)


def given(args: argparse.Namespace) -> dict:
    """The options of :data:`FLAGS` given on the command line, as diagnose's keyword
    arguments (a horizon in seconds as a float, ``--linked-gains off`` as False); an option
    left out is not in the dict."""
    out = {}
    for _, key, _ in FLAGS:
        value = getattr(args, key, None)
        if value is None or key in out:
            continue
        if key == "validation_horizon" and value != "correlation":
            value = float(value)
        out[key] = False if (key == "linked_gains" and value == "off") else value
    return out


def command_text(options: dict) -> str:
    """The flags that reproduce ``options`` (:func:`given`'s dict), each with a leading
    space: ``" --linked-gains off --validation-horizon 10.0"``."""
    text = ""
    for key, value in options.items():
        flags = [(flag, kw) for flag, k, kw in FLAGS if k == key]
        if not flags:
            raise ValueError(f"{key!r} is not a diagnosis option of benchmarks.diagnose_flags")
        if len(flags) > 1:          # a store_true / store_false pair: the one that sets value
            flag = next(f for f, kw in flags
                        if kw["action"] == ("store_true" if value else "store_false"))
            text += f" {flag}"
        elif flags[0][1].get("action") in ("store_true", "store_false"):
            text += f" {flags[0][0]}"
        elif value is True:
            text += f" {flags[0][0]}"
        else:
            text += f" {flags[0][0]} {'off' if value is False else value}"
    return text
