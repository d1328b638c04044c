"""`stripcoef diagnose` end to end: JSON contract, report, calibrated model for simulate."""

import json

import pytest

from stripcoef import cli
from validation.synthetic import generate
from stripcoef.logfile import read_log
from stripcoef.modelfile import load_model
from stripcoef.export import write_export


def save_model(model, path):
    write_export(model, "json" if str(path).endswith(".json") else "yaml", path)




@pytest.fixture(scope="module")
def tether_case(tmp_path_factory):
    d = tmp_path_factory.mktemp("diag")
    log, prior, truth = generate("tether_drag", seed=3, duration=160.0)
    log.write_csv(d / "log.csv")
    save_model(prior, d / "prior.yaml")
    return d, truth


@pytest.fixture(scope="module")
def short_case(tmp_path_factory):
    """A 20 s log and its prior for the refusals below (no diagnosis runs: the 160 s log of
    ``tether_case`` cost 3.4 s of CPU to simulate for them in the fast loop)."""
    d = tmp_path_factory.mktemp("diag-short")
    log, prior, _ = generate("tether_drag", seed=3, duration=20.0)
    log.write_csv(d / "log.csv")
    save_model(prior, d / "prior.yaml")
    return d


@pytest.mark.slow
def test_json_contract_report_and_calibrated_model(tether_case, capsys):
    d, truth = tether_case
    rc = cli.main(["diagnose", str(d / "log.csv"), "--vehicle", str(d / "prior.yaml"),
                   "--dof", "surge", "--json", "--report", str(d / "report.md"),
                   "--out", str(d / "calibrated.yaml")])
    assert rc == 0
    res = json.loads(capsys.readouterr().out)
    for key in ("metric", "baseline_error", "calibrated_error", "steps", "final_error",
                "unexplained"):
        assert key in res
    assert res["metric"] == "rms_window_force_residual"
    step = res["steps"][0]
    for key in ("effect", "parameters", "std", "error_before", "error_after",
                "held_out_error_before", "held_out_error_after"):
        assert key in step
    assert step["effect"] == "tether_drag"
    assert step["parameters"]["c_t"] == pytest.approx(truth["magnitude"], rel=0.15)
    assert res["baseline_error"] > 3 * res["final_error"]
    assert res["unexplained"] is False
    rs = res["resimulated_velocity_rms"]["surge"]
    assert set(rs) == {"baseline", "calibrated", "final"}
    text = (d / "report.md").read_text()
    assert "tether_drag" in text and "![surge residuals](report_surge.png)" in text
    assert (d / "report_surge.png").stat().st_size > 1000
    # the calibrated model is a model file that simulate reads, with the tether effect
    cal = load_model(d / "calibrated.yaml")
    assert [e["name"] for e in cal.effects] == ["tether_drag"]
    # every change it carries survived the free-simulation validation (issue 16)
    assert res["validation"]["kept_changes"]["surge"] <= res["validation"]["prior"]["surge"]


@pytest.mark.slow
def test_calibrated_model_simulates_the_log_better(tmp_path, capsys):
    # truth = prior + an undeclared tether (no coefficient perturbation): the prior's
    # re-simulation misses the tether, the calibrated model reproduces the log
    log, prior, truth = generate("tether_drag", seed=4, perturb=0.0, duration=100.0)
    log.write_csv(tmp_path / "log.csv")
    save_model(prior, tmp_path / "prior.yaml")
    rc = cli.main(["diagnose", str(tmp_path / "log.csv"), "--vehicle",
                   str(tmp_path / "prior.yaml"), "--dof", "surge", "--out",
                   str(tmp_path / "cal.yaml"), "--no-resimulate"])
    capsys.readouterr()
    assert rc == 0
    from stripcoef.diagnose.pipeline import resimulate_rms
    log = read_log(tmp_path / "log.csv")
    before = resimulate_rms(log, load_model(tmp_path / "prior.yaml"), [0], horizon=10.0)[0]
    after = resimulate_rms(log, load_model(tmp_path / "cal.yaml"), [0], horizon=10.0)[0]
    assert after < 0.6 * before
    assert after < 0.02  # velocity noise is 0.01 m/s
    # and `stripcoef simulate` accepts the calibrated model file
    rc = cli.main(["simulate", str(tmp_path / "cal.yaml"), "--inputs", str(tmp_path / "log.csv"),
                   "--out", str(tmp_path / "sim.csv")])
    assert rc == 0
    assert len(read_log(tmp_path / "sim.csv")) == len(log)


@pytest.mark.slow
def test_all_dofs_text_output(tether_case, capsys):
    d, _ = tether_case
    rc = cli.main(["diagnose", str(d / "log.csv"), "--vehicle", str(d / "prior.yaml"),
                   "--no-resimulate"])
    out = capsys.readouterr().out
    assert rc == 0
    for dof in ("surge", "sway", "heave", "yaw"):
        assert dof in out
    assert "tether_drag" in out


@pytest.mark.parametrize("args, needle", [
    (["--dof", "sideways"], "dof"),
    (["--effects", "tether"], "tether_drag"),
    (["--window", "0"], "--window"),
    (["--out", "/nonexistent/dir/cal.yaml"], "--out"),
])
def test_bad_arguments_one_line_exit_2(short_case, capsys, args, needle):
    d = short_case
    rc = cli.main(["diagnose", str(d / "log.csv"), "--vehicle", str(d / "prior.yaml"),
                   "--no-resimulate", *args])
    err = capsys.readouterr().err
    assert rc == 2 and needle in err and len(err.strip().splitlines()) == 1


def test_bad_logs(tmp_path, short_case, capsys):
    d = short_case
    (tmp_path / "short.csv").write_text("t,u,n_port\n0,0,1\n1,0,1\n2,0,1\n")
    (tmp_path / "novel.csv").write_text("t,n_port\n" + "".join(f"{i},1\n" for i in range(100)))
    (tmp_path / "nan.csv").write_text("t,u,n_port\n0,0,1\n1,nan,1\n")
    for name, needle in (("short.csv", "too short"), ("novel.csv", "velocity"),
                         ("nan.csv", "row 3")):
        rc = cli.main(["diagnose", str(tmp_path / name), "--vehicle", str(d / "prior.yaml"),
                       "--out", str(tmp_path / "cal.yaml")])
        err = capsys.readouterr().err
        assert rc == 2 and needle in err, (name, err)
        assert not (tmp_path / "cal.yaml").exists()
