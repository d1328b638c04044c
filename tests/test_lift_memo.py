"""The slender-body rule's memoised stern flow (stripcoef.hull.lift.surface_speed_ratio and
stripcoef.hull.boundary_layer.turbulent_boundary_layer, kept by stripcoef.hull.memo.array_memo):
the same bits as their unmemoised functions, and a caller's change of a result does not
reach the memo."""

import numpy as np

from stripcoef.hull import boundary_layer, lift


def _body():
    s = np.linspace(0.0, 2.0, 201)
    r = 0.1 * np.sqrt(np.clip(1.0 - (s - 1.0) ** 2, 0.0, None))
    return s, np.pi * r ** 2


def test_surface_speed_ratio_is_its_function_bit_for_bit():
    s, area = _body()
    direct = lift._surface_speed_ratio.__wrapped__(s.copy(), area.copy())
    for _ in range(2):
        got = lift.surface_speed_ratio(s, area)
        np.testing.assert_array_equal(got, direct)
        got[:] = 0.0                                      # the caller's copy only
    np.testing.assert_array_equal(lift.surface_speed_ratio(list(s), list(area)), direct)


def test_boundary_layer_is_its_function_bit_for_bit():
    s, area = _body()
    r = np.sqrt(area / np.pi)
    ue = lift.surface_speed_ratio(s, area)
    direct = boundary_layer._layer.__wrapped__(s, r, ue, 2.0, 1.0e-6)
    for _ in range(2):
        got = lift.turbulent_boundary_layer(s, r, ue, speed=2, viscosity=1.0e-6)
        for key, want in zip(("s", "theta", "H", "delta", "separation", "end"), direct):
            np.testing.assert_array_equal(got[key], want)
        got["theta"][:] = -1.0                            # the caller's copy only
