"""One calibrated model (issue 33): every number `diagnose` prints or reports about the model
it writes is that model's, recomputed here from the file `--out` wrote, read back.

For several logs (the shipped tether sample, per DOF and whole-log, with hold-out and
validation; seeded synthetic logs of validation/synthetic.py with a native effect) the
command is run with --out, --json and --report (and a tether that one DOF names without
determining its c_t: not written), the model file is read back
(`stripcoef.modelfile.load_model`) and each printed value is recomputed from it: the
calibrated coefficients, the parameters of each kept effect, the absence of each removed
one, the final window error on the fitting part of the log, the validation and held-out
free-simulation errors. Equal within 1e-9 relative (the file holds the floats' repr).
"""

import json

import numpy as np
import pytest

import stripcoef.diagnose.pipeline as pipeline
from stripcoef import cli, samples
from stripcoef.conventions import DOF, parse_dof
from stripcoef.diagnose.calibrate import SHARED_TIMING, bounds_hit
from stripcoef.diagnose.heldout import EACH, compare, split
from stripcoef.diagnose.report import _fmt, text_summary
from stripcoef.diagnose.settings import VALIDATION_FRACTION
from stripcoef.diagnose.validate import validation_errors
from stripcoef.diagnose.written import coefficient, window_errors, written_effects
from stripcoef.effects.laws import get_effect
from stripcoef.export import write_export
from stripcoef.logfile import read_log
from stripcoef.modelfile import load_model
from validation.synthetic import generate

import _shared_memo

REL = 1e-9

#: each case diagnoses a log (5-11 s of CPU): slow, like the other diagnose tests
pytestmark = pytest.mark.slow


def _synthetic(tmp, effect, seed, duration):
    log, prior, _ = generate(effect, seed=seed, duration=duration)
    log.write_csv(tmp / "log.csv")
    write_export(prior, "json", tmp / "prior.json")
    return str(tmp / "log.csv"), str(tmp / "prior.json")


def _gains_off(tmp):
    """The synthetic ROV whose port and starboard thrusters deliver 0.8 and 1.2 of the
    prior's map, with a tether (seed 1, 120 s): one DOF fits the thrusters' gains in its
    balance (``dof_gains``, the default) and names the tether on the gained map, identified
    apart from the gains, and writes both (stripcoef.diagnose.undetermined's rule; on the
    prior's map the tether is found only with the gains free and not written,
    tests/test_undetermined.py)."""
    from dataclasses import replace

    from validation.synthetic import rov_model
    gains = {"port": 0.8, "starboard": 1.2}
    prior = rov_model()
    truth = replace(prior, thrusters=[
        replace(th, eta_forward=th.eta_forward * gains.get(th.name, 1.0),
                eta_backward=th.eta_backward * gains.get(th.name, 1.0))
        for th in prior.thrusters])
    log, _, _ = generate("tether_drag", 1, prior=truth, duration=120.0)
    log.write_csv(tmp / "log.csv")
    write_export(prior, "json", tmp / "prior.json")
    return str(tmp / "log.csv"), str(tmp / "prior.json")


def _sample(tmp):
    return str(samples.path("rov_tether.csv")), str(samples.path("rov_prior.json"))


CASES = {
    # the tutorial's run: M_heave of the written file was not the printed one
    "sample-surge": (_sample, ["--dof", "surge"]),
    # a hold-out: the validation removes the tether step, the calibration is refitted
    "sample-surge-holdout": (_sample, ["--dof", "surge", "--holdout", "0.3"]),
    # whole-log: several DOFs, cross added masses of DOFs diagnosed themselves
    "sample-all": (_sample, ["--dof", "all"]),
    # a native effect (folded into the thrusters), read back from the provenance
    "synthetic-deadband": (lambda t: _synthetic(t, "deadband", 3, 120.0), ["--dof", "surge"]),
    # a non-native effect with a nonlinear parameter
    "synthetic-current": (lambda t: _synthetic(t, "current", 1, 120.0), ["--dof", "surge"]),
    # a tether written beside the thrusters' gains fitted in the DOF (both written)
    "synthetic-tether-gains-off": (_gains_off, ["--dof", "surge"]),
}


@pytest.fixture(scope="module", params=sorted(CASES))
def run(request, tmp_path_factory):
    tmp = tmp_path_factory.mktemp(request.param)
    make, extra = CASES[request.param]
    log_path, prior_path = make(tmp)
    out, report = tmp / "calibrated.yaml", tmp / "report.md"
    import contextlib
    import io
    buf = io.StringIO()
    # diagnose() once per run for the arguments the documentation's commands also run (the
    # tutorial's is sample-surge, diagnose.md's held-out check sample-surge-holdout:
    # tests/_shared_memo.py), its warnings issued again
    shared = _shared_memo.shared_call(pipeline.diagnose, "stripcoef.diagnose.pipeline.diagnose")
    captured = {}

    def capture(*args, **kwargs):       # the Diagnosis itself: its fits, beyond the JSON
        captured["result"] = shared(*args, **kwargs)
        return captured["result"]

    with contextlib.redirect_stdout(buf), pytest.MonkeyPatch.context() as mp:
        mp.setattr(pipeline, "diagnose", capture)
        rc = cli.main(["diagnose", log_path, "--vehicle", prior_path, "--no-resimulate",
                       "--json", "--out", str(out), "--report", str(report), *extra])
    assert rc == 0
    res = json.loads(buf.getvalue())
    return {"res": res, "model": load_model(out), "log": read_log(log_path),
            "prior": load_model(prior_path), "report": report.read_text(),
            "text": text_summary(res), "holdout": "--holdout" in extra, "case": request.param,
            "result": captured["result"]}


def _same(a, b):
    assert a == pytest.approx(b, rel=REL, abs=1e-12)


def test_calibrated_coefficients_are_the_files(run):
    res, model, text = run["res"], run["model"], run["text"]
    for d, r in res["per_dof"].items():
        i = parse_dof(d)
        cal = r["calibration"]
        assert set(cal["written"]) == set(cal["parameters"])
        for k, w in cal["written"].items():
            _same(w, coefficient(model, i, k))
            _same(cal["prior"][k] + cal["final_parameters"][k], coefficient(model, i, k))
            assert f"{k} {_fmt(cal['prior'][k])} -> {_fmt(w)}" in text
            assert f"| {k}[{d}] | {_fmt(cal['prior'][k])} | {_fmt(w)} |" in run["report"]


def test_effects_kept_are_the_files_and_removed_ones_are_absent(run):
    res, model = run["res"], run["model"]
    for d, r in res["per_dof"].items():
        written = written_effects(model, d)
        in_effects = {e["name"]: e for e in model.effects if e.get("dof") == d}
        for s in r["steps"]:
            if s["kept"]:
                assert set(s["parameters"]) == set(written[s["effect"]])
                for k, v in s["parameters"].items():
                    _same(v, written[s["effect"]][k])
                    _same(s["final_parameters"][k], v)
                if not get_effect(s["effect"]).native:
                    for k, v in s["parameters"].items():
                        _same(v, in_effects[s["effect"]]["parameters"][k])
            elif s.get("not_determined"):
                # named, its value not determined by one DOF: not written, reported with
                # the gain-free value, said so (stripcoef.diagnose.undetermined)
                nd = s["not_determined"]
                assert s["effect"] not in written and s["effect"] not in in_effects
                assert s["parameters"] == {nd["parameter"]: nd["gains_free"]}
                assert f"{nd['parameter']} not determined by one DOF" in run["text"]
                assert nd["advice"] in run["text"] and nd["advice"] in run["report"]
                assert f"{s['effect']} (not determined by one DOF)" in run["report"]
            else:
                assert s["effect"] not in written and s["effect"] not in in_effects
                assert any(x.startswith(f"{s['effect']} {d}")
                           for x in res["validation"]["removed"])
        kept = [s["effect"] for s in r["steps"] if s["kept"]]
        assert sorted(written) == sorted(kept)
    removed = [s for r in res["per_dof"].values() for s in r["steps"]
               if not s["kept"] and not s.get("not_determined")]
    for s in removed:   # shown as removed in the text and in the report
        assert "[removed" in run["text"] and f"{s['effect']} (removed)" in run["report"]


def test_the_gains_off_case_writes_the_tether_beside_the_gains_fitted_in_the_dof(run):
    """The case is what it is meant to be: the gains fitted in the DOF and written, the
    tether named first on the gained map and written (identified apart from the gains)."""
    steps = run["res"]["per_dof"]["surge"]["steps"]
    named = [s for s in steps if s.get("not_determined")]
    if run["case"] == "synthetic-tether-gains-off":
        assert run["res"]["thruster_gains"]["applied"]
        assert steps[0]["effect"] == "tether_drag" and not named
        assert steps[0]["kept"] is True
    elif run["res"]["dof"] == "all" or run["case"].startswith("sample"):
        assert not named


def _parts(run):
    """(fitting, validation, held-out) parts of the log, cut as diagnose cuts them."""
    log = run["log"]
    fit_log, test_log = split(log, 0.3) if run["holdout"] else (log, None)
    train, val = split(fit_log, VALIDATION_FRACTION, key="validation")
    t0, t1 = run["res"]["fitted_on_s"]
    assert train["t"][0] == t0 and train["t"][-1] == t1
    return train, val, test_log


def test_final_error_is_the_written_models(run):
    res, model = run["res"], run["model"]
    train, _, _ = _parts(run)
    dofs = [parse_dof(d) for d in res["per_dof"]]
    errors = window_errors(train, model, dofs, window=res["window_s"])
    for d, r in res["per_dof"].items():
        _same(r["final_error"], errors[d])
        row = [line for line in run["report"].splitlines() if line.startswith(f"| {d} [")][0]
        assert f"| {_fmt(r['final_error'])} |" in row
    if res["dof"] == "all":
        rel = np.sqrt(np.mean([(errors[d] / r["baseline_error"]) ** 2
                               for d, r in res["per_dof"].items()]))
        _same(res["final_error"], rel)
    else:
        _same(res["final_error"], errors[res["dof"]])


def test_a_dof_fitted_beside_another_added_mass_says_so(run):
    """Whole-log: another DOF's added mass enters a DOF's balance through C_A(nu) nu and is
    written once, its own DOF's value; a DOF whose fit held it at another value is written
    with the rest of its fit (`calibration.fitted_with`, printed and reported) and its final
    error is the written model's (test_final_error_is_the_written_models). The shipped
    sample's whole-log run has such DOFs (surge's fit holds M_heave at 4.30 where heave's
    own calibration, written, gives 3.78, 5.9 sd apart): the chain is exercised, not
    vacuous. Each fitted value is the DOF's final fit's, read from the Diagnosis."""
    res, model, result = run["res"], run["model"], run["result"]
    beside = {d: dict(r["calibration"].get("fitted_with") or {})
              for d, r in res["per_dof"].items()}
    if res["dof"] == "all":
        assert any(beside.values())
    else:
        assert not any(beside.values())
    refitted = set(res["validation"].get("refitted") or {})
    for d, r in res["per_dof"].items():
        i = parse_dof(d)
        cal = r["calibration"]
        for k, v in beside[d].items():
            w = coefficient(model, i, k)
            assert abs(v - w) > 1e-9 * abs(w)
            assert f"{k} {_fmt(v)} (written {_fmt(w)})" in run["text"]
            assert f"{k} {_fmt(v)} (written {_fmt(w)})" in run["report"]
        fit = result.fits[d]
        if (d in refitted or cal.get("kept") is False or fit.config.data.known_added_mass
                or not all(st["kept"] for st in r["steps"])):
            continue            # refitted (written_fit): not the selection's final fit
        theta = fit.evaluation["full"]["theta"]
        for j, k in enumerate(fit.config.cal.names):
            if k.startswith("M_"):
                value = cal["prior"][k] + float(theta[j])
                if abs(value - coefficient(model, i, k)) > 1e-9 * abs(value):
                    _same(beside[d][k], value)
                else:
                    assert k not in beside[d]


def test_validation_and_held_out_errors_are_the_written_models(run):
    res, model, prior = run["res"], run["model"], run["prior"]
    _, val, test_log = _parts(run)
    dofs = [parse_dof(d) for d in res["per_dof"]]
    # the DOFs the validation took from the log: "each" (the default: each diagnosed DOF
    # alone, the other five logged), or a list (with "logged": a one-DOF diagnosis every
    # other one); the horizon of each DOF's segments as recorded (None: the free simulation's)
    logged = res["validation"]["logged_dofs"]
    if logged != EACH:
        logged = [parse_dof(d) for d in logged]
        assert logged == ([j for j in range(6) if j not in dofs] if len(dofs) == 1 else [])
    horizon = res["validation"]["horizon_s"]
    horizon = None if horizon is None else [horizon[DOF[i]] for i in dofs]
    kept = validation_errors(val, model, dofs, logged, horizon)
    for d in res["per_dof"]:
        _same(res["validation"]["kept_changes"][d], kept[d])
    if test_log is not None:
        errors = compare(test_log, {"prior": prior, "calibrated": model}, dofs)
        for d, e in res["holdout"]["errors"].items():
            _same(e["calibrated"], errors[d]["calibrated"])
            _same(e["prior"], errors[d]["prior"])
            _same(e["zero_velocity"], errors[d]["zero_velocity"])


def test_a_removed_step_leaves_its_partners_refitted(run):
    """The effects of a DOF whose calibration is removed go with it (the thrusters' shared
    timing excepted: refitted alone); the changes kept beside a removed one are refitted
    (and said so)."""
    res = run["res"]
    for d, r in res["per_dof"].items():
        if r["calibration"].get("kept") is False:
            assert not any(s["kept"] for s in r["steps"] if s["effect"] not in SHARED_TIMING)
        removed = (any(not s["kept"] and not s.get("not_determined") for s in r["steps"])
                   or r["calibration"].get("kept") is False)
        kept = [s for s in r["steps"] if s["kept"]] or r["calibration"].get("kept") is not False
        if removed and kept:
            assert d in res["validation"]["refitted"]


def test_bounds_hit_lists_an_effect_written_at_a_bound():
    """A thrust scale written at its lower bound 0.05 is listed (issue 33: it was not)."""
    prior = load_model(samples.path("rov_prior.json"))
    cal = prior.with_provenance(diagnose=[{
        "dof": "pitch", "calibration": {}, "effects": ["thrust_effectiveness"],
        "parameters": {"thrust_effectiveness": {"scale": 0.05}},
        "at_bound": {"thrust_effectiveness": "lower"}}])
    hits = bounds_hit(prior, cal)
    assert "0.05 at the lower bound" in hits["pitch"]["thrust_effectiveness"]


def test_a_report_asked_after_the_budget_deadline_is_written(monkeypatch):
    """The report's residual curves refit the stored configurations: they ran under the
    diagnosis's own budget, a deadline 300 s after the call began, so a report asked later
    (a notebook, a shared result, a long log's report after 290 s of diagnosing) stopped with
    'over its time budget'. The figure's fits are not the diagnosis's: no deadline."""
    import warnings

    import stripcoef.diagnose.settings as settings
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.logfile import read_log
    from stripcoef.modelfile import load_model

    log = read_log(samples.path("rov_tether.csv"))
    model = load_model(samples.path("rov_prior.json"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = diagnose(log, model, dof="surge", resimulate=False, time_limit=300.0)
    real = settings.time.process_time
    monkeypatch.setattr(settings.time, "process_time", lambda: real() + 1000.0)
    t, curves = result.residual_curves("surge")
    assert [label for label, _ in curves][:2] == ["prior", "calibrated"]
    assert all(np.all(np.isfinite(c)) and len(c) == len(t) for _, c in curves)
