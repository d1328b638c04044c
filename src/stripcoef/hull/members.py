r"""Longitudinal members and junctions of a multi-member mesh body (3D correction per member).

One added-mass-equivalent body of revolution (:mod:`stripcoef.hull.corrections`) is exact for a
body of revolution and good for a hull with fins, but it fails on an open frame made of
separate longitudinal members (a float, two pontoons) joined by short crossing members
(posts).  Measured on the open-frame ROV of ``benchmarks/mesh_shapes.py`` against
Capytaine (docs/performance.md, "Meshes and BEM"):

- the frame *without* its posts (three separate boxes): one equivalent body gives pitch
  -24 %, yaw -29 %, surge +32 %, while each box with its *own* equivalent body is within
  -8 %..+4 % of the BEM of that box alone, and their sum within 3 % of the BEM of the three
  together (pitch +0.1 %, yaw -3 %; the boxes' 3D interaction is small);
- at the posts' stations the 2D section is one closed frame (float, posts and pontoons in one
  contour), whose 2D sway added mass is 5.5 times that of the neighbouring sections
  (507 vs 93 kg/m) over only 0.06 m: strip theory puts this at x = +-0.38 m, and the single
  equivalent body turns it into two flanges that double pitch and yaw (+108 %, +113 %).

So the body is decomposed, from the strips' sections alone, into

**members** -- the connected components of the body once the junctions' crossing material is
removed; each is a polygon part of its own, its 2D sections solved alone and then given the
2D interaction of the joint section in proportion (:func:`_share_interaction`; in a junction
run, of the members' own sections solved together), and

**junctions** -- runs of strips whose section joins components that are separate on both sides
of the run (a component overlapping two or more components of the adjacent strip outside the
run).  In a junction run the members' sections are the run's section clipped to the union of
the sections just before and after it,

.. math:: P^{base}_i = P_i \cap (P_{before} \cup P_{after}),

and the rest, :math:`P_i \setminus P^{base}_i`, is the crossing material.  The junction's
2D added mass is the excess of the joined section over its members' sections,

.. math:: \Delta m(x_i) = m^{2D}[P_i] - \sum_{members} H_2^T m^{2D}[P^{base}_{i,k}] H_2
          \quad (\ge 0 \text{ per direction})

about the crossing material's centroid, with the crossing material's area for its surge term.

Every member and junction then gets the 3D correction of :func:`stripcoef.hull.corrections.
hull_corrections` from its *own* added-mass-equivalent bodies of revolution, about its own
centre :math:`a_e` (volume centroid), and the corrected matrices are moved to the common point
and added (Fossen 2011, sec. 7.5.3; :func:`stripcoef.conventions.transform_matrix`):

.. math:: M_A = \sum_e H(a_e - c)^T\,\big(D_e S_e D_e + \text{axial}_e + \Delta_e\big)\,
          H(a_e - c)

so the offset members' roll and pitch/yaw terms (their sway/heave added mass times the lever
arm squared) carry their own end reliefs.  A junction piece's equivalent body is a short disc;
its sway and heave are then weighted for the piece's own slenderness in the section plane
(:func:`crossing_weights`: a post moving along its axis adds almost nothing in 3D, measured
against Capytaine on two frames other than the ROV, docs/theory.md sec. 6).  The members' 2D roll interaction (the joint
sections' roll terms minus the members' own, outside the junction runs) is added with the
roll relief of the joint sections (:func:`stripcoef.hull.corrections.roll_relief`).  A body with a
single member and no junction is left to the single equivalent body (identical results).

[assumption] members and junction pieces add without 3D interaction: the usual build-up of a
frame's added mass from its members (e.g. DNV-RP-H103 (2011) ch. 4); measured on the ROV
without posts, the sum of the three boxes' own BEM is within 3 % of the BEM of the three
together in translation and pitch/yaw, 9 % above it in roll (hence the 2D roll interaction).

References
----------
Newman (1977) *Marine Hydrodynamics*, sec. 4.13-4.15 and 7.4 (strip theory, end effects);
Fossen (2011) sec. 7.5.3 (moving a matrix between points).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import warnings

import numpy as np

from stripcoef.conventions import transform_matrix
from stripcoef.errors import ModelWarning
from stripcoef.geometry.mesh import rings_integrals, section_geometry, section_properties
from stripcoef.hull.corrections import (DEFAULT_PANELS, _polygon_roll_mode, apply_corrections,
                                        hull_corrections, roll_relief)
from stripcoef.hull.lamb import lamb_k_factors
from stripcoef.sections import get_shape, section_added_mass
from stripcoef.sections.panel import added_mass_sections
from stripcoef.strips import Part, Strips, shift_section_matrices, strip_added_mass

#: Overlap area below which two components of adjacent strips are not connected
#: (relative to the smaller component's area).
_OVERLAP_REL = 1e-6


@dataclass
class Entity:
    """A member or a junction: its own strips and 2D sections.

    Attributes
    ----------
    kind : str
        ``member`` or ``junction``
    strips : Strips
        The entity's strips (its own x-range; one polygon part, indices local)
    mats : (k, 3, 3) array
        2D added mass per strip about the part's centroid [kg/m, kg, kg m]
    roll_m44 : (k,) array, optional
        For the roll-interaction entity: the joint sections' roll added mass [kg m] (its
        roll relief)
    crossing_weights : (2,) array, optional
        For a junction piece: the factors of its sway and heave added mass for motion along
        its own in-plane axis (:func:`crossing_weights`) [-]
    """

    kind: str
    strips: Strips
    mats: np.ndarray
    roll_m44: np.ndarray | None = None
    crossing_weights: np.ndarray | None = None


def _components(rings):
    """Shapely polygons (outer ring with its holes) of one section's rings."""
    geom = section_geometry(rings)
    return [g for g in getattr(geom, "geoms", [geom]) if not g.is_empty and g.area > 0]


def _rings(polys):
    """(n, 2) rings of shapely polygons: outer counter-clockwise, holes clockwise."""
    from shapely.geometry.polygon import orient
    out = []
    for p in polys:
        p = orient(p, sign=1.0)
        out.append(np.asarray(p.exterior.coords)[:-1])
        out.extend(np.asarray(h.coords)[:-1] for h in p.interiors)
    return out


def _overlaps(a, b) -> bool:
    """Whether polygons ``a`` and ``b`` share more than :data:`_OVERLAP_REL` of the smaller
    one's area.  Two bounds decide most pairs without the (costly) polygon intersection: the
    overlap of their bounding boxes bounds the intersection's area from above, a disc inside
    both from below."""
    limit = _OVERLAP_REL * min(a.area, b.area)
    ay0, az0, ay1, az1 = a.bounds
    by0, bz0, by1, bz1 = b.bounds
    box = max(0.0, min(ay1, by1) - max(ay0, by0)) * max(0.0, min(az1, bz1) - max(az0, bz0))
    if box <= limit:
        return False
    # a disc of radius r about a point inside both lies in the intersection: if its area
    # pi r^2 exceeds the limit the answer is yes, again without the intersection (the
    # common case of one member's sections in adjacent strips, nearly the same polygon)
    p = a.representative_point()
    r = min(a.boundary.distance(p), b.boundary.distance(p))
    if b.contains(p) and np.pi * r * r > limit:
        return True
    return a.intersection(b).area > limit


def _junction_runs(comps):
    """Runs [j0, j1] (inclusive, local strip indices) whose sections join components that
    are separate just outside the run (see module docstring)."""
    n = len(comps)
    counts = [len(c) for c in comps]
    # maximal runs of equal component count
    runs, start = [], 0
    for j in range(1, n + 1):
        if j == n or counts[j] != counts[start]:
            runs.append([start, j - 1])
            start = j
    flags = []
    for j0, j1 in runs:
        merging = False
        for inside, outside in ((j0, j0 - 1), (j1, j1 + 1)):
            if outside < 0 or outside >= n:
                continue
            for c in comps[inside]:
                if sum(_overlaps(c, o) for o in comps[outside]) >= 2:
                    merging = True
        flags.append(merging)
    # adjacent junction runs form one junction region
    out = []
    for (j0, j1), f in zip(runs, flags):
        if not f:
            continue
        if out and out[-1][1] == j0 - 1:
            out[-1][1] = j1
        else:
            out.append([j0, j1])
    return out


def _polygon_part(name, index, polys_per_strip, length, role):
    contours = [_rings(ps) for ps in polys_per_strip]
    props = section_properties(contours)
    return Part(name=name, shape="polygon", index=np.asarray(index), y=props[:, 1],
                z=props[:, 2], half_breadth=props[:, 3], half_height=props[:, 4],
                area=props[:, 0], iyy=props[:, 5], izz=props[:, 6], rounded=False,
                length=length, role=role, contours=contours)


def decompose(strips: Strips, rho: float, joint=None,
              section_panels: int | None = None) -> list[Entity] | None:
    r"""Members and junctions of a single-mesh body (module docstring), or None when the body
    is one member without junctions, or is not a single polygon part (vehicle-file bodies).

    Parameters
    ----------
    strips : Strips
        The body's strips (one ``polygon`` part, from a mesh)
    rho : float
        Fluid density [kg/m^3] (the junctions' 2D excess added mass)
    joint : (n, 3, 3) array, optional
        The part's 2D sections about their centroids (solved if omitted)
    section_panels : int, optional
        Panels per 2D section (:func:`stripcoef.sections.panel.discretise`; default adaptive)

    Returns
    -------
    list of Entity or None
    """
    if len(strips.parts) != 1 or not get_shape(strips.parts[0].shape).contoured \
            or strips.holes:
        return None
    part = strips.parts[0]
    if part.contours is None or not np.allclose(part.coverage, 1.0):
        return None
    if max(len(r) for r in part.contours) < 2:
        return None             # one ring per section: one member, no junction
    comps = [_components(r) for r in part.contours]
    if max(len(c) for c in comps) < 2:
        return None
    runs = _junction_runs(comps)
    base = [list(c) for c in comps]
    crossing = {}
    for j0, j1 in runs:
        import shapely
        around = [comps[j] for j in (j0 - 1, j1 + 1) if 0 <= j < len(comps)]
        if not around:
            continue
        env = shapely.union_all([p for ps in around for p in ps])
        for j in range(j0, j1 + 1):
            kept, rest = [], []
            for c in comps[j]:
                inter = c.intersection(env)
                kept.extend(g for g in getattr(inter, "geoms", [inter])
                            if g.geom_type == "Polygon" and g.area > 0)
                diff = c.difference(env)
                rest.extend(g for g in getattr(diff, "geoms", [diff])
                            if g.geom_type == "Polygon" and g.area > 0)
            base[j] = kept
            crossing[j] = rest
    # members: connected components of the base sections across adjacent strips
    groups = _tracks({j: base[j] for j in range(len(base)) if base[j]})
    if len(groups) < 2 and not crossing:
        return None
    entities = []
    gidx = part.index
    for g, per in enumerate(groups):
        js = np.array(sorted(per))
        if js.size < 2:
            return _too_short("member", strips.x[gidx[js[0]]])
        sub = _sub_strips(strips, gidx[js])
        length = float(sub.x_max - sub.x_min)
        p = _polygon_part(f"{part.name}:member{g}", np.arange(js.size), [per[j] for j in js],
                          length, part.role)
        sub.parts = [p]
        entities.append(Entity("member", sub, section_added_mass(p, rho, section_panels)))
    member_of = {}
    for e in entities:
        p = e.strips.parts[0]
        for k, xi in enumerate(e.strips.x):
            member_of.setdefault(float(xi), []).append((e, k))
    if joint is None:
        joint = added_mass_sections(part.contours, rho=rho, panels=section_panels,
                                    about=np.column_stack([part.y, part.z]))
    _share_interaction(strips, part, member_of, set(crossing), joint)
    # in the junction runs the joint section holds the crossing material too: there the
    # members' 2D interaction is that of their own sections solved together
    rows = [j for j in sorted(crossing) if len(base[j]) > 1]
    if rows:
        together = added_mass_sections([_rings(base[j]) for j in rows], rho=rho,
                                       panels=section_panels, about=np.zeros((len(rows), 2)))
        _share_interaction(strips, part, member_of, set(), dict(zip(rows, together)), rows)
    # junctions: excess of the joined section over its members' sections
    for r, (j0, j1) in enumerate(runs):
        js = np.array([j for j in range(j0, j1 + 1) if crossing.get(j)])
        if js.size == 0:
            continue                  # the run's sections lie inside its neighbours': no excess
        if js.size < 2:
            return _too_short("junction", strips.x[gidx[js[0]]])
        whole = _polygon_part("run", np.arange(js.size), [crossing[j] for j in js], 0.0,
                              "appendage")
        about = np.column_stack([whole.y, whole.z])
        full = added_mass_sections([part.contours[j] for j in js], rho=rho, about=about,
                                   panels=section_panels)
        excess = full.copy()
        for k, j in enumerate(js):
            for me, mk in member_of.get(float(strips.x[gidx[j]]), []):
                mp = me.strips.parts[0]
                excess[k] -= shift_section_matrices(me.mats[mk], mp.y[mk] - whole.y[k],
                                                    mp.z[mk] - whole.z[k])
        d = np.clip(np.einsum("kii->ki", excess[:, :2, :2]), 0.0, None)
        # the crossing pieces (one per connected run of crossing material) share the
        # excess in proportion to their section areas [assumption]
        pieces = _tracks({j: crossing[j] for j in js})
        for q, piece in enumerate(pieces):
            pj = np.array(sorted(piece))
            if pj.size < 2:
                return _too_short("junction piece", strips.x[gidx[pj[0]]])
            k_of = {int(j): k for k, j in enumerate(js)}
            ks = np.array([k_of[int(j)] for j in pj])
            sub = _sub_strips(strips, gidx[pj])
            p = _polygon_part(f"{part.name}:junction{r}.{q}", np.arange(pj.size),
                              [piece[j] for j in pj], float(sub.x_max - sub.x_min), "appendage")
            share = p.area / whole.area[ks]
            m = np.zeros((pj.size, 3, 3))
            m[:, 0, 0] = share * d[ks, 0]
            m[:, 1, 1] = share * d[ks, 1]
            sub.parts = [p]
            entities.append(Entity("junction", sub, m, crossing_weights=crossing_weights(
                [piece[j] for j in pj], float(sub.x_max - sub.x_min))))
    # 2D roll interaction outside the junction runs: the joint section's roll terms minus the
    # members' about the section's centroid; the translations are the members'
    resid = joint.copy()
    for j in range(part.index.size):
        for e, k in member_of.get(float(strips.x[part.index[j]]), []):
            mp = e.strips.parts[0]
            resid[j] -= shift_section_matrices(e.mats[k], mp.y[k] - part.y[j],
                                               mp.z[k] - part.z[j])
    resid[:, :2, :2] = 0.0
    resid[sorted(crossing)] = 0.0     # junction runs: their excess is the pieces' (translation)
    entities.append(Entity("roll interaction", strips, resid, joint[:, 2, 2].copy()))
    return entities


def _share_interaction(strips, part, member_of, junction_strips, joint, rows=None):
    r"""Give the members the 2D interaction of the joint section, in proportion (in place).

    Where a strip's section is the union of its members' sections (not in a junction run),
    the joint 2D solve (all contours together, exact 2D interaction) and the members' own
    solves differ by the 2D interaction; each member's sway and heave terms are scaled by

    .. math:: r_d = m^{2D}_{dd}[\text{joint}] / \sum_k m^{2D}_{dd}[k],\qquad
              m_k \leftarrow D\,m_k\,D,\ D = \operatorname{diag}(\sqrt{r_y}, \sqrt{r_z}, 1)

    [assumption] the interaction is shared in proportion to the members' own added mass;
    measured on the ROV's float and pontoons: joint sway 8 % above the sum of the parts,
    heave 3 % below. Roll terms are left as the members' own (their 2D roll interaction is
    the roll-interaction entity of :func:`decompose`). ``joint`` (n, 3, 3) per strip of the
    part [kg/m, kg, kg m] (or a mapping strip -> (3, 3) for the strips ``rows``; in a junction
    run, the members' own sections solved together).
    """
    if rows is None:
        rows = range(part.index.size)
    rows = [j for j in rows if j not in junction_strips
            and len(member_of.get(float(strips.x[part.index[j]]), [])) > 1]
    for j in rows:
        mj = joint[j]
        mine = member_of[float(strips.x[part.index[j]])]
        total = np.zeros(2)
        for e, k in mine:
            total += np.diag(e.mats[k])[:2]
        r = np.ones(3)
        ok = total > 0
        r[:2][ok] = np.diag(mj)[:2][ok] / total[ok]
        d = np.sqrt(np.clip(r, 0.0, None))
        for e, k in mine:
            e.mats[k] = d[:, None] * e.mats[k] * d[None, :]


def crossing_weights(polys_per_strip, length: float) -> np.ndarray:
    r"""Factors of a junction piece's sway and heave added mass for its own slenderness.

    A junction piece (crossing material, e.g. a post between a float and a pontoon) is a
    short member whose long axis :math:`\mathbf t` lies in the section plane, with length h
    along :math:`\mathbf t`, width w across it (in the plane, along :math:`\mathbf n`) and
    length l along x.  Slender-body theory splits a motion into cross-flow and axial parts: a
    prolate spheroid of the same slenderness :math:`\lambda = h/D`, :math:`D = 2\sqrt{lw/\pi}`
    (equal-area diameter of the cross-section), has axial and transverse added-mass
    coefficients :math:`k_1, k_2` (Lamb 1932, sec. 373), so the piece's translation in
    direction :math:`\mathbf d` (y or z) keeps

    .. math:: s_d = (\mathbf d\cdot\mathbf n)^2 + \frac{k_1(\lambda)}{k_2(\lambda)}
              (\mathbf d\cdot\mathbf t)^2 \qquad (s_d = 1 \text{ for } \lambda \le 1)

    of the junction's 3D-relieved excess (its disc, :func:`member_added_mass`): the 2D excess
    of a section closed by the piece comes from blocking the gap flow, which in 3D passes
    round a short piece, and a piece moving along its own axis pushes no water of its own.
    :math:`\mathbf t` is the major principal axis of the piece's section (area-weighted
    second moments over its strips).  [assumption]; measured against Capytaine
    (benchmarks/junction_relief.py, docs/theory.md sec. 6): on a frame with four vertical
    posts 0.06 m long (an arch like the ROV's) the posts add -0.65 kg of heave in 3D, the
    junction's disc gave +5.1 kg, with these weights +0.47 kg (a closed ladder: -1.14 kg,
    now +0.10 kg).  ``polys_per_strip``: the piece's shapely
    polygons per strip [m]; ``length`` l [m].  Returns (s_y, s_z) [-].
    """
    rings = [np.asarray(p.exterior.coords)[:-1] for ps in polys_per_strip for p in ps]
    ints = rings_integrals(rings)                       # per ring: A, S_y, S_z, Iyy, Izz, Iyz
    a = float(np.abs(ints[:, 0]).sum())
    if not a > 0 or not length > 0:
        return np.ones(2)
    _, sy, sz, iyy, izz, iyz = np.sign(ints[:, 0]) @ ints     # every ring counted as solid
    c = np.array([sy, sz]) / a
    inertia = np.array([[iyy, iyz], [iyz, izz]]) - a * np.outer(c, c)
    _, vec = np.linalg.eigh(inertia)
    t, n = vec[:, 1], vec[:, 0]                       # major, minor principal axes
    pts = np.vstack(rings)
    h = float(np.ptp(pts @ t))
    w = float(np.ptp(pts @ n))
    lam = h / (2.0 * np.sqrt(length * w / np.pi)) if w > 0 else np.inf
    if not lam > 1.0:
        return np.ones(2)
    k1, k2, _ = lamb_k_factors(min(lam, 1e6))
    kappa = k1 / k2
    return n ** 2 + kappa * t ** 2


def _too_short(what, x):
    """A member or junction one strip long cannot have its own equivalent body: warn and let
    the caller use the single equivalent body of the whole body (nothing is dropped)."""
    warnings.warn(f"a {what} at x = {x:.4g} m spans a single strip: the whole body is corrected "
                  f"as one (use more strips for the per-member correction)", ModelWarning,
                  stacklevel=3)
    return None


def _tracks(polys_by_strip: dict) -> list[dict]:
    """Connected components of polygons across adjacent strips: list of {strip: [polygons]}."""
    nodes = [(j, k) for j, ps in polys_by_strip.items() for k in range(len(ps))]
    parent = {v: v for v in nodes}

    def find(v):
        while parent[v] != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v

    for j, ps in polys_by_strip.items():
        nxt = polys_by_strip.get(j + 1)
        if not nxt:
            continue
        for a, pa in enumerate(ps):
            for b, pb in enumerate(nxt):
                if _overlaps(pa, pb):
                    parent[find((j, a))] = find((j + 1, b))
    groups: dict = {}
    for v in sorted(nodes):
        groups.setdefault(find(v), []).append(v)
    out = []
    for members in groups.values():
        per: dict = {}
        for j, k in members:
            per.setdefault(j, []).append(polys_by_strip[j][k])
        out.append(per)
    return out


def _sub_strips(strips: Strips, idx) -> Strips:
    idx = np.asarray(idx, dtype=int)
    return Strips(x=strips.x[idx].copy(), dx=strips.dx[idx].copy(), parts=[], holes=[])


def member_added_mass(strips: Strips, rho: float, center, entities=None, joint=None,
                      panels: int | None = None, section_panels: int | None = None):
    r"""Corrected 6x6 added mass about ``center`` as the sum over members and junctions.

    .. math:: M_A = \sum_e H(a_e - c)^T\,\mathrm{corr}_e\big(S_e(a_e)\big)\,H(a_e - c)

    with :math:`S_e(a_e)` the entity's strip matrix about its centre :math:`a_e` (volume
    centroid of a member, area centroid of a junction's crossing material) and corr the
    per-direction equivalent-body correction of :func:`stripcoef.hull.corrections.hull_corrections`
    and :func:`~stripcoef.hull.corrections.apply_corrections` (``panels``: its meridian panels,
    default :data:`stripcoef.hull.corrections.DEFAULT_PANELS`; ``section_panels``: the 2D
    sections', see :func:`decompose`).  ``rho`` [kg/m^3], ``center`` [m];
    returns (M_A [kg, kg m, kg m^2], list of per-entity info) or None when the body is not
    decomposed (:func:`decompose`).

    References
    ----------
    Module docstring; Fossen (2011) sec. 7.5.3.
    """
    panels = DEFAULT_PANELS if panels is None else int(panels)
    if entities is None:
        entities = decompose(strips, rho, joint, section_panels)
    if not entities:
        return None
    center = np.asarray(center, dtype=float)
    total = np.zeros((6, 6))
    info = []
    for e in entities:
        st = e.strips
        p = st.parts[0]
        mats = [e.mats]
        if e.kind == "roll interaction":
            # relieved like the whole body's roll (the joint sections' roll relief)
            s = strip_added_mass(st, mats, center)
            m44 = e.roll_m44
            fp = roll_relief(st, m44, rho=rho, mode=_polygon_roll_mode(st, m44), panels=panels)
            total += fp * s
            info.append({"kind": e.kind, "name": p.name, "roll_relief": fp})
            continue
        w = p.area * st.dx
        a_e = np.array([np.sum(st.x * w), np.sum(p.y * w), np.sum(p.z * w)]) / np.sum(w)
        s = strip_added_mass(st, mats, a_e)
        corr = hull_corrections(st, rho=rho, center=a_e, section_added_mass=mats[0],
                                panels=panels)
        if e.kind == "junction":
            # a crossing piece is short along x: its equivalent body is a disc whose broadside
            # rotation is not the piece's; its own pitch/yaw about its centre (O(dx^3)) take
            # the translation factors and no coupling increment [assumption]
            scale = np.array(corr.scale)
            if e.crossing_weights is not None:
                # motion along the piece's own in-plane axis (crossing_weights)
                scale[1] *= e.crossing_weights[0]
                scale[2] *= e.crossing_weights[1]
            scale[4], scale[5] = scale[2], scale[1]
            corr = replace(corr, scale=scale, coupling_26=0.0, coupling_35=0.0)
        m = apply_corrections(s, corr)
        total += transform_matrix(m, from_point=a_e, to_point=center)
        info.append({"kind": e.kind, "name": p.name, "centre": a_e.tolist(),
                     "x_range": [st.x_min, st.x_max], "scale": corr.scale.tolist(),
                     "axial_added_mass": corr.axial_added_mass})
    return 0.5 * (total + total.T), info
