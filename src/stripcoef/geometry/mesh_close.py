r"""Closing a mesh that stays open after the loader's hole filling: each open part capped,
the parts united (``stripcoef mesh FILE --repair``; ``load_mesh(..., close_parts=True)``).

Meshes of simulators are often collision meshes built from loose CAD parts: closed bodies
beside open ones (a thruster duct or a motor housing as a tube without end caps, a shaft
without ends), faces written twice.  trimesh fills only holes of three or four edges
(``trimesh.repair.fill_holes``) and manifold3d unites only closed bodies, so such a mesh is
refused as found.  :func:`close_open_parts`:

1. splits the surface into parts, faces connected across edges shared by exactly two faces
   (``trimesh.graph.connected_component_labels`` of ``Trimesh.face_adjacency``; a non-manifold
   edge where two parts touch separates them);
2. caps every hole of an open part (a loop of edges with one face each) by a fan of triangles
   from the loop's centroid, wound against the loop so that the part is consistently oriented
   (the "fan" closure of a planar, star-shaped hole: the end of a tube, a cut-off cap; Botsch
   et al. 2010, "Polygon Mesh Processing", sec. 3.3, hole filling by triangulating the
   boundary loop).  A part that is still not closed (a vertex on two holes, an edge on three
   faces) is refused, naming where it is;
3. turns each closed part outward (``trimesh.repair.fix_normals``) and unites all parts by the
   boolean union of manifold3d (through ``trimesh.boolean.union``), which gives one closed,
   manifold surface.

A capped tube is a solid cylinder: a duct through which water flows becomes a plug.  The
volume the caps add is reported, so the user sees how much of the body is made up.
"""

from __future__ import annotations

import numpy as np

from stripcoef.errors import InputError
from stripcoef.geometry.slicing import EdgeTopology


def _parts(mesh) -> np.ndarray:
    """Part label of each face (faces connected across manifold edges)."""
    import trimesh

    return trimesh.graph.connected_component_labels(mesh.face_adjacency,
                                                    node_count=len(mesh.faces))


def open_parts_text(mesh) -> str:
    """What is open, in words: '171 open or non-manifold edges (12 of 26 parts open)'."""
    topo = EdgeTopology(mesh.faces)
    labels = _parts(mesh)
    f = np.asarray(mesh.faces)
    n_parts = int(labels.max()) + 1 if labels.size else 0
    n_open = sum(not EdgeTopology(f[labels == k]).watertight for k in range(n_parts))
    return (f"{topo.open_edges} open or non-manifold edges ({n_open} of {n_parts} "
            f"part{'s' if n_parts != 1 else ''} open)")


def cap_holes(vertices, faces):
    """Cap every boundary loop of one part (module docstring, step 2).

    Returns (vertices, faces, loops capped); the faces unchanged when a boundary vertex is on
    more than one loop (the loops do not chain simply: left to the caller's check)."""
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces, dtype=np.int64)
    a = f.reshape(-1)
    b = np.roll(f, -1, axis=1).reshape(-1)
    key = np.minimum(a, b) * len(v) + np.maximum(a, b)
    uniq, inv, count = np.unique(key, return_inverse=True, return_counts=True)
    single = count[inv] == 1
    ea, eb = a[single], b[single]                     # boundary edges as the faces run them
    if ea.size == 0:
        return v, f, 0
    if np.unique(ea).size != ea.size or np.unique(eb).size != eb.size:
        return v, f, 0
    nxt = dict(zip(ea.tolist(), eb.tolist()))
    new_v, new_f, loops = [v], [f], 0
    n = len(v)
    seen = set()
    for start in ea.tolist():
        if start in seen:
            continue
        loop = [start]
        seen.add(start)
        cur = nxt[start]
        while cur != start:
            if cur in seen or cur not in nxt:
                return v, f, 0                        # not a simple loop
            loop.append(cur)
            seen.add(cur)
            cur = nxt[cur]
        idx = np.asarray(loop)
        new_v.append(v[idx].mean(axis=0)[None, :])
        # edge p -> q of the part's faces: the cap face runs q -> p (consistent winding)
        new_f.append(np.column_stack([np.roll(idx, -1), idx, np.full(idx.size, n)]))
        n += 1
        loops += 1
    return np.vstack(new_v), np.vstack(new_f), loops


def manifold_boolean(op: str, meshes, *, what: str, expected: str, file=None, key=None):
    """The boolean ``op`` ('union' or 'difference') of closed ``meshes`` by manifold3d (exact,
    guaranteed-manifold booleans; Lalish et al., https://github.com/elalish/manifold) through
    ``trimesh.boolean``, as a plain ``trimesh.Trimesh`` [m].  Used by every union of the
    package (a mesh's bodies, its capped parts, a vehicle file's parts).  A refusal of
    manifold3d is an :class:`InputError` 'the ``what`` could not be united' with ``expected``."""
    import trimesh

    try:
        import manifold3d  # noqa: F401
    except ImportError:  # pragma: no cover - a core dependency
        raise InputError(f"uniting the {what} needs manifold3d", file=file,
                         expected="pip install manifold3d (a dependency of stripcoef)") from None
    fn = trimesh.boolean.union if op == "union" else trimesh.boolean.difference
    try:
        out = fn(meshes, engine="manifold", check_volume=False)
    except Exception as exc:  # noqa: BLE001 - manifold3d refuses a non-manifold input
        raise InputError(f"the {what} could not be united ({type(exc).__name__})", file=file,
                         key=key, expected=expected) from None
    return trimesh.Trimesh(np.asarray(out.vertices, float), np.asarray(out.faces), process=False)


def closed_union(parts, *, what: str, expected: str, file=None):
    """:func:`manifold_boolean` union of closed ``parts`` that must give one closed surface
    (winding consistent, volume > 0), else an :class:`InputError` naming its open edges."""
    out = manifold_boolean("union", parts, what=what, expected=expected, file=file)
    topo = EdgeTopology(out.faces)
    if len(out.faces) == 0 or not topo.consistent or not out.volume > 0:
        raise InputError(f"the union of the {what} is not a closed surface", file=file,
                         value=f"{topo.open_edges} open edges",
                         expected="closed parts that unite into one closed surface")
    return out


def close_open_parts(mesh, *, where: str = ""):
    """The mesh closed part by part and its parts united (module docstring).

    Parameters
    ----------
    mesh : trimesh.Trimesh
        The loader's mesh [m] (degenerate and duplicate faces removed).
    where : str
        The file, for the errors and notes.

    Returns
    -------
    (trimesh.Trimesh, list of str)
        One closed, outward-oriented surface and what was done, in words.

    Raises
    ------
    InputError
        A part that the caps do not close, or a union that is not a closed surface.
    """
    import trimesh

    v = np.asarray(mesh.vertices, dtype=float)
    f = np.asarray(mesh.faces, dtype=np.int64)
    labels = _parts(mesh)
    n_parts = int(labels.max()) + 1
    parts, n_open, n_loops, cap_volume = [], 0, 0, 0.0
    for k in range(n_parts):
        part = trimesh.Trimesh(v, f[labels == k], process=False)
        part.remove_unreferenced_vertices()
        if not EdgeTopology(part.faces).watertight:
            pv, pf, loops = cap_holes(part.vertices, part.faces)
            part = trimesh.Trimesh(pv, pf, process=False)
            topo = EdgeTopology(part.faces)
            if not topo.watertight:
                c = 0.5 * (part.bounds[0] + part.bounds[1])
                raise InputError(f"part {k} of {n_parts} (centre {np.round(c, 4).tolist()} m, "
                                 f"{len(part.faces)} faces) cannot be closed by capping its "
                                 "holes", file=where or None,
                                 value=f"{topo.open_edges} open or non-manifold edges",
                                 expected="holes bounded by simple loops (close the part or "
                                          "remove it in CAD)")
            n_open += 1
            n_loops += loops
            trimesh.repair.fix_normals(part)
            cap_volume += abs(float(part.volume))
        else:
            trimesh.repair.fix_normals(part)
        parts.append(part)
    total = float(sum(abs(p.volume) for p in parts))
    notes = []
    if n_open:
        notes.append(f"capped {n_loops} holes of {n_open} open parts (a fan from each hole's "
                     f"centroid): they enclose {cap_volume:.3g} m^3, {100 * cap_volume / total:.1f} "
                     "% of the parts' volume (a capped duct is solid)")
    if n_parts == 1:
        return parts[0], notes
    out = closed_union(parts, what="closed parts", expected="closed, manifold parts",
                       file=where or None)
    out, n_frag = _drop_fragments(out)
    notes.append(f"united {n_parts} parts into one closed surface (manifold3d); "
                 f"{max(total - float(out.volume), 0.0):.3g} m^3 of overlap removed"
                 + (f"; {n_frag} slivers of the union under {FRAGMENT:g} of its volume dropped"
                    if n_frag else ""))
    return out, notes


#: A closed piece of the union enclosing less than this fraction of its volume is a sliver that
#: the boolean cut off where two parts nearly touch, not a part of the vehicle [-].
FRAGMENT = 1e-6


def _drop_fragments(mesh):
    r"""The union without its closed pieces of under :data:`FRAGMENT` of its volume (signed
    tetrahedron sums per piece, :math:`V = \tfrac16\sum_f \mathbf p_0\cdot(\mathbf p_1
    \times\mathbf p_2)` [m^3]); returns (mesh, pieces dropped)."""
    import trimesh

    topo = EdgeTopology(mesh.faces)
    if not topo.watertight:
        return mesh, 0
    labels = topo.component_labels()
    t = np.asarray(mesh.vertices)[np.asarray(mesh.faces)]
    vol = np.einsum("fi,fi->f", t[:, 0], np.cross(t[:, 1], t[:, 2])) / 6.0
    per = np.bincount(labels, weights=vol)
    small = np.flatnonzero(np.abs(per) < FRAGMENT * abs(per.sum()))
    if small.size == 0:
        return mesh, 0
    out = trimesh.Trimesh(mesh.vertices, np.asarray(mesh.faces)[~np.isin(labels, small)],
                          process=False)
    out.remove_unreferenced_vertices()
    return out, int(small.size)
