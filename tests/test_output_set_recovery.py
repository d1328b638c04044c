"""Recovery of a killed run's output set, one cause at a time (deterministic counterparts of
the random kills of tests/test_output_set_kill.py; :func:`stripcoef.files.recover_outputs`).

The kill test failed about once in 10 loaded full runs with a staging folder left behind:
the child had been killed between creating the staging folder's journal pointer and writing
its text, and the empty pointer was read as ``Path("")`` (the current folder, which exists),
so the folder was never removed: 9 of 2000 kills under CPU load left one, each with an empty
pointer and its writer's pid dead (neither pid reuse nor a zombie); 0 of 2000 after the fix
(the kill test's trials in a loop, two CPU-burning processes, writer at nice 9:
``python -m benchmarks.output_set_kills --kills 1000 --seed 2`` and ``--seed 3``)."""

import json
import os
import shutil
import signal
import tempfile

import pytest

from stripcoef import files
from stripcoef.files import OutputSet, read_text, recover_outputs

NAMES = ("cal.yaml", "report.md", "result.json")
DEAD = 999_999_999                      # a pid that cannot run (above any pid_max)
pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="needs fork")


def write_set(folder, gen):
    with OutputSet() as outs:
        for name in NAMES:
            outs.path(folder / name).write_text(f"{gen}\n")


def generations(folder):
    return [int((folder / n).read_text().split()[0]) for n in NAMES]


def leftovers(folder):
    return sorted(p.name for p in folder.iterdir() if p.name.startswith("."))


def staged_set(folder, pid, gen, pointer=None):
    """A staging folder as a run with process id ``pid`` leaves it, killed before its commit
    (``pointer``: the text of its journal pointer, if the kill came after it was created)."""
    staging = folder / f".stripcoef-{pid}-abc.tmp"
    staging.mkdir()
    for name in NAMES:
        (staging / name).write_text(f"{gen}\n")
    if pointer is not None:
        (staging / ".journal").write_text(pointer)
    return staging


@pytest.mark.parametrize("cut", [0, 20, -1])
def test_a_pointer_cut_short_by_a_kill_is_rolled_back(tmp_path, cut):
    """Killed while writing the pointer (empty: opened, not yet written; or no final newline):
    the journal was not committed, so the staged set is removed and the old one stays."""
    write_set(tmp_path, 0)
    journal = tmp_path.resolve() / f".stripcoef-commit-{DEAD}-abc.json"
    staged_set(tmp_path, DEAD, 1, pointer=(str(journal) + "\n")[:cut])
    recover_outputs(tmp_path)
    assert generations(tmp_path) == [0, 0, 0] and leftovers(tmp_path) == []


def test_a_staging_folder_with_a_pointer_to_a_deleted_journal_is_removed(tmp_path):
    """Killed after the journal was deleted, before the staging folders were: the folder holds
    only its pointer (its files were moved); it is removed and the new set stays."""
    write_set(tmp_path, 1)
    journal = tmp_path.resolve() / f".stripcoef-commit-{DEAD}-abc.json"
    staging = tmp_path / f".stripcoef-{DEAD}-abc.tmp"
    staging.mkdir()
    (staging / ".journal").write_text(f"{journal}\n")
    recover_outputs(tmp_path)
    assert generations(tmp_path) == [1, 1, 1] and leftovers(tmp_path) == []


def _forked(body):
    """Run ``body()`` in a forked child that never returns into pytest; its pid."""
    pid = os.fork()
    if pid == 0:
        try:
            body()
        finally:
            os._exit(0)
    return pid


def _stage_then_die(folder):
    outs = OutputSet()
    for name in NAMES:
        outs.path(folder / name).write_text("1\n")
    os.kill(os.getpid(), signal.SIGKILL)


@pytest.mark.parametrize("locks", [True, False])
def test_a_zombie_writer_is_over(tmp_path, monkeypatch, locks):
    """A writer killed but not yet reaped by its parent (a zombie) still answers kill(pid, 0);
    its run is over: its staging folder is removed (its lock was dropped when it died; without
    locks, /proc/<pid>/stat says Z)."""
    if not locks:
        if not os.path.exists(f"/proc/{os.getpid()}/stat"):
            pytest.skip("needs /proc")
        monkeypatch.setattr(files, "fcntl", None)
    write_set(tmp_path, 0)
    pid = _forked(lambda: _stage_then_die(tmp_path))
    try:
        os.waitid(os.P_PID, pid, os.WEXITED | os.WNOWAIT)     # dead, not reaped: a zombie
        os.kill(pid, 0)                                        # ... that answers kill(pid, 0)
        left = leftovers(tmp_path)
        assert len(left) == 1 and left[0].startswith(f".stripcoef-{pid}-")
        recover_outputs(tmp_path)
        assert generations(tmp_path) == [0, 0, 0] and leftovers(tmp_path) == []
    finally:
        os.waitpid(pid, 0)


def test_a_reused_pid_does_not_keep_a_killed_run_alive(tmp_path):
    """A killed run's journal and staging folder named with a process id that another process
    now has (here our parent's): the set is rolled forward by the next reader all the same
    (the process id said "running" and left the set mixed on disk)."""
    other = os.getppid()
    write_set(tmp_path, 0)
    folder = tmp_path.resolve()
    staging = folder / f".stripcoef-{other}-abc.tmp"
    journal = folder / f".stripcoef-commit-{other}-abc.json"
    staging.mkdir()
    for name in NAMES:
        (staging / name).write_text("1\n")
    (staging / ".journal").write_text(f"{journal}\n")
    moves = [[str(staging / n), str(folder / n)] for n in NAMES]
    journal.write_text(json.dumps({"pid": other, "moves": moves, "staging": [str(staging)]}))
    os.replace(staging / NAMES[0], folder / NAMES[0])          # killed after the first rename
    assert generations(tmp_path) == [1, 0, 0]
    assert read_text(tmp_path / NAMES[1], kind="report").startswith("1\n")
    assert generations(tmp_path) == [1, 1, 1] and leftovers(tmp_path) == []


def test_a_running_writers_set_is_left_alone(tmp_path):
    """A staging folder of a run that still runs (another process, or this one) is not
    removed; once that process is killed, it is."""
    write_set(tmp_path, 0)
    ready, go = os.pipe()
    wait, release = os.pipe()

    def stage_and_wait():
        outs = OutputSet()
        for name in NAMES:
            outs.path(tmp_path / name).write_text("1\n")
        os.write(go, b"x")
        os.read(wait, 1)                                       # until the parent kills it

    pid = _forked(stage_and_wait)
    try:
        assert os.read(ready, 1) == b"x"
        with OutputSet() as outs:                              # this process: running too
            outs.path(tmp_path / "other.txt").write_text("a\n")
            recover_outputs(tmp_path)
            assert len(leftovers(tmp_path)) == 2
        assert len(leftovers(tmp_path)) == 1                   # the child's
        recover_outputs(tmp_path)
        assert len(leftovers(tmp_path)) == 1
        os.kill(pid, signal.SIGKILL)
    finally:
        os.waitpid(pid, 0)
        for fd in (ready, go, wait, release):
            os.close(fd)
    recover_outputs(tmp_path)
    assert generations(tmp_path) == [0, 0, 0] and leftovers(tmp_path) == []


@pytest.mark.parametrize("hook", ["_open_folder", "_lock"])
def test_a_staging_folder_removed_before_it_was_locked_is_made_again(tmp_path, monkeypatch,
                                                                     hook):
    """Between mkdtemp and the lock a new staging folder is unlocked: a recovery in another
    process may remove it (here just before the writer opens it, or before it locks it). The
    writer then makes another one and the set is written whole."""
    write_set(tmp_path, 0)
    made = []
    real_mkdtemp, real_hook = tempfile.mkdtemp, getattr(files, hook)

    def mkdtemp(**kw):
        made.append(real_mkdtemp(**kw))
        return made[-1]

    def removing(*args, **kw):
        if len(made) == 1 and os.path.isdir(made[0]):
            shutil.rmtree(made[0])                      # what the other process's recovery does
        return real_hook(*args, **kw)

    monkeypatch.setattr(files.tempfile, "mkdtemp", mkdtemp)
    monkeypatch.setattr(files, hook, removing)
    write_set(tmp_path, 1)
    assert len(made) == 2
    assert generations(tmp_path) == [1, 1, 1] and leftovers(tmp_path) == []


def test_without_locks_the_process_id_tells(tmp_path, monkeypatch):
    """No fcntl (Windows): a staging folder of a process that no longer runs is removed, one
    of this process is left."""
    monkeypatch.setattr(files, "fcntl", None)
    write_set(tmp_path, 0)
    staged_set(tmp_path, DEAD, 7)
    with OutputSet() as outs:
        outs.path(tmp_path / "other.txt").write_text("a\n")
        recover_outputs(tmp_path)
        assert len(leftovers(tmp_path)) == 1                   # ours, not the dead one's
    assert generations(tmp_path) == [0, 0, 0] and leftovers(tmp_path) == []
