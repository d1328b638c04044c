"""Recovery of a killed run's output set, one cause at a time (deterministic counterparts of
the random kills of tests/test_output_set_kill.py; :func:`stripcoef.files.recover_outputs`).

The kill test failed about once in 10 loaded full runs with a staging folder left behind:
the child had been killed between creating the staging folder's journal pointer and writing
its text, and the empty pointer was read as ``Path("")`` (the current folder, which exists),
so the folder was never removed (5 of 1000 kills under load, all with an empty pointer)."""

import os

import pytest

from stripcoef.files import OutputSet, read_text, recover_outputs

NAMES = ("cal.yaml", "report.md", "result.json")
DEAD = 999_999_999                      # a pid that cannot run (above any pid_max)


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
