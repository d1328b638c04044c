r"""Added mass of flat fins on a hull of revolution: a 3D thin-sheet panel method.

A hull of revolution rolling moves no water; its fins do.  Each fin moves normal to itself
with the speed :math:`p\,r` at radius r (in sway, heave, pitch and yaw too, through the hull's
own cross-flow), and in 3D the water escapes round its leading and trailing edges and its tip,
which no 2D section sees (strip theory's roll is the 2D cruciform's,
:func:`stripcoef.sections.added_mass.finned_circle_roll`, per unit length).  This module solves
the 3D potential flow of the fins as thin sheets on the hull:

- **Unknowns.** Constant-strength doublet panels, i.e. vortex rings of circulation
  :math:`\mu_k` (Katz & Plotkin 2001, sec. 12.3 and 12.5), on the fins (open sheets: the jump of
  the potential across the fin) and on the hull surface (a closed sheet: it keeps the water
  out of the hull).  A ring's velocity is the Biot-Savart law of its four straight segments
  (Katz & Plotkin 2001, eq. 10.115), its potential its solid angle over :math:`4\pi`
  (:func:`quad_solid_angle`).
- **Boundary condition** at one collocation point per panel, normal n, for each rigid-body
  mode j (:math:`n_j` = n for translation, :math:`\mathbf{r}\times\mathbf{n}` for rotation):

  .. math:: \sum_k \mu_k\,\mathbf{v}_k(\mathbf{x}_i)\cdot\mathbf{n}_i = n_{j,i},

  roll's :math:`n_4 = y\,n_z - z\,n_y` being 0 on the hull of revolution.  A constant
  :math:`\mu` on the closed hull induces no velocity; the system is bordered with
  :math:`\sum_{hull}\mu = 0` to fix it.
- **Added mass** (Newman 1977, sec. 4.13, n out of the body):
  :math:`m_{ij} = -\rho\oint_{hull}\phi_i n_j\,dS + \rho\sum_{fins}\mu_i n_j A`
  (:func:`sheet_added_mass`); in roll the hull term vanishes,
  :math:`K_{\dot p} = -m_{44} = -\rho\sum_{fins}\mu\,n_4\,A` [kg m^2].  The fins' share is the
  hull with its fins minus the hull alone on the same panels (:func:`fins_added_mass`).
- **Edges.**  A plate's potential jump vanishes like the square root of the distance to a
  free edge.  Panel edges in cosine spacing with the collocation point at the middle of each
  panel *in the angle variable* (:math:`\xi_k = -\cos(\pi k/N)`, :math:`\xi_c = -\cos(\pi (k +
  1/2)/N)`) make the 2D plate's added mass exact for every N (tests/test_finsheet.py); the
  chord uses it between leading and trailing edge, the span from the root (a wall, mirrored)
  to the tip as its half (:math:`\eta = \sin(\pi k / 2N)`).  Check: the exact disc rotating
  about a diameter, :math:`16\rho a^5/45` (the ellipsoid of Lamb 1932, sec. 373, with one
  semi-axis -> 0: :func:`stripcoef.hull.lamb.ellipsoid_added_mass`; tests).
- **Cross-plane error.**  The hull polygon and the span panels alone make the section's roll
  2-7 % low for short fins and their share of sway up to 4 % high; the same discretisation in
  2D (:func:`section_discrete`) has the same error, and each 3D term is multiplied by exact
  over discrete 2D sections along the fins' chords (:func:`_cross_plane_factors`).

**Thickness.**  A fin of thickness t moves more water than a sheet: its section across the
chord is a c x t rectangle, whose added mass moving normal to its long side is
:math:`C_A(c/t)\,\rho\pi(c/2)^2` (DNV-RP-C205 table A-1; :func:`stripcoef.sections.added_mass.
rectangle_coefficient`), and its section across the span is the thick-finned circle.  The sheet
takes the *equivalent planform* that reproduces both 2D sections exactly: the chord
:math:`c_e = c\sqrt{C_A(c/t)}` about the mid-chord, and the tip radius :math:`a_e` whose thin
cruciform (or pair) section has the thick section's roll added mass (2D panel method,
:func:`stripcoef.sections.panel.added_mass_contours`).  [assumption] both 2D equivalences are
exact in their limits (a long chord, a long span) and the combination is not; against the
converged BEM of six box-finned hulls the roll is +1.3 to +2.9 %.  The other modes take the same
planform (:func:`fins_added_mass`; docs/theory.md, "Fins in 3D").
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

#: Panels along the chord and along the span of each fin, round each quarter of the hull, and
#: along the hull outside the fins (aft of them, ahead of them) [-]: the roll added mass of the
#: six benchmark fins is within 0.6 % of a mesh of twice the panels (docs/performance.md)
CHORD_PANELS = 8
SPAN_PANELS = 6
QUARTER_PANELS = 8
AFT_PANELS = 12
FORE_PANELS = 24
#: Rows of the influence matrix built at a time (memory: rows x panels x 3 doubles) [-]
_ROW_BLOCK = 256


@dataclass(frozen=True)
class FinPlanform:
    """A flat rectangular fin on a hull of revolution, radial at the roll angle ``angle``.

    ``angle`` [rad] from +y towards +z (0 starboard, pi/2 down in FRD axes); chord from
    ``x_aft`` to ``x_fore`` [m]; tip at radius ``tip`` [m] from the hull axis; root on the hull
    surface."""

    angle: float
    x_aft: float
    x_fore: float
    tip: float


def ring_velocity(points, nodes, quads, normals=None) -> np.ndarray:
    r"""Velocity [m/s] at ``points`` (P, 3) induced by unit vortex rings ``quads`` (Q, 4 node
    indices into ``nodes`` (N, 3)) [m]; returns (P, Q, 3), or with ``normals`` (P, 3) the
    component along each point's normal (P, Q).

    Each straight segment A -> B of circulation 1 gives (Katz & Plotkin 2001, eq. 10.115)

    .. math:: \mathbf{v} = \frac{1}{4\pi}\,\frac{\mathbf{r}_1\times\mathbf{r}_2}
              {|\mathbf{r}_1\times\mathbf{r}_2|^2}\;\mathbf{r}_0\cdot
              \left(\frac{\mathbf{r}_1}{r_1} - \frac{\mathbf{r}_2}{r_2}\right)

    with :math:`\mathbf{r}_1 = P - A`, :math:`\mathbf{r}_2 = P - B`,
    :math:`\mathbf{r}_0 = B - A`; a point on a segment's line (or a zero-length segment, a
    closed end's collapsed edge) gets nothing from it.  B -> A gives exactly minus A -> B, so
    each edge the rings share is evaluated once (a sheet's inner edges belong to two rings).
    """
    points = np.asarray(points, dtype=float)
    quads = np.asarray(quads)
    px, py, pz = points.T
    start = quads
    end = np.roll(quads, -1, axis=1)
    forward = start < end
    pairs = np.stack([np.where(forward, start, end), np.where(forward, end, start)], axis=-1)
    edges, which = np.unique(pairs.reshape(-1, 2), axis=0, return_inverse=True)
    which = which.reshape(quads.shape)
    a, b = nodes[edges[:, 0]], nodes[edges[:, 1]]
    ax, ay, az = (a[:, i, None] for i in range(3))
    bx, by, bz = (b[:, i, None] for i in range(3))
    # the points' offsets from each node and distances to it, (N', P) for the N' nodes the
    # edges use, gathered per edge end (the same values as computed per edge)
    used, end = np.unique(edges, return_inverse=True)
    end = end.reshape(edges.shape)
    dx, dy, dz = (p - nodes[used, i, None] for i, p in enumerate((px, py, pz)))
    dist = np.sqrt(dx * dx + dy * dy + dz * dz)
    with np.errstate(divide="ignore", invalid="ignore"):
        # by components: (E, P) arrays (an edge's row is gathered whole for its rings), no
        # (E, P, 3) ones
        r1x, r1y, r1z = dx[end[:, 0]], dy[end[:, 0]], dz[end[:, 0]]          # P - A
        r2x, r2y, r2z = dx[end[:, 1]], dy[end[:, 1]], dz[end[:, 1]]          # P - B
        r0x, r0y, r0z = bx - ax, by - ay, bz - az
        cx = r1y * r2z - r1z * r2y
        cy = r1z * r2x - r1x * r2z
        cz = r1x * r2y - r1y * r2x
        c2 = cx * cx + cy * cy + cz * cz
        n1, n2 = dist[end[:, 0]], dist[end[:, 1]]
        l0 = r0x * r0x + r0y * r0y + r0z * r0z
        ok = (c2 > 1e-12 * l0 * l0) & (n1 > 0) & (n2 > 0) & (l0 > 0)
        f = ((r0x * r1x + r0y * r1y + r0z * r1z) / n1
             - (r0x * r2x + r0y * r2y + r0z * r2z) / n2) / c2
        f = np.where(ok, f, 0.0)
    sign = np.where(forward, 1.0, -1.0)[:, :, None]
    if normals is not None:
        nx, ny, nz = np.asarray(normals, dtype=float).T
        g = (cx * nx + cy * ny + cz * nz) * f
        out = 0.0
        for k in range(4):
            out = out + sign[:, k] * g[which[:, k]]
        return out.T / (4.0 * np.pi)
    vx, vy, vz = cx * f, cy * f, cz * f
    ox = oy = oz = 0.0
    for k in range(4):
        rows, sk = which[:, k], sign[:, k]
        ox = ox + sk * vx[rows]
        oy = oy + sk * vy[rows]
        oz = oz + sk * vz[rows]
    out = np.stack(np.broadcast_arrays(ox.T, oy.T, oz.T), axis=-1)
    return out / (4.0 * np.pi)


def _cosine(a, b, n):
    """The n + 1 panel edges from a to b in full cosine (both ends free edges) and the n
    collocation points at the panels' middle angles (module docstring, "Edges")."""
    k = np.arange(n + 1)
    edges = a + (b - a) * 0.5 * (1.0 - np.cos(np.pi * k / n))
    return edges, a + (b - a) * 0.5 * (1.0 - np.cos(np.pi * (k[:-1] + 0.5) / n))


def _half_cosine(n):
    """Fractions of the span from root (a wall) to tip (a free edge) in half cosine: the n + 1
    panel edges and the n collocation points at the middle angles."""
    k = np.arange(n + 1)
    return np.sin(0.5 * np.pi * k / n), np.sin(0.5 * np.pi * (k[:-1] + 0.5) / n)


def _quarter_angles(quarter: int) -> np.ndarray:
    """Angles [rad] of the hull's panel edges round the axis: each quarter between fin roots
    (0, pi/2, pi, 3 pi/2) in full cosine, so that the hull panels beside a root are as fine as
    the fin's root panels."""
    k = np.arange(quarter)
    return np.concatenate([0.5 * np.pi * (q + 0.5 * (1.0 - np.cos(np.pi * k / quarter)))
                           for q in range(4)])


@dataclass
class SheetMesh:
    """Vortex-ring panels of a hull of revolution and its fins: ``nodes`` (N, 3) [m], ``quads``
    (Q, 4), ``fin`` (Q,) bool, collocation points ``points`` (Q, 3) [m], unit ``normals`` (Q, 3),
    ``areas`` (Q,) [m^2]."""

    nodes: np.ndarray
    quads: np.ndarray
    fin: np.ndarray
    points: np.ndarray
    normals: np.ndarray
    areas: np.ndarray


def sheet_mesh(hull_radius, x_aft: float, x_fore: float, fins, *, chord=CHORD_PANELS,
               span=SPAN_PANELS, quarter=QUARTER_PANELS, aft=AFT_PANELS,
               fore=FORE_PANELS) -> SheetMesh:
    """Panels of the hull of revolution r = ``hull_radius(x)`` (a callable, [m]) from ``x_aft``
    to ``x_fore`` [m] (ends closed by discs where the radius is not 0) and of the
    :class:`FinPlanform` ``fins``, their roots on hull panel edges (module docstring)."""
    fins = list(fins)
    stations = [_cosine(f.x_aft, f.x_fore, chord) for f in fins]
    if fins:
        lo = min(f.x_aft for f in fins)
        hi = max(f.x_fore for f in fins)
        xs = np.concatenate([_cosine(x_aft, lo, aft)[0], _cosine(hi, x_fore, fore)[0],
                             *(e for e, _ in stations)])
    else:                                   # the hull alone
        xs = _cosine(x_aft, x_fore, aft + fore)[0]
    xs = np.unique(np.round(xs, 12))
    xs = xs[(xs >= x_aft) & (xs <= x_fore)]
    rs = np.maximum(np.asarray(hull_radius(xs), dtype=float), 0.0)
    nth = 4 * quarter
    th = _quarter_angles(quarter)
    nodes: list = []
    ring = np.empty((len(xs), nth), dtype=int)
    for i, (x, r) in enumerate(zip(xs, rs)):
        if r <= 0.0:
            ring[i] = len(nodes)
            nodes.append([x, 0.0, 0.0])
            continue
        ring[i] = len(nodes) + np.arange(nth)
        nodes.extend([x, r * np.cos(t), r * np.sin(t)] for t in th)
    quads = [[ring[i, j], ring[i, (j + 1) % nth], ring[i + 1, (j + 1) % nth], ring[i + 1, j]]
             for i in range(len(xs) - 1) for j in range(nth)]
    for end, step in ((0, 1), (len(xs) - 1, -1)):           # flat end discs, a fan of triangles
        if rs[end] > 0.0:
            c = len(nodes)
            nodes.append([xs[end], 0.0, 0.0])
            for j in range(nth):
                a, b = ring[end, j], ring[end, (j + 1) % nth]
                quads.append([c, c, b, a] if step == 1 else [c, c, a, b])
    hull_quads = len(quads)
    eta, eta_c = _half_cosine(span)
    points = []
    for f, (xf, xc) in zip(fins, stations):
        j0 = (int(round(f.angle / (0.5 * np.pi))) % 4) * quarter
        e = np.array([np.cos(th[j0]), np.sin(th[j0])])
        rows = [int(np.argmin(np.abs(xs - x))) for x in xf]
        grid = np.empty((chord + 1, span + 1), dtype=int)
        for k, (x, i) in enumerate(zip(xf, rows)):
            grid[k, 0] = ring[i, j0]
            r0 = rs[i]
            for j in range(1, span + 1):
                r = r0 + (f.tip - r0) * eta[j]
                grid[k, j] = len(nodes)
                nodes.append([x, r * e[0], r * e[1]])
        rc = np.maximum(np.asarray(hull_radius(xc), dtype=float), 0.0)
        for k in range(chord):
            for j in range(span):
                quads.append([grid[k, j], grid[k + 1, j], grid[k + 1, j + 1], grid[k, j + 1]])
                r = rc[k] + (f.tip - rc[k]) * eta_c[j]
                points.append([xc[k], r * e[0], r * e[1]])
    nodes = np.asarray(nodes, dtype=float)
    quads = np.asarray(quads, dtype=int)
    p = nodes[quads]
    nv = np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1])
    areas = 0.5 * np.linalg.norm(nv, axis=1)
    normals = nv / np.where(areas > 0, 2.0 * areas, 1.0)[:, None]
    fin = np.zeros(len(quads), dtype=bool)
    fin[hull_quads:] = True
    col = p.mean(axis=1)
    col[hull_quads:] = np.asarray(points, dtype=float).reshape(-1, 3)
    keep = areas > 1e-12 * float(np.max(areas))     # hull panels collapsed onto the axis
    return SheetMesh(nodes, quads[keep], fin[keep], col[keep], normals[keep], areas[keep])


def quad_solid_angle(points, nodes, quads) -> np.ndarray:
    r"""Signed solid angle [sr] of the panels ``quads`` (Q, 4 node indices into ``nodes`` (N, 3))
    seen from ``points`` (P, 3) [m]; returns (P, Q).  Each quad is two triangles (a, b, c) and
    (a, c, d); a triangle's is (Van Oosterom & Strackee 1983, eq. 8)

    .. math:: \tan\frac{\Omega}{2} = \frac{\mathbf{r}_1\cdot(\mathbf{r}_2\times\mathbf{r}_3)}
              {r_1 r_2 r_3 + (\mathbf{r}_1\cdot\mathbf{r}_2) r_3 + (\mathbf{r}_1\cdot\mathbf{r}_3) r_2
               + (\mathbf{r}_2\cdot\mathbf{r}_3) r_1}

    with :math:`\mathbf{r}_k` from the point to the vertices: :math:`-2\pi` just on the side
    the panel's normal points to, :math:`+2\pi` just behind it, 0 in its plane.  A unit
    vortex ring's potential is :math:`\Omega / 4\pi` (the constant doublet panel of Katz &
    Plotkin 2001, sec. 10.4.2; its gradient is :func:`ring_velocity`, tests)."""
    points = np.asarray(points, dtype=float)
    # by components: (P, Q) arrays, no (P, Q, 3) ones
    r = [[nodes[quads[:, k], i] - points[:, i, None] for i in range(3)] for k in range(4)]
    norm = [np.sqrt(x * x + y * y + z * z) for x, y, z in r]     # the shared diagonal's
                                                                    # ends serve both triangles

    def dot(u, v):
        return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]

    def triangle(a, b, c):
        r1, r2, r3 = r[a], r[b], r[c]
        n1, n2, n3 = norm[a], norm[b], norm[c]
        cross = (r2[1] * r3[2] - r2[2] * r3[1], r2[2] * r3[0] - r2[0] * r3[2],
                 r2[0] * r3[1] - r2[1] * r3[0])
        num = dot(r1, cross)
        den = n1 * n2 * n3 + dot(r1, r2) * n3 + dot(r1, r3) * n2 + dot(r2, r3) * n1
        return 2.0 * np.arctan2(num, den)

    return triangle(0, 1, 2) + triangle(0, 2, 3)


def sheet_added_mass(mesh: SheetMesh, rho: float) -> tuple[np.ndarray, np.ndarray]:
    r"""6x6 added mass [kg, kg m, kg m^2] about the origin of the hull and fins of ``mesh``
    (:func:`sheet_mesh`), and of its hull alone on the same hull panels; ``rho`` [kg/m^3].

    Every rigid-body mode j at once (module docstring): the rings' strengths for the right-hand
    sides :math:`n_j` (the normal and :math:`\mathbf{r}\times\mathbf{n}`), then (Newman 1977,
    sec. 4.13, n out of the body)

    .. math:: m_{ij} = -\rho\oint_{hull}\phi_i\,n_j\,dS + \rho\sum_{fins}\mu_i\,n_j\,A,

    the fins' term from the jump of the potential across each sheet
    (:math:`\phi_+ - \phi_- = -\mu`, + on the normal's side), the hull's from the potential
    just outside its panel i, :math:`\phi_i = \sum_{k\ne i}\mu_k\Omega_{ik}/4\pi - \mu_i/2`
    (:func:`quad_solid_angle`; the panels are plane, so their own solid angle at their centroid
    is 0).  The hull alone is the same system without the fins' rows and columns.  Check: a
    6:1 prolate spheroid within 0.1 % in sway and in pitch of Lamb's exact values
    (tests/test_finsheet.py)."""
    n = len(mesh.quads)
    a = np.empty((n, n))
    for i in range(0, n, _ROW_BLOCK):
        j = min(n, i + _ROW_BLOCK)
        a[i:j] = ring_velocity(mesh.points[i:j], mesh.nodes, mesh.quads, mesh.normals[i:j])
    hull = np.flatnonzero(~mesh.fin)
    phi = np.empty((len(hull), n))
    for i in range(0, len(hull), _ROW_BLOCK):
        rows = hull[i:i + _ROW_BLOCK]
        phi[i:i + len(rows)] = quad_solid_angle(mesh.points[rows], mesh.nodes, mesh.quads)
    phi /= 4.0 * np.pi
    phi[np.arange(len(hull)), hull] = -0.5
    modes = np.c_[mesh.normals, np.cross(mesh.points, mesh.normals)]
    weights = mesh.areas[:, None] * modes
    return (_solve_modes(a, phi, hull, np.arange(n), mesh.fin, modes, weights, rho),
            _solve_modes(a, phi, hull, hull, mesh.fin, modes, weights, rho))


def _solve_modes(a, phi, hull, keep, fin, modes, weights, rho) -> np.ndarray:
    r""":func:`sheet_added_mass` on the panels ``keep`` (indices) of the system ``a`` (normal
    velocities), ``phi`` (the hull panels' potentials, rows ``hull``): the rings' strengths of
    the modes (columns of ``modes``; ``weights`` = area x mode), bordered with
    :math:`\sum_{hull}\mu = 0` (a constant doublet on the closed hull induces nothing), and the
    added mass (6x6 in 3D; :func:`section_discrete` solves its 2D sections with it)."""
    n = len(keep)
    on_hull = (~fin[keep]).astype(float)
    border = 1 if on_hull.any() else 0
    mat = np.zeros((n + border, n + border))
    mat[:n, :n] = a[np.ix_(keep, keep)]
    if border:
        mat[:n, n] = mat[n, :n] = on_hull
    mu = np.linalg.solve(mat, np.r_[modes[keep], np.zeros((border, modes.shape[1]))])[:n]
    sheets = fin[keep]
    m = rho * mu[sheets].T @ weights[keep][sheets]
    if border:
        phi_hull = phi[:, keep] @ mu
        m -= rho * phi_hull.T @ weights[hull]
    return 0.5 * (m + m.T)


def equivalent_planform(fin: FinPlanform, thickness: float, hull_radius_mid: float,
                        tips: int) -> FinPlanform:
    r"""The thin sheet with a thick fin's 2D sections (module docstring, "Thickness").

    Chord :math:`c_e = c\sqrt{C_A(c/t)}` about the mid-chord (DNV-RP-C205 table A-1), tip
    radius :math:`a_e` with :math:`m_{44}^{thin}(R, a_e) = m_{44}^{thick}(R, a)`: the 2D roll of
    the circle R (``hull_radius_mid`` [m], the hull at mid-chord) with ``tips`` fins (4, a
    cruciform; 2, a pair) of thickness t [m], by the 2D panel method, over the same section's
    thin value by the same method (so that the method's own error cancels), applied to the
    exact thin value (:func:`stripcoef.sections.added_mass.finned_circle_roll`)."""
    from scipy.optimize import brentq

    from stripcoef.sections.added_mass import finned_circle_roll, rectangle_coefficient

    c = fin.x_fore - fin.x_aft
    if thickness <= 0.0:
        return fin
    ce = c * float(np.sqrt(rectangle_coefficient(np.array([c / thickness]))[0]))
    mid = 0.5 * (fin.x_aft + fin.x_fore)
    ratio = _thick_section_ratio(hull_radius_mid, fin.tip, thickness, tips)
    target = ratio * finned_circle_roll(hull_radius_mid, fin.tip, fins=tips, rho=1.0)
    ae = brentq(lambda a: finned_circle_roll(hull_radius_mid, a, fins=tips, rho=1.0) - target,
                fin.tip, 2.0 * fin.tip, xtol=1e-9 * fin.tip)
    return FinPlanform(fin.angle, mid - 0.5 * ce, mid + 0.5 * ce, float(ae))


@functools.lru_cache(maxsize=64)
def _thick_section_ratio(radius: float, tip: float, thickness: float, tips: int) -> float:
    """2D roll added mass of the circle ``radius`` with ``tips`` radial fins (4 or 2) of
    ``thickness`` to ``tip`` [m], over the same with fins 1/100 as thick (2D panel method)."""
    from shapely.geometry import Point, box
    from shapely.ops import unary_union

    from stripcoef.sections.panel import added_mass_contours

    def roll(t):
        arms = [box(0.0, -0.5 * t, tip, 0.5 * t), box(-tip, -0.5 * t, 0.0, 0.5 * t)]
        if tips == 4:
            arms += [box(-0.5 * t, 0.0, 0.5 * t, tip), box(-0.5 * t, -tip, 0.5 * t, 0.0)]
        shape = unary_union([Point(0.0, 0.0).buffer(radius, 128)] + arms) if radius > 0 \
            else unary_union(arms)
        ring = np.asarray(shape.exterior.coords)[:-1]
        return float(added_mass_contours([ring], rho=1.0, panels=600)[2, 2])

    return roll(thickness) / roll(0.01 * thickness)


def fins_added_mass(hull_radius, x_aft: float, x_fore: float, fins, thickness, tips,
                    *, rho: float, **mesh) -> np.ndarray:
    r"""The fins' 3D share of the 6x6 added mass [kg, kg m, kg m^2], about the origin, of the
    flat rectangular ``fins`` (:class:`FinPlanform`, with their ``thickness`` [m] and the number
    of fins ``tips`` (4 or 2) of the section each belongs to) on the hull of revolution
    r = ``hull_radius(x)`` [m] from ``x_aft`` to ``x_fore`` [m]; ``rho`` [kg/m^3].

    Each fin's equivalent planform (:func:`equivalent_planform`), then the thin-sheet panel
    method (:func:`sheet_mesh`, :func:`sheet_added_mass`): the hull with its fins minus the hull
    alone on the same hull panels, so that the hull's own discretisation error cancels and what
    is left is the fins' share, their interaction with the hull included (the couplings of sway
    and yaw, heave and pitch).  The roll term is the fins' alone (the hull of revolution moves
    no water in roll).  Each term is multiplied by its cross-plane factor
    (:func:`_cross_plane_factors`: roll; sway for the fins spanning z, heave for those spanning
    y; pitch and yaw as heave and sway).
    [assumption] the translation and pitch/yaw modes take the roll's equivalent planform: its
    chord :math:`c\sqrt{C_A(c/t)}` is the thick section moving normal to itself, as the fins do
    in those modes, but its tip radius matches the thick cross-section in roll, not in sway
    (there the thick section's fins' share is 4-9 % above that tip's in 2D).  Against the
    converged BEM of six finned hulls, with the edgewise strip terms the assembly adds
    (:func:`stripcoef.assembly.added_mass.sheet_fin_shares`), the shares of sway, yaw and their
    coupling are -5.7 to +3.8 % (docs/theory.md, "Fins in 3D")."""
    sheets = [equivalent_planform(f, t, float(hull_radius(0.5 * (f.x_aft + f.x_fore))), k)
              for f, t, k in zip(fins, thickness, tips)]
    lo = min([x_aft] + [f.x_aft for f in sheets])
    hi = max([x_fore] + [f.x_fore for f in sheets])

    def radius(x):
        x = np.asarray(x, dtype=float)
        return np.where((x < x_aft) | (x > x_fore), 0.0, hull_radius(np.clip(x, x_aft, x_fore)))

    with_fins, hull = sheet_added_mass(sheet_mesh(radius, lo, hi, sheets, **mesh), rho)
    roll, sway, heave = _cross_plane_factors(radius, sheets, tips, **mesh)
    scale = np.sqrt(np.array([1.0, sway, heave, roll, heave, sway]))
    return (with_fins - hull) * np.outer(scale, scale)


def _cross_plane_factors(radius, sheets, tips, **mesh) -> tuple[float, float, float]:
    r"""Exact over discretised 2D sections, summed over the fins' chords (their chordwise
    collocation stations x_k, panel widths w_k), :math:`\sum w_k m^{exact}(R(x_k), a) /
    \sum w_k m^{disc}(R(x_k), a)` (:func:`section_discrete`): the correction of the sheet's
    cross-plane discretisation error, for roll (all fins; 3 to 7 % low for short fins with the
    default panels) and for the fins' share of sway (the fins spanning z, normal to y) and of
    heave (those spanning y), tests/test_finsheet.py.  Returns (roll, sway, heave) [-], 1 where
    no fin moves normal to itself in that direction."""
    from stripcoef.sections.added_mass import circle, circle_with_fins, finned_circle_roll

    cross = {k: mesh[k] for k in ("span", "quarter") if k in mesh}
    exact = np.zeros(3)
    disc = np.zeros(3)
    for f, fins in zip(sheets, tips):
        normal = 1 if round(f.angle / (0.5 * np.pi)) % 2 else 2     # spans z: sway; y: heave
        edges, xc = _cosine(f.x_aft, f.x_fore, mesh.get("chord", CHORD_PANELS))
        for w, r in zip(np.diff(edges), np.maximum(np.asarray(radius(xc), dtype=float), 0.0)):
            r = float(r)
            share, roll = section_discrete(r, f.tip, fins, **cross)
            exact[0] += w * finned_circle_roll(r, f.tip, fins=fins, rho=1.0)
            disc[0] += w * roll
            exact[normal] += w * (circle_with_fins(r, f.tip, fins=fins, rho=1.0)[0]
                                  - float(circle(r, rho=1.0)))
            disc[normal] += w * share
    return tuple(float(e / d) if d > 0 else 1.0 for e, d in zip(exact, disc))


@functools.lru_cache(maxsize=256)
def section_discrete(radius: float, tip: float, fins: int, *, span=SPAN_PANELS,
                     quarter=QUARTER_PANELS) -> tuple[float, float]:
    r"""2D added mass per unit length [for rho = 1] of the circle ``radius`` with ``fins`` (4, a
    cruciform; 2, a pair) thin fins to ``tip`` [m], by the 2D counterpart of :func:`sheet_mesh`'s
    cross-plane discretisation: the same hull polygon and fin panels, each constant-doublet
    segment as two point vortices at its ends (Katz & Plotkin 2001, sec. 11.2), collocation at
    the same points.  Returns (the fins' share of the translation normal to a pair [m^2]: the
    section's minus its hull polygon's alone, roll [m^4]).  The 3D solution divided by these
    and multiplied by the exact sections (:func:`stripcoef.sections.added_mass.circle_with_fins`,
    :func:`stripcoef.sections.added_mass.finned_circle_roll`) has the cross-plane
    discretisation error removed (:func:`fins_added_mass`).

    As in 3D (:func:`sheet_added_mass`): :math:`m_{ij} = -\oint_{hull}\phi_i n_j\,dl +
    \sum_{fins}\mu_i n_j\,l`, a segment's potential :math:`\mu\,\Delta\theta / 2\pi`
    (:math:`\Delta\theta` the angle it subtends), :math:`-\mu/2` on its own normal's side."""
    th = _quarter_angles(quarter)
    hull = radius * np.c_[np.cos(th), np.sin(th)] if radius > 0 else np.zeros((0, 2))
    seg_a, seg_b, pts = [], [], []
    for j in range(len(hull)):
        a, b = hull[j], hull[(j + 1) % len(hull)]
        seg_a.append(a), seg_b.append(b), pts.append(0.5 * (a + b))
    n_hull = len(seg_a)
    eta, eta_c = _half_cosine(span)
    for k in range(4) if fins == 4 else (0, 2):
        e = np.array([np.cos(0.5 * np.pi * k), np.sin(0.5 * np.pi * k)])
        r = radius + (tip - radius) * eta
        rc = radius + (tip - radius) * eta_c
        for j in range(span):
            seg_a.append(r[j] * e), seg_b.append(r[j + 1] * e), pts.append(rc[j] * e)
    a, b, p = np.array(seg_a), np.array(seg_b), np.array(pts)
    t = b - a
    length = np.linalg.norm(t, axis=1)
    n = np.c_[t[:, 1], -t[:, 0]] / length[:, None]

    def vortex(q):                       # velocity at p of unit point vortices at q
        d = p[:, None, :] - q[None, :, :]
        r2 = np.einsum("pqi,pqi->pq", d, d)
        return np.stack([-d[..., 1], d[..., 0]], axis=-1) / (2.0 * np.pi * r2[..., None])

    da, db = p[:n_hull, None, :] - a[None], p[:n_hull, None, :] - b[None]
    phi = np.arctan2(da[..., 0] * db[..., 1] - da[..., 1] * db[..., 0],
                     np.einsum("pqi,pqi->pq", da, db)) / (2.0 * np.pi)
    phi[np.arange(n_hull), np.arange(n_hull)] = -0.5
    normal_velocity = np.einsum("pqi,pi->pq", vortex(b) - vortex(a), n)   # signed by normal
    modes = np.c_[n[:, 1], p[:, 0] * n[:, 1] - p[:, 1] * n[:, 0]]        # normal to a pair, roll
    modes[:n_hull, 1] = 0.0

    hull_rows, sheets = np.arange(n_hull), np.arange(len(p)) >= n_hull
    weights = modes * length[:, None]

    def solve(keep):                     # the 3D system's solve on the 2D segments
        return np.diag(_solve_modes(normal_velocity, phi, hull_rows, keep, sheets, modes,
                                    weights, 1.0))

    both = solve(np.arange(len(p)))
    alone = solve(np.arange(n_hull)) if n_hull else np.zeros(2)
    return float(both[0] - alone[0]), float(both[1])
