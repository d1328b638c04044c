"""Progress bars on long work (diagnose, the BEM of compare, long simulations), with tqdm.

Shown on stderr only when it is a terminal (a pipe, a file or a notebook's captured stderr
stays quiet) unless :func:`bars` says otherwise; the CLI's ``--quiet`` turns them off
and ``--verbose`` on. A bar appears only after :data:`DELAY` seconds (quick work shows
nothing), is transient (it disappears when the work ends, so what a command prints is the
same with or without it), and a bar opened inside another one stays silent (the simulations
inside a diagnosis do not stack bars).

No module-global state: whether bars are forced on or off and how many are open live in a
:class:`BarState` held by a :class:`contextvars.ContextVar`, set for a block by :func:`bars`
(each thread and each asyncio task sees its own, and the block restores the caller's).
"""

from __future__ import annotations

import contextlib
import os
import sys
import weakref
from contextvars import ContextVar
from dataclasses import dataclass, replace

#: Seconds of work before a bar appears [s].
DELAY = float(os.environ.get("STRIPCOEF_PROGRESS_DELAY", "0.5"))   # [s]; tests set 0


@dataclass(frozen=True)
class BarState:
    """The progress bars of one context: ``forced`` None (automatic: stderr is a terminal),
    True or False (:func:`bars`), and ``depth``, the bars open now (a bar inside another
    stays silent)."""

    forced: bool | None = None
    depth: int = 0


_STATE: ContextVar[BarState] = ContextVar("stripcoef_progress", default=BarState())


@contextlib.contextmanager
def bars(value: bool | None):
    """Within the block, progress bars forced on (``True``), off (``False``) or automatic
    (``None``); the caller's setting is back after it."""
    token = _STATE.set(replace(_STATE.get(), forced=value))
    try:
        yield
    finally:
        _STATE.reset(token)


def depth() -> int:
    """The bars open now in this context."""
    return _STATE.get().depth


def _open() -> None:
    state = _STATE.get()
    _STATE.set(replace(state, depth=state.depth + 1))


def _closed() -> None:
    state = _STATE.get()
    _STATE.set(replace(state, depth=max(state.depth - 1, 0)))


def enabled() -> bool:
    """Whether a new outermost bar is shown: as forced by :func:`bars`, else when stderr is a
    terminal."""
    forced = _STATE.get().forced
    if forced is not None:
        return forced
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):  # replaced or closed stderr
        return False


def _tqdm(**kw):
    from tqdm import tqdm

    return tqdm(leave=False, file=sys.stderr, dynamic_ncols=True, delay=DELAY, **kw)


def track(iterable, *, desc: str, total: int | None = None, unit: str = "it"):
    """Iterate over ``iterable`` with a bar (``desc``, ``total`` items) when bars are on."""
    if depth() > 0 or not enabled():
        yield from iterable
        return
    _open()
    try:
        with _tqdm(desc=desc, total=total if total is not None else _len(iterable),
                   unit=unit) as b:
            for item in iterable:
                yield item
                b.update()
    finally:
        _closed()


def _len(iterable):
    try:
        return len(iterable)
    except TypeError:
        return None


def _release(bar) -> None:
    bar.close()
    _closed()


class TimeBar:
    """Progress of a simulation in simulated seconds: ``advance(time)`` moves the bar to
    ``time`` [s] (never backwards: an adaptive integrator probes times it then rejects);
    ``close()`` ends it (so does losing the last reference to it, e.g. after an exception).
    Silent when bars are off or inside another bar (``advance`` then costs one comparison)."""

    def __init__(self, t0: float, t1: float, *, desc: str):
        self.shown = float(t0)
        self.step = max(float(t1) - float(t0), 0.0) / 200.0   # redraw every 0.5 % of the span
        self._bar = None
        self._release = None
        if depth() == 0 and enabled():
            self._bar = _tqdm(desc=desc, total=round(float(t1) - float(t0), 6), unit="s",
                              bar_format="{l_bar}{bar}| {n:.4g}/{total:.4g} s "
                                         "[{elapsed}<{remaining}]")
            _open()
            self._release = weakref.finalize(self, _release, self._bar)

    def advance(self, time: float) -> None:
        if self._bar is not None and time >= self.shown + self.step:
            self._bar.update(round(time - self.shown, 6))
            self.shown = time

    def close(self) -> None:
        if self._release is not None:
            self._release()          # runs once
            self._bar = None
