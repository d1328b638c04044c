"""Whole-array ring kernels of corrections.py against plain references.

- the theta moments (closed forms for near rings, the 9-node form of the 16-point trapezoid
  rule for far ones) against a dense trapezoid rule on theta;
- the mode >= 2 kernels (roll relief; the 25-node form of the 48-point rule for far rings)
  against the same dense rule;
- the vectorised influence matrices against the same quadrature written as loops over the
  quadrature points (one kernel call per point, as the solver was first written).
"""

import numpy as np
import pytest

from stripcoef.hull import axisymmetric as C


def dense_moments(p, q, m, nodes=4096):
    """I_m, J_m, J_{m+1} of R^2 = P - Q cos(theta) by the periodic trapezoid rule on `nodes`
    points (spectrally accurate; Q/P <= 0.95 needs far fewer than 4096)."""
    th = 2.0 * np.pi * np.arange(nodes) / nodes
    c = np.cos(th)[None, :]
    inv = 1.0 / np.sqrt(p[:, None] - q[:, None] * c)
    w = 2.0 * np.pi / nodes
    return (w * np.sum(c ** m * inv, axis=1), w * np.sum(c ** m * inv ** 3, axis=1),
            w * np.sum(c ** (m + 1) * inv ** 3, axis=1))


@pytest.mark.parametrize("m", [0, 1])
def test_theta_moments_match_dense_quadrature(m):
    # rings from far (Q/P ~ 1e-4, trapezoid branch) to near (Q/P = 0.95, elliptic branch),
    # on both sides of the switch at Q/P = 0.25
    rng = np.random.default_rng(3)
    r = rng.uniform(0.01, 1.0, 400)
    rq = rng.uniform(0.01, 1.0, 400)
    x = rng.uniform(-1.0, 1.0, 400)
    xq = x + rng.uniform(-3.0, 3.0, 400) * np.abs(r - rq) + rng.uniform(0, 1, 400) ** 4
    got = C._theta_moments(x, r, xq, rq, m)
    p = (x - xq) ** 2 + r * r + rq * rq
    q = 2.0 * r * rq
    keep = q / p <= 0.95
    assert np.sum(keep & (q < 0.25 * p)) > 50 and np.sum(keep & (q >= 0.25 * p)) > 50
    want = dense_moments(p[keep], q[keep], m)
    for g, w in zip(got, want):
        # all three are positive (1/R is largest where cos(theta) = 1); measured <= 1.2e-12
        assert np.all(w > 0)
        assert np.max(np.abs(g[keep] - w) / w) < 1e-10


def test_theta_moments_broadcast_shapes():
    # (1, n, 1) collocation against (4, 1, n) points gives (4, n, n), equal to the flat call
    rng = np.random.default_rng(5)
    x, r = rng.uniform(-1, 1, 6), rng.uniform(0.1, 1, 6)
    xq, rq = rng.uniform(-1, 1, (4, 6)), rng.uniform(0.1, 1, (4, 6))
    got = C._theta_moments(x[None, :, None], r[None, :, None], xq[:, None, :], rq[:, None, :], 1)
    X, R, XQ, RQ = np.broadcast_arrays(x[None, :, None], r[None, :, None], xq[:, None, :],
                                       rq[:, None, :])
    flat = C._theta_moments(X.ravel(), R.ravel(), XQ.ravel(), RQ.ravel(), 1)
    for g, f in zip(got, flat):
        assert g.shape == (4, 6, 6)
        assert np.allclose(g.ravel(), f, rtol=1e-14, atol=0.0)


def loop_influence(xn, rn, mode):
    """The quadrature of corrections._influence as loops over its points: 4 Gauss points on
    far panels, 12 clustered points from the nearest end on the two neighbours, 12 on each
    half of the own panel from its mid-point."""
    n = xn.size - 1
    length, tx, tr, nx, nr = C._panel_geometry(xn, rn)
    xc, rc = 0.5 * (xn[1:] + xn[:-1]), 0.5 * (rn[1:] + rn[:-1])
    S = np.zeros((n, n))
    D = np.zeros((n, n))
    for gk, wk in zip(*C._GAUSS_FAR):
        xq = xc + 0.5 * gk * length * tx
        rq = rc + 0.5 * gk * length * tr
        s, d = C._kernels(xc[:, None], rc[:, None], xq[None, :], rq[None, :],
                          nx[None, :], nr[None, :], mode)
        S += s * (0.5 * wk * length[None, :])
        D += d * (0.5 * wk * length[None, :])
    for off in (-1, 0, 1):
        i = np.arange(max(0, -off), min(n, n - off))
        j = i + off
        S[i, j] = 0.0
        D[i, j] = 0.0
        for tk, wk in zip(C._CLUSTER_T, C._CLUSTER_W):
            if off == 0:
                for sign in (1.0, -1.0):
                    sq = tk * 0.5 * length[j]
                    s, d = C._self_kernels(xc[i], rc[i], xc[j] + sign * sq * tx[j],
                                           rc[j] + sign * sq * tr[j], nx[j], nr[j], mode)
                    S[i, j] += s * wk * 0.5 * length[j]
                    D[i, j] += d * wk * 0.5 * length[j]
            else:
                x0 = xn[j] if off > 0 else xn[j + 1]
                r0 = rn[j] if off > 0 else rn[j + 1]
                sq = tk * length[j]
                s, d = C._kernels(xc[i], rc[i], x0 + off * sq * tx[j], r0 + off * sq * tr[j],
                                  nx[j], nr[j], mode)
                S[i, j] += s * wk * length[j]
                D[i, j] += d * wk * length[j]
    return S, D


def _spheroid_nodes(panels=30):
    x = np.linspace(-0.75, 0.75, 21)
    r = 0.1 * np.sqrt(np.clip(1.0 - (x / 0.75) ** 2, 0.0, None))
    return C._meridian(x, r, panels, area_linear=True)


@pytest.mark.parametrize("mode", [0, 1, 2])
@pytest.mark.parametrize("block", [C._BLOCK_PAIRS, 50])
def test_influence_equals_loop_over_points(mode, block, monkeypatch):
    monkeypatch.setattr(C, "_BLOCK_PAIRS", block)         # one block, or one row per block
    for xn, rn in (_spheroid_nodes(), C._meridian([0.0, 0.5], [0.1, 0.1], 24)):
        S, D, _ = C._influence(xn, rn, mode)
        S_ref, D_ref = loop_influence(xn, rn, mode)
        assert np.max(np.abs(S - S_ref)) <= 1e-13 * np.max(np.abs(S_ref))
        assert np.max(np.abs(D - D_ref)) <= 1e-13 * np.max(np.abs(D_ref))


@pytest.mark.parametrize("mode", [0, 1])
def test_closed_influence_corner_pairs(mode):
    # the closed meridian's first and last panels are neighbours: same clustered rule from
    # their shared node as loops over the points
    xn, rn = C._closed_meridian([0.0, 0.3, 0.3, 0.0], [0.05, 0.05, 0.08, 0.08], 24)
    S, D, (length, nx, nr, xc, rc) = C._influence_closed(xn, rn, mode)
    _, tx, tr, _, _ = C._panel_geometry(xn, rn)
    n = xc.size
    for i, j, x0, r0, dirn in ((n - 1, 0, xn[0], rn[0], 1.0), (0, n - 1, xn[n], rn[n], -1.0)):
        s_ij = d_ij = 0.0
        for tk, wk in zip(C._CLUSTER_T, C._CLUSTER_W):
            sq = tk * length[j]
            s, d = C._kernels(np.array([xc[i]]), np.array([rc[i]]),
                              np.array([x0 + dirn * sq * tx[j]]),
                              np.array([r0 + dirn * sq * tr[j]]), nx[j], nr[j], mode)
            s_ij += s[0] * wk * length[j]
            d_ij += d[0] * wk * length[j]
        assert S[i, j] == pytest.approx(s_ij, rel=1e-13)
        assert D[i, j] == pytest.approx(d_ij, rel=1e-13)


@pytest.mark.parametrize("mode", [2, 3])
def test_mode_kernels_match_dense_quadrature(mode):
    # S_m = -r_q/(4 pi) int cos(m t)/R, D_m = r_q/(4 pi) int ((x_q - x_c) n_x + n_r r_q
    # - n_r r_c cos t) cos(m t)/R^3 against a dense trapezoid rule: far rings (the 25-node
    # form of the 48-point rule) to 1e-10 (measured 2e-16), near rings (toroidal functions by
    # upward recurrence, _toroidal) to 1e-9 (measured 5e-13)
    rng = np.random.default_rng(7)
    n = 300
    rc, rq = rng.uniform(0.05, 1.0, n), rng.uniform(0.05, 1.0, n)
    xc = rng.uniform(-1.0, 1.0, n)
    xq = xc + rng.uniform(-3.0, 3.0, n) * np.abs(rc - rq) + rng.uniform(0, 1, n) ** 4
    nx, nr = np.cos(rng.uniform(0, np.pi, n)), np.sin(rng.uniform(0, np.pi, n))
    s, d = C._mode_kernels(xc, rc, xq, rq, nx, nr, mode)
    p = (xc - xq) ** 2 + rc * rc + rq * rq
    q = 2.0 * rc * rq
    th = 2.0 * np.pi * np.arange(4096) / 4096
    c, cm = np.cos(th)[None, :], np.cos(mode * th)[None, :]
    inv = 1.0 / np.sqrt(p[:, None] - q[:, None] * c)
    w = 2.0 * np.pi / 4096
    base = ((xq - xc) * nx + nr * rq)[:, None]
    s_ref = -rq * w * np.sum(cm * inv, axis=1) / (4.0 * np.pi)
    d_ref = rq * w * np.sum((base - (nr * rc)[:, None] * c) * cm * inv ** 3, axis=1) / (4.0 * np.pi)
    far, keep = q < 0.25 * p, q / p <= 0.95
    assert np.sum(far) > 50 and np.sum(keep & ~far) > 50
    # relative to the size of the integrand (the cos(m t) integrals can be close to 0)
    s_scale = rq * w * np.sum(inv, axis=1) / (4.0 * np.pi)
    d_scale = rq * w * np.sum(np.abs(base - (nr * rc)[:, None] * c) * inv ** 3,
                              axis=1) / (4.0 * np.pi)
    for tol, sel in ((1e-10, far), (1e-9, keep & ~far)):
        assert np.max(np.abs(s - s_ref)[sel] / s_scale[sel]) < tol
        assert np.max(np.abs(d - d_ref)[sel] / d_scale[sel]) < tol
