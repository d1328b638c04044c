"""Progress bars on long work (diagnose, the BEM of compare, long simulations), with tqdm.

Shown on stderr only when it is a terminal (a pipe, a file or a notebook's captured stderr
stays quiet) unless :func:`set_enabled` says otherwise; the CLI's ``--quiet`` turns them off
and ``--verbose`` on. A bar appears only after :data:`DELAY` seconds (quick work shows
nothing), is transient (it disappears when the work ends, so what a command prints is the
same with or without it), and a bar opened inside another one stays silent (the simulations
inside a diagnosis do not stack bars).
"""

from __future__ import annotations

import os
import sys
import weakref

#: None: automatic (stderr is a terminal); True/False: forced by :func:`set_enabled`.
_ENABLED: bool | None = None
#: Bars open now (a bar inside another stays silent).
_DEPTH = 0
#: Seconds of work before a bar appears [s].
DELAY = float(os.environ.get("STRIPCOEF_PROGRESS_DELAY", "0.5"))   # [s]; tests set 0


def set_enabled(value: bool | None) -> None:
    """Force progress bars on (``True``) or off (``False``), or back to automatic (``None``)."""
    global _ENABLED
    _ENABLED = value


def enabled() -> bool:
    """Whether a new outermost bar is shown: as forced by :func:`set_enabled`, else when
    stderr is a terminal."""
    if _ENABLED is not None:
        return _ENABLED
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):  # replaced or closed stderr
        return False


def _tqdm(**kw):
    from tqdm import tqdm

    return tqdm(leave=False, file=sys.stderr, dynamic_ncols=True, delay=DELAY, **kw)


def track(iterable, *, desc: str, total: int | None = None, unit: str = "it"):
    """Iterate over ``iterable`` with a bar (``desc``, ``total`` items) when bars are on."""
    global _DEPTH
    if _DEPTH > 0 or not enabled():
        yield from iterable
        return
    _DEPTH += 1
    try:
        with _tqdm(desc=desc, total=total if total is not None else _len(iterable),
                   unit=unit) as b:
            for item in iterable:
                yield item
                b.update()
    finally:
        _DEPTH -= 1


def _len(iterable):
    try:
        return len(iterable)
    except TypeError:
        return None


def _release(bar) -> None:
    global _DEPTH
    bar.close()
    _DEPTH -= 1


class TimeBar:
    """Progress of a simulation in simulated seconds: ``advance(time)`` moves the bar to
    ``time`` [s] (never backwards: an adaptive integrator probes times it then rejects);
    ``close()`` ends it (so does losing the last reference to it, e.g. after an exception).
    Silent when bars are off or inside another bar (``advance`` then costs one comparison)."""

    def __init__(self, t0: float, t1: float, *, desc: str):
        global _DEPTH
        self.shown = float(t0)
        self.step = max(float(t1) - float(t0), 0.0) / 200.0   # redraw every 0.5 % of the span
        self._bar = None
        self._release = None
        if _DEPTH == 0 and enabled():
            self._bar = _tqdm(desc=desc, total=round(float(t1) - float(t0), 6), unit="s",
                              bar_format="{l_bar}{bar}| {n:.4g}/{total:.4g} s "
                                         "[{elapsed}<{remaining}]")
            _DEPTH += 1
            self._release = weakref.finalize(self, _release, self._bar)

    def advance(self, time: float) -> None:
        if self._bar is not None and time >= self.shown + self.step:
            self._bar.update(round(time - self.shown, 6))
            self.shown = time

    def close(self) -> None:
        if self._release is not None:
            self._release()          # runs once
            self._bar = None
