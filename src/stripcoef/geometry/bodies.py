r"""Bodies that make up a vehicle: the hull, appendages and through-holes.

Each body turns the strip stations ``x`` (centres) into :class:`~stripcoef.strips.Part`
sections (or :class:`~stripcoef.strips.HoleCut` for holes and duct interiors).
Section properties, outlines and chords of the shapes: :mod:`stripcoef.geometry.shapes`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stripcoef.strips import HoleCut, Part
from stripcoef.geometry.profiles import Profile
from stripcoef.geometry.shapes import (ellipse_section, rectangle_section, section_half_chord,
                                       shape_geometry)


def _inside(x, lo, hi):
    return np.nonzero((x >= lo) & (x <= hi))[0]


def _overlap(x, dx, lo, hi):
    """Strips overlapping [lo, hi]: indices, covered fraction of each, and the x at which to
    evaluate the section (the centre of the covered part of the strip)."""
    a = np.maximum(x - 0.5 * dx, lo)
    b = np.minimum(x + 0.5 * dx, hi)
    idx = np.nonzero(b > a + 1e-15 * np.maximum(dx, 1.0))[0]
    return idx, (b[idx] - a[idx]) / dx[idx], 0.5 * (a[idx] + b[idx])


def mean_chord(x, dx, center, radius):
    r"""Mean over each strip of the chord :math:`c(\xi) = 2\sqrt{r^2 - \xi^2}` of a circle.

    .. math:: \bar c = \frac{F(\xi_2) - F(\xi_1)}{dx},\quad
              F(\xi) = \xi\sqrt{r^2-\xi^2} + r^2 \arcsin(\xi / r)

    (exact strip integral, so hole volumes converge at any strip count) [m].
    ``x``, ``dx``, ``center``, ``radius`` [m]. Reference: elementary integral
    :math:`\int\sqrt{r^2-\xi^2}\,d\xi` (area of a circular segment).
    """
    xi1 = np.clip(x - 0.5 * dx - center, -radius, radius)
    xi2 = np.clip(x + 0.5 * dx - center, -radius, radius)

    def f(t):
        return t * np.sqrt(np.maximum(radius**2 - t**2, 0.0)) + radius**2 * np.arcsin(t / radius)

    return (f(xi2) - f(xi1)) / dx


@dataclass
class Hull:
    """The main hull: half-breadth and half-height profiles, elliptic or rectangular section."""

    name: str
    half_breadth: Profile
    half_height: Profile
    section: str = "ellipse"
    y: float = 0.0
    z: float = 0.0

    def x_extent(self):
        return (min(self.half_breadth.x_aft, self.half_height.x_aft),
                max(self.half_breadth.x_fwd, self.half_height.x_fwd))

    def parts(self, x, dx):
        b = self.half_breadth(x)
        h = self.half_height(x)
        idx = np.nonzero((b > 0) & (h > 0))[0]
        b, h = b[idx], h[idx]
        spec = shape_geometry(self.section)
        area, iyy, izz = spec.properties(b, h)
        lo, hi = self.x_extent()
        return [Part(name=self.name, shape=self.section, index=idx, y=self.y, z=self.z,
                     half_breadth=b, half_height=h, area=area, iyy=iyy, izz=izz,
                     rounded=spec.rounded, length=hi - lo, role="hull")]

    def max_diameter(self) -> float:
        xs = np.linspace(*self.x_extent(), 2001)
        return float(2.0 * np.max(np.sqrt(self.half_breadth(xs) * self.half_height(xs))))


@dataclass
class Cylinder:
    """A solid or hollow (duct) cylinder along x, y or z.

    ``inner_diameter > 0`` makes a duct: its wall displaces water, its interior is
    water carried in cross-flow and free in flow along the axis (a :class:`HoleCut`).
    """

    name: str
    axis: str
    center: np.ndarray
    diameter: float
    length: float
    inner_diameter: float = 0.0
    role: str = "appendage"

    def x_extent(self):
        half = 0.5 * self.length if self.axis == "x" else 0.5 * self.diameter
        return (self.center[0] - half, self.center[0] + half)

    def parts(self, x, dx):
        lo, hi = self.x_extent()
        idx, cov, xs = _overlap(x, dx, lo, hi)
        if idx.size == 0:
            return []
        ro, ri = 0.5 * self.diameter, 0.5 * self.inner_diameter
        if self.axis == "x":
            b = h = np.full(idx.size, ro)
            area, iyy, izz = ellipse_section(b, h)
            a_in, iyy_in, izz_in = ellipse_section(np.full(idx.size, ri), np.full(idx.size, ri))
            return [Part(name=self.name, shape="ellipse", index=idx, y=self.center[1],
                         z=self.center[2], half_breadth=b, half_height=h, area=area - a_in,
                         iyy=iyy - iyy_in, izz=izz - izz_in, rounded=True, length=self.length,
                         role=self.role, coverage=cov)]
        # Axis y or z: each strip cuts a rectangle whose x-width is the mean chord.
        c_out = mean_chord(x[idx], dx[idx], self.center[0], ro)
        c_in = mean_chord(x[idx], dx[idx], self.center[0], ri) if ri > 0 else np.zeros(idx.size)
        keep = c_out > 0
        idx, c_out, c_in = idx[keep], c_out[keep], c_in[keep]
        half_len = np.full(idx.size, 0.5 * self.length)
        if self.axis == "y":
            b, h = half_len, 0.5 * c_out      # long along y, thin along z
        else:
            b, h = 0.5 * c_out, half_len
        area, iyy, izz = rectangle_section(b, h)
        # a hollow cylinder across x: remove the interior (its water is a HoleCut)
        if ri > 0:
            bi, hi_ = (half_len, 0.5 * c_in) if self.axis == "y" else (0.5 * c_in, half_len)
            a_in, iyy_in, izz_in = rectangle_section(bi, hi_)
            area, iyy, izz = area - a_in, iyy - iyy_in, izz - izz_in
        return [Part(name=self.name, shape="rectangle", index=idx, y=self.center[1],
                     z=self.center[2], half_breadth=b, half_height=h, area=area, iyy=iyy,
                     izz=izz, rounded=True, length=self.diameter, role=self.role)]
        # (the mean chord already carries the partial coverage of the end strips)

    def holes(self, x, dx):
        """The duct interior as a hole along the cylinder's axis."""
        if self.inner_diameter <= 0:
            return []
        ri = 0.5 * self.inner_diameter
        if self.axis == "x":
            lo, hi = self.center[0] - 0.5 * self.length, self.center[0] + 0.5 * self.length
            idx, cov, _ = _overlap(x, dx, lo, hi)
            # per unit x-length the interior is a disc: model as chord = area / depth
            area = np.pi * ri**2
            return [HoleCut(name=self.name + ":interior", axis="x", index=idx,
                            chord=cov * area / (2 * ri),
                            depth=np.full(idx.size, 2 * ri),
                            y=np.full(idx.size, self.center[1]),
                            z=np.full(idx.size, self.center[2]), in_hull=False)]
        idx, _, _ = _overlap(x, dx, self.center[0] - ri, self.center[0] + ri)
        chord = mean_chord(x[idx], dx[idx], self.center[0], ri)
        keep = chord > 0
        idx, chord = idx[keep], chord[keep]
        return [HoleCut(name=self.name + ":interior", axis=self.axis, index=idx, chord=chord,
                        depth=np.full(idx.size, self.length), y=np.full(idx.size, self.center[1]),
                        z=np.full(idx.size, self.center[2]), in_hull=False)]


@dataclass
class Box:
    """An axis-aligned box (skid, battery pod, frame member)."""

    name: str
    center: np.ndarray
    size: np.ndarray  # [lx, ly, lz]
    role: str = "appendage"

    def x_extent(self):
        return (self.center[0] - 0.5 * self.size[0], self.center[0] + 0.5 * self.size[0])

    def parts(self, x, dx):
        idx, cov, _ = _overlap(x, dx, *self.x_extent())
        if idx.size == 0:
            return []
        b = np.full(idx.size, 0.5 * self.size[1])
        h = np.full(idx.size, 0.5 * self.size[2])
        area, iyy, izz = rectangle_section(b, h)
        return [Part(name=self.name, shape="rectangle", index=idx, y=self.center[1],
                     z=self.center[2], half_breadth=b, half_height=h, area=area, iyy=iyy,
                     izz=izz, rounded=False, length=float(self.size[0]), role=self.role,
                     coverage=cov)]


@dataclass
class Fin:
    """A thin fin (flat plate) of given span along y or z, chord along x, and thickness."""

    name: str
    center: np.ndarray
    span_axis: str
    span: float
    chord: float
    thickness: float

    def x_extent(self):
        return (self.center[0] - 0.5 * self.chord, self.center[0] + 0.5 * self.chord)

    def parts(self, x, dx):
        idx, cov, _ = _overlap(x, dx, *self.x_extent())
        if idx.size == 0:
            return []
        if self.span_axis == "y":
            b, h = 0.5 * self.span, 0.5 * self.thickness
        else:
            b, h = 0.5 * self.thickness, 0.5 * self.span
        b = np.full(idx.size, b)
        h = np.full(idx.size, h)
        area, iyy, izz = rectangle_section(b, h)
        return [Part(name=self.name, shape="rectangle", index=idx, y=self.center[1],
                     z=self.center[2], half_breadth=b, half_height=h, area=area, iyy=iyy,
                     izz=izz, rounded=False, length=self.chord, role="fin", coverage=cov)]


@dataclass
class Hole:
    """A through-hole in the hull: a cylinder of diameter d along y or z at (x, y or z).

    Motion along the axis passes freely (no added mass, no drag area); motion across it
    carries the water inside (Ferreira et al. 2009, sec. IV.C).
    """

    name: str
    axis: str
    x: float
    offset: float  # y of a z-hole, z of a y-hole [m]
    diameter: float

    def x_extent(self):
        r = 0.5 * self.diameter
        return (self.x - r, self.x + r)

    def cut(self, x, dx, hull: Hull) -> HoleCut:
        r = 0.5 * self.diameter
        idx, _, _ = _overlap(x, dx, self.x - r, self.x + r)
        chord = mean_chord(x[idx], dx[idx], self.x, r)
        keep = chord > 0
        idx, chord = idx[keep], chord[keep]
        xs = x[idx]
        b, h = hull.half_breadth(xs), hull.half_height(xs)
        if self.axis == "z":  # through the height: depth = hull height at the hole's y
            depth = 2.0 * section_half_chord(hull.section, b, h, self.offset)
            y, z = np.full(idx.size, self.offset), np.full(idx.size, hull.z)
        else:
            depth = 2.0 * section_half_chord(hull.section, h, b, self.offset)
            y, z = np.full(idx.size, hull.y), np.full(idx.size, self.offset)
        return HoleCut(name=self.name, axis=self.axis, index=idx, chord=chord, depth=depth,
                       y=y, z=z)
