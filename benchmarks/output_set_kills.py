"""Kills of a writer of an output set at random moments, under CPU load (issue 31).

The loop of tests/test_output_set_kill.py, many more times: a forked child writes sets of
three files through :class:`stripcoef.files.OutputSet` again and again (renames slowed by
2 ms so that kills land between them), the parent kills it with SIGKILL after U(0.02, 0.25) s,
reaps it, runs :func:`stripcoef.files.recover_outputs` and checks that (a) the three files
are of one generation (a whole set) and (b) nothing of the killed run is left in the folder
(no staging folder, no journal). ``--load K`` starts K processes that burn CPU beside it and
``--child-nice`` starves the writer, which is what made the rare leftover of a kill between
creating a staging folder's journal pointer and writing its text appear (docs/reliability.md).

Usage:
    python -m benchmarks.output_set_kills [--kills 1000] [--load 2] [--child-nice 9] [--seed 2]

Prints the counts; exits 1 if any kill left a mixed set or a leftover.
"""

from __future__ import annotations

import argparse
import multiprocessing
import os
import shutil
import signal
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from stripcoef import files
from stripcoef.files import OutputSet, recover_outputs

NAMES = ("cal.yaml", "report.md", "result.json")


def write_set(folder: Path, generation: int, size: int = 20_000) -> None:
    """One set of :data:`NAMES`, each file starting with its generation's number."""
    with OutputSet() as outs:
        for name in NAMES:
            outs.path(folder / name).write_text(f"{generation}\n" + "x" * size)


def generations(folder: Path) -> list[int]:
    """The generation of each output as it is on disk (raw reads: no recovery)."""
    out = []
    for name in NAMES:
        with open(folder / name) as f:
            out.append(int(f.readline()))
    return out


def writer(folder: Path, start: int, slow: float, stop_after_renames: int = 0,
           nice: int = 0) -> None:
    """The child: writes generations start, start+1, ... with the set's renames slowed by
    ``slow`` [s] (or stopped for a minute after ``stop_after_renames`` renames of a commit,
    where the kill test kills it), at niceness ``nice``."""
    if nice:
        os.nice(nice)
    real = os.replace
    count = [0]

    def replace(src, dst):
        real(src, dst)
        if str(src).endswith((".tmp", ".part")) or ".stripcoef-" not in str(src):
            return                                # not a staged output's rename
        count[0] += 1
        if stop_after_renames and count[0] == stop_after_renames:
            time.sleep(60)                        # killed here
        time.sleep(slow)

    files.os.replace = replace
    generation = start
    while True:
        write_set(folder, generation)
        generation += 1


def _burn() -> None:
    while True:
        pass


def run(kills: int, load: int, child_nice: int, seed: int) -> dict:
    """Counts of ``kills`` trials: mixed sets and leftovers (with what each leftover held)."""
    ctx = multiprocessing.get_context("fork")
    burners = [ctx.Process(target=_burn, daemon=True) for _ in range(load)]
    for p in burners:
        p.start()
    rng = np.random.default_rng(seed)
    folder = Path(tempfile.mkdtemp(prefix="stripcoef-kills-"))
    write_set(folder, 0)
    last, mixed, leftovers = 0, 0, []
    try:
        for trial in range(kills):
            p = ctx.Process(target=writer, args=(folder, last + 1, 0.002, 0, child_nice))
            p.start()
            time.sleep(float(rng.uniform(0.02, 0.25)))
            os.kill(p.pid, signal.SIGKILL)
            p.join()
            recover_outputs(folder)
            gens = generations(folder)
            mixed += len(set(gens)) != 1
            left = sorted(x for x in folder.iterdir() if x.name.startswith("."))
            if left:
                leftovers.append((trial, [x.name for x in left]))
                for x in left:
                    shutil.rmtree(x) if x.is_dir() else x.unlink()
            last = max(gens)
    finally:
        for p in burners:
            p.kill()
            p.join()
        shutil.rmtree(folder, ignore_errors=True)
    return {"kills": kills, "mixed": mixed, "leftovers": leftovers, "last": last}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--kills", type=int, default=1000)
    ap.add_argument("--load", type=int, default=2, help="CPU-burning processes beside it")
    ap.add_argument("--child-nice", type=int, default=9, help="niceness of the writer")
    ap.add_argument("--seed", type=int, default=2)
    args = ap.parse_args(argv)
    out = run(args.kills, args.load, args.child_nice, args.seed)
    print(f"kills {out['kills']}  mixed sets {out['mixed']}  leftovers {len(out['leftovers'])}"
          f"  last generation {out['last']}")
    for trial, names in out["leftovers"]:
        print(f"  trial {trial}: {', '.join(names)}")
    return 1 if out["mixed"] or out["leftovers"] else 0


if __name__ == "__main__":
    sys.exit(main())
