"""benchmarks.public_meshes reads a mesh at its pinned commit from a local clone (the CI
machine cannot reach GitHub), and its table lists at least eight vehicles with a license."""

import dataclasses
import shutil
import subprocess

import pytest

from benchmarks import public_meshes as PM


def test_at_least_eight_vehicles_each_with_commit_and_license():
    vehicles = {m.vehicle for m in PM.MESHES}
    assert len(vehicles) >= 8
    for m in PM.MESHES:
        assert len(m.commit) == 40 and m.license and m.path


@pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
def test_read_from_a_clone_at_the_commit(tmp_path):
    repo = tmp_path / "mirror" / "owner+name"
    (repo / "meshes").mkdir(parents=True)
    (repo / "meshes" / "body.stl").write_bytes(b"solid x\nendsolid x\n")
    def git(*a):
        return subprocess.run(["git", "-C", str(repo), *a], check=True, capture_output=True,
                              text=True).stdout.strip()
    git("init", "-q")
    git("add", ".")
    git("-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "m")
    commit = git("rev-parse", "HEAD")
    mesh = dataclasses.replace(PM.MESHES[0], repo="owner/name", commit=commit,
                               path="meshes/body.stl")
    assert PM.read_from_mirror(tmp_path / "mirror", mesh) == b"solid x\nendsolid x\n"
    missing = dataclasses.replace(mesh, path="meshes/none.stl")
    with pytest.raises(FileNotFoundError):
        PM.read_from_mirror(tmp_path / "mirror", missing)


@pytest.mark.slow     # 2.8 s of CPU (-n 0, load ~11): two CLI runs and a repair
def test_a_refusal_naming_the_repair_is_repaired_so(tmp_path):
    """The benchmark runs the command that a refusal names (stripcoef mesh FILE --repair -o
    OUT) and then OUT, as a user told so would."""
    import numpy as np
    import trimesh

    box = trimesh.creation.box([0.8, 0.3, 0.3])
    tube = trimesh.creation.cylinder(radius=0.05, height=0.3, sections=20)
    side = np.abs(np.asarray(tube.triangles_center)[:, 2]) < 0.149       # no end caps
    tube = trimesh.Trimesh(tube.vertices, np.asarray(tube.faces)[side], process=False)
    tube.apply_translation([0.0, 0.0, 0.5])
    found = tmp_path / "rov.stl"
    trimesh.util.concatenate([box, tube]).export(found)
    run = PM.run_cli(found)
    assert run["rc"] == 2
    out, note = PM.repair_named(run, found, tmp_path / "rov_closed.stl")
    assert out is not None and out.exists()
    assert note.startswith("stripcoef mesh rov.stl --repair -o rov_closed.stl: ")
    assert "capped 2 holes of 1 open parts" in note
    assert PM.repair_named({"rc": 2, "warnings": ["error: other"]}, found, out) == (None, "")


def test_an_update_names_the_command_of_every_row():
    first = PM.updated_command("run A", ["m1", "m2"], "run B --only m1 m2 --update")
    assert first == "run A; rows of m1 m2 from run B --only m1 m2 --update"
    again = PM.updated_command(first, ["m2"], "run C --only m2 --update")
    assert again == ("run A; rows of m1 from run B --only m1 m2 --update; rows of m2 from "
                     "run C --only m2 --update")


def test_stored_references_give_back_the_compared_matrices(tmp_path):
    """--references reads a stored run's Capytaine matrix and its error back from the CSV
    rows the run wrote (the error from bem_error_rel times the comparison's scale)."""
    import csv

    import numpy as np

    rng = np.random.default_rng(7)
    b = rng.normal(size=(6, 6))
    ref = b @ b.T + 6.0 * np.eye(6)                  # symmetric, positive definite
    err = np.abs(0.05 * ref)
    ours = ref * (1.0 + 0.01 * rng.normal(size=(6, 6)))
    run = {"json": {"added_mass": (0.5 * (ours + ours.T)).tolist(),
                    "added_mass_error": err.tolist(), "reference_point": [0.0, 0.0, 0.0]},
           "command": "stripcoef coefficients m.stl --rho 1000 --json", "seconds": 1.0}
    line = dict(mesh=PM.MESHES[0], label="auto", run=run, terms=PM.compare_at(run, ref, err),
                counts=[500, 1000, 2000], t_bem=12.5, warned=False, note="", levels="1/2/3")
    path = tmp_path / "stored.csv"
    with open(path, "w", newline="") as fh:
        fh.write("# a command\n")
        csv.writer(fh).writerow(PM.HEADER)
        csv.writer(fh).writerows(PM.csv_rows(line))
    back = PM.stored_references(path)[(PM.MESHES[0].name, "auto")]
    np.testing.assert_allclose(back[0], ref, rtol=1e-5)
    np.testing.assert_allclose(back[1], err, rtol=1e-3)
    assert back[2] == [500, 1000, 2000] and back[3] == 12.5


def test_levels_csv_replaces_a_mesh_and_keeps_the_others(tmp_path):
    """--levels-csv: one row per upper-triangle term of each level; a mesh run again
    replaces its own rows, the other meshes' rows stay, in the table's order."""
    import csv

    import numpy as np

    path = tmp_path / "levels.csv"
    a, b = PM.MESHES[0], PM.MESHES[1]
    m = np.arange(36.0).reshape(6, 6)
    PM.write_levels(path, b, [("fam", 100, m), ("fam", 200, 2 * m)], "cmd")
    PM.write_levels(path, a, [("fam", 50, m)], "cmd")
    PM.write_levels(path, b, [("fam", 300, m)], "cmd")
    with open(path, newline="") as fh:
        assert fh.readline().startswith("# cmd --only NAME --levels-csv")
        rows = list(csv.DictReader(fh))
    assert [r["mesh"] for r in rows] == [a.name] * 21 + [b.name] * 21
    assert {r["faces"] for r in rows if r["mesh"] == b.name} == {"300"}
    r01 = next(r for r in rows if r["mesh"] == a.name and r["i"] == "0" and r["j"] == "1")
    assert float(r01["added_mass"]) == 0.5 * (m[0, 1] + m[1, 0])


def test_converged_terms_recover_the_run_point_and_extrapolate(tmp_path):
    """validation.public_meshes.converged_terms: four exact 1/N levels about the origin (so
    that the Eça & Hoekstra value is their limit), a stored run about another point: the
    point is recovered and the model's error against the limit is exact."""
    import csv

    import numpy as np

    from stripcoef.conventions import transform_matrix
    from validation import public_meshes as V

    rng = np.random.default_rng(3)
    b = rng.normal(size=(6, 6))
    limit = b @ b.T + 6.0 * np.eye(6)
    counts = [1000, 2000, 4000, 8000]
    mats = [limit * (1.0 + 50.0 / n) for n in counts]          # error exactly 1/N
    mesh = PM.MESHES[0]
    PM.write_levels(tmp_path / "levels.csv", mesh, [("f", n, m) for n, m in zip(counts, mats)],
                    "cmd")
    point = np.array([0.1, -0.2, 0.05])
    ref_p = transform_matrix(limit, to_point=point)
    model_p = 1.02 * ref_p
    with open(tmp_path / "run.csv", "w", newline="") as fh:
        fh.write("# cmd\n")
        w = csv.writer(fh)
        w.writerow(["mesh", "run", "i", "j", "model", "bem", "bem_error_rel"])
        for i in range(6):
            for j in range(i, 6):
                w.writerow([mesh.name, "auto", i, j, f"{model_p[i, j]:.12g}",
                            f"{ref_p[i, j]:.12g}", 0.01])
    terms = V.converged_terms(tmp_path / "levels.csv", tmp_path / "run.csv")
    assert len(terms) == 6
    for t in terms:
        assert t["fit"] < 1e-8
        assert abs(t["error_eh"] - 0.02) < 1e-6 and abs(t["error_bem"] - 0.02) < 1e-9


def test_converged_terms_take_the_stored_point_and_move_u_with_it(tmp_path):
    """With the run's reference point in the CSV (ref_x, ref_y, ref_z) converged_terms uses it
    (no fit), and U about the origin is carried to it by moved_uncertainty."""
    import csv

    import numpy as np

    from stripcoef.conventions import transform_matrix
    from stripcoef.hull.convergence import eca_hoekstra_terms
    from validation import public_meshes as V

    rng = np.random.default_rng(5)
    b = rng.normal(size=(6, 6))
    limit = b @ b.T + 6.0 * np.eye(6)
    counts = [1000, 2000, 4000, 8000]
    # order-1 levels with scatter: U is not zero
    mats = [limit * (1.0 + 3.0 / np.sqrt(n)) + 0.002 * rng.normal(size=(6, 6)) for n in counts]
    mats = [0.5 * (m + m.T) for m in mats]
    mesh = PM.MESHES[0]
    PM.write_levels(tmp_path / "levels.csv", mesh, [("f", n, m) for n, m in zip(counts, mats)],
                    "cmd")
    point = np.array([0.3, -0.1, 0.2])
    ref_p = transform_matrix(limit, to_point=point)
    with open(tmp_path / "run.csv", "w", newline="") as fh:
        fh.write("# cmd\n")
        w = csv.writer(fh)
        w.writerow(["mesh", "run", "i", "j", "model", "bem", "bem_error_rel", *V.POINT_COLUMNS])
        for i in range(6):
            for j in range(i, 6):
                w.writerow([mesh.name, "auto", i, j, f"{ref_p[i, j]:.12g}",
                            f"{ref_p[i, j]:.12g}", 0.01, *(repr(float(x)) for x in point)])
    terms = V.converged_terms(tmp_path / "levels.csv", tmp_path / "run.csv")
    _, unc, _, _ = eca_hoekstra_terms(counts, [np.asarray(m) for m in mats])
    moved = V.moved_uncertainty(unc, point)
    scale = np.abs(np.diag(ref_p))
    for k, t in enumerate(terms):
        assert t["point_from"] == "stored" and np.allclose(t["point"], point)
        assert t["u"] == pytest.approx(moved[k, k] / max(scale[k], 0.01 * scale[
            slice(0, 3) if k < 3 else slice(3, 6)].max()), rel=1e-4)   # levels at 9 digits
    assert any(t["u"] > t["u_origin"] * 1.01 for t in terms[3:])   # the lever arms add


def test_moved_uncertainty_bounds_every_error_within_the_bands():
    """The moved band contains the moved error of every symmetric error within the bands
    about the origin (random and extreme sign patterns), and is attained by one of them."""
    import numpy as np

    from stripcoef.conventions import transform_matrix
    from validation.public_meshes import moved_uncertainty

    rng = np.random.default_rng(11)
    u = np.abs(rng.normal(size=(6, 6)))
    u = 0.5 * (u + u.T)
    point = np.array([0.4, -0.25, 0.1])
    bound = moved_uncertainty(u, point)
    np.testing.assert_allclose(moved_uncertainty(u, np.zeros(3)), u, rtol=1e-12)
    worst = np.zeros((6, 6))
    for _ in range(400):
        s = rng.choice([-1.0, 1.0], size=(6, 6))
        s = np.triu(s) + np.triu(s, 1).T
        moved = np.abs(transform_matrix(s * u, to_point=point))
        assert np.all(moved <= bound * (1 + 1e-12) + 1e-15)
        worst = np.maximum(worst, moved)
    # the bound is attained term by term by the signs of the transfer's coefficients
    i, j = 3, 4
    signs = np.zeros((6, 6))
    for k in range(6):
        for m in range(k, 6):
            unit = np.zeros((6, 6))
            unit[k, m] = unit[m, k] = 1.0
            signs[k, m] = signs[m, k] = np.sign(transform_matrix(unit, to_point=point)[i, j])
    assert abs(transform_matrix(signs * u, to_point=point)[i, j]) == pytest.approx(
        bound[i, j], rel=1e-12)


def test_a_stored_run_without_the_bem_time_reads_it_as_unknown(tmp_path):
    """A stored row whose ``bem_seconds`` is empty: the time reads back as unknown (NaN) and
    a re-run writes it empty again, never as 0 s."""
    import csv

    import numpy as np

    ref = np.diag([4.0, 5.0, 6.0, 0.4, 0.5, 0.6])
    run = {"json": {"added_mass": ref.tolist(), "added_mass_error": (0.01 * ref).tolist(),
                    "reference_point": [0.0, 0.0, 0.0]},
           "command": "stripcoef coefficients m.stl --rho 1000 --json", "seconds": 1.0}
    line = dict(mesh=PM.MESHES[0], label="auto", run=run,
                terms=PM.compare_at(run, ref, 0.02 * ref), counts=[500, 1000, 2000],
                t_bem=float("nan"), warned=False, note="", levels="1/2/3")
    rows = PM.csv_rows(line)
    assert {r[PM.HEADER.index("bem_seconds")] for r in rows} == {""}
    path = tmp_path / "stored.csv"
    with open(path, "w", newline="") as fh:
        fh.write("# a command\n")
        csv.writer(fh).writerow(PM.HEADER)
        csv.writer(fh).writerows(rows)
    assert np.isnan(PM.stored_references(path)[(PM.MESHES[0].name, "auto")][3])
