"""One computation per test run of the library's memoised pure functions, shared by the
processes of the run (the xdist workers and the documentation's forked commands).

The hull's pure functions of arrays (panel levels, bisections, bodies of revolution, the fins'
sheet: ``stripcoef.hull.memo.array_memo``) are memoised per process; under ``pytest -n 2`` both
workers solved the same panel levels (measured: about 9 s of CPU of the run's panel levels and
the models of the shipped files built twice).  :func:`install`, called by tests/conftest.py
before any hull module is imported, makes the functions that ``array_memo`` decorates from then
on look first in the folder named by the environment variable :data:`ENV` (the run's own
temporary folder, ``pytest-N/shared_memo``, new each run: conftest sets it; nothing is kept
between runs), keyed by the function's module and name and its arguments' bytes (the memo's own
key), and store what they compute there.  A result read back is the pickle of the one computed
by the same function on the same bits, so a caller sees what the function returns; the
per-process memo stays in front of it (copies out, read-only kept values).

:func:`once` is the same store for any pure computation named by a key (the run_once fixture,
the shipped vehicles' models).  The first process to ask computes while holding a lock (fcntl)
on the key; the others wait and read.  Without :data:`ENV`, or without fcntl, each process
computes for itself, as the library does.
"""

from __future__ import annotations

import copyreg
import functools
import hashlib
import io
import os
import pickle
import warnings
from pathlib import Path
from types import MappingProxyType

#: The folder of the shared results (set for the test processes and the commands they start).
ENV = "STRIPCOEF_TESTS_SHARED_MEMO"

#: The hull modules that decorate with ``array_memo`` at import (checked by :func:`install`).
HULL = ("stripcoef.hull.panels", "stripcoef.hull.bisection", "stripcoef.hull.axisymmetric",
        "stripcoef.hull.corrections")

try:
    import fcntl
except ImportError:                      # no POSIX locks: once per process
    fcntl = None


def folder():
    """The shared folder (created), or None when there is none."""
    root = os.environ.get(ENV)
    if not root or fcntl is None:
        return None
    path = Path(root)
    path.mkdir(parents=True, exist_ok=True)
    return path


def _stored(root: Path, digest: str, compute):
    """``compute()`` once for all processes under ``root``: the pickled value of ``digest``."""
    data = root / f"{digest}.pickle"
    if data.is_file():                  # written whole (renamed into place): no lock needed
        return pickle.loads(data.read_bytes())
    try:
        lock = open(root / f"{digest}.lock", "w")
    except OSError:                     # nowhere to lock: computed here, unshared
        return compute()
    with lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if data.is_file():
            return pickle.loads(data.read_bytes())
        value = compute()
        # the built-in open, not Path.write_bytes: a test may make those fail (a full disk);
        # a store that cannot be written only leaves the value unshared
        part = root / f"{digest}.{os.getpid()}.part"
        try:
            with open(part, "wb") as f:
                _pickler(f).dump(value)
            os.replace(part, data)
        except OSError:
            part.unlink(missing_ok=True)
        return value


def _mappingproxy(mapping):
    """A read-only view of ``mapping`` (how :func:`_pickler` rebuilds one)."""
    return MappingProxyType(mapping)


def _pickler(f):
    """A pickler to ``f`` that also writes read-only mappings (``types.MappingProxyType``,
    which pickle refuses: the records of a diagnosis hold them) as :func:`_mappingproxy` of a
    copy; the process's own pickling is left as it is."""
    p = pickle.Pickler(f, protocol=pickle.HIGHEST_PROTOCOL)
    p.dispatch_table = {**copyreg.dispatch_table,
                        MappingProxyType: lambda m: (_mappingproxy, (dict(m),))}
    return p


def once(key, compute):
    """``compute()`` once per test run for the processes that share :data:`ENV` (else a plain
    call); ``key``: a tuple of strings naming the computation exactly."""
    root = folder()
    if root is None:
        return compute()
    return _stored(root, hashlib.sha256(repr(("once",) + tuple(key)).encode()).hexdigest(),
                   compute)


def shared(fn):
    """``fn`` (a pure function of arrays and hashable values) reading and writing its results
    in the shared folder, keyed by its module, name and ``array_memo``'s key of its
    arguments."""
    from stripcoef.hull.memo import _key

    name = (fn.__module__, fn.__qualname__)

    @functools.wraps(fn)
    def call(*args):
        root = folder()
        if root is None:
            return fn(*args)
        try:
            blob = pickle.dumps((name, tuple(_key(a) for a in args)), protocol=4)
        except (pickle.PicklingError, TypeError, AttributeError):
            return fn(*args)
        return _stored(root, "memo-" + hashlib.sha256(blob).hexdigest(), lambda: fn(*args))

    return call


def install() -> None:
    """From now on ``stripcoef.hull.memo.array_memo`` memoises through :func:`shared`; the
    wrapper's ``__wrapped__`` stays the function itself.  Called before the hull modules are
    imported (a warning names any that already is: its functions stay per process, which
    costs time, not correctness)."""
    import sys
    import warnings

    import stripcoef.hull.memo as memo

    if getattr(memo.array_memo, "shared_by_tests", False):
        return
    early = [m for m in HULL if m in sys.modules]
    if early:
        warnings.warn(f"tests/_shared_memo.install: {early} imported before it: their "
                      "memoised functions are computed per process", stacklevel=2)
    per_process = memo.array_memo

    def array_memo(maxsize: int):
        def decorate(fn):
            memoised = per_process(maxsize)(shared(fn))
            memoised.__wrapped__ = fn
            return memoised
        return decorate

    array_memo.shared_by_tests = True
    memo.array_memo = array_memo


def shared_call(fn, name: str):
    """``fn`` (a pure function of picklable arguments) computed once per test run for the
    processes that share :data:`ENV`, keyed by ``name`` and the pickle of its arguments
    (arguments that pickle alike are equal; ones that pickle differently are only computed
    again).  The warnings ``fn`` issued are recorded with its result and issued again, in
    order, by every call that reads it, so a caller sees the warnings and the value of a
    call of its own.  An exception is raised, not stored."""

    @functools.wraps(fn)
    def call(*args, **kwargs):
        root = folder()
        if root is None:
            return fn(*args, **kwargs)
        blob = io.BytesIO()
        try:
            _pickler(blob).dump((name, args, sorted(kwargs.items())))
        except (pickle.PicklingError, TypeError, AttributeError):
            return fn(*args, **kwargs)

        def compute():
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                value = fn(*args, **kwargs)
            return value, [(w.message, w.category, w.filename, w.lineno) for w in caught]

        value, issued = _stored(root, "call-" + hashlib.sha256(blob.getvalue()).hexdigest(),
                                compute)
        for message, category, filename, lineno in issued:
            warnings.warn_explicit(message, category, filename, lineno)
        return value

    call.shared_by_tests = True
    return call


def share_diagnose() -> None:
    """From now on ``stripcoef.diagnose.pipeline.diagnose`` (which ``stripcoef diagnose``
    imports when it runs) is :func:`shared_call` of itself: the documentation's forked
    commands (tests/_doc_commands.py) and tests/test_diagnose_written.py diagnose the
    shipped sample with the same arguments (the tutorial's and diagnose.md's held-out
    command), once per run.  Only those processes call it: the diagnose tests that change
    the pipeline's functions (monkeypatch) keep their own calls."""
    import stripcoef.diagnose.pipeline as pipeline

    if not getattr(pipeline.diagnose, "shared_by_tests", False):
        pipeline.diagnose = shared_call(pipeline.diagnose, "stripcoef.diagnose.pipeline.diagnose")
