"""Strips: the body cut into slices along x, each with the 2D parts of its section.

A :class:`Strips` object is the hand-off between geometry (vehicle file or
mesh) and the section coefficients.  Each strip ``i`` has a centre ``x[i]`` and
a width ``dx[i]``; its section is the set of :class:`Part` entries that cover
strip ``i`` (the hull, appendages, fins, or the polygons of a mesh slice), and
the :class:`HoleCut` entries that cross it.

Coordinates are FRD body axes [m].
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from stripcoef.errors import InputError


@dataclass
class Part:
    """One 2D part of the sections of a run of strips (vectorised over those strips).

    Attributes
    ----------
    name : str
        Hull, appendage or polygon name.
    shape : str
        ``ellipse`` (a circle when both half-axes are equal), ``rectangle`` or
        ``polygon`` (arbitrary contours, from a mesh; see ``contours``): a name of the
        section-shape registry :data:`stripcoef.sections.SHAPES`.
    index : (k,) int array
        Strip indices the part covers.
    y, z : (k,) arrays
        Centre of the part's section [m]
    half_breadth, half_height : (k,) arrays
        Half-extent along y and along z [m]
    area : (k,) array
        Section area [m^2] (solid material / displaced water; 0 for a hollow duct wall's
        entrained water, see ``entrained_area``)
    entrained_area : (k,) array
        Water inside the part that moves with it in cross-flow (duct interior) [m^2]
    iyy, izz : (k,) arrays
        Second moments of the section area about its centre,
        ``iyy = int (y - y_c)^2 dA`` and ``izz = int (z - z_c)^2 dA`` [m^4]
        (rigid-body inertia from density zones)
    rounded : bool
        Rounded edges (Re-dependent drag) or sharp edges (Re-independent drag)
    length : float
        Length of the part along x [m] (finite-length drag correction)
    role : str
        ``hull``, ``appendage`` or ``fin``
    coverage : (k,) array
        Fraction of each strip's width that the part covers (1 inside, < 1 at the part's
        ends); every integral uses ``coverage * dx`` so parts ending mid-strip are exact.
    contours : list, optional
        For ``polygon`` parts: per strip, a list of (n, 2) arrays of (y, z) rings
        (outer rings counter-clockwise, holes clockwise).
    """

    name: str
    shape: str
    index: np.ndarray
    y: np.ndarray
    z: np.ndarray
    half_breadth: np.ndarray
    half_height: np.ndarray
    area: np.ndarray
    entrained_area: np.ndarray | None = None
    iyy: np.ndarray | None = None
    izz: np.ndarray | None = None
    rounded: bool = True
    length: float = 0.0
    role: str = "appendage"
    contours: list | None = None
    coverage: np.ndarray | None = None

    def __post_init__(self):
        self.index = np.asarray(self.index, dtype=int)
        k = self.index.size
        for attr in ("y", "z", "half_breadth", "half_height", "area"):
            val = np.broadcast_to(np.asarray(getattr(self, attr), dtype=float), (k,)).copy()
            setattr(self, attr, val)
        if self.coverage is None:
            self.coverage = np.ones(k)
        for attr in ("entrained_area", "iyy", "izz", "coverage"):
            val = getattr(self, attr)
            val = np.zeros(k) if val is None else np.broadcast_to(
                np.asarray(val, dtype=float), (k,)).copy()
            setattr(self, attr, val)


@dataclass
class HoleCut:
    """A through-hole crossing some strips.

    Attributes
    ----------
    name : str
    axis : str
        ``y`` or ``z``: the hole's axis.  Motion along the axis passes freely;
        motion across it carries the water inside.
    index : (k,) int array
        Strip indices crossed.
    chord : (k,) array
        Width of the hole in the strip's section, across the axis [m]
    depth : (k,) array
        Length of the hole through the hull, along the axis [m]
    y, z : (k,) arrays
        Centre of the hole's water in the section [m]; ``chord`` is the mean over the strip
        (exact strip integral), so ``chord * depth * dx`` is the strip's water volume
    in_hull : bool
        True for a hole cut through a part (its water is removed from that part's
        displaced volume); False for a duct interior (never counted as displaced).
    """

    name: str
    axis: str
    index: np.ndarray
    chord: np.ndarray
    depth: np.ndarray
    y: np.ndarray
    z: np.ndarray
    in_hull: bool = True


@dataclass
class Strips:
    """The body cut into ``n`` strips along x.

    Attributes
    ----------
    x : (n,) array
        Strip centres [m]
    dx : (n,) array
        Strip widths [m]
    parts : list of Part
    holes : list of HoleCut
    length : float
        Body length used for hull-level formulas [m]
    """

    x: np.ndarray
    dx: np.ndarray
    parts: list[Part] = field(default_factory=list)
    holes: list[HoleCut] = field(default_factory=list)

    @property
    def n(self) -> int:
        return int(self.x.size)

    @property
    def x_min(self) -> float:
        return float(self.x[0] - 0.5 * self.dx[0])

    @property
    def x_max(self) -> float:
        return float(self.x[-1] + 0.5 * self.dx[-1])

    @property
    def length(self) -> float:
        return self.x_max - self.x_min

    def width(self, part: Part) -> np.ndarray:
        """Effective widths ``coverage * dx`` of the strips a part covers [m]."""
        return part.coverage * self.dx[part.index]

    def hull_parts(self) -> list[Part]:
        return [p for p in self.parts if p.role == "hull"]

    def strip(self, i: int) -> dict:
        """Everything known about strip ``i``: x, dx, the parts and holes crossing it."""
        parts = []
        for p in self.parts:
            k = np.nonzero(p.index == i)[0]
            if k.size:
                k = int(k[0])
                parts.append({"name": p.name, "shape": p.shape, "role": p.role,
                              "y": float(p.y[k]), "z": float(p.z[k]),
                              "half_breadth": float(p.half_breadth[k]),
                              "half_height": float(p.half_height[k]),
                              "area": float(p.area[k])})
        holes = []
        for h in self.holes:
            k = np.nonzero(h.index == i)[0]
            if k.size:
                k = int(k[0])
                holes.append({"name": h.name, "axis": h.axis, "chord": float(h.chord[k]),
                              "depth": float(h.depth[k])})
        return {"index": i, "x": float(self.x[i]), "dx": float(self.dx[i]),
                "parts": parts, "holes": holes}


#: Most strips a body is cut into: the default 1000 converge to 0.1 % (docs/vehicle-file.md);
#: 100,000 take seconds and tens of MB, 3e7 would exhaust the memory (docs/performance.md).
MAX_STRIPS = 100_000


def uniform_stations(x_min: float, x_max: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Centres and widths of ``n`` equal strips covering [x_min, x_max] [m]."""
    if n > MAX_STRIPS:
        raise InputError("too many strips", key="strips", value=n,
                         expected=f"at most {MAX_STRIPS} (memory; 1000 converge to 0.1 %)")
    if not (np.isfinite(x_min) and np.isfinite(x_max) and x_max > x_min):
        raise InputError("no length to cut into strips", key="strips",
                         value=[float(x_min), float(x_max)],
                         expected="a body of finite, positive length [m]")
    edges = np.linspace(x_min, x_max, n + 1)
    return 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)


def hole_water(strips: Strips):
    """Per hole-cut: water volume per strip [m^3] (only holes cut through displaced parts).

    dV = c d dx, chord c [m], depth d [m], strip width dx [m]; [assumption] prismatic
    hole per strip (Ferreira et al. 2009, sec. IV.C approximates holes by cylinders).
    """
    return [(h, h.chord * h.depth * strips.dx[h.index]) for h in strips.holes]


def _strip_operator(xrel):
    """L(X) for an array of X: (n, 3, 6).

    [v + X r, w - X q, p] = L(X) nu, X = x - x_0 [m]; L is [-] in its 1 entries and [m]
    in the X entries. See module docstring (Newman 1977, sec. 7.4).
    """
    n = xrel.size
    L = np.zeros((n, 3, 6))
    L[:, 0, 1] = 1.0
    L[:, 0, 5] = xrel
    L[:, 1, 2] = 1.0
    L[:, 1, 4] = -xrel
    L[:, 2, 3] = 1.0
    return L


def hole_widths(strips: Strips, part):
    """Per strip of a hull part: open width of holes along z (c_z) and along y (c_y) [m].

    c_z = sum of the chords [m] of the in-hull holes with axis z in the strip (same for y).
    [assumption] widths add (holes do not overlap); used by Ferreira et al. 2009, eq. 40 style
    reductions in :func:`section_matrices` and :func:`~stripcoef.assembly.damping.damping_matrices`.
    """
    cz = np.zeros(part.index.size)
    cy = np.zeros(part.index.size)
    if part.role != "hull":
        return cy, cz
    pos = {int(i): k for k, i in enumerate(part.index)}
    for h in strips.holes:
        if not h.in_hull:
            continue
        for i, c in zip(h.index, h.chord):
            k = pos.get(int(i))
            if k is None:
                continue
            if h.axis == "z":
                cz[k] += c
            elif h.axis == "y":
                cy[k] += c
    return cy, cz


def shift_section_matrices(m, dy, dz) -> np.ndarray:
    r"""2D section matrices (sway, heave, roll) moved to a reference point offset by
    (dy, dz) [m] from their own:

    .. math:: m' = H_2^T m H_2,\qquad
              H_2 = \begin{bmatrix}1&0&-\Delta z\\0&1&\Delta y\\0&0&1\end{bmatrix}

    (a rigid roll p about the new point moves the section's own point by
    :math:`(-\Delta z\,p, \Delta y\,p)`; Fossen 2011, sec. 7.5.3, in 2D).  ``m`` (..., 3, 3)
    [kg/m, kg, kg m], ``dy``, ``dz`` broadcasting over its leading axes; returns the same
    shape.
    """
    dy, dz = np.broadcast_arrays(np.asarray(dy, dtype=float), np.asarray(dz, dtype=float))
    h2 = np.zeros(dy.shape + (3, 3))
    h2[..., 0, 0] = h2[..., 1, 1] = h2[..., 2, 2] = 1.0
    h2[..., 0, 2] = -dz
    h2[..., 1, 2] = dy
    return np.einsum("...ji,...jl,...lm->...im", h2, m, h2)


def strip_added_mass(strips: Strips, mats, about) -> np.ndarray:
    r"""Pure strip-theory 6x6 added mass about point ``about`` (no 3D corrections) [SI].

    .. math:: M_A^{strip} = \sum_{parts}\sum_k dx_k\, L(X_k)^T H_2^T m_k H_2\, L(X_k),
              \quad H_2 = \begin{bmatrix}1&0&-\Delta z\\0&1&\Delta y\\0&0&1\end{bmatrix}

    ``mats`` are the parts' 2D section matrices, one (k, 3, 3) array per part, about the
    part's centre [kg/m, kg, kg m] (:func:`stripcoef.sections.strip_section_matrices`);
    ``about`` [m]; strip widths dx [m]. Returns M_A [kg, kg m, kg m^2].

    References
    ----------
    See module docstring (Newman 1977, sec. 7.4; Fossen 2011, sec. 6.3.3).
    """
    x0, y0, z0 = about
    total = np.zeros((6, 6))
    for p, m in zip(strips.parts, mats):
        m = shift_section_matrices(m, p.y - y0, p.z - z0)
        L = _strip_operator(strips.x[p.index] - x0)
        total += np.einsum("k,kji,kjl,klm->im", strips.width(p), L, m, L)
    return total
