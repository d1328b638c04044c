"""Option ``calibration_named`` (``stripcoef.diagnose.calibnamed``): the written calibration's
departure of a DOF's inertia or linear drag from the prior beyond MIMIC_BANDS bands and
MIN_Z sd is named as the effect that mimics it, its value the written model's change; and
option ``bias_gains_one_dof`` (``stepwise.OneDofBiasParts``): a one-DOF surge bias that the
thrusters' gains take is refused. Issue 33, benchmarks/data/named33i_trace.md."""

import pytest

from stripcoef.diagnose.calibnamed import MIMICS, departures
from stripcoef.diagnose.settings import MIMIC_BANDS, MIN_Z


def _cal(change, std, prior=1.4, band=0.3, key="M", **extra):
    return {"parameters": {key: change}, "std": {key: std}, "prior": {key: prior},
            "band_relative": {key: band}, "band_source": {key: "test"},
            "band_z": {key: change / (band * prior)}, "kept_at_prior": {},
            "information_ratio": {key: 5.0}, "final_parameters": {key: change}, **extra}


def test_a_departure_beyond_the_bands_is_named_with_the_written_change():
    change = 1.01 * MIMIC_BANDS * 0.3 * 1.4
    (found,) = departures(_cal(change, change / (2 * MIN_Z)))
    assert found["effect"] == "added_mass_error"
    assert found["parameters"] == {"delta_m": pytest.approx(change)}
    assert found["written"] == pytest.approx(1.4 + change)
    assert found["bands"] == pytest.approx(1.01 * MIMIC_BANDS)
    assert found["relative"] == pytest.approx(change / 1.4)


@pytest.mark.parametrize("case", ["within the bands", "not determined", "removed",
                                  "kept at the prior", "named by a step"])
def test_nothing_named(case):
    beyond = 1.2 * MIMIC_BANDS * 0.3 * 1.4
    cal = {"within the bands": _cal(0.9 * beyond / 1.2 * 0.99 / 1.01, 0.01),
           "not determined": _cal(beyond, beyond / (0.9 * MIN_Z)),
           "removed": _cal(beyond, 0.01, kept=False),
           "kept at the prior": {**_cal(beyond, 0.01), "kept_at_prior": {"M": "why"}},
           "named by a step": _cal(beyond, 0.01)}[case]
    steps = ([{"effect": "added_mass_error", "kept": True}] if case == "named by a step"
             else [])
    assert departures(cal, steps) == []


def test_a_removed_step_does_not_stop_the_name():
    beyond = 1.2 * MIMIC_BANDS * 0.3 * 1.4
    found = departures(_cal(beyond, 0.01), [{"effect": "added_mass_error", "kept": False}])
    assert [f["effect"] for f in found] == ["added_mass_error"]


def test_a_linear_drag_and_a_decrease():
    prior, band = 2.0, 0.6
    change = -1.1 * MIMIC_BANDS * band * prior
    (found,) = departures(_cal(change, 0.01, prior=prior, band=band, key="D_L"))
    assert (found["effect"], found["parameters"]) == ("linear_drag", {"d_L": change})
    assert found["bands"] < -MIMIC_BANDS
    assert set(MIMICS) == {"M", "D_L"}


def _log(vehicle, category, seed):
    from benchmarks.named33f_trace import _log as log
    return log(vehicle, category, seed)


@pytest.mark.slow
def test_the_absorbed_added_mass_is_named_and_the_model_unchanged():
    """VideoRay added mass 1796071248 (seed 1795971241), one DOF: no step; the calibration
    holds X_udot 1.42 -> 2.52 kg (2.56 bands); the option names it, nothing else changes."""
    import warnings

    from stripcoef.diagnose import diagnose
    from stripcoef.diagnose.report import text_summary

    prior, log, truth = _log("videoray_pro3", "added_mass_error", 1796071248)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        off = diagnose(log, prior, dof="surge", time_limit=float("inf"))
        on = diagnose(log, prior, dof="surge", time_limit=float("inf"),
                      calibration_named=True)
    r_off, r_on = off.per_dof["surge"], on.per_dof["surge"]
    assert r_off.steps == r_on.steps == ()
    assert r_off.calibration_named is None
    (found,) = r_on.calibration_named
    assert found["effect"] == "added_mass_error"
    written = float(on.model.added_mass[0, 0])
    assert written == pytest.approx(float(off.model.added_mass[0, 0]), rel=1e-12)
    assert found["written"] == pytest.approx(written, rel=1e-9)
    assert found["parameters"]["delta_m"] == pytest.approx(written - prior.added_mass[0, 0],
                                                          rel=1e-9)
    assert "named by the calibration" in text_summary(on)
    assert "named by the calibration" not in text_summary(off)


@pytest.mark.slow
def test_a_one_dof_surge_bias_the_gains_take_is_refused():
    """VideoRay thrust effectiveness 1795971251 (seed 1795971241), one DOF: a surge bias
    named first over the scale by default; with the option the scale comes first."""
    import warnings

    from stripcoef.diagnose import diagnose

    prior, log, truth = _log("videoray_pro3", "thrust_effectiveness", 1795971251)
    names = {}
    for flag in (False, True):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = diagnose(log, prior, dof="surge", time_limit=float("inf"),
                           bias_gains_one_dof=flag)
        names[flag] = [s.effect for s in res.per_dof["surge"].steps]
    assert names[False][0] == "buoyancy_offset"
    assert names[True][0] == "thrust_effectiveness"
    assert "buoyancy_offset" not in names[True]


def test_the_benchmark_counts_the_calibration_apart():
    """``benchmarks.diagnose_independent.calibration_named_lines``: a DOF without steps counts
    the calibration's named departure in "first_named"; the table's count stays the steps'."""
    from benchmarks.diagnose_independent import calibration_named_lines

    def row(category, first, named, mode="dof", dof="surge", **extra):
        return {"vehicle": "v", "category": category, "seed": 1, "mode": mode, "dof": dof,
                "first": first, "first_named": first or (named[0]["effect"] if named else None),
                "calibration_named": {dof: named} if named else {}, **extra}

    mass = [{"effect": "added_mass_error", "value": 1.1, "relative": 0.77, "bands": 2.56}]
    rows = [row("added_mass_error", None, mass, calibration_magnitude_error=0.09),
            row("added_mass_error", "thrust_effectiveness", mass),
            row("thrust_effectiveness", None, mass),
            row("clean", None, mass, mode="all")]
    (blank, line) = calibration_named_lines(rows)
    assert blank == ""
    assert "named first, a DOF without steps counting the calibration's named departure: 1/3" \
        in line
    assert "(steps only: 0/3)" in line
    assert "named by the calibration alone in 2 rows, the right effect in 1, its magnitude " \
           "within 15 % in 1" in line
    assert "clean logs with a departure named: 1 of 1" in line
    assert calibration_named_lines([{k: v for k, v in r.items() if k != "first_named"}
                                    for r in rows]) == []
