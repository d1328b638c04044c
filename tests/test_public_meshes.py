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
