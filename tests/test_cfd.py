"""stripcoef cfd: the case files read back, the force reader on real OpenFOAM output, the
damping fit on exact data, the one-line errors, and one smoke run when OpenFOAM is here."""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import numpy as np
import pytest
import trimesh
from conftest import one_line_error

from stripcoef.cfd.case import (
    DOWNSTREAM,
    LATERAL,
    UPSTREAM,
    CaseSpec,
    background,
    freestream_turbulence,
    write_case,
)
from stripcoef.cfd.drag import drag_by_cfd, frontal_area
from stripcoef.cfd.foamdict import parse
from stripcoef.cfd.forces import (
    Settled,
    fatal_line,
    mesh_report,
    read_forces,
    read_log,
    settle,
)
from stripcoef.cfd.result import CONVERGED, DIVERGED, NOT_CONVERGED, fit_damping, judge
from stripcoef.cfd.runner import openfoam_environment
from stripcoef.errors import ExternalToolError

ROOT = Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "reference_tables" / "cfd" / "sample_forces"
CUBE = ROOT / "reference_tables" / "cfd" / "cube_1m.stl"


def _spec(dof="surge", ranks=1, **kw):
    box = trimesh.creation.box((0.46, 0.58, 0.25))
    args = dict(dof=dof, speed=1.5, level=3, length=0.58, size=0.46,
                bounds=tuple(map(tuple, box.bounds)), density=1025.0, viscosity=1.19e-6,
                reference_area=0.145, ranks=ranks, mrf_radius=0.5, mrf_half_length=0.3)
    args.update(kw)
    return CaseSpec(**args), box


def _read(folder, name):
    return parse((folder / name).read_text())


@pytest.mark.parametrize("dof,axis", [("surge", 0), ("sway", 1), ("heave", 2)])
def test_translation_case_box_patches_and_inflow(tmp_path, dof, axis):
    spec, box = _spec(dof)
    case = write_case(tmp_path / dof, spec, box)
    bm = _read(case.folder, "system/blockMeshDict")
    verts = np.array(bm["vertices"], float)
    lo, hi = verts.min(axis=0), verts.max(axis=0)
    L = spec.length
    # clearances (COST 732): at least UPSTREAM L before the body on +axis, DOWNSTREAM behind
    assert hi[axis] - box.bounds[1][axis] >= UPSTREAM * L - 1e-9
    assert box.bounds[0][axis] - lo[axis] >= DOWNSTREAM * L - 1e-9
    for b in range(3):
        if b != axis:
            assert hi[b] - box.bounds[1][b] >= LATERAL * L - 1e-9
    # the background cells tile the box exactly
    cells = np.array(bm["blocks"][2])
    assert np.allclose((hi - lo) / cells, case.background.h0)
    assert np.prod(cells) <= 8000
    patches = bm["boundary"]
    names = set(patches)
    assert {"inlet", "outlet"} <= names and len(names) == 6
    # the inlet is the +axis face: its four vertices share hi[axis]
    face = patches["inlet"]["faces"][0]
    assert np.allclose(verts[face][:, axis], hi[axis])
    assert all(patches[n]["type"] == "symmetryPlane" for n in names - {"inlet", "outlet"})
    # the water flows against the motion at the speed
    u = _read(case.folder, "0.orig/U")
    inflow = u["boundaryField"]["inlet"]["value"][1]
    expect = [0.0, 0.0, 0.0]
    expect[axis] = -1.5
    assert np.allclose(inflow, expect)
    assert u["boundaryField"]["body"]["type"] == "fixedValue"
    # freestream turbulence of the SST model (Menter 1994): omega 5 U/L, nu_t 1e-3 nu
    k, om = freestream_turbulence(spec)
    assert om == pytest.approx(5 * 1.5 / L)
    assert k / om == pytest.approx(1e-3 * 1.19e-6)
    cd = _read(case.folder, "system/controlDict")
    fc = cd["functions"]["forceCoeffs"]
    assert np.allclose(fc["dragDir"], [-v for v in np.eye(3)[axis]])
    assert fc["Aref"] == pytest.approx(0.145) and fc["magUInf"] == pytest.approx(1.5)
    assert cd["functions"]["forces"]["patches"] == ["body"]
    assert not (case.folder / "constant" / "MRFProperties").exists()
    assert trimesh.load(case.folder / "constant/triSurface/body.stl").is_watertight


@pytest.mark.parametrize("dof,axis", [("roll", 0), ("pitch", 1), ("yaw", 2)])
def test_rotation_case_mrf_zone_axis(tmp_path, dof, axis):
    spec, box = _spec(dof, speed=2.0)
    case = write_case(tmp_path / dof, spec, box)
    mrf = _read(case.folder, "constant/MRFProperties")["rotor"]
    assert np.allclose(mrf["axis"], np.eye(3)[axis])
    assert mrf["omega"] == pytest.approx(2.0) and mrf["cellZone"] == "rotor"
    act = _read(case.folder, "system/topoSetDict")["actions"][0]
    p1, p2 = np.array(act["p1"]), np.array(act["p2"])
    assert np.allclose(np.cross(p2 - p1, np.eye(3)[axis]), 0)      # the cylinder's axis
    assert act["radius"] == pytest.approx(0.5)
    u = _read(case.folder, "0.orig/U")
    assert u["internalField"] == ["uniform", [0, 0, 0]]                # still water
    assert set(_read(case.folder, "system/blockMeshDict")["boundary"]) == {"tank"}
    sol = _read(case.folder, "system/fvSolution")["SIMPLE"]
    assert "pRefPoint" in sol                                          # closed tank


def test_decomposition_for_ranks_and_allrun(tmp_path):
    spec, box = _spec(ranks=6)
    case = write_case(tmp_path / "c", spec, box)
    dec = _read(case.folder, "system/decomposeParDict")
    assert dec["method"] == "hierarchical" and dec["numberOfSubdomains"] == 6
    assert int(np.prod(dec["coeffs"]["n"])) == 6
    run = (case.folder / "Allrun").read_text()
    assert "mpirun -np 6 simpleFoam -parallel" in run and "decomposePar" in run
    assert os.access(case.folder / "Allrun", os.X_OK)
    serial = write_case(tmp_path / "s", _spec(ranks=1)[0], box)
    assert "mpirun" not in (serial.folder / "Allrun").read_text()
    assert not (serial.folder / "system" / "decomposeParDict").exists()


def test_snappy_distance_shells_and_levels(tmp_path):
    spec, box = _spec(level=4)
    case = write_case(tmp_path / "c", spec, box)
    snappy = _read(case.folder, "system/snappyHexMeshDict")
    cmc = snappy["castellatedMeshControls"]
    n = case.background.surface_level
    # the surface cell is size / 2**level whatever the background cells
    assert case.background.h0 / 2 ** n == pytest.approx(spec.size / 2 ** 4)
    assert cmc["refinementSurfaces"]["body"]["level"] == [n, n]
    shells = cmc["refinementRegions"]["body"]
    assert shells["mode"] == "distance"
    d = [lv[0] for lv in shells["levels"]]
    lv = [lv[1] for lv in shells["levels"]]
    assert d == sorted(d) and lv == sorted(lv, reverse=True) and lv[0] == n
    loc = np.array(cmc["locationInMesh"])
    assert not box.contains([loc])[0]


def test_background_is_coarsened_for_a_slender_body():
    rod = trimesh.creation.box((2.0, 0.1, 0.1))
    spec = CaseSpec(dof="surge", speed=1, level=3, length=2.0, size=0.1,
                    bounds=tuple(map(tuple, rod.bounds)), density=1000, viscosity=1e-6,
                    reference_area=0.01)
    bg = background(spec)
    assert np.prod(bg.cells) <= 8000
    assert bg.h0 / 2 ** bg.surface_level == pytest.approx(0.1 / 8)


def test_frontal_area_of_a_box():
    box = trimesh.creation.box((0.46, 0.58, 0.25))
    assert frontal_area(box, 0) == pytest.approx(0.58 * 0.25, rel=1e-9)
    assert frontal_area(box, 2) == pytest.approx(0.46 * 0.58, rel=1e-9)


def test_force_reader_on_real_openfoam_output():
    """Stored rows of a real run (cube 1 m face-on, 1 m/s, rho 1000, A 1 m^2): the forces
    read here give the Cd OpenFOAM's own forceCoeffs wrote."""
    hist = read_forces(SAMPLE)
    coef = np.loadtxt(SAMPLE / "forceCoeffs" / "0" / "coefficient.dat")
    assert hist.iteration.size == 60
    assert np.array_equal(hist.iteration, coef[:, 0].astype(int))
    cd = -hist.force[:, 0] / (0.5 * 1000.0 * 1.0 ** 2 * 1.0)
    assert np.allclose(cd, coef[:, 1], rtol=1e-6)
    assert np.allclose(hist.force, hist.pressure_force + hist.viscous_force, rtol=1e-6,
                       atol=1e-6)
    s = settle(hist.force[:, 0])
    assert s.finite and s.spread < 0.02 and s.window == 30 and s.settled
    assert -s.value / 500.0 == pytest.approx(1.06, abs=0.01)


def test_force_reader_old_format_and_restart(tmp_path):
    d0 = tmp_path / "postProcessing" / "forces" / "0"
    d1 = tmp_path / "postProcessing" / "forces" / "2"
    d0.mkdir(parents=True)
    d1.mkdir(parents=True)
    row = "{t}\t(({a} 0 0) (1 0 0) (0 0 0)) ((0 0 {m}) (0 0 0) (0 0 0))\n"
    d0.joinpath("forces.dat").write_text("# Forces\n" + "".join(
        row.format(t=t, a=10 * t, m=t) for t in (1, 2, 3)))
    d1.joinpath("forces.dat").write_text("".join(row.format(t=t, a=-t, m=-t) for t in (3, 4)))
    hist = read_forces(tmp_path)
    assert hist.iteration.tolist() == [1, 2, 3, 4]
    assert hist.force[:, 0].tolist() == [11, 21, -2, -3]     # pressure + viscous; the restart's
    assert hist.moment[:, 2].tolist() == [1, 2, -3, -4]
    with pytest.raises(FileNotFoundError):
        read_forces(tmp_path / "nothing")


def test_log_reader():
    text = ("Time = 1\nsmoothSolver:  Solving for Ux, Initial residual = 1, Final residual"
            " = 0.1, No\nGAMG:  Solving for p, Initial residual = 0.5, Final\n"
            "Time = 2\nsmoothSolver:  Solving for Ux, Initial residual = 0.01, Final\n"
            "Time = 3\n")
    st = read_log(text)
    assert st.iteration == 3 and st.residuals == {"Ux": 0.01} and not st.converged
    assert read_log(text + "SIMPLE solution converged in 3 iterations\n").converged
    err = "[1] --> FOAM FATAL ERROR: \n[1] \n[1]     Maximum number of iterations exceeded\n"
    assert fatal_line(err) == "Maximum number of iterations exceeded"
    assert "diverged" in fatal_line("#0 Foam::sigFpe::sigHandler(int)")
    header = "sigFpe : Enabling floating point exception trapping (FOAM_SIGFPE).\n"
    assert fatal_line(header + "End\n") == ""
    assert fatal_line(header + err) == "Maximum number of iterations exceeded"
    cm = ("    cells:            6642\n\nChecking patch topology\n"
          "                   Patch    Faces   Points\n"
          "                   inlet      121      144\n"
          "                    body      384      418\n\n Failed 1 mesh checks.\n")
    assert mesh_report(cm) == (6642, {"inlet": 121, "body": 384}, 1)


def test_damping_fit_from_two_speeds_exact():
    d_l, d_q = 3.7, 41.0
    u = np.array([0.5, 1.5])
    f = -(d_l * u + d_q * u * np.abs(u))
    fl, fq = fit_damping(u, f)
    assert fl == pytest.approx(d_l, rel=1e-12) and fq == pytest.approx(d_q, rel=1e-12)
    fl1, fq1 = fit_damping([2.0], [-(d_q * 4.0)])
    assert fl1 is None and fq1 == pytest.approx(d_q)


def test_judge_marks_runs():
    def st(value=-5.0, spread=0.01, drift=0.001, finite=True):
        return Settled(value=value, spread=spread, drift=drift, window=100, finite=finite)

    assert judge(st(), False, "", 300)[0] == CONVERGED
    assert judge(st(spread=0.3), False, "", 1000)[0] == NOT_CONVERGED     # a wide swing
    assert judge(st(drift=0.05), False, "", 1000)[0] == NOT_CONVERGED     # a drifting mean
    assert judge(st(drift=0.05), True, "", 400)[0] == CONVERGED           # residuals met
    assert judge(st(value=float("nan"), finite=False), False, "", 10)[0] == DIVERGED
    assert judge(st(), False, "floating point exception", 10)[0] == DIVERGED


def test_openfoam_missing_is_one_line(capsys, monkeypatch, tmp_path):
    monkeypatch.setenv("PATH", str(tmp_path))
    with pytest.raises(ExternalToolError, match="apt-get install openfoam"):
        openfoam_environment(1)
    line = one_line_error(capsys, ["cfd", CUBE, "--case-dir", tmp_path / "c", "-q"],
                          "openfoam", "OpenFOAM not found")
    assert line.startswith("stripcoef cfd: error:")


def test_write_only_needs_no_openfoam(capsys, monkeypatch, tmp_path):
    from stripcoef.cli import main

    monkeypatch.setenv("PATH", str(tmp_path))
    rc = main(["cfd", str(CUBE), "--dofs", "surge,yaw", "--write-only", "--case-dir",
               str(tmp_path / "c"), "--json", "-q"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0 and len(out["written"]) == 4 and out["dofs"] == []
    assert all("/" not in w and (Path(out["case_dir"]) / w / "Allrun").is_file()
               for w in out["written"])


@pytest.mark.parametrize("argv,words", [
    (["--dofs", "surge,spin"], ("--dofs", "spin")),
    (["--levels", "3,x"], ("--levels",)),
    (["--speeds", "-1"], ("--speeds",)),
    (["--ranks", "0"], ("--ranks",)),
])
def test_bad_options_are_one_line(capsys, tmp_path, argv, words):
    one_line_error(capsys, ["cfd", CUBE, "--write-only", "--case-dir", tmp_path / "c", *argv],
                   *words)


def test_vehicle_file_writes_its_united_surface(capsys, tmp_path):
    """A vehicle file: its parts united (geometry.surface.vehicle_surface), its reference
    speed and water in the case."""
    from stripcoef.cli import main
    from stripcoef.geometry.vehicle import load_vehicle

    path = ROOT / "geometry" / "remus100.yaml"
    vehicle = load_vehicle(path)
    rc = main(["cfd", str(path), "--write-only", "--case-dir", str(tmp_path / "c"), "--json",
               "-q"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0 and out["density"] == pytest.approx(vehicle.fluid.density)
    folder = Path(out["case_dir"]) / out["written"][0]
    body = trimesh.load(folder / "constant/triSurface/body.stl")
    assert body.is_watertight and out["length"] == pytest.approx(max(body.extents), rel=1e-6)
    u = _read(folder, "0.orig/U")["boundaryField"]["inlet"]["value"][1]
    assert u[0] == pytest.approx(-vehicle.reference_speed)


def test_open_surface_refused(tmp_path):
    mesh = trimesh.creation.box((1, 1, 1))
    mesh.update_faces(np.arange(len(mesh.faces)) > 0)
    with pytest.raises(Exception, match="closed"):
        drag_by_cfd(mesh, write_only=True, case_dir=tmp_path / "c")


def _need_openfoam():
    if shutil.which("simpleFoam") is None:
        if os.environ.get("STRIPCOEF_REQUIRE_OPENFOAM") == "1":
            pytest.fail("simpleFoam not found but STRIPCOEF_REQUIRE_OPENFOAM=1")
        pytest.skip("OpenFOAM not installed (apt-get install openfoam)")


@pytest.fixture(scope="module")
def serial_smoke(tmp_path_factory):
    """The tiny serial case (a 0.2 m cube, about 4k cells, 60 iterations, one rank), run once
    for the smoke test and as the two-rank test's reference mesh size."""
    _need_openfoam()
    folder = tmp_path_factory.mktemp("cfd_serial") / "c"
    cube = trimesh.creation.box((0.2, 0.2, 0.2))
    res = drag_by_cfd(cube, dofs=("surge",), speeds=(1.0,), levels=(2,), ranks=1,
                      iterations=60, case_dir=folder)
    return res, folder


@pytest.mark.slow
def test_smoke_run_openfoam(serial_smoke):
    """A real run on a tiny case (a 0.2 m cube, about 4k cells, 60 iterations, one rank):
    the pipeline from the mesh to the damping works; the number is not a reference."""
    res, folder = serial_smoke
    run = res.dofs[0].runs[0]
    assert run.cells > 1000 and run.iterations == 60
    assert np.isfinite(run.force) and run.force < 0          # drag opposes the motion
    assert run.status in (CONVERGED, NOT_CONVERGED)
    assert res.dofs[0].d_quadratic > 0
    assert (folder / "surge_1m_s_L2" / "log.simpleFoam").is_file()
    assert run.y_plus is not None and 0 < run.y_plus[0] <= run.y_plus[2] <= run.y_plus[1]


@pytest.mark.slow
def test_smoke_run_two_ranks_decomposed(serial_smoke, tmp_path, monkeypatch):
    """The same tiny case decomposed for 2 ranks (decomposePar, mpirun -np 2 ... -parallel)
    runs through: a mesh of the serial one's size (snappyHexMesh in parallel refines the
    decomposed blocks: measured 3,968 against 3,891 cells) and a finite drag after 20
    iterations (a start-up transient, not a value: the test is that the decomposed solver
    runs and reconstructs, which 20 iterations show as well as 60).

    Open MPI's ranks poll for messages in a busy loop by default; on a machine whose other
    cores run other tests that spin is most of this test's CPU (measured 22.9 s of CPU for
    both runs, 12.1 s with ``mpi_yield_when_idle``): the ranks yield here, which changes no
    number of the run.  Open MPI also pins each rank to a core by default: beside another
    test worker that keeps one core busy, the rank pinned there starves and the other waits
    for it at every exchange (measured beside one busy process: 42.0 s with the pinning,
    6.4 s without; 2.8 s on an idle machine), so the ranks are not pinned here either."""
    _need_openfoam()
    if shutil.which("mpirun") is None:
        pytest.skip("mpirun not installed")
    monkeypatch.setenv("OMPI_MCA_mpi_yield_when_idle", "1")
    monkeypatch.setenv("OMPI_MCA_hwloc_base_binding_policy", "none")
    cube = trimesh.creation.box((0.2, 0.2, 0.2))
    one = serial_smoke[0].dofs[0].runs[0]
    two = drag_by_cfd(cube, ranks=2, case_dir=tmp_path / "two", dofs=("surge",),
                      speeds=(1.0,), levels=(2,), iterations=20).dofs[0].runs[0]
    folder = tmp_path / "two" / two.case
    assert (folder / "processor0").is_dir() and (folder / "processor1").is_dir()
    assert "mpirun -np 2 simpleFoam -parallel" in (folder / "Allrun").read_text()
    assert two.iterations == 20 and two.cells == pytest.approx(one.cells, rel=0.05)
    assert np.isfinite(two.force) and two.status != "diverged"


def _fake_openfoam(tmp_path, monkeypatch, **scripts):
    """Fake OpenFOAM programs on the PATH (each a bash script; ``name=body``)."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    etc = tmp_path / "foam" / "etc"
    etc.mkdir(parents=True)
    (etc / "controlDict").write_text("")
    ok = "echo End; exit 0"
    for name in ("blockMesh", "surfaceFeatureExtract", "snappyHexMesh", "checkMesh",
                 "potentialFoam", "simpleFoam", "topoSet"):
        f = bin_dir / name
        f.write_text("#!/bin/bash\n" + scripts.get(name, ok) + "\n")
        f.chmod(0o755)
    monkeypatch.setenv("PATH", f"{bin_dir}:/usr/bin:/bin")
    monkeypatch.setenv("WM_PROJECT_DIR", str(tmp_path / "foam"))


CHECKMESH_OK = ("cat <<'X'\n    cells:            5000\n\n"
                "                   Patch    Faces   Points\n"
                "                    body      384      418\n\nMesh OK.\nX")


def test_snappy_failure_is_one_line(capsys, monkeypatch, tmp_path):
    _fake_openfoam(tmp_path, monkeypatch, snappyHexMesh=(
        "echo '--> FOAM FATAL ERROR: '; echo '    Cannot find surface body.stl'; exit 1"))
    line = one_line_error(capsys, ["cfd", CUBE, "--ranks", "1", "--levels", "3",
                                   "--case-dir", tmp_path / "c", "-q"],
                          "snappyHexMesh failed", "Cannot find surface body.stl", "log.")
    assert line.startswith("stripcoef cfd: error:")


def test_mesh_without_body_is_one_line(capsys, monkeypatch, tmp_path):
    _fake_openfoam(tmp_path, monkeypatch, checkMesh=CHECKMESH_OK.replace("body", "inlet"))
    one_line_error(capsys, ["cfd", CUBE, "--ranks", "1", "--levels", "3", "--case-dir",
                            tmp_path / "c", "-q"], "no faces on the body")


def test_diverged_run_is_marked_not_a_number(capsys, monkeypatch, tmp_path):
    """A solver that stops on a floating point exception: the result says diverged, the
    command warns, the JSON says converged false."""
    from stripcoef.cli import main

    diverge = ("mkdir -p postProcessing/forces/0; for i in 1 2 3; do echo \"Time = $i\"; "
               "echo \"$i (-$i 0 0) (-$i 0 0) (0 0 0)\" >> postProcessing/forces/0/force.dat; "
               "echo \"$i (0 0 0) (0 0 0) (0 0 0)\" >> postProcessing/forces/0/moment.dat; done;"
               " echo '#0  Foam::sigFpe::sigHandler(int)'; echo 'Floating point exception';"
               " exit 136")
    _fake_openfoam(tmp_path, monkeypatch, checkMesh=CHECKMESH_OK, simpleFoam=diverge)
    rc = main(["cfd", str(CUBE), "--ranks", "1", "--levels", "3", "--case-dir",
               str(tmp_path / "c"), "--json", "-q"])
    captured = capsys.readouterr()
    out = json.loads(captured.out)
    assert rc == 0 and out["converged"] is False
    run = out["dofs"][0]["runs"][0]
    assert run["status"] == DIVERGED and "diverged" in run["note"]
    assert run["cells"] == 5000 and run["iterations"] == 3
    assert "NOT CONVERGED" in captured.err or "not converge" in captured.err
    # the text names it too
    rc = main(["cfd", str(CUBE), "--ranks", "1", "--levels", "3", "--case-dir",
               str(tmp_path / "d"), "-q"])
    assert "DIVERGED" in capsys.readouterr().out


def test_pipeline_fit_and_mesh_spread_on_a_fake_solver(monkeypatch, tmp_path):
    """A fake simpleFoam writes F = -(d_L u + d_Q u^2), 10 % larger on the coarse level: the
    result recovers d_L, d_Q and C_D from the fine runs, and a mesh spread of 10 %."""
    d_l, d_q = 30.0, 512.5
    solver = (
        "u=$(awk '/^internalField/ {gsub(/[()]/, \"\"); print -$3}' 0/U); "
        "case \"$PWD\" in *_L3) f=1.1;; *) f=1.0;; esac; mkdir -p postProcessing/forces/0; "
        "for i in $(seq 1 60); do echo \"Time = $i\"; "
        f"awk -v u=$u -v f=$f -v i=$i 'BEGIN {{F=-({d_l}*u+{d_q}*u*u)*f; "
        "printf \"%d (%.10g 0 0) (%.10g 0 0) (0 0 0)\\n\", i, F, F}' "
        ">> postProcessing/forces/0/force.dat; "
        "echo \"$i (0 0 0) (0 0 0) (0 0 0)\" >> postProcessing/forces/0/moment.dat; done")
    _fake_openfoam(tmp_path, monkeypatch, checkMesh=CHECKMESH_OK, simpleFoam=solver)
    res = drag_by_cfd(trimesh.creation.box((1.0, 1.0, 1.0)), speeds=(0.5, 1.5), levels=(3, 4),
                      ranks=1, case_dir=tmp_path / "c", fluid=None)
    d = res.dofs[0]
    assert [(r.speed, r.level) for r in d.runs] == [(0.5, 4), (1.5, 4), (0.5, 3)]
    assert all(r.status == CONVERGED and r.iterations == 60 for r in d.runs)
    assert d.d_linear == pytest.approx(d_l, rel=1e-8)
    assert d.d_quadratic == pytest.approx(d_q, rel=1e-8)
    assert d.mesh_spread == pytest.approx(0.1, rel=1e-8)
    assert d.drag_coefficient == pytest.approx(d_q / (0.5 * res.density * 1.0), rel=1e-8)
    out = res.to_dict()["dofs"][0]
    assert out["X_uu"] == pytest.approx(-d_q) and out["X_u"] == pytest.approx(-d_l)
    text = res.text()
    assert f"{-d_q:.4g}" in text and "10.0%" in text and "NOT CONVERGED" not in text


def test_early_stop_on_a_settled_limit_cycle(tmp_path):
    """A force on a 1 % limit cycle about a settled mean stops the run; a drifting one not."""
    from stripcoef.cfd.runner import settled_early, stop_now

    spec, box = _spec()
    case = write_case(tmp_path / "c", spec, box)
    d = case.folder / "postProcessing" / "forces" / "0"
    d.mkdir(parents=True)

    def write(values):
        rows = "".join(f"{i + 1} ({v} 0 0) ({v} 0 0) (0 0 0)\n" for i, v in enumerate(values))
        (d / "force.dat").write_text(rows)
        (d / "moment.dat").write_text("".join(f"{i + 1} (0 0 0) (0 0 0) (0 0 0)\n"
                                              for i in range(len(values))))

    i = np.arange(400)
    write(-100.0 * (1 + 0.005 * np.sin(2 * np.pi * i / 25)))
    assert settled_early(case.folder, spec)
    write(-100.0 * (1 + 0.0005 * i))                      # drifts 5 % per 100 iterations
    assert not settled_early(case.folder, spec)
    write(-100.0 * (1 + 0.08 * np.sin(2 * np.pi * i / 25)))   # swings 16 %
    assert not settled_early(case.folder, spec)
    noisy = -100.0 * (1 + 0.005 * np.sin(2 * np.pi * i / 25))
    noisy[200:300] += 30.0 * np.sin(2 * np.pi * i[200:300] / 7)    # a transient window before
    noisy[200:300] -= noisy[200:300].mean() + 100.0                # whose mean matches by chance
    write(noisy)
    assert not settled_early(case.folder, spec)
    write(-100.0 * (1 + 0.005 * np.sin(2 * np.pi * i / 25))[:250])   # too early
    assert not settled_early(case.folder, spec)
    stop_now(case.folder)
    assert _read(case.folder, "system/controlDict")["stopAt"] == "writeNow"


def test_rewriting_a_case_replaces_it_and_a_foreign_folder_is_refused(tmp_path):
    from stripcoef.errors import InputError

    spec, box = _spec()
    case = write_case(tmp_path / "c", spec, box)
    stale = case.folder / "processor0" / "1000"
    stale.mkdir(parents=True)
    write_case(tmp_path / "c", spec, box)
    assert not stale.exists() and (case.folder / "Allrun").is_file()
    other = tmp_path / "mine"
    other.mkdir()
    (other / "notes.txt").write_text("keep")
    with pytest.raises(InputError, match="not a case stripcoef wrote"):
        write_case(other, spec, box)
    assert (other / "notes.txt").read_text() == "keep"
