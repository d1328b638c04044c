r"""Polygons in a section plane (y, z): cleaning, orientation, area, centroid, corners.

The rings that the mesh slicer produces and the panel method solves (outer rings
counter-clockwise, holes clockwise). Shoelace formulas (Green's theorem) throughout.
"""

from __future__ import annotations
import numpy as np
from stripcoef.errors import InputError


#: Turning angle above which a vertex is a sharp corner (cosine clustering) [rad].
CORNER_ANGLE = np.radians(25.0)


def clean_ring(ring, where: str) -> np.ndarray:
    r = np.asarray(ring, dtype=float)
    if r.ndim != 2 or r.shape[1] != 2:
        raise InputError("contour must be an (n, 2) array of (y, z) points", key=where,
                         value=f"shape {r.shape}", expected="(n, 2)")
    if not np.isfinite(r).all():
        raise InputError("contour has non-finite coordinates", key=where)
    if len(r) > 1:
        y0, z0 = r[0]
        y1, z1 = r[-1]
        if abs(y0 - y1) <= 1e-8 + 1e-5 * abs(y1) and abs(z0 - z1) <= 1e-8 + 1e-5 * abs(z1):
            r = r[:-1]                              # the closing point (np.allclose's test)
    if len(r) > 1:
        # drop repeated consecutive points
        y, z = r[:, 0], r[:, 1]
        scale = max(float(y.max() - y.min()), float(z.max() - z.min()), 1e-300)
        d = np.concatenate((r[1:], r[:1])) - r
        keep = d[:, 0] ** 2 + d[:, 1] ** 2 > (1e-12 * scale) ** 2
        if not keep.all():
            r = r[keep]
    if len(r) < 3:
        raise InputError("contour has fewer than 3 distinct points", key=where,
                         value=len(r), expected=">= 3")
    return r


def signed_area(ring) -> float:
    r"""Signed area of a ring in the (y, z) plane, positive counter-clockwise [m^2].

    .. math:: A = \tfrac12 \sum_i (y_i z_{i+1} - y_{i+1} z_i)

    References
    ----------
    Shoelace formula (Gauss's area formula).
    """
    r = np.asarray(ring, dtype=float)
    y, z = r[:, 0], r[:, 1]
    return 0.5 * float(y[:-1] @ z[1:] - y[1:] @ z[:-1] + y[-1] * z[0] - y[0] * z[-1])


def point_in_ring(p, ring) -> bool:
    """Whether the point ``p`` (y, z) lies inside ``ring`` (:func:`points_in_ring`)."""
    return bool(points_in_ring(np.asarray(p, float)[None, :], ring)[0])


def points_in_ring(points, ring) -> np.ndarray:
    r"""Whether each of ``points`` (P, 2) lies inside ``ring`` (n, 2) [m]: the even-odd
    (crossing-number) rule, a ray from the point towards +y crossing the edges
    :math:`(y_i, z_i) \to (y_{i+1}, z_{i+1})` with :math:`z_i > z_p \ne z_{i+1} > z_p` at
    :math:`y = y_i + (z_p - z_i)(y_{i+1} - y_i)/(z_{i+1} - z_i) > y_p` an odd number of times
    (Shimrat 1962, "Algorithm 112: position of point relative to polygon", Commun. ACM 5(8)
    434; O'Rourke 1998, "Computational Geometry in C", 2nd ed., sec. 7.4).  Returns (P,) bool."""
    y, z = ring[:, 0], ring[:, 1]
    y2, z2 = np.roll(y, -1), np.roll(z, -1)
    py, pz = points[:, :1], points[:, 1:]
    cond = (z > pz) != (z2 > pz)
    with np.errstate(divide="ignore", invalid="ignore"):
        yc = y + (pz - z) * (y2 - y) / (z2 - z)
    return np.count_nonzero(cond & (py < yc), axis=1) % 2 == 1


def orient_contours(contours, where: str = "contours") -> list[np.ndarray]:
    """Rings oriented for the solver: outer rings counter-clockwise, holes clockwise.

    A ring is a hole when it lies inside an odd number of the other rings.
    """
    rings = [clean_ring(c, f"{where}[{i}]") for i, c in enumerate(contours)]
    if not rings:
        raise InputError("a section needs at least one contour", key=where, value=0,
                         expected=">= 1 ring")
    out = []
    for i, r in enumerate(rings):
        depth = 0
        if len(rings) > 1:
            probe = r[0]
            for j, other in enumerate(rings):
                if j != i and point_in_ring(probe, other):
                    depth += 1
        a = signed_area(r)
        if a == 0.0:
            raise InputError("contour has zero area", key=f"{where}[{i}]")
        want_ccw = depth % 2 == 0
        out.append(r if (a > 0) == want_ccw else r[::-1].copy())
    return out


def section_centroid(contours) -> tuple[float, float]:
    r"""Area centroid (y_c, z_c) of a section made of rings (holes subtracted) [m].

    .. math:: y_c = \frac{1}{6A}\sum (y_i + y_{i+1})(y_i z_{i+1} - y_{i+1} z_i)

    (with the orientation normalised: outer rings add area, holes subtract it).
    An empty section gives (0, 0). ``contours``: rings of (y, z) points [m].

    References
    ----------
    Shoelace formula for the first moments of a polygon (Green's theorem), as
    :func:`signed_area`.
    """
    if contours is None or len(contours) == 0:
        return (0.0, 0.0)
    return ring_centroid(orient_contours(contours))


def ring_centroid(rings) -> tuple[float, float]:
    """:func:`section_centroid` of rings already oriented (:func:`orient_contours`)."""
    a = sy = sz = 0.0
    for r in rings:
        y, z = r[:, 0], r[:, 1]
        y1, z1 = np.roll(y, -1), np.roll(z, -1)
        c = y * z1 - y1 * z
        a += 0.5 * c.sum()
        sy += ((y + y1) * c).sum() / 6.0
        sz += ((z + z1) * c).sum() / 6.0
    return (sy / a, sz / a)


def ring_shape(r: np.ndarray):
    """Edge lengths (edge i: vertex i -> i+1, closing edge last) and turning angle at each
    vertex [rad] of a ring, computed once for the panel placement."""
    e_out = np.concatenate((r[1:], r[:1])) - r
    e_in = np.concatenate((e_out[-1:], e_out[:-1]))
    seg = np.sqrt(e_out[:, 0] ** 2 + e_out[:, 1] ** 2)
    turn = np.arctan2(e_in[:, 0] * e_out[:, 1] - e_in[:, 1] * e_out[:, 0],
                      e_in[:, 0] * e_out[:, 0] + e_in[:, 1] * e_out[:, 1])
    return seg, np.abs(turn)


def corner_flags(r: np.ndarray) -> np.ndarray:
    """Sharp corners of a ring: turning angle above :data:`CORNER_ANGLE`."""
    return ring_shape(r)[1] > CORNER_ANGLE
