"""One per-process memo for the hull's pure functions of arrays (:func:`array_memo`).

The panel levels (:mod:`stripcoef.hull.panels`), the equivalent bodies of revolution
(:mod:`stripcoef.hull.axisymmetric`), the bisection refinements
(:mod:`stripcoef.hull.bisection`) and the fins' thin-sheet share
(:mod:`stripcoef.hull.corrections`) are pure functions of arrays that every estimate of the
same vehicle asks again (a study's samples, the many commands of the tests on the shipped
files).  :func:`array_memo` keys a ``functools.lru_cache`` on each array's dtype, shape and
bytes (hashable and immutable), hands the function fresh writable copies of its arrays, keeps
the results read-only and copies them out: a caller can neither change the memo's arrays nor
see a difference from a call of the function itself (the same bits).

Depends on: numpy.
"""

from __future__ import annotations

import functools
from typing import NamedTuple

import numpy as np


class _Frozen(NamedTuple):
    """An array as a memo key: dtype (``numpy.dtype.str``), shape and C-order bytes."""

    dtype: str
    shape: tuple
    data: bytes


def _key(value):
    """``value`` as a hashable key part: an array as :class:`_Frozen`, anything else as is
    (it must be hashable: a number, a string, a tuple of them, a frozen dataclass)."""
    if isinstance(value, np.ndarray):
        a = np.ascontiguousarray(value)
        return _Frozen(a.dtype.str, a.shape, a.tobytes())
    return value


def _thaw(value):
    """The argument back from a key part: a :class:`_Frozen` as a fresh writable array."""
    if isinstance(value, _Frozen):
        return np.frombuffer(value.data, dtype=np.dtype(value.dtype)).reshape(value.shape).copy()
    return value


def _freeze(value):
    """A result as the memo keeps it: arrays read-only, lists and tuples as tuples."""
    if isinstance(value, np.ndarray):
        value.flags.writeable = False
        return value
    if isinstance(value, (tuple, list)):
        return tuple(_freeze(v) for v in value)
    return value


def _copy(value):
    """A kept result as the caller receives it: each array a writable copy."""
    if isinstance(value, np.ndarray):
        return value.copy()
    if isinstance(value, tuple):
        return tuple(_copy(v) for v in value)
    return value


def array_memo(maxsize: int):
    """Decorator: memoise a pure function of positional arrays and hashable values per process.

    The key is each argument's :func:`_key` (an array by dtype, shape and bytes: two arrays
    of the same values and dtype are one key, whatever their memory layout); a miss calls the
    function with fresh writable copies of the arrays; the result (an array, or a tuple or list
    of arrays and numbers) is kept read-only and each call gets copies of its arrays.  At most
    ``maxsize`` results are kept, least recently used dropped (``functools.lru_cache``).  The
    wrapper has ``cache_info`` and ``cache_clear`` as ``lru_cache`` has, and ``__wrapped__``
    (the function itself, unmemoised).  Callers normalise their arguments (dtype, float
    numbers) so that equal inputs make equal keys.
    """
    def decorate(fn):
        @functools.lru_cache(maxsize=maxsize)
        def kept(key):
            return _freeze(fn(*(_thaw(k) for k in key)))

        @functools.wraps(fn)
        def memoised(*args):
            return _copy(kept(tuple(_key(a) for a in args)))

        memoised.cache_info = kept.cache_info
        memoised.cache_clear = kept.cache_clear
        return memoised
    return decorate


__all__ = ["array_memo"]
