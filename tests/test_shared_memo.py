"""tests/_shared_memo.py: a memoised hull function's result computed once per test run and
read back bit for bit by the run's other processes; without the shared folder, a plain call."""

import warnings

import numpy as np
import pytest

import _shared_memo


def _level(calls):
    def solve(v, k: float):
        calls.append(1)
        return v * k / 3.0, (len(v), np.array([k]))

    solve.__module__, solve.__qualname__ = "stripcoef.hull.fake", "solve"
    return solve


def test_a_second_process_reads_the_bits_the_first_computed(tmp_path, monkeypatch):
    monkeypatch.setenv(_shared_memo.ENV, str(tmp_path / "shared"))
    first_calls, second_calls = [], []
    first = _shared_memo.shared(_level(first_calls))       # as in one worker
    second = _shared_memo.shared(_level(second_calls))     # the same function in another
    v = np.random.default_rng(5).normal(size=7)
    a, (n, k) = first(v, 0.7)
    b, (m, j) = second(v.copy(), 0.7)
    assert (len(first_calls), len(second_calls)) == (1, 0)
    assert a.tobytes() == b.tobytes() and n == m == 7 and j.tobytes() == k.tobytes()
    second(v, 0.8)                                         # another argument: computed
    second(v.astype(np.float32), 0.7)                      # another dtype: computed
    assert len(second_calls) == 2


def test_without_the_folder_each_call_computes(monkeypatch):
    monkeypatch.delenv(_shared_memo.ENV, raising=False)
    calls = []
    f = _shared_memo.shared(_level(calls))
    f(np.ones(3), 1.0)
    f(np.ones(3), 1.0)
    assert len(calls) == 2
    assert _shared_memo.once(("k",), lambda: 5) == 5


def test_once_computes_once_per_folder(tmp_path, monkeypatch):
    calls = []

    def compute():
        calls.append(1)
        return {"x": np.arange(3.0)}

    monkeypatch.setenv(_shared_memo.ENV, str(tmp_path / "a"))
    for _ in range(2):
        assert _shared_memo.once(("model", "x.yaml"), compute)["x"].tolist() == [0.0, 1.0, 2.0]
    assert len(calls) == 1
    monkeypatch.setenv(_shared_memo.ENV, str(tmp_path / "b"))   # another run: computed again
    _shared_memo.once(("model", "x.yaml"), compute)
    assert len(calls) == 2


def test_the_hull_functions_are_shared_and_keep_their_own_function():
    """conftest installed the sharing before the hull was imported: the memoised functions
    go through it, and ``__wrapped__`` is still the unmemoised function."""
    from stripcoef.hull import bisection, panels

    for memoised in (panels._solved_level, bisection._refined):
        assert memoised.__wrapped__.__module__ == memoised.__module__
        assert not hasattr(memoised.__wrapped__, "cache_info")
    import stripcoef.hull.memo as memo
    assert getattr(memo.array_memo, "shared_by_tests", False)


def test_a_store_that_cannot_be_written_leaves_the_value_unshared(tmp_path, monkeypatch):
    """A test that makes every Path write fail (a full disk) still gets its value."""
    import errno
    from pathlib import Path

    def full(self, *a, **k):
        raise OSError(errno.ENOSPC, "No space left on device", str(self))

    monkeypatch.setenv(_shared_memo.ENV, str(tmp_path / "shared"))
    monkeypatch.setattr(Path, "write_bytes", full)
    monkeypatch.setattr(Path, "write_text", full)
    calls = []
    assert _shared_memo.shared(_level(calls))(np.ones(2), 2.0)[1][0] == 2
    assert _shared_memo.once(("x",), lambda: 3) == 3 and len(calls) == 1


def test_a_shared_call_reads_the_value_and_issues_the_warnings_again(tmp_path, monkeypatch):
    """``shared_call`` (the diagnoses the documentation's commands share): a second caller
    with the same arguments reads the first one's value (read-only mappings included) and
    gets its warnings, in order; other arguments are computed; an exception is not stored."""
    from types import MappingProxyType

    monkeypatch.setenv(_shared_memo.ENV, str(tmp_path / "shared"))
    calls = []

    def fn(x, *, scale=1.0):
        calls.append(x)
        if x < 0:
            raise ValueError("negative")
        warnings.warn(f"first {x}", UserWarning)
        warnings.warn("second", RuntimeWarning)
        return {"view": MappingProxyType({"x": x * scale}), "a": np.arange(3.0) * x}

    first = _shared_memo.shared_call(fn, "fn")             # as in one process
    second = _shared_memo.shared_call(fn, "fn")            # in another
    with warnings.catch_warnings(record=True) as w1:
        warnings.simplefilter("always")
        a = first(2.0, scale=3.0)
    with warnings.catch_warnings(record=True) as w2:
        warnings.simplefilter("always")
        b = second(2.0, scale=3.0)
    assert calls == [2.0]
    assert isinstance(b["view"], MappingProxyType) and b["view"]["x"] == a["view"]["x"] == 6.0
    assert b["a"].tobytes() == a["a"].tobytes()
    seen = [[(type(w.message), str(w.message)) for w in ws] for ws in (w1, w2)]
    assert seen[0] == seen[1] == [(UserWarning, "first 2.0"), (RuntimeWarning, "second")]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        second(2.0, scale=4.0)                             # another argument: computed
    assert calls == [2.0, 2.0]
    for _ in range(2):
        with pytest.raises(ValueError, match="negative"):
            second(-1.0)
    assert calls == [2.0, 2.0, -1.0, -1.0]
