r"""CAD meshes (STL, OBJ, PLY, GLB) as vehicle geometry: loading, defect repair, slicing.

Pipeline: read with trimesh -> convert the length unit to metres -> apply the
optional 4x4 ``transform`` -> map the chosen mesh ``axis`` onto body x ->
move the origin (volume centroid, or a given point) -> find and repair defects
-> slice into strips.

Axis mapping (cyclic, keeps handedness): ``axis="x"`` keeps (x, y, z);
``axis="y"`` maps mesh (y, z, x) to body (x, y, z); ``axis="z"`` maps mesh
(z, x, y) to body (x, y, z).  Body axes are FRD (x forward, y starboard,
z down); use ``transform`` for any other rotation (e.g. a z-up CAD frame).

Slicing (:mod:`stripcoef.geometry.slicing`): each strip's section is the cut of the surface by the plane
``x = x_i`` (the strip centre).  For a watertight, consistently wound mesh
every crossed triangle gives one segment from the edge where its boundary goes
down through the plane to the edge where it goes up, so the segments chain
into closed rings through the shared mesh edges, with outer rings and holes
oriented oppositely -- no floating-point snapping.  The chaining is vectorised
(pointer doubling), so a 100k-face mesh slices in tens of milliseconds.

Per strip the section properties are the polygon integrals

.. math:: A = \tfrac12\oint (y\,dz - z\,dy), \quad
          y_c = \tfrac{1}{A}\int y\,dA, \quad
          I_{yy} = \int (y - y_c)^2 dA

(shoelace / Green's theorem; e.g. Bourke, "Calculating the area and centroid
of a polygon", 1988).

Defects are found and either repaired (reported in :attr:`MeshBody.repairs`)
or refused with an :class:`~stripcoef.errors.InputError`:

=============================  ==========================================
defect                         handling
=============================  ==========================================
degenerate / duplicate faces   removed, counted
inconsistent winding           fixed (trimesh.repair.fix_winding)
inward normals (per body)      flipped (trimesh.repair.fix_normals)
open mesh                      holes filled if trimesh can; else refused
several bodies                 reported; sliced together (one rigid body)
overlapping bodies             shapely union per strip; double-counted
                               volume reported
strip empty inside the body    refused (strip index and x named)
=============================  ==========================================
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import warnings

from stripcoef.errors import InputError, ModelWarning
from stripcoef.geometry.mesh_close import close_open_parts, closed_union, open_parts_text
# the section geometry of a mesh (re-exported: its users import it from here)
from stripcoef.geometry.slicing import (COLLINEAR_TOL, EdgeTopology, _chain_cycles,  # noqa: F401
                                        _corner_points, ring_integrals, rings_integrals,
                                        section_geometry, section_properties, slice_rings)
from stripcoef.strips import Part, Strips, uniform_stations

#: File extensions read through trimesh (COLLADA through pycollada:
#: :mod:`stripcoef.geometry.collada`).
MESH_EXTENSIONS = (".stl", ".obj", ".ply", ".glb", ".dae")
#: Length units and their size in metres.
LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "cm": 1e-2, "in": 0.0254, "ft": 0.3048}
#: Body lengths outside this range [m] mean a wrong length unit.
LENGTH_RANGE = (1e-3, 200.0)
AXES = ("x", "y", "z")
_AXIS_PERM = {"x": (0, 1, 2), "y": (1, 2, 0), "z": (2, 0, 1)}


# --------------------------------------------------------------------------- body

class MeshBody:
    """A watertight mesh in body axes [m], ready to be cut into strips.

    Implements the body protocol of the strip assembly: :meth:`x_extent` and
    :meth:`parts`.

    Attributes
    ----------
    mesh : trimesh.Trimesh
        The repaired mesh in FRD body axes [m], origin applied.
    name : str
    source : str
        File it came from.
    repairs : list of str
        What was found and repaired, in words (empty for a clean mesh).
    n_bodies : int
        Number of connected bodies.
    role : str
        ``hull`` (default; friction and form drag of the hull), ``appendage`` or ``fin``.
    """

    def __init__(self, mesh, *, name: str = "mesh", source: str = "", repairs=None,
                 face_label=None, n_bodies: int = 1, role: str = "hull", topology=None):
        if role not in ("hull", "appendage", "fin"):
            raise InputError("unknown body role", key="role", value=role,
                             expected="hull, appendage or fin")
        self.role = role
        self.mesh = mesh
        self.name = name
        self.source = source
        self.repairs = list(repairs or [])
        self.n_bodies = int(n_bodies)
        self._face_label = face_label
        self._topology = topology               # EdgeTopology of mesh.faces as given here
        self._topology_faces = mesh.faces
        self._overlap_reported = False
        self._bounds = None                     # (vertex array, bbox) of bbox()
        self._united = None                     # united() of several bodies

    def united(self):
        """The body as one closed surface (a ``trimesh.Trimesh``, body axes [m]): the mesh
        itself when it is one body; several bodies (shells, overlapping parts) united by the
        boolean union of manifold3d (Lévy et al., "Manifold", https://github.com/elalish/
        manifold: an exact, guaranteed-manifold mesh boolean), so that a surface inside another
        body is not panelled.  Computed once; the union is reported in :attr:`repairs`."""
        if self.n_bodies <= 1 or self._face_label is None:
            return self.mesh
        if self._united is None:
            self._united = unite_bodies(self.mesh, self._face_label, where=self.source)
            note = (f"united {self.n_bodies} bodies into one closed surface for the panel "
                    f"method (manifold3d); {self._united.metadata['overlap']:.3g} m^3 of overlap "
                    "removed")
            self.repairs.append(note)
            warnings.warn(f"{self.source}: {note}", ModelWarning, stacklevel=2)
        return self._united

    @property
    def volume(self) -> float:
        """Enclosed volume of the mesh [m^3] (double counts overlapping bodies)."""
        return float(self.mesh.volume)

    @property
    def centroid(self) -> np.ndarray:
        """Volume centroid in body axes [m]."""
        return np.asarray(self.mesh.center_mass, dtype=float)

    def bbox(self) -> np.ndarray:
        """Axis-aligned bounding box [[x0, y0, z0], [x1, y1, z1]] [m].

        Computed once per vertex array (trimesh's ``bounds`` re-hashes the mesh on every
        access to validate its cache); every vertex is on a face after the loader's repairs.
        """
        v = self.mesh.vertices
        if self._bounds is None or self._bounds[0] is not v:
            arr = np.asarray(v, dtype=float)
            self._bounds = (v, np.array([arr.min(axis=0), arr.max(axis=0)]))
        return self._bounds[1].copy()

    def x_extent(self) -> tuple[float, float]:
        """(x_min, x_max) of the body [m]."""
        b = self.bbox()
        return float(b[0, 0]), float(b[1, 0])

    def sections(self, x) -> list[list[np.ndarray]]:
        """Contours of the body's section at each ``x`` [m]: per station a list of
        (n, 2) (y, z) rings, outer rings counter-clockwise and holes clockwise,
        overlapping bodies united."""
        x = np.asarray(x, dtype=float)
        try:
            if self._topology is None or self.mesh.faces is not self._topology_faces:
                self._topology = EdgeTopology(self.mesh.faces)
                self._topology_faces = self.mesh.faces
            raw = slice_rings(self.mesh, x, face_label=self._face_label,
                              topology=self._topology)
        except ValueError:
            raw = self._slice_fallback(x)
        out = []
        for rings in raw:
            out.append(self._union_if_overlapping(rings))
        return out

    def _slice_fallback(self, x):
        # trimesh's slicer, for meshes whose cut edges do not chain (non-manifold edges);
        # ring orientation then comes from nesting, not from the winding
        from stripcoef.geometry.polygons import orient_contours

        out = []
        for xi in x:
            sec = self.mesh.section(plane_origin=[xi, 0.0, 0.0], plane_normal=[1.0, 0.0, 0.0])
            rings = []
            if sec is not None:
                for pts in sec.discrete:
                    pts = np.asarray(pts)
                    if len(pts) > 3 and np.allclose(pts[0], pts[-1]):
                        rings.append(pts[:-1, 1:])
            if rings:
                rings = orient_contours(rings)
            out.append([(r, 0) for r in rings])
        return out

    def _union_if_overlapping(self, rings):
        if not rings:
            return []
        labels = {lab for _, lab in rings}
        if len(labels) < 2:
            return [r for r, _ in rings]
        import shapely

        per_body = [section_geometry([r for r, l_ in rings if l_ == lab])
                    for lab in sorted(labels)]
        total = sum(geom.area for geom in per_body)
        union = shapely.union_all(per_body)
        if total - union.area <= 1e-9 * max(total, 1e-300):
            return [r for r, _ in rings]
        out = []
        for poly in getattr(union, "geoms", [union]):
            if poly.is_empty:
                continue
            ext = np.asarray(poly.exterior.coords)[:-1]
            out.append(ext if ring_integrals(ext)[0] > 0 else ext[::-1])
            for hole in poly.interiors:
                h = np.asarray(hole.coords)[:-1]
                out.append(h if ring_integrals(h)[0] < 0 else h[::-1])
        self._overlap_seen = True
        return out

    def parts(self, x, dx) -> list[Part]:
        """The body's sections on the strips centred at ``x`` with widths ``dx`` [m].

        Strips whose centre lies outside the body's x-range are not covered.  A
        strip inside the range whose cut is empty is an error (a gap in the body
        or an open mesh), never silently dropped.

        Returns
        -------
        list of Part
            One ``polygon`` part (all bodies of the mesh together, so that the
            section solver sees their interaction).
        """
        x = np.asarray(x, dtype=float)
        xmin, xmax = self.x_extent()
        inside = np.nonzero((x > xmin) & (x < xmax))[0]
        if inside.size == 0:
            return []
        secs = self.sections(x[inside])
        for i, rings in zip(inside, secs):
            if not rings:
                raise InputError(f"strip {i} at x = {x[i]:.6g} m cuts no material inside the "
                                 f"body (x from {xmin:.6g} to {xmax:.6g} m)", file=self.source,
                                 expected="a body without gaps along its axis (join the parts "
                                          "or use fewer strips)")
        props = section_properties(secs)
        bad = np.nonzero(props[:, 0] <= 0)[0]
        if bad.size:
            i = inside[bad[0]]
            raise InputError(f"strip {i} at x = {x[i]:.6g} m has non-positive section area "
                             f"{props[bad[0], 0]:.3g} m^2", file=self.source,
                             expected="outward normals")
        if getattr(self, "_overlap_seen", False) and not self._overlap_reported:
            dxs = np.asarray(dx, dtype=float)
            dxs = np.broadcast_to(dxs, x.shape)[inside]
            v_strips = float(np.sum(props[:, 0] * dxs))
            note = (f"overlapping bodies: sections united per strip (shapely union); the mesh "
                    f"volume {self.volume:.6g} m^3 double counts {self.volume - v_strips:.3g} m^3")
            self.repairs.append(note)
            warnings.warn(f"{self.source}: {note}", ModelWarning, stacklevel=2)
            self._overlap_reported = True
        corners = _has_sharp_corners(secs[len(secs) // 2])
        part = Part(name=self.name, shape="polygon", index=inside, y=props[:, 1], z=props[:, 2],
                    half_breadth=props[:, 3], half_height=props[:, 4], area=props[:, 0],
                    iyy=props[:, 5], izz=props[:, 6], rounded=not corners,
                    length=xmax - xmin, role=self.role, contours=secs)
        return [part]

    def strips(self, n: int = 200) -> Strips:
        """The body cut into ``n`` equal strips over its length."""
        if int(n) < 2:
            raise InputError("number of strips too small", key="strips", value=n,
                             expected=">= 2")
        x, dx = uniform_stations(*self.x_extent(), int(n))
        return Strips(x=x, dx=dx, parts=self.parts(x, dx))


def unite_bodies(mesh, labels, where=""):
    """Boolean union of the bodies of a closed mesh (faces grouped by ``labels``), by
    manifold3d through ``trimesh.boolean.union``.  Returns a watertight ``trimesh.Trimesh``
    whose ``metadata['overlap']`` is the volume counted twice before [m^3]."""
    import trimesh

    labels = np.asarray(labels)
    parts = []
    for k in range(int(labels.max()) + 1):
        part = trimesh.Trimesh(mesh.vertices, np.asarray(mesh.faces)[labels == k], process=False)
        part.remove_unreferenced_vertices()
        parts.append(part)
    total = float(sum(p.volume for p in parts))
    out = closed_union(parts, what="bodies of the mesh", file=where or None,
                       expected="closed, manifold bodies (stripcoef mesh FILE --repair writes a "
                                "repaired copy)")
    out.metadata["overlap"] = max(total - float(out.volume), 0.0)
    return out


def _has_sharp_corners(rings) -> bool:
    from stripcoef.geometry.polygons import corner_flags, orient_contours

    try:
        return any(corner_flags(r).any() for r in orient_contours(rings))
    except InputError:
        return False


# --------------------------------------------------------------------------- loading

def _fail(path, what, **kw):
    return InputError(what, file=str(path), **kw)


def _read(path: Path):
    import trimesh

    ext = path.suffix.lower()
    if ext not in MESH_EXTENSIONS:
        raise _fail(path, "unknown mesh file extension", value=path.suffix or "(none)",
                    expected="one of " + ", ".join(MESH_EXTENSIONS))
    if not path.is_file():
        raise _fail(path, "mesh file not found", expected="an existing mesh file")
    if ext == ".dae":
        from stripcoef.geometry.collada import read_collada

        return read_collada(path)       # its unit and up axis in metadata (_file_frame)
    try:
        # geometry only: an OBJ's materials and textures are not read (they need pillow,
        # which the base install lacks, and carry nothing the hydrodynamics uses)
        extra = {"skip_materials": True} if ext == ".obj" else {}
        loaded = trimesh.load(str(path), force="mesh", process=True, **extra)
    except Exception as exc:  # trimesh raises many types for garbage input
        raise _fail(path, f"not a readable {ext[1:].upper()} mesh ({type(exc).__name__}: "
                          f"{str(exc).splitlines()[0][:80] if str(exc) else 'no detail'})",
                    expected=f"a valid {ext[1:].upper()} file of a closed surface") from None
    if not isinstance(loaded, trimesh.Trimesh):
        raise _fail(path, "file holds no triangle mesh", value=type(loaded).__name__,
                    expected="a surface mesh with faces")
    if len(loaded.faces) == 0:
        raise _fail(path, "mesh is empty", value="0 faces", expected="a closed surface")
    if not loaded.is_watertight:   # holes: where trimesh dropped the faces of NaN vertices?
        from stripcoef.geometry.mesh_checks import refuse_non_finite_vertices
        refuse_non_finite_vertices(path)
    return loaded


#: Vertices closer than this fraction of the body's largest extent are one vertex (split copies
#: at texture or normal seams; CAD exports print 6-9 significant digits) [-].
MERGE_TOL = 1e-7
#: A body longer than this [m] in metres is more likely a file in millimetres (an underwater
#: vehicle of 20-200 m is rare; beyond 200 m the loader refuses it).
LONG_BODY = 20.0


def merge_close_vertices(mesh, tol: float) -> int:
    """Merge the vertices on open edges of ``mesh`` (in place) that lie within ``tol`` [m] of
    another such vertex, the first of each group kept (groups: connected components of the
    pairs closer than ``tol``, scipy's k-d tree).  Only the ends of open edges are merged:
    a vertex split at a seam leaves the edges on both sides open, while closed bodies that
    touch at a corner (parts of a frame) stay separate, manifold bodies.  Faces keep their
    winding; a face that loses a vertex to the merge is dropped.  Returns the number of
    vertices merged away."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    v = np.asarray(mesh.vertices, dtype=float)
    if len(v) < 2 or not tol > 0:
        return 0
    f = np.asarray(mesh.faces, dtype=np.int64)
    e = np.sort(np.stack([f, np.roll(f, -1, axis=1)], axis=2).reshape(-1, 2), axis=1)
    uniq, count = np.unique(e, axis=0, return_counts=True)
    loose = np.unique(uniq[count == 1])
    if loose.size < 2:
        return 0
    pairs = loose[cKDTree(v[loose]).query_pairs(tol, output_type="ndarray")]
    if len(pairs) == 0:
        return 0
    n = len(v)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    k, lab = connected_components(graph, directed=False)
    first = np.full(k, n, dtype=np.int64)
    np.minimum.at(first, lab, np.arange(n))
    f = first[lab][np.asarray(mesh.faces)]
    keep = (f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])
    mesh.faces = f[keep]
    mesh.remove_unreferenced_vertices()
    return int(n - k)


def repair_degenerate_faces(mesh, height: float, passes: int = 10) -> tuple[int, int]:
    """Remove zero-area faces without opening a closed surface (in place).

    A face whose height over its longest edge is below ``height`` [m] is either a *needle*
    (its shortest edge shorter than ``height``: the edge is collapsed, its two vertices merged
    at their midpoint, and the faces on it vanish with it) or a *cap* (a vertex on the opposite
    edge: that longest edge is flipped with the face beyond it, which splits that face at the
    vertex and leaves the surface and its shape unchanged) -- the two operations of mesh
    simplification and repair that keep a surface closed (Hoppe et al. 1993, "Mesh
    optimization", SIGGRAPH: edge collapse and edge swap; Botsch et al. 2010, "Polygon Mesh
    Processing", sec. 6.5).  Faces on edges without exactly one neighbour (an open mesh)
    are left to the loader's removal.  Returns (edge flips, edges collapsed)."""
    flips = collapses = 0
    for _ in range(passes):
        v = np.asarray(mesh.vertices, dtype=float)
        f = np.array(mesh.faces, dtype=np.int64)
        if len(f) == 0:
            break
        fv = _FaceVectors(v, f)
        bad = np.flatnonzero(~fv.nondegenerate(height))
        if bad.size == 0:
            break
        nv = len(v)
        dkey = (f * nv + np.roll(f, -1, axis=1)).reshape(-1)      # directed edges k -> k+1
        order = np.argsort(dkey, kind="stable")
        sorted_keys = dkey[order]

        def faces_on(a, b):
            lo, hi = np.searchsorted(sorted_keys, [a * nv + b, a * nv + b + 1])
            return [int(x) // 3 for x in order[lo:hi]]

        changed = False
        done = set()
        for i in bad:
            if i in done:
                continue
            t = v[f[i]]
            elen = np.linalg.norm(t[[1, 2, 0]] - t, axis=1)          # edge k: k -> k+1
            k_short, k_long = int(np.argmin(elen)), int(np.argmax(elen))
            if elen[k_short] <= height or elen[k_short] <= 1e-9 * elen[k_long]:
                a, b = f[i, k_short], f[i, (k_short + 1) % 3]
                mid = 0.5 * (v[a] + v[b])
                v[a] = mid
                f[f == b] = a
                done.update(faces_on(a, b) + faces_on(b, a))
                collapses += 1
                changed = True
                mesh.vertices = v
                break                   # the faces changed: rebuild the edge map
            a, b, c = f[i, k_long], f[i, (k_long + 1) % 3], f[i, (k_long + 2) % 3]
            other = faces_on(b, a)
            if len(other) != 1 or len(faces_on(a, b)) != 1 or other[0] in done:
                continue
            j = other[0]
            d = int([x for x in f[j] if x != a and x != b][0])
            # faces (a, b, c) and (b, a, d) -> (a, d, c) and (d, b, c): c lies on edge ab
            f[i] = (a, d, c)
            f[j] = (d, b, c)
            done.update((i, j))
            flips += 1
            changed = True
        keep = (f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])
        mesh.faces = f[keep]
        if not changed:
            break
    mesh.remove_unreferenced_vertices()
    return flips, collapses


def _check_unit_and_axes(where, extent, length_unit, repairs) -> None:
    """Warn (as a repair note) when the size suggests a wrong length unit."""
    size = float(extent.max())
    if length_unit == "m" and size > LONG_BODY:
        repairs.append(f"the body is {size:.4g} m long: if the file is in millimetres, "
                       "use --length-unit mm (Python: length_unit='mm')")


#: The body is said to lie along another file axis (a warning naming ``--axis``) when its extent
#: across body x exceeds this multiple of its extent along x [-]: ROVs are often wider than
#: long (BlueROV2: 0.58 / 0.46 = 1.26), a glider or torpedo AUV along y is 5-10 times longer.
LONG_AXIS_RATIO = 1.5


def _axis_rotation(axis: str, z_up: bool) -> np.ndarray:
    """The rotation (3x3, determinant +1) from the file's axes (after the unit, the transform
    and a COLLADA file's up axis) into the body axes (FRD), ``p_body = R @ p_file``.

    Not z-up: the cyclic mapping of the module docstring (``axis='y'``: (y, z, x) -> body
    (x, y, z)).  z-up (ROS REP 103: x forward, y left, z up; a COLLADA file, whose up axis is
    turned to z first): 180 deg about x, (x, y, z) -> (x, -y, -z); with ``axis='y'`` (the length
    along the file's y) turned about the up axis instead, so that up stays up: (x, y, z) ->
    (y, x, -z); ``axis='z'`` (the length along up): the cyclic mapping, then 180 deg about x."""
    perm = np.eye(3)[list(_AXIS_PERM[axis])]
    if not z_up:
        return perm
    if axis == "y":
        return np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])
    return np.diag([1.0, -1.0, -1.0]) @ perm


def _file_frame(metadata, length_unit: str, axis: str, z_up: bool):
    """(metres per file unit, the rotation (3x3) from the file's axes into the body axes, notes,
    the part of that rotation that ``axis`` chooses (:func:`_axis_rotation`)) of a mesh.  A COLLADA file (``metadata`` from :func:`stripcoef.geometry.collada.read_collada`)
    declares both: its ``<unit meter>`` is the unit unless ``length_unit`` is not ``'m'`` (the
    default), which then overrides it (a note says so); its ``<up_axis>`` is turned to z-up
    (:data:`stripcoef.geometry.collada.TO_Z_UP`) and the body read as a z-up file."""
    notes = []
    scale = LENGTH_UNITS[length_unit]
    unit = metadata.get("collada_unit_meter")
    up_axis = metadata.get("collada_up_axis")
    if unit is not None:
        if length_unit == "m":
            scale = float(unit)
        elif not np.isclose(scale, unit, rtol=1e-9):
            notes.append(f"the length unit '{length_unit}' ({scale:g} m) overrides the file's "
                         f"declared <unit meter=\"{unit:g}\">")
    up = np.eye(3)
    if up_axis is not None:
        from stripcoef.geometry.collada import TO_Z_UP

        if z_up and up_axis != "Z_UP":
            notes.append(f"the file declares {up_axis}: z_up (--z-up) ignored, its up axis used")
        up, z_up = TO_Z_UP[up_axis], True
        if up_axis != "Z_UP":
            notes.append(f"the file declares {up_axis}: turned z-up (COLLADA's right, up and "
                         "in axes), then read as a z-up file")
    body = _axis_rotation(axis, z_up)
    return scale, body @ up, notes, body


def _prepare(mesh, *, path, axis, length_unit, origin, transform, z_up=False, axis_hint=False,
             close_parts=False):
    import trimesh

    if length_unit not in LENGTH_UNITS:
        raise InputError("unknown length unit", key="length_unit", value=length_unit,
                         expected="one of " + ", ".join(LENGTH_UNITS))
    if axis not in AXES:
        raise InputError("unknown body axis", key="axis", value=axis, expected="x, y or z")
    scale, rot, repairs, choice = _file_frame(getattr(mesh, "metadata", None) or {},
                                              length_unit, axis, z_up)
    # a fresh mesh on copied arrays (Trimesh.copy also deep-copies its caches)
    mesh = trimesh.Trimesh(vertices=np.array(mesh.vertices, dtype=float),
                           faces=np.array(mesh.faces, dtype=np.int64), process=False)
    mesh.apply_scale(scale)
    if transform is not None:
        try:
            t = np.asarray(transform, dtype=float)
        except (TypeError, ValueError):
            t = np.full(1, np.nan)
        if t.shape != (4, 4) or not np.all(np.isfinite(t)):
            raise InputError("transform must be a 4x4 matrix", key="transform",
                             value=f"shape {t.shape}", expected="4x4 finite")
        mesh.apply_transform(t)
    mesh.vertices = np.asarray(mesh.vertices) @ rot.T      # a rotation: handedness kept

    where = str(path)
    extent = np.ptp(mesh.vertices, axis=0)
    if not np.all(np.isfinite(extent)):
        raise _fail(where, "mesh has non-finite vertex coordinates",
                    expected="finite coordinates (no NaN or inf)")
    if extent[0] <= 1e-9 * max(extent.max(), 1e-300):
        raise _fail(where, f"the body has no extent along the mesh {axis} axis (the body axis)",
                    value=f"{extent[0]:.3g} m", expected="the mesh axis along the body's length as axis (x, y or z)")
    length = float(extent[0])
    if min(extent[1], extent[2]) <= 1e-9 * length:
        raise _fail(where, "mesh encloses no volume (it is flat)",
                    value=f"extent {extent[1]:.3g} x {extent[2]:.3g} m across the axis",
                    expected="a closed solid")
    if not LENGTH_RANGE[0] <= extent.max() <= LENGTH_RANGE[1]:
        raise _fail(where, f"body is {extent.max():.4g} m long with length unit '{length_unit}'",
                    expected=f"between {LENGTH_RANGE[0]:g} and {LENGTH_RANGE[1]:g} m "
                             "(check --length-unit)")

    size = float(extent.max())
    _check_unit_and_axes(where, extent, length_unit, repairs)
    k = 1 + int(np.argmax(extent[1:]))
    if axis_hint and extent[k] > LONG_AXIS_RATIO * extent[0]:
        named = "xyz"[int(np.argmax(np.abs(choice[k])))]      # of the frame --axis picks in
        turned = " (turned z-up)" if np.any(rot != choice) else ""
        warnings.warn(f"{where}: the body is {extent[k]:.4g} m along the file's {named} "
                      f"axis{turned} "
                      f"but {extent[0]:.4g} m along body x (its length, surge): if the file's "
                      f"{named} axis is the body's length, use --axis {named} (Python: "
                      f"axis='{named}'; a z-up file is turned about its up axis)",
                      ModelWarning, stacklevel=3)
    # vertices split at texture or normal seams (OBJ, glTF): merged by position
    merged = merge_close_vertices(mesh, MERGE_TOL * size)
    if merged:
        repairs.append(f"merged {merged} vertices that repeat the position of another "
                       f"(split at texture or normal seams; within {MERGE_TOL * size:.2g} m)")
    # faces: the per-face vectors are gathered once and reused while the faces are unchanged
    n0 = len(mesh.faces)
    flipped_d, collapsed_d = repair_degenerate_faces(mesh, 1e-10 * length)
    if flipped_d or collapsed_d:
        repairs.append(f"repaired {flipped_d + collapsed_d} degenerate (zero-area) faces without "
                       f"opening the surface ({flipped_d} edge flips, {collapsed_d} edges "
                       "collapsed)")
    fv = _FaceVectors(mesh.vertices, mesh.faces)
    mask = fv.nondegenerate(1e-10 * length)
    if not mask.all():
        mesh.update_faces(mask)
        repairs.append(f"removed {int((~mask).sum())} degenerate (zero-area) faces")
        fv = None
    mesh.remove_unreferenced_vertices()
    if len(mesh.faces) == 0:
        raise _fail(where, "mesh is empty after removing degenerate faces", value=f"{n0} faces",
                    expected="triangles of non-zero area")
    topo = EdgeTopology(mesh.faces)
    labels = topo.component_labels() if topo.watertight else None
    # Duplicate faces: two faces on the same three vertices share all three edges, so in a
    # watertight mesh (every edge on exactly two faces) they can only form a two-face
    # component of their own.  Search for them only if the mesh is open or has a component
    # smaller than a tetrahedron's four faces.
    if labels is None or np.bincount(labels).min() < 4:
        mask = mesh.unique_faces()
        if not mask.all():
            mesh.update_faces(mask)
            mesh.remove_unreferenced_vertices()
            repairs.append(f"removed {int((~mask).sum())} duplicate faces")
            topo, labels, fv = EdgeTopology(mesh.faces), None, None
    if not topo.watertight:
        n_open = topo.open_edges
        trimesh.repair.fill_holes(mesh)
        topo, labels, fv = EdgeTopology(mesh.faces), None, None
        if topo.watertight:
            repairs.append(f"closed holes in the surface ({n_open} open edges; "
                           "trimesh.repair.fill_holes)")
        elif close_parts:
            mesh, notes = close_open_parts(mesh, where=where)
            repairs += notes
            topo, labels, fv = EdgeTopology(mesh.faces), None, None
        else:
            raise _fail(where, f"mesh is not watertight: {open_parts_text(mesh)} after hole "
                               "filling",
                        expected=f"a closed surface: 'stripcoef mesh {Path(where).name} --repair "
                                 f"-o {Path(where).stem}_closed.stl' caps the open parts and "
                                 "unites the parts (Python: close_parts=True); or close it in "
                                 "CAD")
    if not topo.consistent:
        trimesh.repair.fix_winding(mesh)
        repairs.append("made the face winding consistent (trimesh.repair.fix_winding)")
        topo, labels, fv = EdgeTopology(mesh.faces), None, None
    if labels is None:
        labels = topo.component_labels()
    if fv is None:
        fv = _FaceVectors(mesh.vertices, mesh.faces)
    n_bodies = int(labels.max()) + 1 if labels.size else 0
    body_vol = np.bincount(labels, weights=fv.tetra_volumes(), minlength=n_bodies)
    flipped = np.nonzero(body_vol < 0)[0]
    if flipped.size:
        faces = mesh.faces.copy()
        sel = np.isin(labels, flipped)
        faces[sel] = faces[sel][:, ::-1]
        mesh.faces = faces
        topo = EdgeTopology(mesh.faces)          # a flipped face lists its edges reversed
        fv = _FaceVectors(mesh.vertices, mesh.faces)
        repairs.append(f"flipped inward-pointing normals of {flipped.size} of {n_bodies} "
                       "bodies" if n_bodies > 1 else "flipped inward-pointing normals")
    if n_bodies > 1:
        repairs.append(f"mesh has {n_bodies} separate bodies; treated as one rigid body "
                       "(sections solved together)")
    vol = float(np.abs(body_vol).sum())    # each body's, outward normals (as mesh.volume)
    bbox_vol = float(np.prod(np.ptp(mesh.vertices, axis=0)))
    if not vol > 1e-9 * bbox_vol:
        raise _fail(where, "mesh encloses no volume", value=f"{vol:.3g} m^3",
                    expected="a closed solid")

    # origin
    if isinstance(origin, str):
        if origin not in ("centroid", "file"):
            raise InputError("unknown origin", key="origin", value=origin,
                             expected="centroid, file or a point (x, y, z)")
        point = fv.centroid() if origin == "centroid" else np.zeros(3)
    else:
        p = np.asarray(origin, dtype=float)
        if p.shape != (3,) or not np.all(np.isfinite(p)):
            raise InputError("origin point must be 3 numbers", key="origin", value=origin,
                             expected="x, y, z in the mesh file's coordinates and unit")
        p = p * scale
        if transform is not None:
            p = (np.asarray(transform, float) @ np.append(p, 1.0))[:3]
        point = rot @ p
    mesh.apply_translation(-point)
    return mesh, repairs, labels, n_bodies, topo


class _FaceVectors:
    r"""Per-face vectors of a triangle mesh, gathered once and shared by the loader's checks.

    For face f with vertices :math:`\mathbf p_0, \mathbf p_1, \mathbf p_2` [m]: the edge
    vectors :math:`\mathbf a = \mathbf p_1 - \mathbf p_0`, :math:`\mathbf b = \mathbf p_2 -
    \mathbf p_0` and :math:`\mathbf c = \mathbf a \times \mathbf b` (twice the area vector,
    along the outward normal for counter-clockwise winding).  Coordinates are stored as
    (3, F) rows so that every operation runs on contiguous arrays.
    """

    def __init__(self, vertices, faces):
        v = np.ascontiguousarray(np.asarray(vertices, dtype=float).T)      # (3, V)
        f = np.asarray(faces)
        self.p0 = v[:, f[:, 0]]
        self.a = v[:, f[:, 1]] - self.p0
        self.b = v[:, f[:, 2]] - self.p0
        ax, ay, az = self.a
        bx, by, bz = self.b
        self.c = np.array([ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx])

    def tetra_volumes(self) -> np.ndarray:
        r"""Signed volumes of the tetrahedra from the origin to each face [m^3].

        .. math:: V_f = \tfrac16\,\mathbf p_0\cdot(\mathbf p_1\times\mathbf p_2)
                      = \tfrac16\,\mathbf p_0\cdot(\mathbf a\times\mathbf b)

        (the two agree because :math:`\mathbf p_0\cdot(\mathbf p_0\times\cdot) = 0`;
        divergence theorem, e.g. Zhang & Chen 2001, "Efficient feature extraction for
        2D/3D objects in mesh representation").
        """
        return np.einsum("kf,kf->f", self.p0, self.c) / 6.0

    def centroid(self) -> np.ndarray:
        r"""Volume centroid of a closed, outward-oriented triangle mesh [m].

        .. math:: \mathbf c = \frac{\sum_f V_f\,(\mathbf p_0 + \mathbf p_1 + \mathbf p_2)/4}
                  {\sum_f V_f},\qquad \mathbf p_0 + \mathbf p_1 + \mathbf p_2
                  = 3\mathbf p_0 + \mathbf a + \mathbf b

        (Zhang & Chen 2001, as :meth:`tetra_volumes`).
        """
        vol = self.tetra_volumes()
        return ((3.0 * self.p0 + self.a + self.b) @ vol) / (4.0 * vol.sum())

    def nondegenerate(self, height: float) -> np.ndarray:
        """Faces whose two heights over the edges from their first vertex both exceed
        ``height`` [m] (trimesh's ``nondegenerate_faces(height)`` test: the triangle's 2D
        box 2A/|e| > height for e = a and e = b, an edge of 1e-8 m or less counting as 0)."""
        twice_area = np.sqrt(np.einsum("kf,kf->f", self.c, self.c))
        la = np.sqrt(np.einsum("kf,kf->f", self.a, self.a))
        lb = np.sqrt(np.einsum("kf,kf->f", self.b, self.b))
        return (la > 1e-8) & (lb > 1e-8) & (twice_area > height * la) & (twice_area > height * lb)


def volume_centroid(vertices, faces) -> np.ndarray:
    """Volume centroid [m] of a closed, outward-oriented triangle mesh (vertices [m], faces):
    :meth:`_FaceVectors.centroid`."""
    return _FaceVectors(vertices, faces).centroid()


def load_mesh(path, *, axis: str = "x", length_unit: str = "m", origin="centroid",
              transform=None, name: str | None = None, role: str = "hull",
              z_up: bool = False, close_parts: bool = False) -> MeshBody:
    """Read a mesh file, repair what can be repaired and return it in body axes.

    Parameters
    ----------
    path : str or Path
        STL, OBJ, PLY, GLB or COLLADA (.dae) file (scenes are merged with their node
        transforms).
    axis : {"x", "y", "z"}
        Mesh axis along the body's length; mapped cyclically onto body x (a z-up file with
        ``axis='y'``: turned about its up axis, :func:`_axis_rotation`).  A body more than
        :data:`LONG_AXIS_RATIO` times longer across body x than along it is warned about,
        naming the file's axis and this parameter.
    length_unit : {"m", "mm", "cm", "in", "ft"}
        Unit of the file's coordinates (a COLLADA file's declared ``<unit>`` when ``'m'``,
        the default; another value overrides it, with a warning).
    origin : "centroid", "file" or (x, y, z)
        Body origin: the volume centroid (centre of buoyancy), the file's own
        origin (after unit, transform and axis mapping: for meshes placed in a
        vehicle file), or a point given in the file's coordinates and unit.
    transform : (4, 4) array, optional
        Homogeneous transform applied after the unit conversion (translation in
        metres), before the axis mapping.
    name : str, optional
        Body name (default: the file's stem).
    role : {"hull", "appendage", "fin"}
        Role of the mesh's parts in the assembly (an appendage mesh in a vehicle file is
        ``appendage``).
    z_up : bool
        The file's z axis points up (ROS meshes, REP 103: x forward, y left, z up; most CAD
        tools): the body is turned 180 deg about x into FRD (z down) after the axis mapping.
        A COLLADA file is read with its declared ``<up_axis>`` turned to z-up, as z-up.
    close_parts : bool
        A mesh that stays open after hole filling: cap the holes of each open part and unite
        the parts (:func:`stripcoef.geometry.mesh_close.close_open_parts`; ``stripcoef mesh
        FILE --repair``) instead of refusing it.

    Returns
    -------
    MeshBody
        Each repair is in ``MeshBody.repairs`` and is also issued as a
        :class:`~stripcoef.errors.ModelWarning` (the CLI prints it on stderr).

    Raises
    ------
    InputError
        Unknown extension, unreadable file, no faces, zero volume, body length
        outside 1 mm..200 m (wrong unit), no extent along the axis, an open
        mesh that cannot be closed.
    """
    path = Path(path)
    mesh = _read(path)
    mesh, repairs, labels, n_bodies, topo = _prepare(mesh, path=path, axis=axis,
                                                     length_unit=length_unit, origin=origin,
                                                     transform=transform, z_up=z_up,
                                                     axis_hint=True, close_parts=close_parts)
    for note in repairs:
        warnings.warn(f"{path}: {note}", ModelWarning, stacklevel=2)
    return MeshBody(mesh, name=name or path.stem, source=str(path), repairs=repairs,
                    face_label=labels, n_bodies=n_bodies, role=role, topology=topo)


def mesh_body(mesh, *, name: str = "mesh", axis: str = "x", length_unit: str = "m",
              origin="centroid", transform=None, z_up: bool = False) -> MeshBody:
    """:func:`load_mesh` for an in-memory ``trimesh.Trimesh``."""
    mesh, repairs, labels, n_bodies, topo = _prepare(mesh, path=name, axis=axis,
                                                     length_unit=length_unit, origin=origin,
                                                     transform=transform, z_up=z_up)
    return MeshBody(mesh, name=name, source=name, repairs=repairs, face_label=labels,
                    n_bodies=n_bodies, topology=topo)


def revolved_mesh(x, r, *, sections: int = 64):
    """Closed triangle mesh of the body of revolution with radius ``r(x)`` about the x axis.

    Parameters
    ----------
    x, r : arrays
        Meridian stations [m] (increasing) and radii [m]; a zero end radius is a
        tip (one vertex), a non-zero one gets a flat cap.
    sections : int
        Panels around the circumference.

    Returns
    -------
    trimesh.Trimesh
        Watertight mesh, outward normals, x along the axis.
    """

    x = np.asarray(x, dtype=float)
    r = np.asarray(r, dtype=float)
    if x.ndim != 1 or x.shape != r.shape or x.size < 2 or np.any(np.diff(x) <= 0) or np.any(r < 0):
        raise InputError("profile must be increasing x with non-negative radii",
                         key="profile", value=f"{x.size} points", expected="x increasing, r >= 0")
    tiny = 1e-12 * max(float(r.max()), 1e-300)
    if r[0] <= tiny:
        x0, x, r = x[0], x[1:], r[1:]
    else:
        x0 = x[0]
    if r[-1] <= tiny:
        x1, x, r = x[-1], x[:-1], r[:-1]
    else:
        x1 = x[-1]
    if np.any(r <= tiny):
        raise InputError("profile radius is zero inside the body", key="profile",
                         expected="r > 0 except at the two ends")
    n = int(sections)
    th = 2.0 * np.pi * np.arange(n) / n
    rings = np.stack([np.column_stack([np.full(n, xi), ri * np.cos(th), ri * np.sin(th)])
                      for xi, ri in zip(x, r)])                   # (m, n, 3)
    return closed_loft(rings, [x0, 0.0, 0.0], [x1, 0.0, 0.0])


def closed_loft(rings, first, last):
    """A closed ``trimesh.Trimesh`` lofted through ``rings`` ((m, n, 3) [m]: m stations of n
    points each, in the same turning sense), each pair of neighbouring stations joined by 2n
    triangles, closed by a fan from the point ``first`` to the first station and one from
    ``last`` to the last (a tip where the point lies on the body, a flat cap where it is the
    station's centre); turned outward (positive volume)."""
    import trimesh

    rings = np.asarray(rings, float)
    m, n = rings.shape[:2]
    verts = np.vstack([rings.reshape(-1, 3), [first, last]])
    p_first, p_last = m * n, m * n + 1
    k = np.arange(n)
    k1 = (k + 1) % n
    faces = []
    for i in range(m - 1):
        a, b = i * n + k, i * n + k1
        c, d = (i + 1) * n + k, (i + 1) * n + k1
        faces.append(np.column_stack([a, c, d]))
        faces.append(np.column_stack([a, d, b]))
    faces.append(np.column_stack([np.full(n, p_first), k, k1]))         # first fan (or cap)
    end = (m - 1) * n
    faces.append(np.column_stack([np.full(n, p_last), end + k1, end + k]))
    mesh = trimesh.Trimesh(verts, np.vstack(faces), process=False)
    if mesh.volume < 0:
        mesh.invert()
    return mesh
