"""Reading what OpenFOAM wrote: the forces function object's files and the solver's log.

The ``forces`` function object of OpenFOAM v1912 writes ``postProcessing/forces/<t0>/
force.dat`` and ``moment.dat``: a ``#`` header, then per iteration the time and three
vectors in parentheses, total, pressure and viscous [N] or [N m] about ``CofR``. Older
versions wrote one ``forces.dat`` with ``((p) (v)) ((p) (v))``; a restart adds a folder per
start time. Both are read here; the rows of all start folders are joined in time order.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|[-+]?(?:nan|inf)", re.I)


@dataclass(frozen=True)
class ForceHistory:
    """Force and moment on the body per iteration.

    Attributes
    ----------
    iteration : (n,) array
    force, moment : (n, 3) arrays
        Total (pressure + viscous) force [N] and moment about the reference point [N m].
    pressure_force, viscous_force : (n, 3) arrays
        Its two parts [N].
    """

    iteration: np.ndarray
    force: np.ndarray
    moment: np.ndarray
    pressure_force: np.ndarray
    viscous_force: np.ndarray


def _rows(path: Path) -> np.ndarray:
    """The numeric rows of a .dat file (comment lines skipped): time and the numbers."""
    rows = []
    for line in path.read_text().splitlines():
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        vals = [float(v) for v in _NUMBER.findall(line)]
        if vals:
            rows.append(vals)
    width = max((len(r) for r in rows), default=0)
    rows = [r for r in rows if len(r) == width]          # a half-written last line
    return np.asarray(rows, float).reshape(len(rows), width)


def read_forces(folder) -> ForceHistory:
    """The force history of a case (``folder``: the case, its ``postProcessing`` or its
    ``postProcessing/forces``).

    Raises
    ------
    FileNotFoundError
        No force file (the solver wrote no iteration).
    """
    folder = Path(folder)
    if (folder / "postProcessing").is_dir():
        folder = folder / "postProcessing"
    if (folder / "forces").is_dir():
        folder = folder / "forces"
    starts = sorted((d for d in folder.iterdir() if d.is_dir()), key=lambda d: float(d.name)) \
        if folder.is_dir() else []
    force, moment = [], []
    for d in starts:
        if (d / "force.dat").is_file():
            f = _rows(d / "force.dat")
            m = _rows(d / "moment.dat") if (d / "moment.dat").is_file() else np.zeros_like(f)
            n = min(len(f), len(m))
            force.append(f[:n])
            moment.append(m[:n])
        elif (d / "forces.dat").is_file():        # ((pressure) (viscous)) ((pressure) (viscous))
            r = _rows(d / "forces.dat")
            t, p, v, mp, mv = r[:, :1], r[:, 1:4], r[:, 4:7], r[:, 7:10], r[:, 10:13]
            force.append(np.hstack([t, p + v, p, v]))
            moment.append(np.hstack([t, mp + mv, mp, mv]))
    if not force:
        raise FileNotFoundError(str(folder))
    f = np.vstack(force)
    m = np.vstack(moment)
    # a restart repeats iterations: keep the last row of each
    _, last = np.unique(f[::-1, 0], return_index=True)
    keep = np.sort(len(f) - 1 - last)
    f, m = f[keep], m[keep]
    return ForceHistory(iteration=f[:, 0].astype(int), force=f[:, 1:4], moment=m[:, 1:4],
                        pressure_force=f[:, 4:7], viscous_force=f[:, 7:10])


@dataclass(frozen=True)
class Settled:
    """The value of a force history and whether it settled.

    Attributes
    ----------
    value : float
        Mean over the last :data:`WINDOW` iterations (half the history if shorter).
    spread : float
        Peak-to-peak over that window relative to ``|value|`` [-] (the swing).
    drift : float
        Change of that mean from the window before, relative to ``|value|`` [-] (infinite
        without a window before).
    window : int
        Iterations averaged.
    finite : bool
        No NaN or infinity in the history.
    spread_before : float
        The swing over the window before, relative to ``|value|`` [-].
    """

    value: float
    spread: float
    drift: float
    window: int
    finite: bool
    spread_before: float = 0.0

    @property
    def settled(self) -> bool:
        """The mean has settled (:data:`DRIFT_TOLERANCE`) and the swing is bounded
        (:data:`SWING_TOLERANCE`): the judge of a finished run."""
        return self.finite and self.drift < DRIFT_TOLERANCE and self.spread < SWING_TOLERANCE

    @property
    def quiet(self) -> bool:
        """:attr:`settled`, and the window before swung less than :data:`SWING_TOLERANCE`
        too: the early stop's rule. The mean of a window still in the start-up transient can
        match the last one's by chance (measured: the BlueROV2 Heavy's level-5 surge stopped
        at iteration 560 on a window holding +18 N and -18 N about a -8 N value; three
        iterations later its drift was 12 % and the judge refused it)."""
        return (self.settled and self.spread_before < SWING_TOLERANCE
                and self.drift < EARLY_DRIFT_FRACTION * DRIFT_TOLERANCE)


#: Iterations averaged at the end of a steady run.
WINDOW = 100
#: Largest change of the mean force from one window to the one before, relative to it [-]:
#: the mean of a limit cycle over a window that holds no whole number of its periods moves
#: by about a third of its swing from window to window (the BlueROV2-sized box: 1.3 % at a
#: 4 % swing), so the value is known to about this much.
DRIFT_TOLERANCE = 0.02
#: The early stop asks for this fraction of DRIFT_TOLERANCE: the solver runs a few iterations
#: more before it reads the stop, and they move the window (measured: a cylinder's level-4
#: yaw stopped at a drift under 2 % and was judged at 2.12 %, not converged).
EARLY_DRIFT_FRACTION = 0.5
#: Largest peak-to-peak of the force over the window, relative to its mean [-]. Steady RANS of
#: a bluff body often settles on a limit cycle (an unsteady wake it cannot follow) that never
#: meets the residual criterion; the mean over the window is then the value, the swing is
#: reported beside it, and a wider swing marks the run not converged.
SWING_TOLERANCE = 0.10
#: Iterations averaged at the end of a run that met its residual criterion: a steady
#: solution, its last iterate the value (a 100-iteration mean would mix in the start-up
#: transient of a run that converged within 200 iterations of it: the BlueROV2 Heavy's level
#: 3 surge, a 1e8 N transient from potentialFoam's start in its thin gaps, settled at -9.41 N
#: by iteration 270 and met the residuals at 326; its 100-iteration mean was -12.6 N).
STEADY_WINDOW = 10


def settle(values, window: int = WINDOW) -> Settled:
    """The mean of the last ``window`` of ``values``, its swing and its drift."""
    v = np.asarray(values, float)
    if v.size == 0:
        return Settled(value=float("nan"), spread=float("inf"), drift=float("inf"), window=0,
                       finite=False)
    finite = bool(np.all(np.isfinite(v)))
    n = min(window, max(v.size // 2, 1))
    w, before = v[-n:], v[-2 * n:-n]
    mean = float(np.mean(w))
    ok = finite and mean != 0
    spread = float((np.max(w) - np.min(w)) / abs(mean)) if ok else float("inf")
    drift = float(abs(mean - np.mean(before)) / abs(mean)) if ok and before.size else \
        float("inf")
    spread_before = float((np.max(before) - np.min(before)) / abs(mean)) \
        if ok and before.size else float("inf")
    return Settled(value=mean, spread=spread, drift=drift, window=int(n), finite=finite,
                   spread_before=spread_before)


# ----------------------------------------------------------------------------- logs

_TIME = re.compile(r"^Time = (\S+)", re.M)
_RESIDUAL = re.compile(r"Solving for (\w+), Initial residual = ([^,]+),")


@dataclass(frozen=True)
class LogState:
    """Where a solver run stands, read from its log.

    Attributes
    ----------
    iteration : int
        Last iteration begun (0 before the first).
    residuals : dict
        Initial residual of each solved field in that iteration.
    converged : bool
        The solver stopped on its residual criterion ("SIMPLE solution converged").
    fatal : str
        The first line of a FOAM FATAL ERROR or a floating point exception ("" if none).
    """

    iteration: int
    residuals: dict
    converged: bool
    fatal: str


def read_log(text: str) -> LogState:
    """The state of a simpleFoam (or any OpenFOAM application's) log."""
    times = list(_TIME.finditer(text))
    iteration, residuals = 0, {}
    if times:
        try:
            iteration = int(float(times[-1].group(1)))
        except ValueError:
            iteration = len(times)
        # the residuals of the last iteration with any (a running solver's last block may
        # hold none yet)
        ends = [m.end() for m in times] + [len(text)]
        for k in range(len(times) - 1, -1, -1):
            for name, r in _RESIDUAL.findall(text[ends[k]:ends[k + 1]]):
                residuals.setdefault(name, float(r))
            if residuals:
                break
    return LogState(iteration=iteration, residuals=residuals,
                    converged="solution converged in" in text, fatal=fatal_line(text))


def fatal_line(text: str) -> str:
    """The one line of an OpenFOAM log that says why it stopped ("" if it did not)."""
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if "FOAM FATAL" in line:
            for nxt in lines[i + 1:i + 8]:
                msg = nxt.strip().lstrip("[0123456789] ").strip()
                if msg:
                    return msg
            return line.strip()
    # the header's "sigFpe : Enabling floating point exception trapping" is no error
    if "sigFpe::sigHandler" in text or "Floating point exception" in text:
        return "floating point exception (the solution diverged)"
    return ""


def mesh_report(text: str) -> tuple[int, dict, int]:
    """From a checkMesh log: cells, faces per patch, and the number of failed checks."""
    m = re.search(r"^\s*cells:\s+(\d+)", text, re.M)
    cells = int(m.group(1)) if m else 0
    patches = {}
    block = re.search(r"Patch\s+Faces\s+Points.*?\n(.*?)\n\s*\n", text, re.S)
    if block:
        for line in block.group(1).splitlines():
            parts = line.split()
            if len(parts) >= 3 and parts[1].isdigit():
                patches[parts[0]] = int(parts[1])
    m = re.search(r"Failed (\d+) mesh checks", text)
    return cells, patches, int(m.group(1)) if m else 0


def execution_time(text: str) -> float:
    """The last ``ExecutionTime = T s`` of an OpenFOAM log [s] (CPU time of the master
    rank; 0 if none)."""
    found = re.findall(r"ExecutionTime = ([0-9.eE+-]+) s", text)
    return float(found[-1]) if found else 0.0


def read_y_plus(folder) -> tuple[float, float, float] | None:
    """The body's y+ (min, max, area-free mean over its faces) at the last written time, from
    the ``yPlus`` function object's ``postProcessing/yPlus/*/yPlus.dat``; None if absent.

    y+ = u_tau y / nu of the wall-adjacent cell centre (OpenFOAM's ``yPlus`` function
    object); the k-omega SST wall functions of the case hold for 30 < y+ < 300 and blend
    below (Menter, Esch, "Elements of industrial heat transfer predictions", 2001).
    """
    files = sorted(Path(folder).glob("postProcessing/yPlus/*/yPlus.dat"))
    rows = []
    for f in files:
        for line in f.read_text(errors="replace").splitlines():
            parts = line.split()
            if len(parts) == 5 and parts[1] == "body" and not line.startswith("#"):
                try:
                    rows.append((float(parts[0]), *map(float, parts[2:5])))
                except ValueError:
                    continue
    if not rows:
        return None
    last = max(rows)
    return (last[1], last[2], last[3])
