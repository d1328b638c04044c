"""Run many independent evaluations here (processes) or on a Dask cluster, same results.

:func:`run_batches` maps a picklable function over batches of work and returns the results
in batch order, whatever ran them:

- default: this machine, ``workers`` processes (``concurrent.futures``; 1 = in this process);
- ``scheduler``: a Dask distributed scheduler address (``tcp://host:8786``), or a
  ``dask.distributed.Client`` / ``LocalCluster`` object from the API: the same batches are
  submitted to the cluster (``pip install 'stripcoef[dask]'``).

Each evaluation is a pure function of its inputs with single-threaded BLAS, so the numbers
do not depend on where they ran (tests/test_study.py checks local against a LocalCluster
bit for bit).
"""

from __future__ import annotations

import os
from concurrent.futures import ProcessPoolExecutor

from stripcoef.errors import InputError

_BLAS_VARS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def _pin_blas():
    for var in _BLAS_VARS:
        os.environ.setdefault(var, "1")


def default_workers() -> int:
    """Processes used by default: the cores this process may run on."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover (not Linux)
        return max(1, os.cpu_count() or 1)


def _tracked(iterable, total: int, label: str, progress: bool | None):
    """``iterable`` with the package's progress bar (:func:`stripcoef.progress.track`: on a
    terminal, or as ``-q``/``-v`` set it), or bare with ``progress=False``."""
    if progress is False:
        return iterable
    from stripcoef.progress import track

    return track(iterable, desc=label, total=total, unit="batch")


def _refused(address: str) -> None:
    """An InputError at once when nothing listens at a ``tcp://host:port`` scheduler address
    (the connection is refused), instead of Dask's retries until its 10 s timeout; any other
    address, or one that answers or times out, is left to Dask's Client."""
    import socket
    from urllib.parse import urlsplit

    parts = urlsplit(address)
    try:
        host, port = parts.hostname, parts.port
    except ValueError:                       # a port that is not a number: Dask says so
        return
    if parts.scheme != "tcp" or not host or port is None:
        return
    try:
        socket.create_connection((host, port), timeout=10.0).close()
    except ConnectionRefusedError:
        raise InputError("cannot reach the Dask scheduler", key="scheduler", value=address,
                         expected="a running scheduler (nothing listens there: connection "
                                  "refused)") from None
    except OSError:
        return


def _client(scheduler):
    try:
        from dask.distributed import Client
    except ImportError:
        raise InputError("running on a cluster needs Dask", key="scheduler", value=str(scheduler),
                         expected="pip install 'stripcoef[dask]'") from None
    if isinstance(scheduler, Client):
        return scheduler, False
    if hasattr(scheduler, "scheduler_address"):          # a LocalCluster or similar
        return Client(scheduler), True
    _refused(str(scheduler))
    try:
        return Client(str(scheduler), timeout="10s"), True
    except (OSError, TimeoutError) as exc:
        raise InputError("cannot reach the Dask scheduler", key="scheduler",
                         value=str(scheduler), expected=f"a running scheduler ({exc})") from None


def run_batches(fn, batches: list, *, workers: int | None = None, scheduler=None,
                progress: bool | None = None, label: str = "samples") -> list:
    """``[fn(b) for b in batches]``, in order, locally or on a Dask cluster."""
    _pin_blas()
    if scheduler is not None:
        client, owned = _client(scheduler)
        try:
            futures = client.map(fn, batches, pure=False)
            from dask.distributed import as_completed
            for _ in _tracked(as_completed(futures), len(batches), label, progress):
                pass
            return client.gather(futures)
        finally:
            if owned:
                client.close()
    n = default_workers() if workers is None else int(workers)
    if n < 1:
        raise InputError("workers must be positive", key="workers", value=workers,
                         expected="an integer >= 1")
    if n == 1 or len(batches) <= 1:
        return list(_tracked(map(fn, batches), len(batches), label, progress))
    with ProcessPoolExecutor(max_workers=min(n, len(batches))) as pool:
        return list(_tracked(pool.map(fn, batches), len(batches), label, progress))
