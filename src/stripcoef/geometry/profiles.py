r"""Hull profile segments: radius (or half-breadth / half-height) as a function of x.

Each segment covers ``[x_aft, x_fwd]`` in FRD body axes (x forward).  A profile is
a contiguous list of segments; :class:`Profile` evaluates it at strip centres.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stripcoef.errors import InputError

#: Registry of segment types: name -> (evaluator, required shape keys)
SEGMENT_TYPES = ("cylinder", "cone", "ellipsoid_nose", "ellipsoid_tail", "myring_nose",
                 "myring_tail", "table")


def ellipsoid_nose(x, x_aft, x_fwd, radius):
    r"""Semi-ellipsoid nose, tip at ``x_fwd``.

    .. math:: r(x) = R\sqrt{1 - \xi^2},\quad \xi = (x - x_a)/(x_f - x_a)

    Parameters: x [m], segment ends [m], radius R [m].  Returns r [m].

    References
    ----------
    MARES model (Ferreira et al. 2009, sec. IV.A): "the nose and the tail consist in two semi-ellipsoids".
    """
    xi = np.clip((np.asarray(x, float) - x_aft) / (x_fwd - x_aft), 0.0, 1.0)
    return radius * np.sqrt(np.maximum(1.0 - xi**2, 0.0))


def ellipsoid_tail(x, x_aft, x_fwd, radius):
    r"""Semi-ellipsoid tail, tip at ``x_aft``: :math:`r = R\sqrt{1 - \xi^2}`, :math:`\xi = (x_f - x)/(x_f - x_a)` [m].

    Parameters: x [m], segment ends [m], radius R [m].  Returns r [m].

    References
    ----------
    MARES model (Ferreira et al. 2009, sec. IV.A), as :func:`ellipsoid_nose`.
    """
    xi = np.clip((x_fwd - np.asarray(x, float)) / (x_fwd - x_aft), 0.0, 1.0)
    return radius * np.sqrt(np.maximum(1.0 - xi**2, 0.0))


def myring_nose(x, x_aft, x_fwd, radius, n=2.0, length=None):
    r"""Myring nose, tip at ``x_fwd``, nose length ``a``, shape exponent ``n``.

    .. math:: r(s) = R\left[1 - \left(\frac{s - a}{a}\right)^2\right]^{1/n},\quad
              s = x_f - x + (a - (x_f - x_a))

    ``length`` a [m] is the full Myring nose length (default: the segment's); a longer
    ``a`` truncates the tip by :math:`a_{offset} = a - (x_f - x_a)`, as real hulls are
    (Prestero 2001, Table 2.1: REMUS a = 0.191 m, a_offset = 0.0165 m).

    References
    ----------
    Myring, D. F. (1976), "A theoretical study of body drag in subcritical axisymmetric flow",
    Aeronautical Quarterly 27(3), 186-194, eq. for the nose; Prestero (2001), eq. 2.1.
    """
    a = float(length) if length is not None else x_fwd - x_aft
    s = np.clip(x_fwd - np.asarray(x, float) + (a - (x_fwd - x_aft)), 0.0, a)
    return radius * np.maximum(1.0 - ((s - a) / a) ** 2, 0.0) ** (1.0 / n)


def myring_tail(x, x_aft, x_fwd, radius, theta=np.radians(25.0), length=None):
    r"""Myring tail, from full radius at ``x_fwd`` to the tip at ``x_aft``, tip half-angle theta.

    .. math:: r(t) = R - \left(\frac{3R}{c^2} - \frac{\tan\theta}{c}\right)t^2
                     + \left(\frac{2R}{c^3} - \frac{\tan\theta}{c^2}\right)t^3,\quad t = x_f - x

    Parameters: x [m], segment ends [m], radius R [m], ``theta`` [rad], ``length`` c [m]
    (the full Myring tail length, default x_f - x_a; a longer c truncates the tip by
    :math:`c_{offset} = c - (x_f - x_a)`, Prestero 2001, Table 2.1: REMUS c = 0.541 m,
    c_offset = 0.0368 m). Returns r [m].

    References
    ----------
    Myring (1976); Prestero (2001), eq. 2.2 (with d = 2R).
    """
    c = float(length) if length is not None else x_fwd - x_aft
    t = np.clip(x_fwd - np.asarray(x, float), 0.0, c)
    tt = np.tan(theta)
    r = radius - (3 * radius / c**2 - tt / c) * t**2 + (2 * radius / c**3 - tt / c**2) * t**3
    return np.maximum(r, 0.0)


#: Turn of the profile's slope at a junction of two segments above which
#: :meth:`Profile.offsets` marks it a corner [deg] (assumption: 1 degree; two segments that
#: meet tangentially, as a Myring nose or tail or an ellipsoid on a cylinder, turn by 0 there).
KINK_DEGREES = 1.0


def _end_slope(seg, x, r, end: int) -> float:
    """dr/dx [-] of segment ``seg`` at its aft (``end`` 0) or forward (-1) end, from its offsets
    ``x``, ``r`` [m] there: a table's end chord, an analytic segment's one-sided difference
    over 1e-6 of its length."""
    if seg.kind == "table":
        i = (0, 1) if end == 0 else (-2, -1)
        return float((r[i[1]] - r[i[0]]) / (x[i[1]] - x[i[0]]))
    h = 1e-6 * (seg.x_fwd - seg.x_aft)
    a = seg.x_aft if end == 0 else seg.x_fwd - h
    return float((seg(np.array([a + h]))[0] - seg(np.array([a]))[0]) / h)


#: Stations at which :meth:`Profile.offsets` samples an analytic segment (cosine-spaced,
#: so that a round nose or tail is resolved; assumption: 201, finer than the 400 offsets of
#: the whole SUBOFF hull per segment) [-].
OFFSET_POINTS = 201


@dataclass
class Segment:
    """One profile segment (already validated)."""

    kind: str
    x_aft: float
    x_fwd: float
    params: dict

    def __call__(self, x):
        p = self.params
        if self.kind == "cylinder":
            return np.full_like(np.asarray(x, float), p["radius"])
        if self.kind == "cone":
            ra, rf = p["radius"]
            xi = (np.asarray(x, float) - self.x_aft) / (self.x_fwd - self.x_aft)
            return ra + (rf - ra) * xi
        if self.kind == "ellipsoid_nose":
            return ellipsoid_nose(x, self.x_aft, self.x_fwd, p["radius"])
        if self.kind == "ellipsoid_tail":
            return ellipsoid_tail(x, self.x_aft, self.x_fwd, p["radius"])
        if self.kind == "myring_nose":
            return myring_nose(x, self.x_aft, self.x_fwd, p["radius"], p.get("n", 2.0),
                               p.get("length"))
        if self.kind == "myring_tail":
            return myring_tail(x, self.x_aft, self.x_fwd, p["radius"],
                               np.radians(p.get("theta_deg", 25.0)), p.get("length"))
        if self.kind == "table":
            pts = p["points"]
            return np.interp(x, pts[:, 0], pts[:, 1])
        raise AssertionError(self.kind)  # validated at load time


@dataclass
class Profile:
    """A contiguous list of segments sorted from aft to forward."""

    segments: list[Segment]

    @property
    def x_aft(self) -> float:
        return self.segments[0].x_aft

    @property
    def x_fwd(self) -> float:
        return self.segments[-1].x_fwd

    def offsets(self) -> tuple[np.ndarray, np.ndarray]:
        """The profile's offsets, aft to forward: x [m] non-decreasing, r [m]. A ``table``
        segment gives its own points inside it (and its two ends, evaluated), an analytic
        segment its exact values at :data:`OFFSET_POINTS` cosine-spaced stations (dense
        samples of a smooth curve). What a smooth interpolant of the hull is built from
        (:func:`stripcoef.hull.axisymmetric.smooth_meridian`), where the chords between a
        table's points are a polyline: each segment is taken as smooth inside. A junction's
        point is given once where the two segments meet with the same slope, twice where the
        slope turns there by more than :data:`KINK_DEGREES` (a corner, e.g. a cone on a
        cylinder), and both segments' radii where they differ (a step)."""
        xs, rs = [], []
        prev = None
        for seg in self.segments:
            if seg.kind == "table":
                pts = seg.params["points"]
                inner = (pts[:, 0] > seg.x_aft) & (pts[:, 0] < seg.x_fwd)
                x = np.concatenate([[seg.x_aft], pts[inner, 0], [seg.x_fwd]])
            else:
                x = seg.x_aft + (seg.x_fwd - seg.x_aft) * 0.5 * (
                    1.0 - np.cos(np.linspace(0.0, np.pi, OFFSET_POINTS)))
            r = seg(x)
            if prev is not None and abs(r[0] - rs[-1][-1]) <= 1e-12 * max(abs(r[0]), 1.0):
                turn = abs(np.degrees(np.arctan(_end_slope(seg, x, r, 0))
                                      - np.arctan(_end_slope(prev, xs[-1], rs[-1], -1))))
                if turn <= KINK_DEGREES:
                    x, r = x[1:], r[1:]
            xs.append(x)
            rs.append(r)
            prev = seg
        return np.concatenate(xs), np.concatenate(rs)

    def __call__(self, x) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        out = np.zeros_like(x)
        for seg in self.segments:
            inside = (x >= seg.x_aft) & (x <= seg.x_fwd)
            if np.any(inside):
                out[inside] = seg(x[inside])
        return out


def check_contiguous(segments: list[Segment], *, file: str, key: str, tol: float = 1e-9) -> Profile:
    """Sort segments aft to forward; refuse gaps and overlaps (InputError names the segments)."""
    order = sorted(range(len(segments)), key=lambda i: segments[i].x_aft)
    segs = [segments[i] for i in order]
    for a, b, ia, ib in zip(segs[:-1], segs[1:], order[:-1], order[1:]):
        if b.x_aft > a.x_fwd + tol:
            raise InputError(f"gap between segments {ia} and {ib}", file=file, key=key,
                             value=[a.x_fwd, b.x_aft],
                             expected="each segment to start where the previous one ends")
        if b.x_aft < a.x_fwd - tol:
            raise InputError(f"segments {ia} and {ib} overlap", file=file, key=key,
                             value=[a.x_fwd, b.x_aft],
                             expected="each segment to start where the previous one ends")
    return Profile(segs)
