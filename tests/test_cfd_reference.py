"""The stored OpenFOAM references (reference_tables/cfd) and the model-against-CFD comparison:
portable files, exact round trip, the comparison's arithmetic on known matrices, and the
command that reads a stored result."""

from __future__ import annotations

import json
from pathlib import Path, PurePosixPath

import numpy as np
import pytest
from conftest import one_line_error

from stripcoef.cfd.case import DOFS
from stripcoef.cfd.compare import compare_rows
from stripcoef.cfd.result import CfdResult, DofResult, RunResult

ROOT = Path(__file__).resolve().parents[1]
FOLDER = ROOT / "reference_tables" / "cfd"
STORED = sorted(FOLDER.glob("*.json"))


def _strings(obj):
    if isinstance(obj, str):
        yield obj
    elif isinstance(obj, dict):
        for v in obj.values():
            yield from _strings(v)
    elif isinstance(obj, list):
        for v in obj:
            yield from _strings(v)


def test_stored_results_exist():
    assert len(STORED) >= 4


@pytest.mark.parametrize("path", STORED, ids=lambda p: p.name)
def test_stored_result_is_portable_and_round_trips(path):
    """No folder of the machine that wrote it (no absolute path, no /tmp); the source is a
    file of this repository; from_dict -> to_dict gives the file back."""
    data = json.loads(path.read_text())
    for s in _strings(data):
        assert not s.startswith("/") and "/tmp" not in s, s
    assert (ROOT / data["source"]).is_file()
    assert all("/" not in r["case"] for d in data["dofs"] for r in d["runs"])
    again = CfdResult.from_dict(data).to_dict()
    assert json.dumps(again, sort_keys=True) == json.dumps(data, sort_keys=True)


@pytest.mark.parametrize("path", STORED, ids=lambda p: p.name)
def test_stored_result_damping_is_its_runs(path):
    """d_Q of every stored DOF is -F/u|u| of its finest run, the spread that of the two
    levels, C_D = d_Q / (rho A / 2): the stored numbers are consistent with their runs."""
    res = CfdResult.from_dict(json.loads(path.read_text()))
    for d in res.dofs:
        fine = d.runs[0]
        assert d.d_quadratic == pytest.approx(-fine.force / fine.speed ** 2, rel=1e-9)
        if len(d.runs) > 1:
            coarse = d.runs[-1]
            dq0 = -coarse.force / coarse.speed ** 2
            assert d.mesh_spread == pytest.approx(abs(d.d_quadratic - dq0) / d.d_quadratic,
                                                  rel=1e-9)
            assert d.gci == pytest.approx(d.mesh_spread, rel=1e-12)   # Fs 3, r 2, p 2
        if d.drag_coefficient is not None:
            assert d.drag_coefficient == pytest.approx(
                d.d_quadratic / (0.5 * res.density * d.reference_area), rel=1e-9)


def _result(dof, speed, force, levels=(4,)):
    runs = tuple(RunResult(dof=dof, speed=speed, level=lv, cells=1, iterations=1,
                           status="converged", force=force, swing=0.0, drift=0.0,
                           force_vector=(0, 0, 0), moment_vector=(0, 0, 0),
                           case=f"{dof}_L{lv}") for lv in levels)
    d = DofResult(dof=dof, runs=runs, d_linear=None, d_quadratic=-force / speed ** 2,
                  mesh_spread=None, drag_coefficient=None, reference_area=1.0,
                  converged=True)
    return CfdResult(source="x.stl", length=1.0, size=1.0, density=1000.0, viscosity=1e-6,
                     levels=levels, ranks=1, case_dir="c", dofs=(d,))


@pytest.mark.parametrize("dof", list(DOFS))
def test_comparison_puts_the_right_diagonal_term_beside_the_cfd(dof):
    """The model's force at the CFD speed is d_L u + d_Q u^2 of the DOF's own diagonal
    (translations 0-2, rotations 3-5), and the ratio is that over the CFD's force."""
    dl = np.diag([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
    dq = np.diag([10.0, 20.0, 30.0, 40.0, 50.0, 60.0])
    i = DOFS[dof][0] + 3 * DOFS[dof][1]
    (row,) = compare_rows(_result(dof, 0.5, -40.0), dl, dq)
    assert row.model_d_quadratic == dq[i, i] and row.model_d_linear == dl[i, i]
    assert row.model_force == pytest.approx(dl[i, i] * 0.5 + dq[i, i] * 0.25)
    assert row.cfd_force == 40.0 and row.cfd_d_quadratic == pytest.approx(160.0)
    assert row.ratio == pytest.approx(row.model_force / 40.0)


def test_comparison_of_a_non_positive_cfd_force_has_no_ratio():
    (row,) = compare_rows(_result("surge", 1.0, 3.0), np.zeros((6, 6)), np.eye(6))
    assert np.isnan(row.ratio)


@pytest.mark.slow
def test_stored_result_compared_from_the_command(capsys):
    """`stripcoef cfd MESH --result FILE --compare --json`: the CFD numbers are the stored
    ones, the model's those of `stripcoef coefficients` for the same mesh, water and speed
    about the centroid; the text prints the ratio it holds."""
    from stripcoef.cli import main

    stl, stored = FOLDER / "cube_1m.stl", FOLDER / "cube_surge.json"
    assert main(["cfd", str(stl), "--result", str(stored), "--compare", "--json", "-q"]) == 0
    out = json.loads(capsys.readouterr().out)
    ref = json.loads(stored.read_text())
    (row,) = out["compare"]["rows"]
    assert row["cfd_force"] == pytest.approx(-ref["dofs"][0]["runs"][0]["force"])
    assert out["dofs"] == ref["dofs"]
    assert main(["coefficients", str(stl), "--json", "-q", "--speed", "1",
                 "--rho", str(ref["density"]), "--nu", str(ref["viscosity"]),
                 "--added-mass-method", "strips"]) == 0
    model = json.loads(capsys.readouterr().out)
    assert row["model_d_quadratic"] == pytest.approx(model["quadratic_damping"][0][0],
                                                     rel=1e-9)
    assert row["model_d_linear"] == pytest.approx(model["linear_damping"][0][0], rel=1e-9,
                                                  abs=1e-12)
    assert main(["cfd", str(stl), "--result", str(stored), "--compare", "-q"]) == 0
    text = capsys.readouterr().out
    assert f"{row['ratio']:9.3f}" in text and "model/CFD" in text


def test_bad_stored_result_is_one_line(capsys, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"source": "x"}')
    one_line_error(capsys, ["cfd", FOLDER / "cube_1m.stl", "--result", bad], "--result",
                   "bad.json")
    one_line_error(capsys, ["cfd", FOLDER / "cube_1m.stl", "--result", tmp_path / "none.json"],
                   "--result")


def test_run_folder_of_an_old_absolute_path():
    from stripcoef.cfd.result import run_folder

    assert run_folder("/tmp/ref-box/surge_1m_s_L4") == "surge_1m_s_L4"
    assert run_folder(str(PurePosixPath("surge_1m_s_L3"))) == "surge_1m_s_L3"


def test_comparison_model_damping_is_the_default_estimates():
    """The comparison model's coarse section panels (COMPARE_SECTION_PANELS) change only its
    added mass: the damping compared is the default estimate's, bit for bit."""
    import warnings

    from stripcoef.assembly import EstimateOptions, estimate
    from stripcoef.cfd.compare import model_for
    from stripcoef.fluid import Fluid
    from stripcoef.geometry.vehicle import load_vehicle

    vehicle = load_vehicle(Path(__file__).resolve().parent.parent / "reference_tables" / "cfd"
                           / "cylinder_ld1.stl", origin="centroid")
    water = Fluid(density=998.0, kinematic_viscosity=1e-6, source="test water")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fast = model_for(vehicle, speed=0.5, fluid=water)
        full = estimate(vehicle, EstimateOptions(speed=0.5, reference_point="origin",
                                                 fluid=water, added_mass_method="strips"))
    np.testing.assert_array_equal(fast.linear_damping, full.linear_damping)
    np.testing.assert_array_equal(fast.quadratic_damping, full.quadratic_damping)
    assert not np.array_equal(fast.added_mass, full.added_mass)   # the option took effect
