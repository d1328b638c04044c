"""stripcoef.hull.memo.array_memo: one miss per distinct input, the function's own bits, and no
way for a caller to change what the memo keeps; the four memoised hull functions return what
their unmemoised function returns."""

import numpy as np

from stripcoef.hull.memo import array_memo


def _counted():
    calls = []

    @array_memo(maxsize=4)
    def f(a, b, k: float):
        calls.append(1)
        return a * k + b.sum(), (len(a), np.array([k]))

    return f, calls


def test_equal_arrays_are_one_key_and_dtype_is_part_of_it():
    f, calls = _counted()
    a = np.arange(6.0).reshape(2, 3)
    f(a, np.ones(2), 2.0)
    f(np.asfortranarray(a.copy()), np.ones(2), 2.0)     # same values, other layout: a hit
    assert len(calls) == 1
    f(a.astype(np.float32), np.ones(2), 2.0)            # other dtype: a miss
    f(a, np.ones(2), 3.0)                               # other number: a miss
    f(a.reshape(3, 2), np.ones(2), 2.0)                 # other shape: a miss
    assert len(calls) == 4
    assert f.cache_info().hits == 1


def test_results_are_fresh_copies_and_the_kept_ones_cannot_change():
    f, _ = _counted()
    a = np.arange(3.0)
    first, (n, arr) = f(a, np.ones(2), 2.0)
    assert first.flags.writeable and arr.flags.writeable and n == 3
    first[:] = -1.0
    arr[:] = -1.0
    a[:] = 99.0                                        # the caller's input changed afterwards
    again, (_, arr2) = f(np.arange(3.0), np.ones(2), 2.0)
    np.testing.assert_array_equal(again, np.arange(3.0) * 2.0 + 2.0)
    np.testing.assert_array_equal(arr2, [2.0])


def test_the_function_receives_writable_copies():
    @array_memo(maxsize=2)
    def g(a):
        a += 1.0                                         # the function may work in place
        return a

    x = np.zeros(3)
    np.testing.assert_array_equal(g(x), np.ones(3))
    np.testing.assert_array_equal(x, np.zeros(3))      # the caller's array untouched
    np.testing.assert_array_equal(g(x), np.ones(3))    # the kept result, not a second +1


def test_memoised_hull_functions_are_their_functions_bit_for_bit():
    from stripcoef.hull import axisymmetric, bisection, panels
    from stripcoef.hull.panels import panel_levels
    import trimesh

    x = np.linspace(-1.0, 1.0, 41)
    r = 0.2 * np.sqrt(np.clip(1.0 - x * x, 0.0, None))
    direct = axisymmetric._body_of_revolution.__wrapped__(x, r, 1000.0, 0.1, 80, (0, 1), False)
    for _ in range(2):
        got = axisymmetric.body_of_revolution_added_mass(x, r, rho=1000.0, x_ref=0.1, panels=80)
        np.testing.assert_array_equal(got, direct)

    box = trimesh.creation.box(extents=(0.4, 0.3, 0.2))
    v, f = np.asarray(box.vertices), np.asarray(box.faces, dtype=np.int64)
    rv, rf = bisection._refined.__wrapped__(v.copy(), f.copy(), 200)
    for _ in range(2):
        gv, gf = bisection.refine(v, f, 200)
        np.testing.assert_array_equal(gv, rv)
        np.testing.assert_array_equal(gf, rf)

    pv, pf = panel_levels(v, f, 400)[0][:2]
    scale = float(np.ptp(pv, axis=0).max())
    n0, a0 = panels._solved_level.__wrapped__(pv, pf, scale, 1000.0, (0.0, 0.0, 0.0), 2.0, ())
    for _ in range(2):
        n, a = panels._solve_level(pv, pf, scale, 1000.0, (0.0, 0.0, 0.0), 2.0)
        assert n == n0
        np.testing.assert_array_equal(a, a0)


def test_level_moved_to_a_reference_point_is_the_direct_solve_there():
    """A level solved about its own origin and moved to p by A_p = H(-p)^T A_0 H(-p) (Fossen
    2011 sec. 7.5.3) is the level solved about p directly, within 1e-12 of its largest term:
    the transfer is exact for the panel method's generalised normals (Newman 1977 eq. 4.104)."""
    import trimesh

    from stripcoef.hull import panels

    body = trimesh.creation.box(extents=(0.5, 0.3, 0.2))
    body.apply_translation([0.11, -0.04, 0.03])          # couplings about every point
    v, f = np.asarray(body.vertices), np.asarray(body.faces, dtype=np.int64)
    pv, pf = panels.panel_levels(v, f, 600)[1][:2]
    scale = float(np.ptp(pv, axis=0).max())
    for p in [(0.0, 0.0, 0.0), (0.07, -0.03, 0.05), (-0.4, 0.2, 0.3)]:
        direct = panels._solve_level_now(pv, pf, scale, 1000.0, np.array(p), 2.0)[1]
        n, moved = panels._solve_level(pv, pf, scale, 1000.0, p, 2.0)
        assert n == len(pf)
        assert np.abs(moved - direct).max() <= 1e-12 * np.abs(direct).max()
        assert np.abs(direct[3:, :3]).max() > 1e-3 * np.abs(direct).max()   # not trivially 0
