"""BLAS threads for small matrices, in the library (not only in the CLI).

stripcoef's linear algebra is many small solves (strips, 2D panels of 32-160 unknowns, the
axisymmetric panel solver): threaded BLAS only adds start-up and contention there, and on a
loaded 2-core machine it made ``estimate`` 2.8 times slower (docs/performance.md). The CLI
sets ``OPENBLAS_NUM_THREADS=1`` before numpy loads; a notebook or a script importing
stripcoef gets the same by :func:`small_matrices`, which limits BLAS to one thread for the
duration of a call with threadpoolctl. A user's own ``OPENBLAS_NUM_THREADS``,
``OMP_NUM_THREADS`` or ``MKL_NUM_THREADS`` wins, and without threadpoolctl nothing changes.
"""

from __future__ import annotations

import contextlib
import functools
import os

#: Environment variables by which a user sets BLAS threads (then left alone).
USER_SETTINGS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def single_blas_thread():
    """A context in which BLAS runs on one thread (threadpoolctl), unless the user set the
    thread count in the environment or threadpoolctl is missing (then it does nothing)."""
    if any(os.environ.get(v) for v in USER_SETTINGS):
        return contextlib.nullcontext()
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:
        return contextlib.nullcontext()
    return threadpool_limits(limits=1, user_api="blas")


def small_matrices(func):
    """Decorator: run ``func`` within :func:`single_blas_thread`."""
    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        with single_blas_thread():
            return func(*args, **kwargs)
    return wrapper
