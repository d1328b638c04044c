r"""Clocks of real log streams: the offset between two streams' clocks, and a fixed-rate
source timed only by its bursty receive times.

**Clock offset** (``streams.NAME.align``). Two loggers (a navigation computer and a thruster
controller) stamp with clocks that differ by a constant offset :math:`\delta` [s]. When both
streams log one shared quantity (the heading, the depth, an echoed command), :math:`\delta`
is the shift that maximises the normalised cross-correlation of the two records of it
(Knapp & Carter 1976, eq. 1: the delay estimate is the argument of the cross-correlation's
peak):

.. math:: \hat\delta = \arg\max_{|\delta| \le \delta_{max}} \rho(\delta), \quad
          \rho(\delta) = \operatorname{corr}\big(s_{ref}(t_j),\; s(t_j - \delta)\big)

over the reference stream's own samples :math:`t_j` (Pearson's coefficient on the overlap, the
aligned stream interpolated linearly), on the lags :math:`\delta = k h` (h the finer of the
two streams' median steps [s]); the peak is refined between samples by the parabola through
the best lag and its two neighbours (Jacovitti & Scarano 1993, eq. 12). The aligned stream's
stamps become :math:`t + \hat\delta`.

Why a shared signal first, and not the offset that best aligns a commanded input with the
measured response: the response lags the command physically (thruster spin-up, dead time),
so that alignment mixes the clock offset with the actuator delay and lag that ``diagnose``
identifies as effects (``thrust_delay``, ``thruster_lag``) and would remove them from the
log. A shared signal has no dynamics between its two records. When the streams share none,
``response: rate`` (:func:`estimate_response_offset`) takes the offset that best explains the
response by the command: for each lag, the least-squares fit of the first-order surge-like
model :math:`\dot v = a\,x(t - \delta) + b\,v + c` (the force drives the acceleration
against a linear drag, Fossen 2011, eq. 6.1 in one DOF) and the lag of the best fit
(largest :math:`R^2`; the delay chosen by comparing the losses of models with different
delays, Ljung 1999, ch. 16). A plain correlation of the command with :math:`\dot v` would be
biased by the drag term (0.09 s early for a 2.5 s time constant, test). The estimate includes
the actuator's delay (reported with it).

**Bursty receive times** (``time: {column: C, retime: true}``). A source sampled at a fixed
period h, stamped when received (a serial link, a network buffer) arrives in bursts: the
receive time of sample k is :math:`r_k = a + h k + d_k` with a latency :math:`d_k \ge 0`.
The line :math:`a + h k` under every point that is closest to them in total,

.. math:: \min_{a, h} \sum_k (r_k - a - h k) \quad \text{subject to} \quad r_k \ge a + h k,

is the linear-programming estimate of Moon, Skelly & Towsley (1999), sec. III (clock skew
from one-way delays): unlike a least-squares fit or the median step it is not biased by the
latency, which is one-sided. Its solution is the edge of the lower convex hull of the points
:math:`(k, r_k)` above the mean index (the objective is linear, so a hull vertex or edge is
optimal); the samples are re-timed :math:`t_k = \hat a + \hat h k`. It assumes that no
sample of the source was lost (every k arrives); the largest latency it implies is reported.

References
----------
Knapp, C. H. & Carter, G. C. (1976). The generalized correlation method for estimation of
time delay. IEEE Trans. Acoustics, Speech, and Signal Processing 24(4), 320-327.
Jacovitti, G. & Scarano, G. (1993). Discrete time techniques for time delay estimation. IEEE
Trans. Signal Processing 41(2), 525-533.
Ljung, L. (1999). System Identification: Theory for the User, 2nd ed. Prentice Hall.
Moon, S. B., Skelly, P. & Towsley, D. (1999). Estimation and removal of clock skew from network
delay measurements. Proc. IEEE INFOCOM '99, 227-234.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stripcoef.errors import InputError

#: A peak normalised cross-correlation below this does not determine an offset [-]: the two
#: columns do not record one quantity (or it does not vary).
MIN_CORRELATION = 0.5
#: Most lags searched (a longer search is refused: give ``max`` smaller) [-].
MAX_LAGS = 20_001


@dataclass(frozen=True)
class Offset:
    """An estimated clock offset: ``offset`` [s] added to the aligned stream's stamps, the
    peak normalised cross-correlation ``correlation`` [-] and the lag step ``step`` [s]."""
    offset: float
    correlation: float
    step: float


def _pearson(x, y) -> float:
    x = x - x.mean()
    y = y - y.mean()
    den = float(np.sqrt(np.dot(x, x) * np.dot(y, y)))
    return float(np.dot(x, y) / den) if den > 0 else 0.0


def estimate_offset(t, s, t_ref, s_ref, *, max_offset: float, where: str = "",
                    key: str = "align") -> Offset:
    r"""The clock offset of the stream (t, s) to the reference (t_ref, s_ref) (module
    docstring): ``t + offset`` is the aligned time [s].

    Raises
    ------
    InputError
        A signal that does not vary, too short an overlap, a peak correlation below
        :data:`MIN_CORRELATION` or a peak at the edge of the search (the offset may be
        larger than ``max_offset``): each with the remedy (``align.offset`` given, or a
        larger ``align.max``).
    """
    s_ref = np.asarray(s_ref, float)
    return _best_lag(t, s, t_ref, s_ref,
                     lambda inside, shifted: _pearson(s_ref[inside], shifted),
                     max_offset=max_offset, where=where, key=key)


def _best_lag(t, s, t_ref, s_ref, score, *, max_offset, where, key) -> Offset:
    """The lag [s] of the highest ``score(inside, s(t_ref[inside] - lag))`` within
    +-``max_offset`` on the finer stream's step, refined by a parabola (module docstring)."""
    t = np.asarray(t, float)
    s = np.asarray(s, float)
    t_ref = np.asarray(t_ref, float)
    s_ref = np.asarray(s_ref, float)
    h = min(float(np.median(np.diff(t))), float(np.median(np.diff(t_ref))))
    remedy = "a column that logs the same varying quantity, or align.offset: SECONDS (given)"
    if not h > 0 or np.ptp(s) == 0 or np.ptp(s_ref) == 0:
        raise InputError("a constant signal gives no clock offset", file=where,
                         key=f"{key}.signal", expected=remedy)
    n = int(np.floor(max_offset / h))
    if 2 * n + 1 > MAX_LAGS:
        raise InputError("too many lags to search", file=where, key=f"{key}.max",
                         value=max_offset, expected=f"at most {(MAX_LAGS - 1) // 2 * h:.4g} s "
                         f"at a step of {h:.4g} s")
    lags = np.arange(-n, n + 1) * h
    rho = np.full(lags.size, -np.inf)
    for i, d in enumerate(lags):
        inside = (t_ref - d >= t[0]) & (t_ref - d <= t[-1])
        if inside.sum() < 10:
            continue
        rho[i] = score(inside, np.interp(t_ref[inside] - d, t, s))
    if not np.isfinite(rho).any():
        raise InputError("the streams overlap too little to align them", file=where,
                         key=f"{key}.to", expected="streams sharing at least 10 samples "
                         "within align.max seconds")
    k = int(np.argmax(rho))
    if k in (0, lags.size - 1) or not (np.isfinite(rho[k - 1]) and np.isfinite(rho[k + 1])):
        weak = rho[k] < MIN_CORRELATION
        raise InputError(f"the best offset is at the edge of the search ({lags[k]:+.4g} s, "
                         f"peak correlation {rho[k]:.2f})", file=where, key=f"{key}.max",
                         value=max_offset, expected="a larger align.max"
                         + (", a column that logs the same varying quantity" if weak else "")
                         + ", or align.offset: SECONDS (given)")
    if rho[k] < MIN_CORRELATION:
        raise InputError(f"the signals do not correlate (peak {rho[k]:.2f} at "
                         f"{lags[k]:+.4g} s)", file=where, key=f"{key}.signal",
                         expected=f"a peak correlation >= {MIN_CORRELATION:g}: " + remedy)
    a, b, c = rho[k - 1], rho[k], rho[k + 1]
    den = a - 2.0 * b + c
    frac = 0.5 * (a - c) / den if den < 0 else 0.0        # vertex of the parabola, |frac| <= 1/2
    return Offset(offset=float(lags[k] + frac * h), correlation=float(b), step=h)


def estimate_response_offset(t, x, t_ref, v_ref, *, max_offset: float, where: str = "",
                             key: str = "align") -> Offset:
    r"""The clock offset of a command stream (t, x) to the stream (t_ref, v_ref) of the
    response it drives (module docstring): the lag of the best least-squares fit of
    :math:`\dot v = a\,x(t - \delta) + b\,v + c` over the reference samples (:math:`\dot v`
    by central differences); ``correlation`` is the fit's multiple correlation
    :math:`\sqrt{R^2}`. Errors as :func:`estimate_offset`."""
    t_ref = np.asarray(t_ref, float)
    v_ref = np.asarray(v_ref, float)
    rate = np.gradient(v_ref, t_ref)

    def fit(inside, shifted):
        a = np.column_stack([shifted, v_ref[inside], np.ones(shifted.size)])
        y = rate[inside]
        coef, *_ = np.linalg.lstsq(a, y, rcond=None)
        sst = float(np.sum((y - y.mean()) ** 2))
        r2 = 1.0 - float(np.sum((y - a @ coef) ** 2)) / sst if sst > 0 else 0.0
        return float(np.sqrt(max(r2, 0.0)))

    return _best_lag(t, x, t_ref, v_ref, fit, max_offset=max_offset, where=where, key=key)


@dataclass(frozen=True)
class Retimed:
    """Re-timed stamps ``t`` [s] of a fixed-rate source, its period ``period`` [s] and the
    largest latency of a receive time behind its re-timed stamp ``max_latency`` [s]."""
    t: np.ndarray
    period: float
    max_latency: float


def _lower_hull(x, y) -> list:
    """Indices of the lower convex hull of points sorted by x (Andrew's monotone chain)."""
    hull: list = []
    for i in range(x.size):
        while len(hull) >= 2:
            o, a = hull[-2], hull[-1]
            if (x[a] - x[o]) * (y[i] - y[o]) - (y[a] - y[o]) * (x[i] - x[o]) <= 0:
                hull.pop()
            else:
                break
        hull.append(i)
    return hull


def retime(receive, *, where: str = "", key: str = "time") -> Retimed:
    r"""Sample times of a fixed-rate source from its receive times ``receive`` [s] (module
    docstring): :math:`t_k = \hat a + \hat h k`, the LP estimate of Moon et al. (1999)."""
    r = np.asarray(receive, dtype=np.longdouble)
    r0 = r[0]
    y = np.asarray(r - r0, dtype=float)
    k = np.arange(y.size, dtype=float)
    hull = _lower_hull(k, y)
    kbar = float(k.mean())
    for i, j in zip(hull[:-1], hull[1:]):
        if k[i] <= kbar <= k[j]:
            break
    h = (y[j] - y[i]) / (k[j] - k[i])
    if not h > 0:
        raise InputError("receive times that do not advance", file=where, key=f"{key}.retime",
                         value=f"period {h:.3g} s", expected="receive times of a source "
                         "sampled at a fixed rate")
    a = y[i] - h * k[i]
    fit = a + h * k
    return Retimed(t=np.asarray(r0 + np.asarray(fit, dtype=np.longdouble)), period=float(h),
                   max_latency=float(np.max(y - fit)))
