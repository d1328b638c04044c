"""kill -9 while a run writes its outputs (issue 36): the set (a model, a report, a JSON) is
all old or all new once the next run or a reader looked at the folder
(:class:`stripcoef.files.OutputSet`, :func:`stripcoef.files.recover_outputs`).

A forked child writes generation after generation of the set; the parent kills it (SIGKILL)
at seeded random moments, and once exactly between two of the commit's renames (where the
set on disk is mixed until recovery)."""

import multiprocessing
import os
import signal
import time

import numpy as np
import pytest

from benchmarks.output_set_kills import NAMES, generations, write_set
from benchmarks.output_set_kills import writer as _writer
from stripcoef.files import read_text, recover_outputs

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="needs fork")


def leftovers(folder):
    return sorted(p.name for p in folder.iterdir() if p.name.startswith("."))


def described(folder):
    """What a failed check shows of each leftover: its files and its journal pointer's text
    (a pointer cut short by the kill was the cause of a leftover folder: issue 31)."""
    out = []
    for name in leftovers(folder):
        p = folder / name
        pointer = p / ".journal"
        out.append((name, sorted(c.name for c in p.iterdir()) if p.is_dir() else "file",
                    pointer.read_text() if pointer.is_file() else None))
    return out


def _kill_child(folder, start, delay, *, slow=0.002, stop_after_renames=0):
    ctx = multiprocessing.get_context("fork")
    p = ctx.Process(target=_writer, args=(folder, start, slow, stop_after_renames))
    p.start()
    time.sleep(delay)
    os.kill(p.pid, signal.SIGKILL)
    p.join()                                     # reaped: its pid is dead
    assert p.exitcode == -signal.SIGKILL


def test_kill_at_random_moments_leaves_a_whole_set(tmp_path):
    """Six kills at seeded random moments, then (a loaded machine may start a child too late
    to commit anything within 0.25 s) kills at doubling delays until a child has committed a
    set, so that the test always sees both kinds of moment: before any commit and after."""
    write_set(tmp_path, 0)
    last = 0
    rng = np.random.default_rng(3600)
    delays = [float(d) for d in rng.uniform(0.02, 0.25, 6)] + [0.5, 1.0, 2.0, 4.0, 8.0]
    for trial, delay in enumerate(delays):
        if trial >= 6 and last > 0:
            break
        _kill_child(tmp_path, last + 1, delay)
        recover_outputs(tmp_path)                   # what the next run does first
        gens = generations(tmp_path)
        assert len(set(gens)) == 1, (trial, delay, gens)
        assert gens[0] >= last and leftovers(tmp_path) == [], (trial, described(tmp_path))
        last = gens[0]
    assert last > 0                                 # the children did commit sets


@pytest.mark.parametrize("renames", [1, 2])
def test_kill_between_the_renames_rolls_forward(tmp_path, renames):
    """Killed after the journal was committed and 1 or 2 of the 3 renames were done: the set
    on disk is mixed, then a reader of one of the files (read_text) rolls the journal forward
    and the next run's staging removes nothing of it."""
    write_set(tmp_path, 0)
    _kill_child(tmp_path, 1, 1.0, stop_after_renames=renames)
    gens = generations(tmp_path)
    assert sorted(gens) == sorted([1] * renames + [0] * (3 - renames))      # mixed on disk
    assert any(n.startswith(".stripcoef-commit-") for n in leftovers(tmp_path))
    assert read_text(tmp_path / "cal.yaml", kind="model file").startswith("1\n")
    assert generations(tmp_path) == [1, 1, 1]
    assert leftovers(tmp_path) == []


def test_kill_before_the_commit_keeps_the_old_set(tmp_path):
    """A staging folder of a dead run that no journal commits is removed by the next run;
    the outputs stay the old ones."""
    write_set(tmp_path, 0)
    staging = tmp_path / ".stripcoef-999999999-abc.tmp"     # a pid that cannot run
    staging.mkdir()
    for name in NAMES:
        (staging / name).write_text("7\n")
    write_set(tmp_path, 1)
    assert generations(tmp_path) == [1, 1, 1] and leftovers(tmp_path) == []

