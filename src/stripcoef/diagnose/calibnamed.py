r"""The calibration's own departures from the prior named as the effects they are
(option ``calibration_named``, :attr:`~stripcoef.diagnose.settings.DiagnoseSettings.
calibration_named`; off by default).

The calibration (:mod:`.pipeline`, step 2) fits each DOF's inertia and drags within their
bands before any effect, and refits them beside every step. A log whose effect is a change
of one of those coefficients (an added mass 2-3 times the file's, a larger linear drag) can
be explained by the calibration alone: the release of the coefficient then adds little to
what the calibration already did, fails the evidence gate (:mod:`.evidence`: "the release
is named only if it explains more of the residual than the calibration already did") and
no step names anything, although the written model holds the change (issue 33, VideoRay
added mass 1796071248 of seed 1795971241: X_udot 1.42 -> 2.52 kg, +77 %, 2.56 bands, cut
12.6x, "nothing named"; benchmarks/data/named33i_trace.md).

The rule names such a departure with the gate an effect that only mimics a calibrated
coefficient must pass (:func:`~stripcoef.diagnose.select._judge`): the coefficient's change
in the **written** model lies beyond :data:`~stripcoef.diagnose.settings.MIMIC_BANDS` bands of
its prior (the band: the Gaussian prior's 1-sigma, ``band_relative`` x the prior value),
and the log determines it (:math:`|\Delta c| / \sigma_{\Delta c} \ge` ``MIN_Z``, the
step's z gate). The named effect is the library's that mimics the coefficient
(:data:`MIMICS`: ``M`` -> ``added_mass_error``, ``D_L`` -> ``linear_drag``; no library
effect is a change of ``D_Q``), its parameter the change as written, so the name is what the
written model holds. A calibration the validation removed names nothing, nor a coefficient
kept at the prior, nor one whose effect a kept step of the DOF already names. Nothing else
changes: the steps, the calibration and the written model are the same with the option off.

Depends on: diagnose.result, diagnose.settings, effects.
"""

from __future__ import annotations

from dataclasses import replace

from stripcoef.diagnose.settings import MIMIC_BANDS, MIN_Z

#: calibrated coefficient -> (the library effect that mimics it, that effect's parameter)
MIMICS = {"M": ("added_mass_error", "delta_m"), "D_L": ("linear_drag", "d_L")}


def departures(calibration, steps=()) -> list[dict]:
    """The departures of one DOF's written calibration (a :class:`~.result.Calibration` or
    its dictionary) that the rule names (module docstring), each ``effect``, ``parameters``
    (the change in the written model [kg, kg m^2, N s/m or N m s/rad]), ``coefficient``,
    ``prior``, ``written``, ``relative`` (change / prior [-]), ``bands`` (change / band [-]),
    ``z`` (change / its posterior sd [-]) and ``rule``; ``steps``: the DOF's steps (their
    dictionaries), whose kept effects are not named again."""
    cal = calibration if isinstance(calibration, dict) else calibration.to_dict()
    if cal.get("kept") is False:
        return []
    named = {s["effect"] for s in steps if s.get("kept", True) is not False}
    final = cal.get("final_parameters") or cal["parameters"]
    held = cal.get("kept_at_prior") or {}
    out = []
    for key, (effect, parameter) in MIMICS.items():
        if key not in final or key in held or effect in named:
            continue
        change, prior = float(final[key]), float(cal["prior"][key])
        band = float(cal["band_relative"][key]) * abs(prior)
        std = float(cal["std"].get(key, float("nan")))
        if not (band > 0 and std > 0):
            continue
        bands, z = change / band, change / std
        if abs(bands) >= MIMIC_BANDS and abs(z) >= MIN_Z:
            out.append({"effect": effect, "parameters": {parameter: change},
                        "coefficient": key, "prior": prior, "written": prior + change,
                        "relative": change / prior if prior else float("nan"),
                        "bands": bands, "z": z,
                        "rule": f"the calibrated {key} is {bands:+.2f} bands from the prior "
                                f"(beyond {MIMIC_BANDS:g}) and {z:+.1f} sd from it (beyond "
                                f"{MIN_Z:g}): the written model holds it"})
    return out


def named(per: dict) -> dict:
    """``per`` (DOF -> :class:`~.result.DofResult`) with each DOF's ``calibration_named``
    set to its :func:`departures` (None where there are none)."""
    out = {}
    for d, r in per.items():
        found = departures(r.calibration, [s.to_dict() if hasattr(s, "to_dict") else s
                                           for s in r.steps])
        out[d] = replace(r, calibration_named=tuple(found) or None)
    return out
