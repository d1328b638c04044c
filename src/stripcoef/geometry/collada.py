r"""COLLADA (.dae) mesh files read with pycollada: every triangle of the scene in the file's
coordinates, its declared length unit and up axis.

COLLADA 1.4.1 (Khronos Group 2008, "COLLADA -- Digital Asset Schema Release 1.4.1
Specification", 5.15 ``<asset>``): ``<unit meter="s">`` says that one unit of the file is
``s`` metres (default 1), ``<up_axis>`` which axis points up (default ``Y_UP``).  The
specification's table of the three values (right, up and "in" axes):

=========  ==========  =========  =========
value      right       up         in
=========  ==========  =========  =========
``X_UP``   -y          +x         +z
``Y_UP``   +x          +y         +z
``Z_UP``   +x          +z         -y
=========  ==========  =========  =========

:data:`TO_Z_UP` turns each into the z-up frame of ``Z_UP`` (right = x, up = z, right-handed;
ROS REP 103 and Blender write this frame): a ``Y_UP`` point (x, y, z) is (x, -z, y) there, an
``X_UP`` point (-y, -z, x).  Both matrices are rotations (determinant +1), so the body keeps its
handedness.  The mesh loader (:mod:`stripcoef.geometry.mesh`) turns that z-up frame into the
body axes (FRD) as it does a z-up STL.

Why pycollada (https://github.com/pycollada/pycollada, BSD, pure Python): it is the COLLADA
reader trimesh itself uses, maintained since 2011; reading the scene with it directly keeps
its errors (a malformed file, a geometry the scene names but the file lacks), which trimesh's
loader turns into an empty scene.  Every node transform of the scene graph is applied
(pycollada's bound geometry: the product of the matrices from the scene root to the
instance), and the triangles of all geometries are one mesh, as the other formats' scenes are.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from stripcoef.errors import InputError

#: The rotation [-] from each ``<up_axis>`` frame into the z-up frame (module docstring):
#: ``p_zup = TO_Z_UP[axis] @ p_file``.
TO_Z_UP = {
    "Z_UP": np.eye(3),
    "Y_UP": np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]),
    "X_UP": np.array([[0.0, -1.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]]),
}
#: The specification's defaults when ``<asset>`` omits them.
DEFAULT_UNIT_METER = 1.0
DEFAULT_UP_AXIS = "Y_UP"


def _asset_values(doc, where):
    """(metres per unit, up axis) of the document's ``<asset>``, each checked."""
    asset = getattr(doc.assetInfo, "xmlnode", None)
    unit, up = DEFAULT_UNIT_METER, DEFAULT_UP_AXIS
    if asset is None:
        return unit, up
    node = asset.find(doc.tag("unit"))
    if node is not None and node.get("meter") is not None:
        text = node.get("meter")
        try:
            unit = float(text)
        except ValueError:
            unit = float("nan")
        if not (np.isfinite(unit) and unit > 0):
            raise InputError("bad COLLADA length unit", file=where, key="<unit meter>",
                             value=text, expected="a positive number of metres per unit "
                                                  "(e.g. 1 or 0.001)")
    node = asset.find(doc.tag("up_axis"))
    if node is not None:
        text = (node.text or "").strip()
        if text not in TO_Z_UP:
            raise InputError("bad COLLADA up axis", file=where, key="<up_axis>", value=text,
                             expected="X_UP, Y_UP or Z_UP")
        up = text
    return unit, up


def read_collada(path):
    """The triangles of a COLLADA file as one ``trimesh.Trimesh`` in the file's coordinates
    (node transforms applied; exact duplicate vertices merged as trimesh does for every
    format), with ``metadata['collada_unit_meter']`` (metres per file unit) and
    ``metadata['collada_up_axis']`` (``X_UP``, ``Y_UP`` or ``Z_UP``) from its ``<asset>``.

    Raises
    ------
    InputError
        Not a COLLADA document (not XML, a malformed or incomplete element, a geometry the
        scene names but the file lacks), a bad ``<unit>`` or ``<up_axis>``, no ``<scene>``,
        no triangles in the scene.
    """
    import trimesh

    path = Path(path)
    where = str(path)
    try:
        import collada
    except ImportError:  # pragma: no cover - a core dependency
        raise InputError("reading a COLLADA file needs pycollada", file=where,
                         expected="pip install pycollada (a dependency of stripcoef)") from None
    expected = "a COLLADA 1.4/1.5 document whose <scene> instances triangle geometry"
    try:
        # materials and images do not matter for the hydrodynamics: an unsupported effect is
        # skipped; a broken geometry reference is found below (the scene's triangles)
        doc = collada.Collada(where, ignore=[collada.common.DaeUnsupportedError,
                                             collada.common.DaeBrokenRefError])
    except Exception as exc:  # noqa: BLE001 - lxml, ElementTree and pycollada raise many types
        detail = str(exc).splitlines()[0][:100] if str(exc) else "no detail"
        raise InputError(f"not a readable COLLADA file ({type(exc).__name__}: {detail})",
                         file=where, expected=expected) from None
    unit, up = _asset_values(doc, where)
    if doc.scene is None:
        raise InputError("COLLADA file has no <scene>", file=where, expected=expected)
    verts, faces, n = [], [], 0
    try:
        for geom in doc.scene.objects("geometry"):
            for prim in geom.primitives():
                if hasattr(prim, "triangleset"):          # polylist, polygons
                    prim = prim.triangleset()
                index = getattr(prim, "vertex_index", None)
                if index is None or getattr(prim, "vertex", None) is None or len(index) == 0:
                    continue                               # lines, points: no surface
                v = np.asarray(prim.vertex, dtype=float).reshape(-1, 3)
                f = np.asarray(index, dtype=np.int64).reshape(-1, 3)
                verts.append(v)
                faces.append(f + n)
                n += len(v)
    except collada.common.DaeError as exc:
        raise InputError(f"COLLADA scene cannot be read ({type(exc).__name__}: "
                         f"{str(exc)[:100]})", file=where, expected=expected) from None
    if not faces:
        raise InputError("COLLADA scene holds no triangles", file=where, value="0 faces",
                         expected=expected)
    v, f = np.vstack(verts), np.vstack(faces)
    bad = np.flatnonzero(~np.all(np.isfinite(v), axis=1))
    if bad.size:           # trimesh's processing would drop their faces without a word
        raise InputError(f"non-finite vertex coordinates (in {bad.size} of {len(v)} "
                         "vertices)", file=where, key=f"vertex {int(bad[0])}",
                         value=v[bad[0]].tolist(), expected="finite coordinates (no NaN or inf)")
    if f.min() < 0 or f.max() >= len(v):
        raise InputError("COLLADA triangle indexes a vertex the file lacks", file=where,
                         value=f"index {int(f.max())} of {len(v)} vertices", expected=expected)
    mesh = trimesh.Trimesh(v, f, process=True)
    mesh.metadata["collada_unit_meter"] = unit
    mesh.metadata["collada_up_axis"] = up
    return mesh
