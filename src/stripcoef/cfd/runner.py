"""Running a written case: OpenFOAM's environment, the commands in order, the progress.

OpenFOAM is a system dependency (Debian's package ``openfoam``, v1912). Its environment
script ``/usr/share/openfoam/etc/bashrc`` is broken in that package; the one variable its
programs need is ``WM_PROJECT_DIR`` (the folder whose ``etc/`` holds ``controlDict`` and
``caseDicts``): measured, blockMesh, snappyHexMesh, checkMesh, topoSet, potentialFoam and
simpleFoam with the forces library run with only it set. A ``WM_PROJECT_DIR`` already set (a
sourced OpenFOAM of another version) is kept.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path


from stripcoef.cfd.case import CaseFiles, copy_fields_shell
from stripcoef.cfd.forces import (
    WINDOW,
    execution_time,
    fatal_line,
    mesh_report,
    read_forces,
    read_log,
    settle,
)
from stripcoef.errors import ExternalToolError

#: The Debian package that provides OpenFOAM, named in the error when it is missing.
PACKAGE = "openfoam"
#: Where Debian's package keeps OpenFOAM's etc folder.
DEBIAN_PROJECT_DIR = "/usr/share/openfoam"
#: The programs a run needs.
PROGRAMS = ("blockMesh", "surfaceFeatureExtract", "snappyHexMesh", "checkMesh", "simpleFoam")


def openfoam_environment(ranks: int = 1) -> dict:
    """The environment OpenFOAM's programs run in, or one-line error naming the package.

    Raises
    ------
    ExternalToolError
        A program of :data:`PROGRAMS` (or ``mpirun`` for ``ranks`` > 1) not on the PATH, or
        no OpenFOAM ``etc`` folder.
    """
    env = dict(os.environ)
    missing = [p for p in PROGRAMS if shutil.which(p, path=env.get("PATH")) is None]
    if missing:
        raise ExternalToolError(
            f"OpenFOAM not found ({missing[0]} is not on the PATH); expected OpenFOAM "
            f"installed: apt-get install {PACKAGE} (Debian/Ubuntu), or an OpenFOAM "
            "environment sourced")
    if ranks > 1 and shutil.which("mpirun", path=env.get("PATH")) is None:
        raise ExternalToolError(f"mpirun not found for {ranks} ranks; expected MPI (Debian's "
                                f"{PACKAGE} brings openmpi-bin) or --ranks 1")
    if not env.get("WM_PROJECT_DIR"):
        env["WM_PROJECT_DIR"] = DEBIAN_PROJECT_DIR
    if not (Path(env["WM_PROJECT_DIR"]) / "etc" / "controlDict").is_file():
        raise ExternalToolError(f"OpenFOAM's etc/controlDict not found under WM_PROJECT_DIR="
                                f"{env['WM_PROJECT_DIR']}; expected the Debian package "
                                f"{PACKAGE} or WM_PROJECT_DIR set to an OpenFOAM installation")
    env.setdefault("FOAM_SIGFPE", "true")             # a diverged solution stops, not NaN
    if hasattr(os, "geteuid") and os.geteuid() == 0:  # Open MPI refuses root otherwise
        env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
        env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    return env


@dataclass(frozen=True)
class RunOutcome:
    """What running a case gave, before it is judged (:mod:`stripcoef.cfd.result`).

    Attributes
    ----------
    cells : int
        Cells of the mesh (checkMesh).
    failed_checks : int
        Mesh checks checkMesh failed (snappyHexMesh's meshes often fail one or two: a
        warning, not an error).
    iterations : int
        simpleFoam iterations run.
    residuals_met : bool
        simpleFoam stopped on its residual criterion.
    solver_error : str
        Why simpleFoam stopped early ("" if it did not).
    cpu_seconds : float
        CPU time [s]: OpenFOAM's ``ExecutionTime`` of each program (the master rank's CPU
        time) times the ranks it ran on, summed.
    wall_seconds : float
        Wall-clock time of the run [s].
    """

    cells: int
    failed_checks: int
    iterations: int
    residuals_met: bool
    solver_error: str
    cpu_seconds: float
    wall_seconds: float = 0.0


def _app(cmd: tuple) -> str:
    return cmd[3] if cmd[0] == "mpirun" else cmd[0]


def run_case(case: CaseFiles, *, env: dict, on_progress=None, poll: float = 2.0) -> RunOutcome:
    """Run the commands of ``case`` in its folder, each into ``log.<application>``.

    ``on_progress(state, force, moment)`` is called while simpleFoam runs (about every
    ``poll`` seconds) with the :class:`~stripcoef.cfd.forces.LogState`, the last force [N]
    and moment [N m] (arrays, or ``None`` before the first iteration).

    Raises
    ------
    ExternalToolError
        A meshing step failed, or the mesh has no body faces (one line: the step, OpenFOAM's
        reason, the log).
    """
    folder = case.folder
    started = time.monotonic()
    cells, failed, patches = 0, 0, {}
    state = None
    solver_error = ""
    cpu = 0.0
    for cmd in case.commands:
        if cmd[0] == "stripcoef-copy-fields":
            subprocess.run(["bash", "-c", copy_fields_shell(case.spec.ranks)], cwd=folder,
                           check=True)
            continue
        app = _app(cmd)
        log = folder / f"log.{app}"
        with open(log, "w") as out:
            proc = subprocess.Popen(list(cmd), cwd=folder, env=env, stdout=out,
                                    stderr=subprocess.STDOUT)
            stopping = False
            try:
                while True:
                    try:
                        proc.wait(timeout=poll)
                        break
                    except subprocess.TimeoutExpired:
                        pass
                    if app == "simpleFoam":
                        if on_progress is not None:
                            _report(folder, log, on_progress)
                        if not stopping and settled_early(folder, case.spec):
                            stop_now(folder)
                            stopping = True
            except BaseException:
                proc.terminate()
                proc.wait()
                raise
        text = log.read_text(errors="replace")
        cpu += execution_time(text) * (case.spec.ranks if cmd[0] == "mpirun" else 1)
        if app == "checkMesh":
            cells, patches, failed = mesh_report(text)
            if patches.get("body", 0) == 0:
                raise ExternalToolError(
                    f"snappyHexMesh left no faces on the body ({folder}/log.snappyHexMesh); "
                    "expected a closed surface inside the box (a body thinner than the "
                    "surface cells needs a higher --levels)")
        if app == "simpleFoam":
            state = read_log(text)
            if proc.returncode != 0:
                solver_error = fatal_line(text) or f"simpleFoam stopped (exit {proc.returncode})"
            if on_progress is not None:
                _report(folder, log, on_progress)
            continue
        if proc.returncode != 0:
            reason = fatal_line(text) or f"exit status {proc.returncode}"
            raise ExternalToolError(f"{app} failed: {reason} (log: {log})")
    return RunOutcome(cells=cells, failed_checks=failed,
                      iterations=state.iteration if state else 0,
                      residuals_met=bool(state and state.converged), solver_error=solver_error,
                      cpu_seconds=cpu, wall_seconds=time.monotonic() - started)


#: Early stop: simpleFoam is told to write and stop once the force along the motion has
#: settled quietly (:attr:`stripcoef.cfd.forces.Settled.quiet`: the mean of the last 100
#: iterations within 2 % of the 100 before, the swing under 10 % in both), after EARLY_MIN
#: iterations at least.
EARLY_MIN = 300


def settled_early(folder: Path, spec) -> bool:
    """Whether the force along the motion has settled after :data:`EARLY_MIN` iterations."""
    try:
        hist = read_forces(folder)
    except (OSError, ValueError, IndexError):
        return False
    if hist.iteration.size < max(EARLY_MIN, 2 * WINDOW):
        return False
    return settle((hist.moment if spec.rotation else hist.force)[:, spec.axis]).quiet


def stop_now(folder: Path) -> None:
    """Make a running solver write its fields and stop (``stopAt writeNow``: the controlDict
    is re-read while it runs, ``runTimeModifiable true``)."""
    path = folder / "system" / "controlDict"
    text = path.read_text()
    path.write_text(re.sub(r"^stopAt\s+\w+;", "stopAt writeNow;", text, flags=re.M))


def _report(folder: Path, log: Path, on_progress) -> None:
    try:
        state = read_log(log.read_text(errors="replace"))
        hist = read_forces(folder)
        force = hist.force[-1] if hist.iteration.size else None
        moment = hist.moment[-1] if hist.iteration.size else None
    except (OSError, ValueError, IndexError):
        return
    on_progress(state, force, moment)
